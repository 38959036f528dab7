//! DDGI's GPU memory: the volume uniform, the ray buffers and the two probe atlases.

use glam::{UVec3, Vec3};
use irradiant_gpu::{GpuContext, wgpu};
use irradiant_scene::ProbeVolumeDesc;

use super::DdgiSettings;
use crate::RenderError;
use crate::gpu_types::{GpuDdgiRayHit, GpuDdgiRaySample, GpuDdgiShadowRay};
use crate::pipeline::{storage_buffer, uniform_buffer};

/// Where the probes are and how the atlases are laid out.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeLayout {
    pub origin: Vec3,
    pub spacing: Vec3,
    pub counts: UVec3,
    pub probe_count: u32,
    pub probes_per_row: u32,
    pub rows: u32,
}

impl VolumeLayout {
    /// Probes on a regular grid from `min` to `max` (one probe a volume of count 1 sits in the
    /// middle), their tiles laid out in rows whose width (tiles of `tile_sides` texels, border
    /// included, 8 bytes a texel) is a multiple of 256 bytes: a buffer-to-texture copy's row
    /// alignment.
    pub fn new(desc: &ProbeVolumeDesc, tile_sides: &[u32]) -> Self {
        let counts = UVec3::from(desc.counts).max(UVec3::ONE);
        let steps = (counts.as_vec3() - 1.0).max(Vec3::ONE);
        let extent = desc.max - desc.min;
        let spacing = extent / steps;
        let origin = Vec3::select(
            counts.cmpeq(UVec3::ONE).into(),
            (desc.min + desc.max) * 0.5,
            desc.min,
        );
        let probe_count = counts.x * counts.y * counts.z;
        // Tiles a row must be a multiple of for each tile side: 32 texels ÷ gcd(side, 32).
        let multiple = tile_sides
            .iter()
            .map(|&side| 32 / gcd(side, 32))
            .fold(1, lcm);
        let probes_per_row = ((probe_count as f32).sqrt().ceil() as u32).next_multiple_of(multiple);
        let rows = probe_count.div_ceil(probes_per_row);
        Self {
            origin,
            spacing: Vec3::select(
                counts.cmpeq(UVec3::ONE).into(),
                extent.max(Vec3::splat(1e-3)),
                spacing,
            ),
            counts,
            probe_count,
            probes_per_row,
            rows,
        }
    }

    pub fn min_spacing(&self) -> f32 {
        self.spacing.min_element()
    }

    pub fn probe_position(&self, probe: u32) -> Vec3 {
        let c = self.counts;
        let coord = UVec3::new(probe % c.x, (probe / c.x) % c.y, probe / (c.x * c.y));
        self.origin + coord.as_vec3() * self.spacing
    }

