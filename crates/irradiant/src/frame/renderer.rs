use glam::Vec3;
use irradiant_gpu::{GpuContext, Profiler, wgpu};
use irradiant_scene::{Camera, Pose};

use super::{Image, ToneSettings, Tonemapper, read_radiance};
use crate::RenderError;
use crate::gpu_scene::GpuScene;
use crate::gpu_types::{GpuCamera, GpuFrameParams, GpuGBufferTexel};
use crate::pipeline::*;

/// A global-illumination technique as the frame sees it: it updates its own state from the
/// scene, then turns the G-buffer into indirect light. A host engine can drive the same calls
/// with its own G-buffer.
pub trait Technique {
    /// Label prefix of the technique's passes (`ddgi`).
    fn name(&self) -> &'static str;
    /// Binds the frame's buffers; called when they are (re)created.
    fn bind_frame(&mut self, ctx: &GpuContext, frame: &FrameBuffers);
    /// Uploads per-frame parameters (before the frame's commands are submitted).
    fn prepare(&mut self, ctx: &GpuContext);
    /// Records the technique's per-frame update.
    fn update(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        profiler: Option<&mut Profiler>,
    );
    /// Records the resolve: indirect light into `frame.indirect`.
    fn resolve(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        frame: &FrameBuffers,
        profiler: Option<&mut Profiler>,
    );
    /// Records a debug overlay into `frame.radiance` (after compose).
    fn visualize(
        &self,
        _encoder: &mut wgpu::CommandEncoder,
        _scene: &GpuScene,
        _frame: &FrameBuffers,
    ) {
    }
    /// Forgets all history (the next frame starts from scratch).
    fn reset(&mut self);
    /// Told when the scene changes between frames, so that it can adapt (DDGI lowers its
    /// hysteresis for a while, 003 §4.3).
    fn scene_changed(&mut self, _change: &SceneChange) {}
}

/// How much the lighting changed between two poses (003 §4.3's scene-level heuristics).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum LightingChange {
    #[default]
    None,
    /// A light moved, turned, or changed its power by less than half.
    Small,
    /// A light switched on or off, or its power changed by half or more.
    Large,
}

/// What changed between two poses of the scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneChange {
    pub lighting: LightingChange,
    /// An instance moved.
    pub geometry: bool,
    /// World bounds of every animated instance at the new pose (GpuScene::dynamic_bounds).
    pub dynamic_bounds: Vec<(glam::Vec3, glam::Vec3)>,
}

