//! The window: winit's event loop, the surface the frame and the panel are presented to, and
//! keys and the mouse turned into the viewer's actions. A script drives the same loop.

use std::sync::Arc;
use std::time::Instant;

use irradiant_gpu::wgpu;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::camera::Movement;
use crate::{
    RunReport, SCRIPT_FPS, ScriptRunner, ViewError, ViewOptions, Viewer, is_device_lost, present,
    ui,
};

/// Keys held down, for flying.
#[derive(Default)]
struct Held {
    keys: std::collections::HashSet<String>,
    looking: bool,
    cursor: Option<(f64, f64)>,
}

impl Held {
    fn movement(&self) -> Movement {
        let axis = |plus: &str, minus: &str| {
            self.keys.contains(plus) as i32 as f32 - self.keys.contains(minus) as i32 as f32
        };
        Movement {
            forward: axis("w", "s"),
            right: axis("d", "a"),
            up: axis("e", "q"),
            fast: self.keys.contains("Shift"),
        }
    }
}

/// What lives while the window is open.
struct Open {
    window: Arc<Window>,
    /// Shared with the bake painter, which draws into it while a bake blocks the loop.
    surface: Arc<wgpu::Surface<'static>>,
    config: wgpu::SurfaceConfiguration,
    viewer: Viewer,
    presenter: present::Presenter,
    egui_ctx: egui::Context,
    egui_state: egui_winit::State,
    panel: ui::PanelState,
    last: Instant,
    frame_ms: f64,
    /// Why the device was lost, while the window waits for `R`.
    lost: Option<String>,
    /// Where the cursor is, for a click's pick.
    cursor: (f32, f32),
}

/// Draws a progress bar into the window from inside a bake, which blocks the event loop: its
/// own egui and presenter (egui's font atlas is per context), the window's surface.
struct BakePainter {
    ctx: Arc<irradiant::GpuContext>,
    surface: Arc<wgpu::Surface<'static>>,
    presenter: present::Presenter,
    egui: egui::Context,
    blank: wgpu::TextureView,
}

impl BakePainter {
    fn paint(&mut self, window: &Window, what: &str, done: u32, all: u32) {
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame)
            | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            _ => return,
        };
        let size = window.inner_size();
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(size.width as f32, size.height as f32),
            )),
            ..Default::default()
        };
        let output = self.egui.run_ui(input, |ui| {
            egui::Area::new(egui::Id::unique("bake"))
                .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
                .show(ui.ctx(), |ui| {
                    ui.label(format!("{what}…"));
                    ui.add(
                        egui::ProgressBar::new(done as f32 / all.max(1) as f32)
                            .desired_width(320.0)
                            .text(format!("{done} of {all}")),
                    );
                });
        });
        let view = frame.texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(self.presenter.format),
            ..Default::default()
        });
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        let shown = present::Shown {
            image: &self.blank,
            decode: present::Decode::Shown,
            exposure: 1.0,
            filmic: false,
            beside: None,
        };
        let target = (frame.texture.width(), frame.texture.height());
        self.presenter.record(
            &self.ctx,
            &mut encoder,
            &view,
            target,
            shown,
            output,
            &self.egui,
        );
        self.ctx.queue.submit([encoder.finish()]);
        window.pre_present_notify();
        self.ctx.queue.present(frame);
    }
}

/// Where the bake progress callback finds the painter (none until the window is attached).
type PainterSlot = Arc<std::sync::Mutex<Option<BakePainter>>>;

struct App {
    painter: PainterSlot,
    options: ViewOptions,
    open: Option<Open>,
    script: Option<ScriptRunner>,
    held: Held,
    error: Option<ViewError>,
    report: RunReport,
}

/// Runs the window until it closes, the script quits or an error stops it.
pub fn run(options: &ViewOptions) -> Result<RunReport, ViewError> {
    let script = match &options.script {
        Some(path) => Some(ScriptRunner::new(crate::script::read_script(path)?)),
        None => None,
    };
    let event_loop = EventLoop::new().map_err(|e| {
        ViewError::Window(format!(
            "no display to open a window on ({e}); set DISPLAY, run under Xvfb (xvfb-run irradiant view …), or use --offscreen"
        ))
    })?;
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut app = App {
        painter: Default::default(),
        options: options.clone(),
        open: None,
        script,
        held: Held::default(),
        error: None,
        report: RunReport::default(),
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| ViewError::Window(format!("the window's event loop failed: {e}")))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(app.report),
    }
}

