//! The viewer's state, apart from any window: the session, the technique chosen and each
//! technique's settings as last edited, the fly camera, the path tracer's progressive
//! reference, and what a key or a script step does. The window (window.rs) and the offscreen
//! runner (lib.rs) feed it input and draw what it shows.

use std::collections::{HashMap, VecDeque};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use irradiant::frame::{Image, write_png};
use irradiant::inspect::Inspection;
use irradiant::pathtrace::reference_cache::ReferenceEntry;
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::technique::ProbeView;
use irradiant::{GpuContext, Session, TechniqueSpec};

use crate::ViewError;
use crate::camera::{FlyCamera, Movement};
use crate::present::{Decode, Shown};
use crate::truth::Truth;

/// The reference path tracer's name in the technique list, beside the registered techniques.
pub const PATH: &str = "path";
/// Path-traced samples a pixel a frame, at most (the path view and the truth): enough to
/// converge in seconds, few enough that the window keeps its frame rate.
const PATH_SAMPLES_PER_FRAME: u32 = 4;
/// Frames between two timed frames: a timed frame waits for its timestamps and counters.
pub const PROFILE_EVERY: u64 = 30;
/// Timed frames the panel's chart keeps.
pub const HISTORY: usize = 120;
/// The truth's samples a pixel unless `--truth-spp` says otherwise: `irradiant compare`'s
/// default reference, so that the two share cache entries.
pub const TRUTH_SPP: u32 = 2048;

/// What the viewer can show instead of the final frame: a frame texture and how to read it.
/// Name, frame texture, decoding.
pub const DEBUG_VIEWS: &[(&str, &str, Decode)] = &[
    ("final", "output", Decode::Shown),
    ("direct", "direct", Decode::Radiance),
    ("indirect", "indirect", Decode::WeightedRadiance),
    ("radiance", "radiance", Decode::Radiance),
    ("albedo", "gbuffer_albedo", Decode::Colour),
    ("normal", "gbuffer_normal", Decode::Normal),
    ("depth", "gbuffer_depth", Decode::Depth),
    ("emission", "gbuffer_emission", Decode::Colour),
    ("motion", "gbuffer_motion", Decode::Motion),
];

/// The path tracer accumulating while the camera rests (shown through the blit's
/// [`Decode::Accumulation`]: nothing is read back).
struct PathView {
    tracer: PathTracer,
    settings: PathTraceSettings,
}

/// Everything the viewer shows and changes.
pub struct Viewer {
    /// The session every real-time frame renders through.
    pub session: Session,
    /// The registered techniques, then `path`.
    pub techniques: Vec<String>,
    /// Index of the one shown.
    pub current: usize,
    /// Each technique's spec as last set (a switch back keeps its edits).
    pub specs: HashMap<String, TechniqueSpec>,
    /// The real-time technique the session runs (shown unless the path tracer is).
    realtime: String,
    /// The camera the keys and the mouse move.
    pub fly: FlyCamera,
    path: Option<PathView>,
    /// The path-traced truth of the view and its comparison (`T`).
    pub truth: Option<Truth>,
    /// The truth's samples a pixel.
    pub truth_spp: u32,
    /// Where references are cached (shared with `irradiant compare`).
    pub cache_dir: PathBuf,
    /// The program's version and commit, part of a reference's cache key.
    pub build: String,
    /// Probes drawn in the world, and how (`P` cycles: off, light, states).
    pub probe_view: Option<ProbeView>,
    /// The technique's state as pictures (`I`), and the probe picked in it by a click.
    pub inspection: Option<Inspection>,
    /// Index into the inspection's probes of the one clicked.
    pub picked: Option<usize>,
    /// The key list (`F1`).
    pub show_help: bool,
    /// Index into [`DEBUG_VIEWS`] of what is shown of the frame (0: the final image).
    pub debug_view: usize,
    /// The scene's animation runs.
    pub playing: bool,
    /// How fast the animation runs.
    pub speed: f32,
    /// What the last action said: an error in words, or what was written.
    pub status: String,
    /// The last timed frame's passes, milliseconds each.
    pub timings: Vec<(String, f64)>,
    /// The last timed frames' GPU totals, oldest first (the panel's chart).
    pub timing_history: VecDeque<f64>,
    /// The technique's counters at the last timed frame (probes by state, rays).
    pub counters: Vec<(String, f64)>,
    /// GPU memory the frame, the technique and the path tracer hold, as planned (bytes).
    pub memory_bytes: u64,
    /// Counts inspections, so that the panel knows when its pictures are stale.
    pub inspections: u64,
    /// Frames rendered.
    pub frames: u64,
    /// Where screenshots and bookmarks go.
    pub out_dir: PathBuf,
    /// `R` after the device was lost: the run loop starts a new session on a new device.
    pub restart_requested: bool,
    bookmarks: u32,
    screenshots: u32,
}