impl SceneChange {
    pub fn between(old: &Pose, new: &Pose) -> Self {
        let mut lighting = LightingChange::None;
        for (a, b) in old.lights.iter().zip(&new.lights) {
            let (pa, pb) = (a.power().max_element(), b.power().max_element());
            let change = if (pa > 0.0) != (pb > 0.0) || (pa - pb).abs() >= 0.5 * pa.max(pb) {
                LightingChange::Large
            } else if a != b {
                LightingChange::Small
            } else {
                LightingChange::None
            };
            lighting = lighting.max(change);
        }
        Self {
            lighting,
            geometry: old.instance_transforms != new.instance_transforms,
            dynamic_bounds: Vec::new(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.lighting == LightingChange::None && !self.geometry
    }
}

/// Moves the scene to a new pose: uploads it, resets the frame's accumulated history and tells
/// the technique what changed — the one path by which a change reaches everything it affects.
pub fn apply_pose(
    ctx: &GpuContext,
    scene: &mut GpuScene,
    frame: &mut FrameRenderer,
    technique: Option<&mut dyn Technique>,
    old: &Pose,
    new: &Pose,
) {
    let change = SceneChange::between(old, new);
    if change.is_empty() && old == new {
        return;
    }
    scene.update(ctx, new);
    frame.invalidate_history();
    if let Some(t) = technique {
        t.scene_changed(&SceneChange {
            dynamic_bounds: scene.dynamic_bounds(),
            ..change
        });
    }
}

/// How the frame renders what is not the technique's job.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameSettings {
    /// Emitter samples per pixel per frame for direct light from emissive surfaces. More:
    /// less noise on the first frames after a change; the running mean removes it over time.
    pub area_light_samples: u32,
    pub seed: u32,
}

impl Default for FrameSettings {
    fn default() -> Self {
        Self {
            area_light_samples: 4,
            seed: 0,
        }
    }
}

/// The frame's buffers, which techniques bind by name.
pub struct FrameBuffers {
    pub width: u32,
    pub height: u32,
    /// `GpuFrameParams`
    pub params: wgpu::Buffer,
    /// `GpuGBufferTexel` a pixel
    pub gbuffer: wgpu::Buffer,
    /// vec4 a pixel: direct light (running mean)
    pub direct: wgpu::Buffer,
    /// vec4 a pixel: the technique's indirect light
    pub indirect: wgpu::Buffer,
    /// vec4 a pixel: the composed linear radiance (a = 1)
    pub radiance: wgpu::Buffer,
    sky: wgpu::Buffer,
}

pub struct FrameRenderer {
    pub buffers: FrameBuffers,
    pub settings: FrameSettings,
    gbuffer: ComputeStage,
    direct: ComputeStage,
    compose: ComputeStage,
    tonemapper: Tonemapper,
    gbuffer_group: wgpu::BindGroup,
    direct_group: wgpu::BindGroup,
    compose_group: wgpu::BindGroup,
    frame_index: u32,
    accumulated_frames: u32,
    previous_camera: Option<Camera>,
}

impl FrameRenderer {
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        width: u32,
        height: u32,
        settings: FrameSettings,
    ) -> Result<Self, RenderError> {
        let device = &ctx.device;
        let pixels = width as u64 * height as u64;
        let buffers = FrameBuffers {
            width,
            height,
            params: uniform_buffer(device, "frame/params", size_of::<GpuFrameParams>()),
            gbuffer: storage_buffer(
                device,
                "frame/gbuffer",
                pixels * size_of::<GpuGBufferTexel>() as u64,
            ),
            direct: storage_buffer(device, "frame/direct", pixels * 16),
            indirect: storage_buffer(device, "frame/indirect", pixels * 16),
            radiance: storage_buffer(device, "frame/radiance", pixels * 16),
            sky: uniform_buffer(device, "frame/sky", 16),
        };
        let sky: Vec3 = scene.sky;
        ctx.queue.write_buffer(
            &buffers.sky,
            0,
            bytemuck::cast_slice(&sky.extend(1.0).to_array()),
        );
        let l_gbuffer = buffer_layout(device, "frame/gbuffer", &[(0, UNIFORM), (1, STORAGE_WRITE)]);
        let l_direct = buffer_layout(
            device,
            "frame/direct",
            &[(0, UNIFORM), (1, STORAGE_READ), (2, STORAGE_WRITE)],
        );
        let l_compose = buffer_layout(
            device,
            "frame/compose",
            &[
                (0, UNIFORM),
                (1, STORAGE_READ),
                (2, STORAGE_READ),
                (3, STORAGE_READ),
                (4, STORAGE_WRITE),
                (5, UNIFORM),
            ],
        );
        let b = &buffers;
        Ok(Self {
            gbuffer: ComputeStage::tracing(
                ctx,
                scene,
                "frame/gbuffer",
                include_str!("gbuffer.wgsl"),
                &[],
                &l_gbuffer,
            )?,
            direct: ComputeStage::tracing(
                ctx,
                scene,
                "frame/direct",
                include_str!("direct.wgsl"),
                &[],
                &l_direct,
            )?,
            compose: ComputeStage::new(
                ctx,
                "frame/compose",
                include_str!("compose.wgsl"),
                &[],
                &[&l_compose],
            )?,
            tonemapper: Tonemapper::new(ctx)?,
            gbuffer_group: bind_at(
                device,
                "frame/gbuffer",
                &l_gbuffer,
                &[(0, &b.params), (1, &b.gbuffer)],
            ),
            direct_group: bind_at(
                device,
                "frame/direct",
                &l_direct,
                &[(0, &b.params), (1, &b.gbuffer), (2, &b.direct)],
            ),
            compose_group: bind_at(
                device,
                "frame/compose",
                &l_compose,
                &[
                    (0, &b.params),
                    (1, &b.gbuffer),
                    (2, &b.direct),
                    (3, &b.indirect),
                    (4, &b.radiance),
                    (5, &b.sky),
                ],
            ),
            buffers,
            settings,
            frame_index: 0,
            accumulated_frames: 0,
            previous_camera: None,
        })
    }

    /// The one mechanism that resets accumulated history: call it whenever anything that
    /// changes the image changes (scene pose, lights, settings). A camera move is detected here.
    pub fn invalidate_history(&mut self) {
        self.accumulated_frames = 0;
    }

