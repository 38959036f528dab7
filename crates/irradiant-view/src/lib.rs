//! `irradiant view`: fly through a scene with every technique live, switch them, turn their
//! settings, and put the path-traced reference one key away — on the same [`Session`] that
//! `irradiant render` drives. A window (winit + egui), or with `--offscreen` the same frames and
//! panel drawn into a texture, for tests and for measuring the viewer where there is no display.
//! The library crates never depend on this one.

#![warn(missing_docs)]

pub mod camera;
pub mod inspector;
pub mod present;
pub mod script;
pub mod truth;
pub mod ui;
pub mod viewer;
mod window;

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use irradiant::{AdapterChoice, GpuContext, Session, SessionSettings, TechniqueSpec};

pub use viewer::Viewer;

/// Why the viewer stopped. Each message names the problem and the fix.
#[derive(Debug, thiserror::Error)]
pub enum ViewError {
    /// Rendering failed: a technique, a size or the device.
    #[error(transparent)]
    Render(#[from] irradiant::RenderError),
    /// The GPU context could not be made or was lost.
    #[error(transparent)]
    Gpu(#[from] irradiant::GpuError),
    /// The scene did not load.
    #[error(transparent)]
    Scene(#[from] irradiant_scene::SceneError),
    /// A setting could not be used.
    #[error(transparent)]
    SettingsFile(#[from] irradiant::SettingsError),
    /// A technique or setting typed into the viewer could not be used.
    #[error("{0}")]
    Settings(String),
    /// A script could not be read or run.
    #[error("{path}: {problem}")]
    Script {
        /// The script.
        path: PathBuf,
        /// What is wrong, and the fix.
        problem: String,
    },
    /// A file could not be written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// No window: no display, or the adapter cannot present to it.
    #[error("{0}")]
    Window(String),
}

/// How the viewer starts.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    /// A built-in scene, a manifest or a mesh file.
    pub scene: String,
    /// The window's (or the offscreen target's) size in pixels.
    pub size: (u32, u32),
    /// The technique shown first, as a spec (`ddgi{preset = "quality"}`) or `path`.
    pub technique: String,
    /// The GPU adapter.
    pub adapter: AdapterChoice,
    /// Steps to run instead of a person (`--script`).
    pub script: Option<PathBuf>,
    /// Draw into a texture instead of a window (no display needed).
    pub offscreen: bool,
    /// Draw the panel (off: the frame alone, to measure what the panel costs).
    pub panel: bool,
    /// Where screenshots, bookmarks and settings files go.
    pub out_dir: PathBuf,
    /// Where the light field's bakes and the truth's references are cached.
    pub cache_dir: Option<PathBuf>,
    /// The truth's samples a pixel (`T`).
    pub truth_spp: u32,
    /// The program's version and commit: part of a cached reference's key, so that `compare`
    /// and the viewer share references rendered by the same build.
    pub build: String,
    /// Told how a bake goes (the light field's): the command line's bar on the terminal; the
    /// window adds its title.
    pub progress: Option<irradiant::technique::Progress>,
}

/// Frames a second a script's frames stand for: every scripted frame advances the scene by its
/// reciprocal, so a script renders the same frames on every machine.
pub const SCRIPT_FPS: f32 = 60.0;

/// What the viewer measured over a run (`--offscreen`): the frames and the time they took.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunReport {
    /// Frames rendered.
    pub frames: u64,
    /// Median wall-clock milliseconds a frame, the GPU waited for (offscreen only): the median
    /// leaves out the first frames' pipeline builds.
    pub frame_ms: f64,
    /// Mean CPU milliseconds a frame spent building and tessellating the panel.
    pub ui_cpu_ms: f64,
    /// Median GPU milliseconds of the viewer's own passes a frame (the blit, and the panel
    /// when drawn), from timestamp queries; None where the adapter has none.
    pub present_gpu_ms: Option<f64>,
    /// Sessions restarted after the device was lost.
    pub restarts: u32,
}

/// Builds the viewer: the scene, the GPU context and the session showing the first technique.
pub fn start(options: &ViewOptions) -> Result<Viewer, ViewError> {
    let loaded = irradiant_scene::load(&options.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let first = if options.technique.trim() == viewer::PATH {
        "ddgi"
    } else {
        options.technique.as_str()
    };
    // The spec, with the manifest's technique table under it, is checked before the adapter
    // is opened: a bad setting comes first.
    let spec = parse_spec(first)?.on_scene(&loaded.scene)?;
    spec.kind()?.check(&spec)?;
    let ctx = Arc::new(GpuContext::new(&options.adapter)?);
    let session = Session::new(
        ctx,
        loaded.scene,
        SessionSettings {
            size: options.size,
            technique: spec,
            cache_dir: options.cache_dir.clone(),
            progress: options.progress.clone(),
            ..Default::default()
        },
    )?;
    for w in session.warnings() {
        eprintln!("warning: {w}");
    }
    let mut viewer = Viewer::new(session, options.out_dir.clone());
    viewer.cache_dir =
        irradiant::pathtrace::reference_cache::cache_dir(options.cache_dir.as_deref());
    viewer.build = options.build.clone();
    viewer.truth_spp = options.truth_spp;
    if options.technique.trim() == viewer::PATH {
        viewer.switch_to(viewer::PATH)?;
    }
    viewer.camera_moved()?;
    Ok(viewer)
}

/// A viewer on a new device showing what `old` showed (technique, camera, debug view): the
/// restart a lost device offers (`R`).
pub fn restart(options: &ViewOptions, old: &Viewer) -> Result<Viewer, ViewError> {
    let mut viewer = start(options)?;
    viewer.apply(old.session.spec().clone())?;
    viewer.fly = old.fly.clone();
    viewer.debug_view = old.debug_view;
    viewer.camera_moved()?;
    viewer.status = "restarted on a new device after the last one was lost".into();
    Ok(viewer)
}

/// Whether an error is the device's loss (the viewer then waits for `R`, not an exit).
pub fn is_device_lost(error: &ViewError) -> bool {
    matches!(
        error,
        ViewError::Gpu(irradiant::GpuError::DeviceLost(_))
            | ViewError::Render(irradiant::RenderError::Gpu(
                irradiant::GpuError::DeviceLost(_)
            ))
    )
}

/// A spec as the command line writes it: `name` or `name{key = value, preset = "…"}`.
pub fn parse_spec(text: &str) -> Result<TechniqueSpec, ViewError> {
    let parsed = irradiant::settings::SpecText::parse(text)?;
    let spec = TechniqueSpec {
        name: parsed.name,
        preset: parsed.preset.unwrap_or(irradiant::Preset::Balanced),
        settings: parsed.settings,
    };
    spec.kind()?.check(&spec)?;
    Ok(spec)
}

/// Opens the window and runs until it closes (or the script quits).
pub fn run(options: &ViewOptions) -> Result<RunReport, ViewError> {
    if options.offscreen {
        return run_offscreen(options);
    }
    window::run(options)
}

/// What a script does next, frame by frame.
pub struct ScriptRunner {
    steps: std::collections::VecDeque<script::Step>,
    frames_left: u32,
    /// Frames rendered while waiting for the truth (`wait = "truth"`).
    waited: u32,
    waiting_truth: bool,
    /// Where the next frame, panel included, is to be written.
    capture: Option<PathBuf>,
}

impl ScriptRunner {
    /// Runs `steps` from the first.
    pub fn new(steps: Vec<script::Step>) -> Self {
        Self {
            steps: steps.into(),
            frames_left: 0,
            waited: 0,
            waiting_truth: false,
            capture: None,
        }
    }

    /// A capture the frame just drawn is due for (taken once).
    pub fn take_capture(&mut self) -> Option<PathBuf> {
        self.capture.take()
    }

    /// Does the steps due before the next frame; false when the script has quit or ended.
    pub fn before_frame(&mut self, viewer: &mut Viewer) -> Result<bool, ViewError> {
        use script::Step;
        if self.waiting_truth {
            let Some(truth) = &viewer.truth else {
                return Err(ViewError::Settings(
                    "wait = \"truth\": the truth was dropped (the view moved?)".into(),
                ));
            };
            if truth.verdict().is_none() {
                self.waited += 1;
                if self.waited > script::MAX_SCRIPT_FRAMES {
                    return Err(ViewError::Settings(
                        "wait = \"truth\": no verdict after the most frames a script may render"
                            .into(),
                    ));
                }
                return Ok(true);
            }
            self.waiting_truth = false;
        }
        while self.frames_left == 0 {
            let Some(step) = self.steps.pop_front() else {
                return Ok(false);
            };
            match step {
                Step::Technique(t) => viewer.apply_text(&t)?,
                Step::Camera(c) => viewer.set_camera(&c)?,
                Step::Move(m, seconds) => viewer.fly(m, seconds)?,
                Step::Key(k) => viewer.press(&k)?,
                Step::Show(v) => viewer.show(&v)?,
                Step::Frames(n) => self.frames_left = n,
                Step::Screenshot(path) => viewer.screenshot(&path)?,
                Step::Capture(path) => {
                    // The frame after the step: one more is rendered for it.
                    self.capture = Some(path);
                    self.frames_left = 1;
                }
                Step::Light(index, on) => viewer.set_light(index, on)?,
                Step::Truth(show) => match &mut viewer.truth {
                    Some(truth) => truth.show = show,
                    None => {
                        return Err(ViewError::Settings(
                            "truth = …: there is no truth to show; press T first".into(),
                        ));
                    }
                },
                Step::WaitTruth => {
                    if viewer.truth.is_none() {
                        return Err(ViewError::Settings(
                            "wait = \"truth\": there is no truth to wait for; press T first".into(),
                        ));
                    }
                    self.waiting_truth = true;
                    self.waited = 0;
                    return self.before_frame(viewer);
                }
                Step::Click(x, y) => {
                    viewer.pick_probe((x, y));
                }
                Step::LoseDevice => {
                    viewer.ctx().device.destroy();
                    let _ = viewer
                        .ctx()
                        .device
                        .poll(irradiant_gpu::wgpu::PollType::wait_indefinitely());
                }
                Step::Quit => return Ok(false),
            }
        }
        self.frames_left -= 1;
        Ok(true)
    }
}

/// The viewer without a window: frames and panel drawn into a texture, driven by the script
/// (without one, a single frame).
pub fn run_offscreen(options: &ViewOptions) -> Result<RunReport, ViewError> {
    let steps = match &options.script {
        Some(path) => script::read_script(path)?,
        None => vec![script::Step::Frames(1)],
    };
    let mut viewer = start(options)?;
    let presenter_for = |viewer: &Viewer| {
        present::Presenter::new(viewer.ctx(), irradiant_gpu::wgpu::TextureFormat::Rgba8Unorm)
            .timed(viewer.ctx())
    };
    let mut presenter = presenter_for(&viewer);
    let mut egui_ctx = egui::Context::default();
    let mut panel = ui::PanelState::default();
    let mut runner = ScriptRunner::new(steps);
    let mut report = RunReport::default();
    let mut frame_times = Vec::new();
    let mut present_times = Vec::new();
    let mut ui_total = 0.0;
    let mut last_ms = 0.0;
    let mut target: Option<((u32, u32), present::Offscreen)> = None;
    let mut lost = false;
    while runner.before_frame(&mut viewer)? {
        if viewer.restart_requested {
            // Everything made on the lost device goes with it: a new one, and egui anew.
            viewer = restart(options, &viewer)?;
            presenter = presenter_for(&viewer);
            egui_ctx = egui::Context::default();
            target = None;
            lost = false;
            report.restarts += 1;
        }
        if lost {
            continue;
        }
        let start = Instant::now();
        match viewer.render(1.0 / SCRIPT_FPS) {
            Err(e) if is_device_lost(&e) => {
                eprintln!("{e}\npress R to restart the session on a new device");
                lost = true;
                continue;
            }
            other => other?,
        }
        let size = viewer.session.frame().size();
        if target.as_ref().is_none_or(|(s, _)| *s != size) {
            target = Some((size, present::Offscreen::new(viewer.ctx(), size)));
        }
        let target = &target.as_ref().expect("made above").1;
        let ui_start = Instant::now();
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(size.0 as f32, size.1 as f32),
            )),
            // The script's clock, so that a window's fade-in ends as it would on screen.
            time: Some(report.frames as f64 / SCRIPT_FPS as f64),
            predicted_dt: 1.0 / SCRIPT_FPS,
            ..Default::default()
        };
        let output = egui_ctx.run_ui(input, |ui| {
            if options.panel {
                ui::draw(ui, &mut viewer, &mut panel, last_ms);
            }
        });
        ui_total += ui_start.elapsed().as_secs_f64() * 1e3;
        let ctx = viewer.ctx();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        presenter.record(
            ctx,
            &mut encoder,
            &target.view,
            size,
            viewer.image_view(),
            output,
            &egui_ctx,
        );
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        last_ms = start.elapsed().as_secs_f64() * 1e3;
        if let Some(ms) = presenter.read_gpu_ms(ctx)? {
            present_times.push(ms);
        }
        if let Some(path) = runner.take_capture() {
            let pixels = target.read(ctx)?;
            irradiant::frame::write_png(&path, &pixels, size.0, size.1)?;
        }
        frame_times.push(last_ms);
        report.frames += 1;
    }
    if report.frames > 0 {
        frame_times.sort_by(f64::total_cmp);
        report.frame_ms = frame_times[frame_times.len() / 2];
        report.ui_cpu_ms = ui_total / report.frames as f64;
    }
    if !present_times.is_empty() {
        present_times.sort_by(f64::total_cmp);
        report.present_gpu_ms = Some(present_times[present_times.len() / 2]);
    }
    Ok(report)
}
