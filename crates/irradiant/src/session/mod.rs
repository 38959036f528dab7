//! The session: the one frame loop. It owns the GPU scene, the frame, the technique, the camera
//! and the clock; `render`, `compare`, `bench`, the tests and the viewer all drive frames
//! through it. Every size is checked before anything is allocated, and one call,
//! [`Session::invalidate`], resets every kind of history (house rule 7).

use std::sync::Arc;

use irradiant_gpu::{Allocation, GpuContext, PassTiming, Profiler, wgpu};
use irradiant_scene::{Camera, Pose, Scene};

use crate::RenderError;
use crate::frame::{Frame, FrameNeeds, FrameSettings, GBufferSample, Image, SceneChange};
use crate::scene::{GpuScene, GpuSceneSettings};
use crate::settings::TechniqueSpec;
use crate::technique::{ProbeView, Technique, TechniqueContext};

mod scene_edits;

/// What messages call a scene given by hand (a host's, or meshes added to a session), where a
/// loaded scene's name its file.
pub(crate) const HOST_SCENE: &str = "the host's scene";

/// How a session starts.
#[derive(Clone, Debug)]
pub struct SessionSettings {
    /// Image width and height in pixels.
    pub size: (u32, u32),
    /// The frame's settings: TAA, tonemapping, the G-buffer pyramid, direct light.
    pub frame: FrameSettings,
    /// The technique to build, with its preset and settings.
    pub technique: TechniqueSpec,
    /// How the scene is put on the GPU (BVH build quality, texture size).
    pub scene: GpuSceneSettings,
    /// Animation time, in seconds, of the first frame.
    pub time: f32,
    /// Where techniques cache what they bake (light-field probes); None: bake every time.
    pub cache_dir: Option<std::path::PathBuf>,
    /// Told how a bake progresses (the CLI draws a bar).
    pub progress: Option<crate::technique::Progress>,
}

impl Default for SessionSettings {
    fn default() -> Self {
        Self {
            size: (640, 480),
            frame: FrameSettings::default(),
            technique: TechniqueSpec::default(),
            scene: GpuSceneSettings::default(),
            time: 0.0,
            cache_dir: None,
            progress: None,
        }
    }
}

/// Pass timings a frame can hold (the frame's and the technique's passes).
const PROFILED_PASSES: u32 = 64;

/// Frames submitted and not yet finished that `render` lets the CPU run ahead by. A loop with no
/// swap chain to throttle it (bench, soak, compare) otherwise queues frames as fast as it
/// records them, and the driver holds host memory for every one: Sibenik's DDGI soak grew by
/// 650 MiB between two checks 1000 frames apart on the H100.
const MAX_FRAMES_IN_FLIGHT: usize = 3;

/// Where a frame's G-buffer comes from.
#[derive(Clone, Copy)]
pub(crate) enum GBufferSource<'a> {
    /// frame/gbuffer's primary rays (Irradiant's own frames).
    Traced,
    /// A host's G-buffer, through host/import bound to its textures (None: the host drew
    /// into the frame's own, host::NativeGBuffer). frame/direct runs only where `direct` (the
    /// host reads it) or the technique needs it (the pyramid's light); frame/compose only under
    /// the probe overlay: a host composes the light itself.
    Host {
        import: Option<&'a irradiant_gpu::BoundPass>,
        direct: bool,
    },
}

/// What a frame of `size` and the technique of `spec` allocate on the GPU.
fn plan_of(
    scene: &Scene,
    spec: &TechniqueSpec,
    size: (u32, u32),
) -> Result<Vec<Allocation>, RenderError> {
    let kind = spec.kind()?;
    let mut plan = Frame::plan(size.0, size.1, kind.frame_needs(spec));
    plan.extend(kind.plan(spec, scene, size)?);
    Ok(plan)
}