impl Viewer {
    /// A viewer over a session, showing the session's technique.
    pub fn new(session: Session, out_dir: PathBuf) -> Self {
        let mut techniques: Vec<String> = irradiant::registry::names()
            .into_iter()
            .map(String::from)
            .collect();
        techniques.push(PATH.into());
        let name = session.spec().name.clone();
        let current = techniques.iter().position(|t| *t == name).unwrap_or(0);
        let mut specs = HashMap::new();
        specs.insert(name.clone(), session.spec().clone());
        let (lo, hi) = session.scene().bounds();
        let size = (hi - lo).length();
        let speed = if size.is_finite() && size > 0.0 {
            size / 10.0
        } else {
            1.0
        };
        let fly = FlyCamera::from_camera(session.camera(), speed);
        Self {
            session,
            techniques,
            current,
            specs,
            realtime: name,
            fly,
            path: None,
            truth: None,
            truth_spp: TRUTH_SPP,
            cache_dir: irradiant::pathtrace::reference_cache::cache_dir(None),
            build: concat!("irradiant-view ", env!("CARGO_PKG_VERSION")).into(),
            probe_view: None,
            inspection: None,
            picked: None,
            show_help: false,
            debug_view: 0,
            playing: true,
            speed: 1.0,
            status: String::new(),
            timings: Vec::new(),
            timing_history: VecDeque::new(),
            counters: Vec::new(),
            memory_bytes: 0,
            inspections: 0,
            frames: 0,
            out_dir,
            restart_requested: false,
            bookmarks: 0,
            screenshots: 0,
        }
    }

    /// The GPU context.
    pub fn ctx(&self) -> &GpuContext {
        self.session.ctx()
    }

    /// The name of what is shown: a registered technique or `path`.
    pub fn technique(&self) -> &str {
        &self.techniques[self.current]
    }

    /// The spec of technique `name` as last set (if never set, its balanced preset with what
    /// the scene's manifest sets for it: the large world's cascades).
    pub fn spec_of(&self, name: &str) -> TechniqueSpec {
        self.specs.get(name).cloned().unwrap_or_else(|| {
            let spec = TechniqueSpec::new(name, irradiant::Preset::Balanced);
            // The manifest's table read as a spec when the viewer started (`start`).
            spec.on_scene(self.session.scene()).unwrap_or(spec)
        })
    }

    /// Shows technique `name` (or the path tracer) with its last spec. Errors leave the
    /// shown technique as it was, and say why in the status line.
    pub fn switch_to(&mut self, name: &str) -> Result<(), ViewError> {
        let index = self
            .techniques
            .iter()
            .position(|t| t == name)
            .ok_or_else(|| {
                ViewError::Settings(format!(
                    "unknown technique '{name}': use one of {}",
                    self.techniques.join(", ")
                ))
            })?;
        if name == PATH {
            self.start_path()?;
        } else {
            self.path = None;
            let spec = self.spec_of(name);
            self.apply(spec)?;
        }
        self.current = index;
        self.inspection = None;
        Ok(())
    }