    /// Atlas size in texels for tiles of `texels` interior texels.
    pub fn atlas_size(&self, texels: u32) -> (u32, u32) {
        (self.probes_per_row * (texels + 2), self.rows * (texels + 2))
    }
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

fn lcm(a: u32, b: u32) -> u32 {
    a / gcd(a, b) * b
}

pub struct DdgiResources {
    pub volume: wgpu::Buffer,
    /// The ray set before rotation, uploaded once (vec4 a ray, in trace order).
    pub ray_set: wgpu::Buffer,
    /// The rotated ray set of this frame (vec4 a ray).
    pub directions: wgpu::Buffer,
    pub hits: wgpu::Buffer,
    pub samples: wgpu::Buffer,
    /// Two packed f16 pairs a texel (rgb, value^(1/gamma)).
    pub irradiance: wgpu::Buffer,
    /// Two f32 a texel: mean distance and mean squared distance.
    pub distance: wgpu::Buffer,
    /// Copies of the two atlases that the query samples (rgba16float and rg32float: the
    /// buffers' bytes as they are), copied after each blend. Hardware bilinear filtering and
    /// gathers take one or two fetches where loading texels took four.
    pub irradiance_texture: wgpu::Texture,
    pub distance_texture: wgpu::Texture,
    /// vec4 a probe: relocation offset (xyz) and the share of its rays that hit backfaces (w).
    pub offsets: wgpu::Buffer,
    /// u32 a probe: state, near-geometry flag and blends since it started (ddgi/states.wgsl).
    pub states: wgpu::Buffer,
    /// Two vec4 (min, max) a box: where animated instances may wake sleeping probes.
    pub wake_boxes: wgpu::Buffer,
    /// GpuDdgiBlendWeight lists: per tile texel, the rays of its blend and their weights, the
    /// same for every probe (layout in ddgi/blend_weights.wgsl).
    pub blend_weights: wgpu::Buffer,
    /// ddgi/shade's queue of shadow rays for ddgi/shadow: a 16-byte header (count, then the
    /// shadow pass's indirect dispatch) and a GpuDdgiShadowRay a probe ray. Header only when
    /// no shadow ray is queued (DdgiSettings::queues_shadow_rays).
    pub shadow_queue: wgpu::Buffer,
}

/// Bytes before the queued rays in `shadow_queue`; the indirect dispatch's (x, y, z) start
/// at byte 4.
pub const SHADOW_QUEUE_HEADER: u64 = 16;

/// Wake boxes the buffer holds; further animated instances merge into the last box.
pub const MAX_WAKE_BOXES: usize = 64;

impl DdgiResources {
    pub fn new(
        ctx: &GpuContext,
        layout: &VolumeLayout,
        settings: &DdgiSettings,
    ) -> Result<Self, RenderError> {
        let rays = layout.probe_count as u64 * settings.rays_per_probe as u64;
        let (iw, ih) = layout.atlas_size(settings.irradiance_texels);
        let (dw, dh) = layout.atlas_size(settings.distance_texels);
        let sizes = [
            ("ddgi/hits", rays * size_of::<GpuDdgiRayHit>() as u64),
            ("ddgi/samples", rays * size_of::<GpuDdgiRaySample>() as u64),
            ("ddgi/irradiance_atlas", iw as u64 * ih as u64 * 8),
            ("ddgi/distance_atlas", dw as u64 * dh as u64 * 8),
            (
                "ddgi/shadow_queue",
                SHADOW_QUEUE_HEADER
                    + if settings.queues_shadow_rays() {
                        rays * size_of::<GpuDdgiShadowRay>() as u64
                    } else {
                        0
                    },
            ),
        ];
        let limit = ctx.info.max_storage_buffer_binding_size;
        for (label, size) in sizes {
            if size > limit {
                return Err(RenderError::Settings(format!(
                    "{label} would need {} MiB, more than this adapter binds ({} MiB): use fewer probes or fewer rays per probe",
                    size >> 20,
                    limit >> 20
                )));
            }
        }
        let side_limit = ctx.device.limits().max_texture_dimension_2d;
        for (label, (width, height)) in [("irradiance", (iw, ih)), ("distance", (dw, dh))] {
            if width.max(height) > side_limit {
                return Err(RenderError::Settings(format!(
                    "the {label} atlas would be {width}×{height} texels, more than this adapter's textures hold ({side_limit} a side): use fewer probes or fewer texels a probe"
                )));
            }
        }
        let device = &ctx.device;
        let ray_set: Vec<[f32; 4]> =
            super::octahedral::probe_ray_set(settings.rays_per_probe, settings.coherent_rays)
                .iter()
                .map(|d| d.extend(0.0).to_array())
                .collect();
        let ray_set_buffer =
            storage_buffer(device, "ddgi/ray_set", settings.rays_per_probe as u64 * 16);
        ctx.queue
            .write_buffer(&ray_set_buffer, 0, bytemuck::cast_slice(&ray_set));
        let atlas_texture = |label: &str, (width, height): (u32, u32), format| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            })
        };
        Ok(Self {
            irradiance_texture: atlas_texture(
                "ddgi/irradiance_texture",
                (iw, ih),
                wgpu::TextureFormat::Rgba16Float,
            ),
            distance_texture: atlas_texture(
                "ddgi/distance_texture",
                (dw, dh),
                wgpu::TextureFormat::Rg32Float,
            ),
            ray_set: ray_set_buffer,
            volume: uniform_buffer(
                device,
                "ddgi/volume",
                size_of::<crate::gpu_types::GpuDdgiVolume>(),
            ),
            directions: storage_buffer(
                device,
                "ddgi/directions",
                settings.rays_per_probe as u64 * 16,
            ),
            hits: storage_buffer(device, sizes[0].0, sizes[0].1),
            samples: storage_buffer(device, sizes[1].0, sizes[1].1),
            irradiance: storage_buffer(device, sizes[2].0, sizes[2].1),
            distance: storage_buffer(device, sizes[3].0, sizes[3].1),
            offsets: storage_buffer(device, "ddgi/probe_offsets", layout.probe_count as u64 * 16),
            states: storage_buffer(device, "ddgi/probe_states", layout.probe_count as u64 * 4),
            wake_boxes: storage_buffer(device, "ddgi/wake_boxes", MAX_WAKE_BOXES as u64 * 32),
            shadow_queue: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(sizes[4].0),
                size: sizes[4]
                    .1
                    .max(SHADOW_QUEUE_HEADER + size_of::<GpuDdgiShadowRay>() as u64),
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::INDIRECT
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            blend_weights: storage_buffer(
                device,
                "ddgi/blend_weights",
                (settings.irradiance_texels.pow(2) + settings.distance_texels.pow(2)) as u64
                    * (settings.rays_per_probe as u64 + 1)
                    * size_of::<crate::gpu_types::GpuDdgiBlendWeight>() as u64,
            ),
        })
    }
}
