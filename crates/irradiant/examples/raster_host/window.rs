//! `--window`: the host's frames shown as they are made, each through the PNG's tone curve
//! into the window. Escape or closing the window ends the run, `--frames N` after N frames;
//! the last frame is what `main.rs` writes.

use std::error::Error;
use std::sync::Arc;

use winit::application::ApplicationHandler;
use winit::event::{ElementState, KeyEvent, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::host::Host;
use crate::{Options, host_instance};

/// The window and what draws into it.
struct Shown {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The sRGB view of the surface's format the present pass writes.
    view_format: wgpu::TextureFormat,
    present: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
}

struct App<'a> {
    options: &'a Options,
    host: Host,
    shown: Option<Shown>,
    frames: u32,
    error: Option<Box<dyn Error>>,
}

/// Opens the window and renders into it until it is closed (or `--frames` are done); returns
/// the last frame's linear image.
pub fn run(options: &Options) -> Result<irradiant::frame::Image, Box<dyn Error>> {
    let mut builder = EventLoop::builder();
    {
        // Tests run it off the main thread.
        use winit::platform::x11::EventLoopBuilderExtX11;
        builder.with_any_thread(true);
    }
    let event_loop = builder.build().map_err(|e| {
        format!("no display to open a window on ({e}): set DISPLAY, run under xvfb-run, or leave out --window")
    })?;
    let mut app = App {
        options,
        host: Host::new(options, host_instance())?,
        shown: None,
        frames: 0,
        error: None,
    };
    event_loop.run_app(&mut app)?;
    if let Some(e) = app.error {
        return Err(e);
    }
    app.host.image()
}

impl App<'_> {
    fn open(&self, event_loop: &ActiveEventLoop) -> Result<Shown, Box<dyn Error>> {
        let (w, h) = self.host.size;
        let window = Arc::new(
            event_loop.create_window(
                Window::default_attributes()
                    .with_title("Irradiant: raster host")
                    .with_inner_size(winit::dpi::PhysicalSize::new(w, h))
                    // The G-buffer and Irradiant stay at --size.
                    .with_resizable(false),
            )?,
        );
        let ctx = &self.host.ctx;
        let surface = ctx.instance.create_surface(window.clone())?;
        if !ctx.adapter.is_surface_supported(&surface) {
            return Err(format!("{} cannot present to this window", ctx.info.name).into());
        }
        let caps = surface.get_capabilities(&ctx.adapter);
        let format = caps.formats[0];
        let view_format = format.add_srgb_suffix();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: w,
            height: h,
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes[0],
            color_space: wgpu::SurfaceColorSpace::Auto,
            view_formats: vec![view_format],
        };
        surface.configure(&self.host.device, &config);
        let device = &self.host.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("host/present"),
            source: wgpu::ShaderSource::Wgsl(include_str!("present.wgsl").into()),
        });
        let present = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("host/present"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fragment"),
                compilation_options: Default::default(),
                targets: &[Some(view_format.into())],
            }),
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        let hdr = self.host.hdr.create_view(&Default::default());
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("host/present"),
            layout: &present.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&hdr),
            }],
        });
        Ok(Shown {
            window,
            surface,
            config,
            view_format,
            present,
            group,
        })
    }

    /// One frame: the host's passes and Irradiant's, then the image into the window. False
    /// when the run is over.
    fn frame(&mut self) -> Result<bool, Box<dyn Error>> {
        let Some(shown) = &self.shown else {
            return Ok(true);
        };
        let surface_texture = match shown.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                shown.surface.configure(&self.host.device, &shown.config);
                return Ok(true);
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(true);
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                return Err("the window's surface refused the frame".into());
            }
        };
        let target = surface_texture
            .texture
            .create_view(&wgpu::TextureViewDescriptor {
                format: Some(shown.view_format),
                ..Default::default()
            });
        let mut encoder = self.host.device.create_command_encoder(&Default::default());
        self.host.record(&mut encoder, false)?;
        crate::host::fullscreen_pass(
            &mut encoder,
            "host/present",
            &target,
            &shown.present,
            &shown.group,
        );
        self.host.queue.submit([encoder.finish()]);
        shown.window.pre_present_notify();
        self.host.queue.present(surface_texture);
        self.frames += 1;
        Ok(self.options.frames.is_none_or(|n| self.frames < n))
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, error: Box<dyn Error>) {
        self.error = Some(error);
        event_loop.exit();
    }
}

impl ApplicationHandler for App<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.shown.is_none() {
            match self.open(event_loop) {
                Ok(shown) => {
                    shown.window.request_redraw();
                    self.shown = Some(shown);
                }
                Err(e) => self.fail(event_loop, e),
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested
            | WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        logical_key: Key::Named(NamedKey::Escape),
                        state: ElementState::Pressed,
                        ..
                    },
                ..
            } => event_loop.exit(),
            WindowEvent::RedrawRequested => match self.frame() {
                Ok(true) => {
                    if let Some(shown) = &self.shown {
                        shown.window.request_redraw();
                    }
                }
                Ok(false) => event_loop.exit(),
                Err(e) => self.fail(event_loop, e),
            },
            _ => {}
        }
    }
}