impl App {
    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<Open, ViewError> {
        let (w, h) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title(format!("Irradiant — {}", self.options.scene))
            .with_inner_size(winit::dpi::PhysicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| ViewError::Window(format!("cannot open a window: {e}")))?,
        );
        // A bake blocks the frame it is asked in: meanwhile its progress is drawn into the
        // window (once the window has a surface) and shown in the title.
        let terminal = self.options.progress.clone();
        let titled = window.clone();
        let scene = self.options.scene.clone();
        let painter = self.painter.clone();
        let mut options = self.options.clone();
        options.progress = Some(irradiant::technique::Progress(Arc::new(
            move |what: &str, done: u32, all: u32| {
                if let Some(t) = &terminal {
                    t.report(what, done, all);
                }
                titled.set_title(&if done < all {
                    format!("Irradiant — {scene} — {what}: {done} of {all}")
                } else {
                    format!("Irradiant — {scene}")
                });
                if let Some(painter) = painter.lock().unwrap_or_else(|e| e.into_inner()).as_mut() {
                    painter.paint(&titled, what, done, all);
                }
            },
        )));
        self.options = options;
        let viewer = crate::start(&self.options)?;
        attach(window, viewer, &self.painter)
    }

    /// One frame: the script's steps or the held keys, the frame, the panel, presented. After
    /// the device was lost, nothing is drawn until `R` restarts the session on a new one.
    fn frame(&mut self) -> Result<bool, ViewError> {
        if self
            .open
            .as_ref()
            .is_some_and(|open| open.viewer.restart_requested)
        {
            let old = self.open.take().expect("checked above");
            let viewer = crate::restart(&self.options, &old.viewer)?;
            let window = old.window.clone();
            drop(old);
            window.set_title(&format!("Irradiant — {}", self.options.scene));
            self.open = Some(attach(window, viewer, &self.painter)?);
            self.report.restarts += 1;
        }
        let Some(open) = &mut self.open else {
            return Ok(true);
        };
        if open.lost.is_some() {
            // Only the script (or R, through key()) can go on.
            if let Some(script) = &mut self.script {
                return script.before_frame(&mut open.viewer);
            }
            return Ok(true);
        }
        let now = Instant::now();
        let mut dt = (now - open.last).as_secs_f32().min(0.25);
        open.frame_ms = (now - open.last).as_secs_f64() * 1e3;
        open.last = now;
        if let Some(script) = &mut self.script {
            if !script.before_frame(&mut open.viewer)? {
                return Ok(false);
            }
            if let Some(path) = script.take_capture() {
                return Err(ViewError::Script {
                    path,
                    problem: "a capture (the frame with the panel) needs --offscreen; in a window, screenshot writes the frame".into(),
                });
            }
            dt = 1.0 / SCRIPT_FPS;
        } else {
            open.viewer.fly(self.held.movement(), dt)?;
        }
        match open.viewer.render(dt) {
            Err(e) if is_device_lost(&e) => {
                eprintln!(
                    "{e}\npress R in the window to restart the session on a new device, Esc to quit"
                );
                open.window.set_title(
                    "Irradiant — the GPU device was lost: press R to restart, Esc to quit",
                );
                open.lost = Some(e.to_string());
                return Ok(true);
            }
            other => other?,
        }
        // The panel first: a technique it switches to may bake, and the bake's progress is
        // drawn into the surface, which must not be held then.
        let input = open.egui_state.take_egui_input(&open.window);
        let output = open.egui_ctx.run_ui(input, |ui| {
            ui::draw(ui, &mut open.viewer, &mut open.panel, open.frame_ms)
        });
        let mut output = output;
        open.egui_state
            .handle_platform_output(&open.window, std::mem::take(&mut output.platform_output));
        let frame = match open.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame)
            | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                open.surface
                    .configure(&open.viewer.ctx().device, &open.config);
                return Ok(true);
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(true);
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                return Err(ViewError::Window(
                    "the window's surface refused the frame (a validation error)".into(),
                ));
            }
        };
        let view = frame.texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(open.presenter.format),
            ..Default::default()
        });
        let ctx = open.viewer.ctx();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        open.presenter.record(
            ctx,
            &mut encoder,
            &view,
            (open.config.width, open.config.height),
            open.viewer.image_view(),
            output,
            &open.egui_ctx,
        );
        ctx.queue.submit([encoder.finish()]);
        open.window.pre_present_notify();
        ctx.queue.present(frame);
        self.report.frames += 1;
        Ok(true)
    }

    fn key(
        &mut self,
        event_loop: &ActiveEventLoop,
        key: &Key,
        pressed: bool,
    ) -> Result<(), ViewError> {
        let name = match key {
            Key::Character(c) => c.to_lowercase(),
            Key::Named(NamedKey::Shift) => "Shift".into(),
            Key::Named(NamedKey::Space) => "Space".into(),
            Key::Named(NamedKey::F1) => "F1".into(),
            Key::Named(NamedKey::F12) => "F12".into(),
            Key::Named(NamedKey::Escape) => {
                event_loop.exit();
                return Ok(());
            }
            _ => return Ok(()),
        };
        if pressed {
            self.held.keys.insert(name.clone());
        } else {
            self.held.keys.remove(&name);
            return Ok(());
        }
        let Some(open) = &mut self.open else {
            return Ok(());
        };
        let action = match name.as_str() {
            "f" | "p" | "b" | "t" | "i" | "r" => name.to_uppercase(),
            _ => name,
        };
        open.viewer.press(&action)
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.open.is_some() {
            return;
        }
        match self.open(event_loop) {
            Ok(open) => self.open = Some(open),
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(open) = &mut self.open else {
            return;
        };
        let consumed = open
            .egui_state
            .on_window_event(&open.window, &event)
            .consumed;
        let result = match event {
            WindowEvent::CloseRequested => {
                event_loop.exit();
                Ok(())
            }
            WindowEvent::Resized(size) => {
                open.config.width = size.width.max(1);
                open.config.height = size.height.max(1);
                open.surface
                    .configure(&open.viewer.ctx().device, &open.config);
                open.viewer.resize((open.config.width, open.config.height))
            }
            WindowEvent::RedrawRequested => match self.frame() {
                Ok(true) => Ok(()),
                Ok(false) => {
                    event_loop.exit();
                    Ok(())
                }
                Err(e) => Err(e),
            },
            WindowEvent::KeyboardInput { event, .. } if !consumed && !event.repeat => self.key(
                event_loop,
                &event.logical_key,
                event.state == ElementState::Pressed,
            ),
            WindowEvent::MouseInput {
                state: ElementState::Pressed,
                button: MouseButton::Left,
                ..
            } if !consumed && open.viewer.inspection.is_some() => {
                open.viewer.pick_probe(open.cursor);
                Ok(())
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Right,
                ..
            } => {
                self.held.looking = state == ElementState::Pressed;
                self.held.cursor = None;
                Ok(())
            }
            WindowEvent::CursorMoved { position, .. } => {
                open.cursor = (position.x as f32, position.y as f32);
                if self.held.looking {
                    if let Some((x, y)) = self.held.cursor {
                        open.viewer
                            .fly
                            .look((position.x - x) as f32, (position.y - y) as f32);
                        let _ = open.viewer.camera_moved();
                    }
                    self.held.cursor = Some((position.x, position.y));
                }
                Ok(())
            }
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let notches = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => (p.y / 40.0) as f32,
                };
                open.viewer.fly.change_speed(notches);
                Ok(())
            }
            _ => Ok(()),
        };
        if let Err(e) = result {
            // A bad setting or a failed step is said in the panel; a lost device or a failed
            // script ends the viewer with its message.
            let fatal = matches!(
                e,
                ViewError::Gpu(_) | ViewError::Window(_) | ViewError::Script { .. }
            ) || self.script.is_some();
            match (&mut self.open, fatal) {
                (Some(open), false) => open.viewer.status = format!("error: {e}"),
                _ => {
                    self.error = Some(e);
                    event_loop.exit();
                }
            }
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(open) = &self.open {
            open.window.request_redraw();
        }
    }
}

