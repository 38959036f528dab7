//! The frame's resources, by the names its passes and every technique's passes bind them by:
//! the parameters, the G-buffer's channels (gbuffer_layout.wgsl), direct and indirect light,
//! the composed radiance, the TAA history (last frame's final image, `previous_radiance`), the
//! display output, and mip chains of the G-buffer where a technique asks for them.

use irradiant_gpu::{Allocation, GpuContext, ResourceTable, wgpu};

use super::types::GpuFrameParams;
use crate::RenderError;

/// What a technique needs of the frame beyond the G-buffer and the light buffers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameNeeds {
    /// Mip levels of the G-buffer pyramid (`pyramid_*`; 0: none). Level 0 is full resolution.
    pub pyramid_levels: u32,
}

impl FrameNeeds {
    /// What satisfies both needs: the most of each.
    pub fn union(self, other: Self) -> Self {
        Self {
            pyramid_levels: self.pyramid_levels.max(other.pyramid_levels),
        }
    }
}

/// The frame's textures: name, format, bytes a texel. Every one is a storage texture for the
/// pass that writes it and a sampled texture for the passes that read it.
const TEXTURES: &[(&str, wgpu::TextureFormat, u64)] = &[
    // direct light at each pixel: a running mean while the view and the scene stay still
    ("direct", wgpu::TextureFormat::Rgba32Float, 16),
    // its diffuse part, the view-independent light each surface sends every way (frame/pyramid)
    ("direct_diffuse", wgpu::TextureFormat::Rgba32Float, 16),
    // emitter reservoirs (shaders/resampling.wgsl): frame/direct's (its candidates and last
    // frame's), and the one frame/direct_reuse keeps for the next frame with the geometry it
    // was kept for (normal, view depth)
    ("direct_reservoirs", wgpu::TextureFormat::Rgba32Uint, 16),
    (
        "direct_reservoirs_final",
        wgpu::TextureFormat::Rgba32Uint,
        16,
    ),
    (
        "direct_reservoir_geometry",
        wgpu::TextureFormat::Rgba16Float,
        8,
    ),
    // the technique's indirect light: rgb a weighted sum, a its weight (probe volumes blend
    // into it one after another)
    ("indirect", wgpu::TextureFormat::Rgba32Float, 16),
    ("gbuffer_depth", wgpu::TextureFormat::R32Float, 4),
    ("gbuffer_normal", wgpu::TextureFormat::Rgba16Float, 8),
    ("gbuffer_albedo", wgpu::TextureFormat::Rgba16Float, 8),
    ("gbuffer_emission", wgpu::TextureFormat::Rgba16Float, 8),
    ("gbuffer_motion", wgpu::TextureFormat::Rgba32Float, 16),
    // compose's linear radiance, before TAA
    ("radiance", wgpu::TextureFormat::Rgba32Float, 16),
    // TAA's output: this frame's final linear image. f16, so that the history it becomes is
    // sampled bilinearly (f32 does not filter everywhere) at half the bytes; frame/taa rounds
    // it stochastically, since a still view's history is a running mean over up to 1/blend
    // frames whose steps f16's nearest rounding drops (at blend 0.01 it stalled 3.4 % short).
    ("resolved", wgpu::TextureFormat::Rgba16Float, 8),
    // last frame's `resolved`
    ("previous_radiance", wgpu::TextureFormat::Rgba16Float, 8),
    // tonemapped sRGB, what a window presents
    ("output", wgpu::TextureFormat::Rgba8Unorm, 4),
];

/// The G-buffer pyramid's chains (when a technique asks for one): name, format, bytes a texel.
/// Level 0 is filled from the G-buffer by frame/pyramid, each further level from the one
/// before by frame/pyramid_down.
const PYRAMID: &[(&str, wgpu::TextureFormat, u64)] = &[
    // xyz: shading normal, w: view depth (distance along the camera's forward axis; < 0: sky)
    ("pyramid_normal_depth", wgpu::TextureFormat::Rgba32Float, 16),
    // rgb: the direct light the surface reflects diffusely (not its emission, which
    // frame/direct already samples as light, nor its highlights, which depend on the view)
    ("pyramid_radiance", wgpu::TextureFormat::Rgba16Float, 8),
    // rgb: diffuse albedo
    ("pyramid_albedo", wgpu::TextureFormat::Rgba16Float, 8),
];

/// The setting that sizes every per-pixel resource.
const SIZE_SETTING: &str = "the image size (--size)";

pub(crate) struct FrameTexture {
    pub name: &'static str,
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    /// One view a mip level (pyramids only), named `<name>_level<k>`.
    pub levels: Vec<(String, wgpu::TextureView)>,
}

