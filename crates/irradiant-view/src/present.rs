//! The frame and the UI drawn into a target: the session's tonemapped output (or the path
//! tracer's image) copied by `view/blit`, then egui's shapes over it. The same code draws into a
//! window's surface and into an offscreen texture (tests, measurements on a machine with no
//! display).

use irradiant_gpu::{GpuContext, wgpu};

/// How the blit turns a texel into a pixel: each of the viewer's debug views is a frame texture
/// read one of these ways.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decode {
    /// Already sRGB-encoded, shown as it is (the frame's output, the path tracer's image).
    Shown = 0,
    /// Linear radiance: exposure, a Reinhard curve, sRGB (direct light).
    Radiance = 1,
    /// A weighted sum, rgb ÷ a, then as radiance (the technique's indirect light).
    WeightedRadiance = 2,
    /// Octahedral normals in xy: the direction as colour, (n + 1) ÷ 2.
    Normal = 3,
    /// Distance along the ray: near bright, far dark, the sky black.
    Depth = 4,
    /// Linear reflectance or emission in rgb, sRGB-encoded.
    Colour = 5,
    /// Screen-space motion in pixels: x red, y green, around grey.
    Motion = 6,
    /// The path tracer's running sums over the count in alpha, tonemapped as the frame's
    /// output is (exposure, then the filmic curve or a clamp).
    Accumulation = 7,
}

/// What the blit shows: an image decoded one way at the frame's tone and, from column
/// `beside.1` on, another image as it is (the truth's wipe).
#[derive(Clone, Copy)]
pub struct Shown<'a> {
    /// The image.
    pub image: &'a wgpu::TextureView,
    /// How its texels become pixels.
    pub decode: Decode,
    /// The frame's exposure.
    pub exposure: f32,
    /// The frame's filmic curve (off: a clamp), for [`Decode::Accumulation`].
    pub filmic: bool,
    /// Another sRGB image of the same size, shown from a column on.
    pub beside: Option<(&'a wgpu::TextureView, u32)>,
}

/// The blit's uniforms (WGSL `Show`).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuShow {
    decode: u32,
    exposure: f32,
    filmic: u32,
    /// The first column the image beside is shown in (u32::MAX: none).
    split: u32,
}
const _: () = assert!(std::mem::size_of::<GpuShow>() == 16);

/// The blit's fragment stage, after the octahedral mapping's (the full-screen triangle is
/// irradiant_gpu's): it loads the image
/// texel under each pixel (the image is the target's size; a texel past its edge repeats the
/// last, during a resize) and decodes it as `Show.decode` says.
const BLIT_WGSL: &str = r#"
struct Show {
    decode: u32,
    exposure: f32,
    filmic: u32,
    split: u32,
}

@group(0) @binding(0) var image: texture_2d<f32>;
@group(0) @binding(1) var<uniform> show: Show;
@group(0) @binding(2) var beside: texture_2d<f32>;

fn encode_srgb(c: vec3f) -> vec3f {
    let x = clamp(c, vec3f(0.0), vec3f(1.0));
    return select(1.055 * pow(x, vec3f(1.0 / 2.4)) - 0.055, 12.92 * x, x <= vec3f(0.0031308));
}

fn radiance(c: vec3f) -> vec4f {
    let x = max(c, vec3f(0.0)) * show.exposure;
    return vec4f(encode_srgb(x / (1.0 + x)), 1.0);
}

// The frame's tonemap (frame::Image::to_srgb8): exposure, then ACES's fitted curve or a clamp.
fn tonemapped(c: vec3f) -> vec4f {
    let x = max(c, vec3f(0.0)) * show.exposure;
    let aces = clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3f(0.0), vec3f(1.0));
    return vec4f(encode_srgb(select(min(x, vec3f(1.0)), aces, show.filmic != 0u)), 1.0);
}

@fragment
fn fragment(@builtin(position) pixel: vec4f) -> @location(0) vec4f {
    let at = vec2i(pixel.xy);
    if show.split != 0xffffffffu && u32(at.x) >= show.split {
        // The wipe: a one-pixel white line, then the image beside.
        if u32(at.x) == show.split {
            return vec4f(1.0);
        }
        return textureLoad(beside, min(at, vec2i(textureDimensions(beside)) - 1), 0);
    }
    let last = vec2i(textureDimensions(image)) - 1;
    let t = textureLoad(image, min(at, last), 0);
    switch show.decode {
        case 1u: { return radiance(t.rgb); }
        case 2u: { return radiance(t.rgb / max(t.a, 1e-6)); }
        case 3u: { return vec4f(oct_decode(t.xy) * 0.5 + 0.5, 1.0); }
        case 4u: {
            let d = select(1.0 / (1.0 + 0.25 * t.r), 0.0, t.r < 0.0);
            return vec4f(vec3f(d), 1.0);
        }
        case 5u: { return vec4f(encode_srgb(t.rgb), 1.0); }
        case 6u: { return vec4f(clamp(0.5 + 0.05 * t.xy, vec2f(0.0), vec2f(1.0)), 0.5, 1.0); }
        case 7u: { return tonemapped(t.rgb / max(t.a, 1.0)); }
        default: { return t; }
    }
}
"#;

/// Timestamps around the viewer's own pass (the blit and the panel), where the adapter has
/// timestamp queries.
struct PresentTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    period_ns: f64,
}

/// What draws the frame and the UI into a target of one format.
pub struct Presenter {
    timer: Option<PresentTimer>,
    blit: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    /// The blit's bind group and the views it binds (image, beside): made again only when
    /// what is shown changes, not every frame.
    group: Option<((wgpu::TextureView, wgpu::TextureView), wgpu::BindGroup)>,
    show: wgpu::Buffer,
    /// egui's renderer, for the target's format.
    pub egui: egui_wgpu::Renderer,
    /// The format drawn into: never an sRGB one, since the image already holds sRGB-encoded
    /// values (and egui encodes its own colours for a plain target).
    pub format: wgpu::TextureFormat,
}