/// The frame loop: owns the GPU scene, the frame, the technique, the camera and the clock.
pub struct Session {
    ctx: Arc<GpuContext>,
    scene: Scene,
    gpu_scene: GpuScene,
    frame: Frame,
    technique: Box<dyn Technique>,
    spec: TechniqueSpec,
    camera: Camera,
    time: f32,
    pose: Pose,
    /// Lights switched off by hand ([`Session::set_light_enabled`]), in the scene's order.
    lights_off: Vec<bool>,
    /// Instances moved or placed by hand ([`Session::set_instance_transform`],
    /// [`Session::add_instance`]), in the scene's order.
    moved: Vec<Option<glam::Mat4>>,
    /// Each instance's id, in the scene's order: its index in the loaded scene, or what
    /// [`Session::add_instance`] returned. Ids stay when other instances are removed.
    instance_ids: Vec<usize>,
    next_instance_id: usize,
    scene_settings: GpuSceneSettings,
    /// The technique's probe overlay, when drawn.
    probes_shown: Option<ProbeView>,
    profiler: Profiler,
    warnings: Vec<String>,
    cache_dir: Option<std::path::PathBuf>,
    progress: Option<crate::technique::Progress>,
    in_flight: std::collections::VecDeque<wgpu::SubmissionIndex>,
}

impl Session {
    /// Every GPU allocation the frame and the technique would make, before any is made.
    pub fn plan(scene: &Scene, settings: &SessionSettings) -> Result<Vec<Allocation>, RenderError> {
        plan_of(scene, &settings.technique, settings.size)
    }

    /// Checks the settings and every size, then builds the scene, the frame and the technique.
    pub fn new(
        ctx: Arc<GpuContext>,
        scene: Scene,
        settings: SessionSettings,
    ) -> Result<Self, RenderError> {
        let kind = settings.technique.kind()?;
        // A lost device fails here, named, rather than inside wgpu's buffer creation.
        ctx.check("starting a session")?;
        let mut warnings = kind.check(&settings.technique)?;
        warnings.extend(kind.scene_warnings(&settings.technique, &scene));
        settings.frame.validate()?;
        ctx.check_allocations(&Self::plan(&scene, &settings)?)?;
        let pose = scene.pose_at(settings.time);
        let mut gpu_scene = GpuScene::new(&ctx, &scene, &settings.scene)?;
        gpu_scene.update(&ctx, &pose);
        let needs = kind.frame_needs(&settings.technique);
        let frame = Frame::new(
            &ctx,
            &gpu_scene,
            settings.size,
            settings.frame.clone(),
            needs,
        )?;
        let technique = kind.build(
            &TechniqueContext {
                ctx: &ctx,
                scene: &scene,
                gpu_scene: &gpu_scene,
                frame: &frame,
                cache_dir: settings.cache_dir.as_deref(),
                progress: settings.progress.as_ref(),
            },
            &settings.technique,
        )?;
        warnings.dedup();
        let profiler = Profiler::new(&ctx, PROFILED_PASSES);
        let lights_off = vec![false; scene.lights.len()];
        let moved = vec![None; scene.instances.len()];
        let mut session = Self {
            instance_ids: (0..scene.instances.len()).collect(),
            next_instance_id: scene.instances.len(),
            scene_settings: settings.scene,
            camera: pose.camera.clone(),
            ctx,
            scene,
            gpu_scene,
            frame,
            technique,
            spec: settings.technique,
            time: settings.time,
            lights_off,
            moved,
            pose,
            probes_shown: None,
            profiler,
            warnings,
            cache_dir: settings.cache_dir,
            progress: settings.progress,
            in_flight: Default::default(),
        };
        session.tell_pose();
        Ok(session)
    }

    /// The GPU context it renders with.
    pub fn ctx(&self) -> &GpuContext {
        &self.ctx
    }

    /// The GPU context, shared (for work that outlives a borrow of the session).
    pub fn shared_ctx(&self) -> Arc<GpuContext> {
        self.ctx.clone()
    }