    /// Sets a technique's spec: live where only live settings change, rebuilt otherwise.
    pub fn apply(&mut self, spec: TechniqueSpec) -> Result<(), ViewError> {
        self.session.set_technique(spec.clone())?;
        if let Some(i) = self.techniques.iter().position(|t| *t == spec.name) {
            self.current = i;
        }
        self.path = None;
        self.realtime = spec.name.clone();
        self.specs.insert(spec.name.clone(), spec);
        Ok(())
    }

    /// Switches to a spec typed as on the command line (`ddgi{preset = "quality"}`, `path`).
    pub fn apply_text(&mut self, text: &str) -> Result<(), ViewError> {
        let text = text.trim();
        if text == PATH {
            return self.switch_to(PATH);
        }
        let spec = crate::parse_spec(text)?.on_scene(self.session.scene())?;
        self.apply(spec)
    }

    fn start_path(&mut self) -> Result<(), ViewError> {
        let ctx = self.session.ctx();
        let (w, h) = self.session.frame().size();
        let tracer = PathTracer::new(ctx, self.session.gpu_scene(), w, h)?;
        let mut settings = PathTraceSettings::balanced();
        settings.samples_per_pixel = u32::MAX;
        self.path = Some(PathView { tracer, settings });
        self.restart_path()
    }

    fn restart_path(&mut self) -> Result<(), ViewError> {
        if let Some(path) = &mut self.path {
            let ctx = self.session.ctx();
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            path.tracer.reset(&mut encoder);
            ctx.queue.submit([encoder.finish()]);
        }
        Ok(())
    }

    /// Whether the path tracer is shown.
    pub fn path_tracing(&self) -> bool {
        self.path.is_some()
    }

    /// Samples a pixel the path tracer has accumulated.
    pub fn path_samples(&self) -> u32 {
        self.path.as_ref().map_or(0, |p| p.tracer.samples_done)
    }