/// The surface, the presenter and egui on `window` for `viewer`'s device (at opening, and again
/// after a restart on a new device).
fn attach(window: Arc<Window>, viewer: Viewer, painter: &PainterSlot) -> Result<Open, ViewError> {
    let ctx = viewer.ctx();
    let surface = Arc::new(
        ctx.instance
            .create_surface(window.clone())
            .map_err(|e| ViewError::Window(format!("cannot draw into the window: {e}")))?,
    );
    if !ctx.adapter.is_surface_supported(&surface) {
        return Err(ViewError::Window(format!(
            "{} cannot present to this window; pick another adapter with --adapter, or use --offscreen",
            ctx.info.name
        )));
    }
    let caps = surface.get_capabilities(&ctx.adapter);
    let format = caps.formats[0];
    let size = window.inner_size();
    let config = wgpu::SurfaceConfiguration {
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        format,
        width: size.width.max(1),
        height: size.height.max(1),
        present_mode: wgpu::PresentMode::AutoNoVsync,
        desired_maximum_frame_latency: 1,
        alpha_mode: caps.alpha_modes[0],
        color_space: wgpu::SurfaceColorSpace::Auto,
        view_formats: vec![format.remove_srgb_suffix()],
    };
    surface.configure(&ctx.device, &config);
    let presenter = present::Presenter::new(ctx, format);
    *painter.lock().unwrap_or_else(|e| e.into_inner()) = Some(BakePainter {
        ctx: viewer.session.shared_ctx(),
        surface: surface.clone(),
        presenter: present::Presenter::new(ctx, format),
        egui: egui::Context::default(),
        blank: crate::truth::upload_rgba8(ctx, "view/bake_blank", (1, 1), &[0, 0, 0, 255])
            .create_view(&Default::default()),
    });
    let egui_ctx = egui::Context::default();
    let egui_state = egui_winit::State::new(
        egui_ctx.clone(),
        egui::ViewportId::ROOT,
        &window,
        Some(window.scale_factor() as f32),
        None,
        Some(ctx.device.limits().max_texture_dimension_2d as usize),
    );
    let mut viewer = viewer;
    viewer.resize((config.width, config.height))?;
    Ok(Open {
        window,
        surface,
        config,
        viewer,
        presenter,
        egui_ctx,
        egui_state,
        panel: ui::PanelState::default(),
        last: Instant::now(),
        frame_ms: 0.0,
        lost: None,
        cursor: (0.0, 0.0),
    })
}