    /// The scene, as loaded (on the CPU).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene on the GPU, posed at the current time.
    pub fn gpu_scene(&self) -> &GpuScene {
        &self.gpu_scene
    }

    /// The frame: its resources, settings and history.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Whether frames that allow it light in one pass: [`Frame::set_one_pass_direct`].
    pub fn set_one_pass_direct(&mut self, on: bool) {
        self.frame.set_one_pass_direct(on);
    }

    /// The technique it renders indirect light with.
    pub fn technique(&self) -> &dyn Technique {
        self.technique.as_ref()
    }

    /// The technique, mutably.
    pub fn technique_mut(&mut self) -> &mut dyn Technique {
        self.technique.as_mut()
    }

    /// The technique as its concrete type (tests and tools that read its state).
    pub fn technique_as<T: Technique>(&self) -> Option<&T> {
        self.technique.as_any().downcast_ref()
    }

    /// The technique as its concrete type, mutably; None when it is of another type.
    pub fn technique_as_mut<T: Technique>(&mut self) -> Option<&mut T> {
        self.technique.as_any_mut().downcast_mut()
    }

    /// The spec the technique was built (or last reconfigured) from.
    pub fn spec(&self) -> &TechniqueSpec {
        &self.spec
    }

    /// Adds warnings for the user (a host's scene repaired on the way in).
    pub(crate) fn add_warnings(&mut self, warnings: Vec<String>) {
        self.warnings.extend(warnings);
    }

