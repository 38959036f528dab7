//! The viewer's state, apart from any window: the session, the technique chosen and each
//! technique's settings as last edited, the fly camera, the path tracer's progressive
//! reference, and what a key or a script step does. The window (window.rs) and the offscreen
//! runner (lib.rs) feed it input and draw what it shows.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use irradiant::frame::{Image, write_png};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{GpuContext, Session, TechniqueSpec};
use irradiant_gpu::wgpu;

use crate::ViewError;
use crate::camera::{FlyCamera, Movement};
use crate::present::Decode;

/// The reference path tracer's name in the technique list, beside the registered techniques.
pub const PATH: &str = "path";
/// Path-traced samples a pixel between two updates of the shown image: each update reads the
/// image back, which waits for the GPU.
const PATH_SAMPLES_PER_UPDATE: u32 = 4;
/// Frames between two timed frames: a timed frame waits for its timestamps.
pub const PROFILE_EVERY: u64 = 30;

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

/// The path tracer accumulating while the camera rests.
struct PathView {
    tracer: PathTracer,
    settings: PathTraceSettings,
    /// What is shown: the accumulation tonemapped, as the frame's output is.
    display: wgpu::Texture,
    display_view: wgpu::TextureView,
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
    /// Probes drawn in the world (`P`).
    pub show_probes: bool,
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
    /// Frames rendered.
    pub frames: u64,
    /// Where screenshots and bookmarks go.
    pub out_dir: PathBuf,
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
            show_probes: false,
            show_help: false,
            debug_view: 0,
            playing: true,
            speed: 1.0,
            status: String::new(),
            timings: Vec::new(),
            frames: 0,
            out_dir,
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

    /// The spec of technique `name` as last set (its balanced preset if never set).
    pub fn spec_of(&self, name: &str) -> TechniqueSpec {
        self.specs
            .get(name)
            .cloned()
            .unwrap_or_else(|| TechniqueSpec::new(name, irradiant::Preset::Balanced))
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
        let spec = crate::parse_spec(text)?;
        self.apply(spec)
    }

    fn start_path(&mut self) -> Result<(), ViewError> {
        let ctx = self.session.ctx();
        let (w, h) = self.session.frame().size();
        let tracer = PathTracer::new(ctx, self.session.gpu_scene(), w, h)?;
        let display = irradiant_gpu::texture_2d(
            &ctx.device,
            "view/path_display",
            (w, h),
            wgpu::TextureFormat::Rgba8Unorm,
            1,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        let display_view = display.create_view(&Default::default());
        let mut settings = PathTraceSettings::balanced();
        settings.samples_per_pixel = u32::MAX;
        self.path = Some(PathView {
            tracer,
            settings,
            display,
            display_view,
        });
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

    /// Does what a key does: `Space` the path tracer on and off, `F` frames the scene, `P` the
    /// probes, `1`…`9` a technique, `F1` help, `F12` a screenshot, `B` a bookmark.
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
                self.show_probes = !self.show_probes;
                self.session.set_show_probes(self.show_probes);
            }
            "F1" => self.show_help = !self.show_help,
            "F12" => {
                self.screenshots += 1;
                let path = self
                    .out_dir
                    .join(format!("irradiant-view-{:03}.png", self.screenshots));
                self.screenshot(&path)?;
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

    /// Puts the camera at a view.
    pub fn set_camera(&mut self, camera: &irradiant_scene::Camera) -> Result<(), ViewError> {
        self.fly = FlyCamera::from_camera(camera, self.fly.speed);
        self.camera_moved()
    }

    /// Tells the session and the path tracer that the view changed.
    pub fn camera_moved(&mut self) -> Result<(), ViewError> {
        self.session.set_camera(self.fly.camera());
        self.restart_path()
    }

    /// Renders one frame of what is shown, `dt` seconds after the last.
    pub fn render(&mut self, dt: f32) -> Result<(), ViewError> {
        self.frames += 1;
        if let Some(path) = &mut self.path {
            let ctx = self.session.ctx();
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            let samples = path
                .settings
                .samples_per_dispatch_on(&ctx.info)
                .min(PATH_SAMPLES_PER_UPDATE);
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
            let image = path.tracer.image(ctx)?;
            let tone = &self.session.frame().settings().tone;
            let rgba = rgba(&image.to_srgb8(tone.exposure, tone.filmic));
            ctx.queue.write_texture(
                path.display.as_image_copy(),
                &rgba,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * image.width),
                    rows_per_image: None,
                },
                path.display.size(),
            );
            return Ok(());
        }
        if self.playing && dt > 0.0 {
            self.session.advance(dt * self.speed);
        }
        if self.frames.is_multiple_of(PROFILE_EVERY) {
            let timings = self.session.render_profiled()?;
            self.timings = timings
                .into_iter()
                .map(|t| (t.label, t.milliseconds))
                .collect();
        } else {
            self.session.render()?;
        }
        Ok(())
    }

    /// The image shown and how to decode it: the frame's tonemapped output or one of its
    /// textures ([`DEBUG_VIEWS`]), or the path tracer's image; with the exposure.
    pub fn image_view(&self) -> (&wgpu::TextureView, Decode, f32) {
        let exposure = self.session.frame().settings().tone.exposure;
        match &self.path {
            Some(path) => (&path.display_view, Decode::Shown, exposure),
            None => {
                let (_, texture, decode) = DEBUG_VIEWS[self.debug_view];
                (
                    self.session.frame().resources.view(texture),
                    decode,
                    exposure,
                )
            }
        }
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
            let pixels = rgba(&image.to_srgb8(tone.exposure, tone.filmic));
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

/// RGB8 to RGBA8, opaque.
fn rgba(rgb: &[u8]) -> Vec<u8> {
    rgb.chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect()
}

/// A shared context, for the window and the offscreen runner.
pub type SharedContext = Arc<GpuContext>;