    /// Does what a key does: `Space` the path tracer on and off, `T` the truth beside the
    /// frame, `F` frames the scene, `P` the probes (off, light, states), `I` the inspector,
    /// `1`…`9` a technique, `F1` help, `F12` a screenshot (PNG and EXR), `B` a bookmark.
    pub fn press(&mut self, key: &str) -> Result<(), ViewError> {
        match key {
            "Space" => {
                let to = if self.path_tracing() {
                    self.realtime.clone()
                } else {
                    PATH.to_owned()
                };
                self.switch_to(&to)?;
            }
            "F" => {
                let framed = irradiant_scene::camera_for_bounds(self.session.scene());
                self.fly = FlyCamera::from_camera(&framed, self.fly.speed);
                self.camera_moved()?;
            }
            "P" => {
                let next = match self.probe_view {
                    None => Some(ProbeView::Light),
                    Some(ProbeView::Light) => Some(ProbeView::States),
                    Some(ProbeView::States) => Some(ProbeView::Volumes),
                    Some(ProbeView::Volumes) => None,
                };
                self.set_probe_view(next);
            }
            "T" => self.toggle_truth()?,
            "R" => self.restart_requested = self.ctx().lost().is_some(),
            "I" => self.toggle_inspector()?,
            "F1" => self.show_help = !self.show_help,
            "F12" => {
                self.screenshots += 1;
                let stem = format!("irradiant-view-{:03}", self.screenshots);
                self.screenshot(&self.out_dir.join(format!("{stem}.exr")))?;
                self.screenshot(&self.out_dir.join(format!("{stem}.png")))?;
                self.status = format!(
                    "wrote {stem}.png (as shown) and {stem}.exr (linear) in {}",
                    self.out_dir.display()
                );
            }
            "B" => {
                self.bookmarks += 1;
                let path = self
                    .out_dir
                    .join(format!("view-{:03}.toml", self.bookmarks));
                self.bookmark(&path)?;
            }
            digit if digit.len() == 1 && digit.as_bytes()[0].is_ascii_digit() => {
                let i = (digit.as_bytes()[0] - b'1') as usize;
                if let Some(name) = self.techniques.get(i).cloned() {
                    self.switch_to(&name)?;
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// Moves the camera for `seconds` with keys held.
    pub fn fly(&mut self, movement: Movement, seconds: f32) -> Result<(), ViewError> {
        if self.fly.step(movement, seconds) {
            self.camera_moved()?;
        }
        Ok(())
    }

    /// Puts the camera at a view: a jump, which the frame takes as a cut (`Session::cut_to`:
    /// no history from the last view's pixels; the probes keep theirs).
    pub fn set_camera(&mut self, camera: &irradiant_scene::Camera) -> Result<(), ViewError> {
        self.fly = FlyCamera::from_camera(camera, self.fly.speed);
        self.session.cut_to(self.fly.camera());
        self.camera_moved()
    }

    /// Tells the session and the path tracer that the view changed; the truth of another view
    /// is dropped.
    pub fn camera_moved(&mut self) -> Result<(), ViewError> {
        self.session.set_camera(self.fly.camera());
        if self
            .truth
            .as_ref()
            .is_some_and(|t| t.camera != self.fly.camera())
        {
            self.truth = None;
            self.status = "the truth was of another view: T renders this one's".into();
        }
        self.restart_path()
    }

    /// Draws the probes as `view` says, or none.
    pub fn set_probe_view(&mut self, view: Option<ProbeView>) {
        self.probe_view = view;
        self.session.set_probe_view(view);
    }

    /// Switches the scene's light `index` on or off: the path tracer restarts, and the truth,
    /// of another scene now, is dropped.
    pub fn set_light(&mut self, index: usize, on: bool) -> Result<(), ViewError> {
        self.session.set_light_enabled(index, on);
        self.truth = None;
        self.restart_path()
    }

    /// `T`: the truth of this view, or off again. A second press on an unmoved view compares
    /// the technique's frame as it is now.
    pub fn toggle_truth(&mut self) -> Result<(), ViewError> {
        if self.truth.take().is_some() {
            return Ok(());
        }
        let size = self.session.frame().size();
        let settings = PathTraceSettings {
            samples_per_pixel: self.truth_spp.max(1),
            ..PathTraceSettings::balanced()
        };
        let mut pose = self.session.pose().clone();
        pose.camera = self.fly.camera();
        let entry = ReferenceEntry::new(
            &self.cache_dir,
            self.session.scene(),
            &pose,
            size,
            &settings,
            &self.build,
        );
        let truth = Truth::new(
            self.ctx(),
            self.session.gpu_scene(),
            pose.camera,
            size,
            settings,
            entry,
        )?;
        self.status = if truth.cached {
            "the truth of this view was in the cache".into()
        } else {
            format!(
                "rendering the truth of this view ({} samples a pixel)",
                truth.settings.samples_per_pixel
            )
        };
        self.truth = Some(truth);
        Ok(())
    }

    /// `I`: reads the technique's state back as pictures (it waits for the GPU once), or
    /// closes the inspector.
    pub fn toggle_inspector(&mut self) -> Result<(), ViewError> {
        self.picked = None;
        if self.inspection.take().is_some() || self.path_tracing() {
            return Ok(());
        }
        let inspection = self.session.technique().inspect(self.session.ctx())?;
        if inspection.images.is_empty() {
            self.status = format!("{} has no state to inspect", self.technique());
            return Ok(());
        }
        self.inspection = Some(inspection);
        self.inspections += 1;
        Ok(())
    }

    /// Picks the probe of the inspection drawn under pixel `(x, y)`: the nearest whose sphere
    /// the pixel's ray meets.
    pub fn pick_probe(&mut self, (x, y): (f32, f32)) -> Option<usize> {
        let inspection = self.inspection.as_ref()?;
        let (w, h) = self.session.frame().size();
        let camera = self.fly.camera();
        let dir = irradiant::scene::types::GpuCamera::new(&camera, w, h).ray_dir(
            glam::Vec2::new(x, y),
            w,
            h,
        );
        let hit = |centre: glam::Vec3, radius: f32| {
            let oc = camera.position - centre;
            let b = oc.dot(dir);
            let disc = b * b - (oc.length_squared() - radius * radius);
            (disc >= 0.0 && -b - disc.sqrt() > 0.0).then(|| -b - disc.sqrt())
        };
        let picked = inspection
            .probes
            .iter()
            .enumerate()
            .filter_map(|(i, p)| hit(p.position, p.radius).map(|t| (i, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i);
        if picked.is_some() {
            self.picked = picked;
        }
        picked
    }

    /// Renders one frame of what is shown, `dt` seconds after the last, and moves the truth on.
    pub fn render(&mut self, dt: f32) -> Result<(), ViewError> {
        // A lost device fails here, named, before any command is recorded on it.
        self.ctx().check("the viewer's frame")?;
        self.frames += 1;
        let samples = PathTraceSettings::balanced()
            .samples_per_dispatch_on(&self.ctx().info)
            .min(PATH_SAMPLES_PER_FRAME);
        if let Some(path) = &mut self.path {
            let ctx = self.session.ctx();
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            path.tracer.record(
                ctx,
                &mut encoder,
                self.session.gpu_scene(),
                &self.fly.camera(),
                &path.settings,
                samples,
                None,
            )?;
            ctx.queue.submit([encoder.finish()]);
            return Ok(());
        }
        if self.playing && dt > 0.0 && self.truth.is_none() {
            self.session.advance(dt * self.speed);
        }
        if self.frames.is_multiple_of(PROFILE_EVERY) {
            let timings = self.session.render_profiled()?;
            self.timings = timings
                .into_iter()
                .map(|t| (t.label, t.milliseconds))
                .collect();
            self.timing_history
                .push_back(self.timings.iter().map(|t| t.1).sum());
            while self.timing_history.len() > HISTORY {
                self.timing_history.pop_front();
            }
            // The timed frame waited for the GPU already: its counters cost no further stall.
            self.counters = self
                .session
                .technique()
                .counters(self.session.ctx())?
                .into_iter()
                .map(|c| (c.name.to_owned(), c.value))
                .collect();
            let truth = (self.truth.as_ref()).map_or(Vec::new(), |t| t.allocations());
            self.memory_bytes = (self.session.allocations()?.iter())
                .chain(&truth)
                .map(|a| a.bytes)
                .sum();
        } else {
            self.session.render()?;
        }
        self.step_truth(samples)
    }

    fn step_truth(&mut self, samples: u32) -> Result<(), ViewError> {
        let Some(truth) = &mut self.truth else {
            return Ok(());
        };
        if truth.step(self.session.ctx(), self.session.gpu_scene(), samples)? {
            let frame = self.session.image()?;
            let tone = &self.session.frame().settings().tone;
            let spec = self.session.spec();
            let technique = format!("{} ({})", spec.name, spec.preset.name());
            truth.compare(
                self.session.ctx(),
                frame,
                technique,
                (tone.exposure, tone.filmic),
            );
        }
        Ok(())
    }

    /// What the blit shows: the frame's tonemapped output or one of its textures
    /// ([`DEBUG_VIEWS`]), the path tracer's running mean, or the truth beside the frame.
    pub fn image_view(&self) -> Shown<'_> {
        let tone = &self.session.frame().settings().tone;
        let (image, decode) = match &self.path {
            Some(path) => (path.tracer.accumulation_view(), Decode::Accumulation),
            None => {
                let (_, texture, decode) = DEBUG_VIEWS[self.debug_view];
                (self.session.frame().resources.view(texture), decode)
            }
        };
        let mut shown = Shown {
            image,
            decode,
            exposure: tone.exposure,
            filmic: tone.filmic,
            beside: None,
        };
        if self.path.is_none()
            && let Some((image, column)) = self.truth.as_ref().and_then(|t| t.shown())
        {
            match column {
                Some(column) => shown.beside = Some((image, column)),
                None => {
                    shown.image = image;
                    shown.decode = Decode::Shown;
                }
            }
        }
        shown
    }

    /// Shows the debug view named `name` (one of [`DEBUG_VIEWS`]).
    pub fn show(&mut self, name: &str) -> Result<(), ViewError> {
        self.debug_view = DEBUG_VIEWS
            .iter()
            .position(|(n, ..)| *n == name)
            .ok_or_else(|| {
                let names: Vec<&str> = DEBUG_VIEWS.iter().map(|v| v.0).collect();
                ViewError::Settings(format!(
                    "unknown view '{name}': use one of {}",
                    names.join(", ")
                ))
            })?;
        Ok(())
    }

    /// Changes the image size (the window's): the session's frame and technique are rebuilt.
    pub fn resize(&mut self, size: (u32, u32)) -> Result<(), ViewError> {
        let size = (size.0.max(1), size.1.max(1));
        if size == self.session.frame().size() {
            return Ok(());
        }
        self.session.resize(size)?;
        if self.path.is_some() {
            self.start_path()?;
        }
        Ok(())
    }

    /// Writes what is shown: `.png` as shown (tonemapped), `.exr` linear.
    pub fn screenshot(&mut self, path: &Path) -> Result<(), ViewError> {
        let exr = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("exr"));
        let image = match &self.path {
            Some(p) => p.tracer.image(self.session.ctx())?,
            None if exr => self.session.image()?,
            None => {
                let (w, h) = self.session.frame().size();
                write_png(path, &self.session.tonemapped()?, w, h)?;
                self.status = format!("wrote {}", path.display());
                return Ok(());
            }
        };
        if exr {
            image.write_exr(path)?;
        } else {
            let tone = &self.session.frame().settings().tone;
            let pixels = crate::truth::rgba(&image.to_srgb8(tone.exposure, tone.filmic));
            write_png(path, &pixels, image.width, image.height)?;
        }
        self.status = format!("wrote {}", path.display());
        Ok(())
    }

    /// Writes the view as a camera file that `irradiant render --camera-from` reads.
    pub fn bookmark(&mut self, path: &Path) -> Result<(), ViewError> {
        let text = irradiant_scene::camera_file_text(&self.fly.camera());
        std::fs::write(path, text).map_err(|e| ViewError::Io {
            path: path.to_owned(),
            message: e.to_string(),
        })?;
        self.status = format!("bookmarked the view in {}", path.display());
        Ok(())
    }

    /// Writes the shown technique's spec as a settings file that `irradiant render --settings`
    /// reads.
    pub fn save_settings(&mut self, path: &Path) -> Result<(), ViewError> {
        let file = irradiant::SettingsFile {
            frame: None,
            technique: Some(self.session.spec().clone()),
        };
        let text = toml::to_string(&file).map_err(|e| ViewError::Settings(e.to_string()))?;
        std::fs::write(path, text).map_err(|e| ViewError::Io {
            path: path.to_owned(),
            message: e.to_string(),
        })?;
        self.status = format!("wrote {}", path.display());
        Ok(())
    }

    /// The last frame's linear image (tests compare it with `irradiant render`'s).
    pub fn image(&self) -> Result<Image, ViewError> {
        Ok(match &self.path {
            Some(p) => p.tracer.image(self.session.ctx())?,
            None => self.session.image()?,
        })
    }
}

/// A shared context, for the window and the offscreen runner.
pub type SharedContext = Arc<GpuContext>;