    /// Frames in the current direct-light running mean.
    pub fn accumulated_frames(&self) -> u32 {
        self.accumulated_frames
    }

    /// Renders one frame into `buffers.radiance`.
    pub fn render(
        &mut self,
        ctx: &GpuContext,
        scene: &GpuScene,
        camera: &Camera,
        mut technique: Option<&mut dyn Technique>,
        show_probes: bool,
        mut profiler: Option<&mut Profiler>,
    ) -> Result<(), RenderError> {
        let (w, h) = (self.buffers.width, self.buffers.height);
        if self.previous_camera.as_ref() != Some(camera) {
            self.accumulated_frames = 0;
        }
        let previous = self
            .previous_camera
            .clone()
            .unwrap_or_else(|| camera.clone());
        let params = GpuFrameParams {
            camera: GpuCamera::new(camera, w, h),
            previous_camera: GpuCamera::new(&previous, w, h),
            width: w,
            height: h,
            frame_index: self.frame_index,
            area_light_samples: self.settings.area_light_samples,
            seed: self.settings.seed,
            accumulated_frames: self.accumulated_frames,
            _pad0: 0,
            _pad1: 0,
        };
        ctx.queue
            .write_buffer(&self.buffers.params, 0, bytemuck::bytes_of(&params));
        if let Some(t) = technique.as_deref_mut() {
            t.prepare(ctx);
        }
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        let pixel_groups = [w.div_ceil(8), h.div_ceil(8), 1];
        self.gbuffer.dispatch(
            &mut encoder,
            profiler.as_deref_mut(),
            &[&scene.bind_group, &self.gbuffer_group],
            pixel_groups,
        );
        self.direct.dispatch(
            &mut encoder,
            profiler.as_deref_mut(),
            &[&scene.bind_group, &self.direct_group],
            pixel_groups,
        );
        match technique.as_deref_mut() {
            Some(t) => {
                t.update(&mut encoder, scene, profiler.as_deref_mut());
                t.resolve(&mut encoder, scene, &self.buffers, profiler.as_deref_mut());
            }
            None => encoder.clear_buffer(&self.buffers.indirect, 0, None),
        }
        self.compose.dispatch(
            &mut encoder,
            profiler.as_deref_mut(),
            &[&self.compose_group],
            [(w * h).div_ceil(64), 1, 1],
        );
        if let (true, Some(t)) = (show_probes, technique.as_deref()) {
            t.visualize(&mut encoder, scene, &self.buffers);
        }
        if let Some(p) = profiler {
            p.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        self.frame_index += 1;
        self.accumulated_frames += 1;
        self.previous_camera = Some(camera.clone());
        ctx.check("rendering a frame")?;
        Ok(())
    }

    /// The last frame's linear radiance.
    pub fn image(&self, ctx: &GpuContext) -> Result<Image, RenderError> {
        read_radiance(
            ctx,
            &self.buffers.radiance,
            self.buffers.width,
            self.buffers.height,
        )
    }

    /// A buffer's per-pixel vec4 (direct, indirect) as an image.
    pub fn read(&self, ctx: &GpuContext, buffer: &wgpu::Buffer) -> Result<Image, RenderError> {
        let sums: Vec<[f32; 4]> = irradiant_gpu::read_buffer_as(ctx, buffer)?;
        let n = (self.buffers.width * self.buffers.height) as usize;
        Ok(Image {
            width: self.buffers.width,
            height: self.buffers.height,
            pixels: sums[..n].iter().map(|s| [s[0], s[1], s[2]]).collect(),
        })
    }

    pub fn read_gbuffer(&self, ctx: &GpuContext) -> Result<Vec<GpuGBufferTexel>, RenderError> {
        let texels: Vec<GpuGBufferTexel> =
            irradiant_gpu::read_buffer_as(ctx, &self.buffers.gbuffer)?;
        Ok(texels[..(self.buffers.width * self.buffers.height) as usize].to_vec())
    }

    /// The last frame, tonemapped to sRGB RGBA8.
    pub fn tonemapped(
        &self,
        ctx: &GpuContext,
        tone: &ToneSettings,
    ) -> Result<Vec<u8>, RenderError> {
        self.tonemapper.run(
            ctx,
            &self.buffers.radiance,
            self.buffers.width,
            self.buffers.height,
            tone,
        )
    }
}