impl Presenter {
    /// The blit and egui's renderer for targets of `format` (its sRGB suffix removed).
    pub fn new(ctx: &GpuContext, format: wgpu::TextureFormat) -> Self {
        let format = format.remove_srgb_suffix();
        let device = &ctx.device;
        let image_entry = irradiant_gpu::unfiltered_texture_entry(0);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("view/blit"),
            entries: &[
                image_entry,
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    ..image_entry
                },
            ],
        });
        let show = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view/show"),
            size: std::mem::size_of::<GpuShow>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let blit = irradiant_gpu::fullscreen_pipeline(
            device,
            "view/blit",
            &format!(
                "{}\n{BLIT_WGSL}",
                irradiant::probes::octahedral::OCTAHEDRAL_WGSL
            ),
            &layout,
            format.into(),
        );
        let egui = egui_wgpu::Renderer::new(device, format, egui_wgpu::RendererOptions::default());
        Self {
            timer: None,
            blit,
            layout,
            group: None,
            show,
            egui,
            format,
        }
    }

    /// Times the viewer's pass with timestamp queries (nothing where the adapter has none);
    /// [`Presenter::read_gpu_ms`] reads the last one.
    pub fn timed(mut self, ctx: &GpuContext) -> Self {
        self.timer = ctx.info.timestamps.then(|| PresentTimer {
            queries: ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("view/present_timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view/present_timestamps"),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            period_ns: ctx.queue.get_timestamp_period() as f64,
        });
        self
    }

    /// GPU milliseconds of the last recorded pass (it waits for the GPU); None untimed.
    pub fn read_gpu_ms(&self, ctx: &GpuContext) -> Result<Option<f64>, irradiant_gpu::GpuError> {
        let Some(timer) = &self.timer else {
            return Ok(None);
        };
        let ticks: Vec<u64> = irradiant_gpu::read_buffer_as(ctx, &timer.resolve)?;
        Ok(Some(
            ticks[1].saturating_sub(ticks[0]) as f64 * timer.period_ns * 1e-6,
        ))
    }

    /// Records the image's blit (as `shown` says) and the UI's shapes into `target` (`size`
    /// pixels).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        size: (u32, u32),
        shown: Shown,
        mut ui: egui::FullOutput,
        egui_ctx: &egui::Context,
    ) {
        let device = &ctx.device;
        for (id, deltas) in &ui.textures_delta.set {
            for delta in deltas {
                self.egui.update_texture(device, &ctx.queue, *id, delta);
            }
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [size.0, size.1],
            pixels_per_point: ui.pixels_per_point,
        };
        let shapes = egui_ctx.tessellate(std::mem::take(&mut ui.shapes), ui.pixels_per_point);
        let extra = self
            .egui
            .update_buffers(device, &ctx.queue, encoder, &shapes, &screen);
        assert!(
            extra.is_empty(),
            "egui paint callbacks are not used by the viewer"
        );
        let show = GpuShow {
            decode: shown.decode as u32,
            exposure: shown.exposure,
            filmic: shown.filmic as u32,
            split: shown.beside.map_or(u32::MAX, |b| b.1),
        };
        let beside = shown.beside.map_or(shown.image, |b| b.0);
        ctx.queue
            .write_buffer(&self.show, 0, bytemuck::bytes_of(&show));
        let views = (shown.image.clone(), beside.clone());
        if self.group.as_ref().is_none_or(|(bound, _)| *bound != views) {
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("view/blit"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(shown.image),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: self.show.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::TextureView(beside),
                    },
                ],
            });
            self.group = Some((views, group));
        }
        let group = &self.group.as_ref().expect("made above").1;
        let mut pass = encoder
            .begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("view/present"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: self
                    .timer
                    .as_ref()
                    .map(|t| wgpu::RenderPassTimestampWrites {
                        query_set: &t.queries,
                        beginning_of_pass_write_index: Some(0),
                        end_of_pass_write_index: Some(1),
                    }),
                occlusion_query_set: None,
                multiview_mask: None,
            })
            .forget_lifetime();
        pass.set_pipeline(&self.blit);
        pass.set_bind_group(0, group, &[]);
        pass.draw(0..3, 0..1);
        self.egui.render(&mut pass, &shapes, &screen);
        drop(pass);
        if let Some(t) = &self.timer {
            encoder.resolve_query_set(&t.queries, 0..2, &t.resolve, 0);
        }
        for id in &ui.textures_delta.free {
            self.egui.free_texture(id);
        }
        // Applied above: egui checks that no delta is dropped unapplied.
        ui.textures_delta.clear();
    }
}

/// A texture the viewer draws into when there is no window: the target of tests and of the
/// viewer's measurements, read back for screenshots.
pub struct Offscreen {
    /// Rgba8Unorm, the size of the frame.
    pub texture: wgpu::Texture,
    /// Its view, the render target.
    pub view: wgpu::TextureView,
}

impl Offscreen {
    /// A target of `size` pixels.
    pub fn new(ctx: &GpuContext, size: (u32, u32)) -> Self {
        let texture = irradiant_gpu::texture_2d(
            &ctx.device,
            "view/offscreen",
            size,
            wgpu::TextureFormat::Rgba8Unorm,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let view = texture.create_view(&Default::default());
        Self { texture, view }
    }

    /// What was drawn, RGBA8 rows top to bottom.
    pub fn read(&self, ctx: &GpuContext) -> Result<Vec<u8>, irradiant_gpu::GpuError> {
        irradiant_gpu::read_texture(ctx, &self.texture, 4)
    }
}