/// The frame's buffers, textures and sampler, bound by name (see [`FrameResources::table`]).
pub struct FrameResources {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// What the technique asked of the frame (the pyramid's levels).
    pub needs: FrameNeeds,
    /// `GpuFrameParams`
    pub params: wgpu::Buffer,
    /// vec4: radiance of rays that leave the scene
    pub sky: wgpu::Buffer,
    pub(crate) textures: Vec<FrameTexture>,
    /// Bilinear, clamped to the edge: TAA's history taps.
    linear_clamp: wgpu::Sampler,
}

impl FrameResources {
    /// Every allocation the frame makes at this size, to check before making any.
    pub fn plan(width: u32, height: u32, needs: FrameNeeds) -> Vec<Allocation> {
        let mut plan = Vec::new();
        for &(name, _, texel) in TEXTURES {
            plan.push(Allocation::texture(
                format!("frame/{name}"),
                (width, height),
                texel,
                1,
                SIZE_SETTING,
            ));
        }
        if needs.pyramid_levels > 0 {
            for &(name, _, texel) in PYRAMID {
                plan.push(Allocation::texture(
                    format!("frame/{name}"),
                    (width, height),
                    texel,
                    needs.pyramid_levels,
                    format!("{SIZE_SETTING} or the technique's mip levels"),
                ));
            }
        }
        plan
    }

    /// Checks the plan against the adapter, then allocates every resource and uploads the sky
    /// radiance.
    pub fn new(
        ctx: &GpuContext,
        width: u32,
        height: u32,
        needs: FrameNeeds,
        sky: glam::Vec3,
    ) -> Result<Self, RenderError> {
        ctx.check_allocations(&Self::plan(width, height, needs))?;
        let device = &ctx.device;
        let buffer = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage,
                mapped_at_creation: false,
            })
        };
        let uniform = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        let mut textures: Vec<FrameTexture> = TEXTURES
            .iter()
            .map(|&(name, format, _)| {
                frame_texture(device, name, format, (width, height), 1, false)
            })
            .collect();
        if needs.pyramid_levels > 0 {
            for &(name, format, _) in PYRAMID {
                textures.push(frame_texture(
                    device,
                    name,
                    format,
                    (width, height),
                    needs.pyramid_levels,
                    true,
                ));
            }
        }
        let resources = Self {
            width,
            height,
            needs,
            params: buffer("frame/params", size_of::<GpuFrameParams>() as u64, uniform),
            sky: buffer("frame/sky", 16, uniform),
            textures,
            linear_clamp: device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("frame/linear_clamp"),
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                ..Default::default()
            }),
        };
        ctx.queue.write_buffer(
            &resources.sky,
            0,
            bytemuck::cast_slice(&sky.extend(1.0).to_array()),
        );
        Ok(resources)
    }

    /// Every resource by its name, for binding passes.
    pub fn table(&self) -> ResourceTable<'_> {
        let mut table = ResourceTable::new()
            .buffer("frame", &self.params)
            .buffer("sky", &self.sky)
            .sampler("linear_clamp", &self.linear_clamp);
        for t in &self.textures {
            table = table.texture(t.name, &t.view);
            for (name, view) in &t.levels {
                table = table.texture(name.clone(), view);
            }
        }
        table
    }

    /// A frame texture by name (see the list in this file).
    pub fn texture(&self, name: &str) -> &wgpu::Texture {
        &self
            .textures
            .iter()
            .find(|t| t.name == name)
            .unwrap_or_else(|| panic!("the frame has no texture '{name}'"))
            .texture
    }

    /// The view of a frame texture (every mip) by name.
    pub fn view(&self, name: &str) -> &wgpu::TextureView {
        &self
            .textures
            .iter()
            .find(|t| t.name == name)
            .unwrap_or_else(|| panic!("the frame has no texture '{name}'"))
            .view
    }

    /// Pixels in the image: width × height.
    pub fn pixels(&self) -> u64 {
        self.width as u64 * self.height as u64
    }
}

fn frame_texture(
    device: &wgpu::Device,
    name: &'static str,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    mip_levels: u32,
    per_level_views: bool,
) -> FrameTexture {
    let texture = irradiant_gpu::texture_2d(
        device,
        name,
        (width, height),
        format,
        mip_levels,
        wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST
            // A host may rasterize into the G-buffer itself (host::NativeGBuffer).
            | if name.starts_with("gbuffer_") {
                wgpu::TextureUsages::RENDER_ATTACHMENT
            } else {
                wgpu::TextureUsages::empty()
            },
    );
    let view = texture.create_view(&Default::default());
    let levels = if per_level_views {
        (0..mip_levels)
            .map(|level| {
                (
                    format!("{name}_level{level}"),
                    texture.create_view(&wgpu::TextureViewDescriptor {
                        base_mip_level: level,
                        mip_level_count: Some(1),
                        ..Default::default()
                    }),
                )
            })
            .collect()
    } else {
        Vec::new()
    };
    FrameTexture {
        name,
        texture,
        view,
        levels,
    }
}