    /// Warnings from the settings (unknown keys), for the user to see.
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The view the next frame renders.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Moves the view; the frame notices the move (its running means restart, TAA reprojects).
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = camera;
    }

    /// Moves the view by a cut, as between two shots: the next frame takes nothing from the
    /// last one's pixels (TAA's history, the direct light's mean and reservoirs), where after
    /// [`set_camera`](Self::set_camera) it would reproject what it can find and clip it. The
    /// frame then does what it does with no history (docs/frame.md: more emitter candidates
    /// a pixel, TAA's reconstruction from the neighbours' samples and, under emitters, the
    /// colour of the surface's light). The technique keeps its history: probes hold the world's
    /// light, not the view's, and its screen-space histories (the final gather's, the
    /// reflections', SSIL's, the light field's) take only what reprojects onto the same surface.
    pub fn cut_to(&mut self, camera: Camera) {
        self.camera = camera;
        self.frame.invalidate();
    }

    /// Animation time, in seconds.
    pub fn time(&self) -> f32 {
        self.time
    }

    /// Moves the scene to its pose at `time`: uploads it, restarts the frame's direct-light mean
    /// and tells the technique what changed — the one path by which a change reaches everything
    /// it affects.
    pub fn seek(&mut self, time: f32) {
        self.time = time;
        self.repose(Vec::new());
    }

    /// Poses the scene at the session's time with what was set by hand, and tells the frame
    /// and the technique what changed; `vacated` are the bounds of instances just removed.
    fn repose(&mut self, vacated: Vec<(glam::Vec3, glam::Vec3)>) {
        let mut next = self.scene.pose_at(self.time);
        for (light, off) in next.lights.iter_mut().zip(&self.lights_off) {
            light.enabled &= !off;
        }
        for (transform, moved) in next.instance_transforms.iter_mut().zip(&self.moved) {
            if let Some(m) = moved {
                *transform = *m;
            }
        }
        if next == self.pose {
            return;
        }
        // Only a camera animation moves the view: a view set by hand stays otherwise.
        if next.camera != self.pose.camera {
            self.camera = next.camera.clone();
        }
        let change = SceneChange::between(&self.pose, &next);
        if change.is_empty() {
            self.pose = next;
            self.tell_pose();
            return;
        }
        self.gpu_scene.update(&self.ctx, &next);
        self.frame.restart_direct();
        let mut dynamic_bounds = self.gpu_scene.dynamic_bounds();
        dynamic_bounds.extend(vacated);
        self.technique.scene_changed(&SceneChange {
            dynamic_bounds,
            ..change
        });
        self.pose = next;
        self.tell_pose();
    }

    /// Tells the technique the scene's pose (at the start, after a change, after a rebuild).
    fn tell_pose(&mut self) {
        self.technique.pose_changed(&self.scene, &self.pose);
    }

    /// Starts the direct light's running mean again (a host turned frame/direct back on).
    pub(crate) fn restart_direct(&mut self) {
        self.frame.restart_direct();
    }

    /// [`Self::seek`] `dt` seconds on.
    pub fn advance(&mut self, dt: f32) {
        self.seek(self.time + dt);
    }

    /// The scene as posed now: its lights (those switched off by hand disabled), instances
    /// and camera path.
    pub fn pose(&self) -> &Pose {
        &self.pose
    }

    /// Switches the scene's light `index` (in [`Scene::lights`]' order) on or off, from the
    /// next frame; the technique is told as of any light change. An index past the lights is
    /// ignored.
    pub fn set_light_enabled(&mut self, index: usize, on: bool) {
        if let Some(off) = self.lights_off.get_mut(index) {
            *off = !on;
            self.seek(self.time);
        }
    }

    /// Whether light `index` is on by hand (an animation may still dim it).
    pub fn light_enabled(&self, index: usize) -> bool {
        self.lights_off.get(index).is_some_and(|off| !off)
    }

    /// Draws the technique's debug overlay (DDGI: the probes, lit by their light) over the
    /// image.
    pub fn set_show_probes(&mut self, show: bool) {
        self.probes_shown = show.then_some(ProbeView::Light);
    }

    /// Draws the technique's probes as `view` says, or none.
    pub fn set_probe_view(&mut self, view: Option<ProbeView>) {
        self.probes_shown = view;
    }

    /// Every GPU allocation the frame and the technique hold now, as planned before they were
    /// made (the memory the viewer reports).
    pub fn allocations(&self) -> Result<Vec<Allocation>, RenderError> {
        plan_of(&self.scene, &self.spec, self.frame.size())
    }

    /// Forgets every kind of history — the frame's running means, TAA's history, the
    /// technique's probes — so that the next frame starts from scratch.
    pub fn invalidate(&mut self) {
        self.frame.invalidate();
        self.technique.invalidate();
    }

    /// Changes the frame's settings between frames (all of them can change live).
    pub fn set_frame_settings(&mut self, settings: FrameSettings) -> Result<(), RenderError> {
        self.frame.set_settings(settings)
    }

    /// Changes the technique: live where only live settings differ, otherwise rebuilt (same
    /// technique with new sizes, or another technique).
    pub fn set_technique(&mut self, spec: TechniqueSpec) -> Result<(), RenderError> {
        let kind = spec.kind()?;
        self.warnings = kind.check(&spec)?;
        if spec.name == self.spec.name && self.technique.reconfigure(&self.ctx, &spec)? {
            self.spec = spec;
            return Ok(());
        }
        let needs = kind.frame_needs(&spec);
        let mut plan = kind.plan(&spec, &self.scene, self.frame.size())?;
        if needs != self.frame.resources.needs {
            let (w, h) = self.frame.size();
            plan.extend(Frame::plan(w, h, needs));
        }
        self.ctx.check_allocations(&plan)?;
        if needs != self.frame.resources.needs {
            self.frame = Frame::new(
                &self.ctx,
                &self.gpu_scene,
                self.frame.size(),
                self.frame.settings().clone(),
                needs,
            )?;
        }
        self.technique = self.build_technique(kind, &spec)?;
        self.spec = spec;
        self.frame.invalidate();
        self.tell_pose();
        Ok(())
    }

    /// Builds a technique bound to the session's scene and frame.
    fn build_technique(
        &self,
        kind: &dyn crate::technique::TechniqueKind,
        spec: &TechniqueSpec,
    ) -> Result<Box<dyn Technique>, RenderError> {
        kind.build(
            &TechniqueContext {
                ctx: &self.ctx,
                scene: &self.scene,
                gpu_scene: &self.gpu_scene,
                frame: &self.frame,
                cache_dir: self.cache_dir.as_deref(),
                progress: self.progress.as_ref(),
            },
            spec,
        )
    }

    /// Changes the image size: the frame and the technique are built anew at it (the scene and
    /// its trees stay). Waits for the frames in flight, which use the old textures.
    pub fn resize(&mut self, size: (u32, u32)) -> Result<(), RenderError> {
        if size == self.frame.size() {
            return Ok(());
        }
        self.ctx.wait()?;
        self.in_flight.clear();
        let kind = self.spec.kind()?;
        let needs = kind.frame_needs(&self.spec);
        let mut plan = Frame::plan(size.0, size.1, needs);
        plan.extend(kind.plan(&self.spec, &self.scene, size)?);
        self.ctx.check_allocations(&plan)?;
        self.frame = Frame::new(
            &self.ctx,
            &self.gpu_scene,
            size,
            self.frame.settings().clone(),
            needs,
        )?;
        self.technique = self.build_technique(kind, &self.spec)?;
        self.tell_pose();
        Ok(())
    }

    /// Renders one frame.
    pub fn render(&mut self) -> Result<(), RenderError> {
        self.record_and_submit(false)?;
        self.ctx.check("rendering a frame")?;
        Ok(())
    }

    /// Renders one frame with every pass timed (GPU timestamps; empty where the adapter has
    /// none), in the order the passes ran.
    pub fn render_profiled(&mut self) -> Result<Vec<PassTiming>, RenderError> {
        self.record_and_submit(true)?;
        self.read_timings()
    }

    /// Records a frame into `encoder`: the G-buffer from `source`, the direct light and the
    /// pyramid, the technique, the composed radiance, and for a traced G-buffer TAA and the
    /// tone curve. The one path by which both Irradiant's own frames and a host's are made
    /// (host::HostGi), so that neither can drift from the other.
    pub(crate) fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        source: GBufferSource,
        profiled: bool,
    ) {
        self.frame.prepare(&self.ctx, &self.camera);
        self.technique.prepare(&self.ctx, &self.camera);
        let mut profiler = (profiled && self.profiler.enabled()).then_some(&mut self.profiler);
        match source {
            GBufferSource::Traced => self.frame.record_inputs(encoder, profiler.as_deref_mut()),
            GBufferSource::Host { import, direct } => {
                if let Some(import) = import {
                    import.dispatch(encoder, profiler.as_deref_mut(), self.frame.image_groups());
                }
                let direct = direct || self.frame.resources.needs.pyramid_levels > 0;
                self.frame
                    .record_lighting(encoder, profiler.as_deref_mut(), direct);
            }
        }
        self.technique.update(encoder, profiler.as_deref_mut());
        self.technique.resolve(encoder, profiler.as_deref_mut());
        if matches!(source, GBufferSource::Traced) || self.probes_shown.is_some() {
            self.frame.record_compose(encoder, profiler.as_deref_mut());
        }
        if let Some(view) = self.probes_shown {
            self.technique.visualize(encoder, view);
        }
        if matches!(source, GBufferSource::Traced) {
            self.frame.record_output(encoder, profiler);
        }
    }

    /// The profiler, when this frame is timed and the adapter has timestamps: a host's own
    /// passes after [`Session::record`] are timed with it.
    pub(crate) fn profiler(&mut self, profiled: bool) -> Option<&mut Profiler> {
        (profiled && self.profiler.enabled()).then_some(&mut self.profiler)
    }

    /// Records the copy of a timed frame's timestamps, after its last pass.
    pub(crate) fn resolve_timestamps(&mut self, encoder: &mut wgpu::CommandEncoder) {
        if self.profiler.enabled() {
            self.profiler.resolve(encoder);
        }
    }

    /// A timed frame's pass times, once its commands were submitted (it waits for the GPU).
    pub fn read_timings(&mut self) -> Result<Vec<PassTiming>, RenderError> {
        self.ctx.wait()?;
        Ok(self.profiler.read(&self.ctx)?)
    }

    /// Counts a recorded frame (the frame's running means and TAA's history move on).
    pub(crate) fn finish_frame(&mut self) {
        self.frame.finish();
    }

    fn record_and_submit(&mut self, profiled: bool) -> Result<(), RenderError> {
        let mut encoder = self
            .ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        self.record(&mut encoder, GBufferSource::Traced, profiled);
        if profiled {
            self.resolve_timestamps(&mut encoder);
        }
        self.in_flight
            .push_back(self.ctx.queue.submit([encoder.finish()]));
        if self.in_flight.len() > MAX_FRAMES_IN_FLIGHT
            && let Some(oldest) = self.in_flight.pop_front()
        {
            self.ctx.wait_for(oldest)?;
        }
        // Without a poll, wgpu keeps every finished frame's command buffers and staging
        // memory until something waits on the device: a frame loop that never reads back
        // grew by megabytes a frame (found by `irradiant soak`). Non-blocking.
        let _ = self.ctx.device.poll(wgpu::PollType::Poll);
        self.frame.finish();
        Ok(())
    }

    /// Writes the technique's DDGI probes to `path` (`ddgi`, `ssil+ddgi`; it waits for the GPU):
    /// [`Session::load_probes`] starts another session of the same scene and settings from them.
    pub fn save_probes(&self, path: &std::path::Path) -> Result<(), RenderError> {
        let ddgi = (self.technique_as::<crate::ddgi::Ddgi>())
            .or_else(|| {
                self.technique_as::<crate::ssil::SsilDdgi>()
                    .map(|h| &h.ddgi)
            })
            .ok_or_else(|| self.no_probes("save"))?;
        ddgi.save_probes(&self.ctx, path)
    }

    /// Starts the technique's DDGI probes from a file [`Session::save_probes`] wrote for this
    /// scene and these settings; a file for anything else is refused with the reason.
    pub fn load_probes(&mut self, path: &std::path::Path) -> Result<(), RenderError> {
        let no_probes = self.no_probes("load");
        let ctx = self.ctx.clone();
        let technique = self.technique.as_any_mut();
        let ddgi = match technique.downcast_mut::<crate::ddgi::Ddgi>() {
            Some(ddgi) => ddgi,
            None => match technique.downcast_mut::<crate::ssil::SsilDdgi>() {
                Some(hybrid) => &mut hybrid.ddgi,
                None => return Err(no_probes),
            },
        };
        ddgi.load_probes(&ctx, path)
    }

    fn no_probes(&self, what: &str) -> RenderError {
        RenderError::Settings(format!(
            "{} has no DDGI probes to {what}: use --technique ddgi or ssil+ddgi",
            self.spec.name
        ))
    }

    /// The last frame's final linear radiance.
    pub fn image(&self) -> Result<Image, RenderError> {
        self.frame.image(&self.ctx)
    }

    /// The last frame's direct light (running mean).
    pub fn direct(&self) -> Result<Image, RenderError> {
        self.frame.read(&self.ctx, "direct")
    }

    /// The last frame's indirect light, as the technique resolved it.
    pub fn indirect(&self) -> Result<Image, RenderError> {
        self.frame.read(&self.ctx, "indirect")
    }

    /// The last frame's G-buffer, one sample a pixel, row by row.
    pub fn gbuffer(&self) -> Result<Vec<GBufferSample>, RenderError> {
        self.frame.read_gbuffer(&self.ctx)
    }

    /// The last frame tonemapped: sRGB RGBA8, rows top to bottom.
    pub fn tonemapped(&self) -> Result<Vec<u8>, RenderError> {
        self.frame.tonemapped(&self.ctx)
    }

    /// The frame's needs (what the technique asked of it).
    pub fn frame_needs(&self) -> FrameNeeds {
        self.frame.resources.needs
    }
}
