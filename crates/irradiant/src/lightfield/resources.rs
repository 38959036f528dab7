//! Light-field probes' GPU memory: the baked maps (a texture-array layer a probe), the
//! prefiltered atlases in DDGI's layout with the small buffers DDGI's query reads beside them,
//! the bake's reduced maps, and the frame's traced, filtered and history buffers.

use irradiant_gpu::{Allocation, GpuContext, ResourceTable, wgpu};

use super::constants::MIN_MIP_FACTOR;
use super::settings::LightfieldSettings;
use super::types::{GpuLightfieldFilterPass, GpuLightfieldParams};
use crate::RenderError;
use crate::ddgi::types::GpuDdgiVolume;
use crate::probes::{AtlasLayout, ProbeGrid};

const MAP_SETTING: &str = "technique.bake.resolution or the probe counts";
const TILE_SETTING: &str = "technique.bake.irradiance_texels / distance_texels or the probe counts";
const FRAME_SETTING: &str = "the image size (--size)";

/// Bytes a texel of each baked map: radiance R11G11B10 (4), normal RG8 + distance R16F (4) —
/// the paper's 8 bytes — and the min-mip's f32.
const MAP_TEXEL_BYTES: u64 = 4;

/// The tile sides (border included) of the prefiltered atlases.
pub fn tile_sides(settings: &LightfieldSettings) -> [u32; 2] {
    [
        settings.bake.irradiance_texels + 2,
        settings.bake.distance_texels + 2,
    ]
}

/// Every allocation, from the grid, the settings and the image size alone.
pub fn plan(grid: &ProbeGrid, settings: &LightfieldSettings, size: (u32, u32)) -> Vec<Allocation> {
    let b = &settings.bake;
    let probes = grid.probe_count;
    let res = b.resolution;
    let low = res / MIN_MIP_FACTOR;
    let small = settings.prefilter_side();
    let atlas = AtlasLayout::new(probes, &tile_sides(settings));
    let mut all = vec![
        Allocation::texture_array(
            "lightfield/radiance",
            (res, res),
            probes,
            MAP_TEXEL_BYTES,
            MAP_SETTING,
        ),
        Allocation::texture_array(
            "lightfield/geometry",
            (res, res),
            probes,
            MAP_TEXEL_BYTES,
            MAP_SETTING,
        ),
        Allocation::texture_array("lightfield/low", (low, low), probes, 4, MAP_SETTING),
        Allocation::texture_array(
            "lightfield/small_radiance",
            (small, small),
            probes,
            8,
            "technique.bake.prefilter_resolution",
        ),
        Allocation::texture_array(
            "lightfield/small_moments",
            (small, small),
            probes,
            8,
            "technique.bake.prefilter_resolution",
        ),
        Allocation::texture(
            "lightfield/irradiance",
            atlas.size(b.irradiance_texels),
            8,
            1,
            TILE_SETTING,
        ),
        Allocation::texture(
            "lightfield/distance",
            atlas.size(b.distance_texels),
            8,
            1,
            TILE_SETTING,
        ),
        Allocation::storage(
            "lightfield/probe_offsets",
            probes as u64 * 16,
            "the probe counts",
        ),
        Allocation::storage(
            "lightfield/probe_states",
            probes as u64 * 4,
            "the probe counts",
        ),
    ];
    for label in FRAME_TEXTURES {
        all.push(Allocation::texture(label, size, 8, 1, FRAME_SETTING));
    }
    // At the finest block the settings allow (2: the exact query needs none).
    let coarse = (size.0.div_ceil(2), size.1.div_ceil(2));
    for label in ["lightfield/coarse_irradiance", "lightfield/coarse_normal"] {
        all.push(Allocation::texture(label, coarse, 8, 1, FRAME_SETTING));
    }
    for label in [
        "lightfield/geometry_history_0",
        "lightfield/geometry_history_1",
    ] {
        all.push(Allocation::texture(label, size, 16, 1, FRAME_SETTING));
    }
    all
}

/// The frame-sized rgba16float buffers: this frame's traced light, the filter's intermediate
/// and output, and two sets of filtered light (this frame's is next frame's history).
const FRAME_TEXTURES: [&str; 9] = [
    "lightfield/lambert",
    "lightfield/glossy",
    "lightfield/filter_scratch",
    "lightfield/lambert_spatial",
    "lightfield/glossy_spatial",
    "lightfield/lambert_history_0",
    "lightfield/lambert_history_1",
    "lightfield/glossy_history_0",
    "lightfield/glossy_history_1",
];

/// A texture and the view passes bind.
pub struct Texture {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl Texture {
    fn plain(texture: wgpu::Texture) -> Self {
        let view = texture.create_view(&Default::default());
        Self { texture, view }
    }

    /// Probe maps: a layer a probe, bound as an array even with one probe.
    fn array(texture: wgpu::Texture) -> Self {
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        Self { texture, view }
    }
}

const USAGE: wgpu::TextureUsages = wgpu::TextureUsages::STORAGE_BINDING
    .union(wgpu::TextureUsages::TEXTURE_BINDING)
    .union(wgpu::TextureUsages::COPY_SRC)
    .union(wgpu::TextureUsages::COPY_DST);

/// The baked probe data: what the cache stores, and what every frame reads.
pub struct ProbeMaps {
    /// R11G11B10 radiance a texel (u32).
    pub radiance: Texture,
    /// Octahedral normal (2 × 8 bits) and f16 radial distance a texel (u32).
    pub geometry: Texture,
    /// The min-mip: the nearest distance of each 16×16 block (f32).
    pub low: Texture,
    /// Prefiltered irradiance (rgba16float, value^(1/gamma)) and distance moments (rg32float),
    /// in DDGI's atlas layout.
    pub irradiance: Texture,
    pub distance: Texture,
    /// DDGI's state word a probe (lightfield/probe_states): PROBE_OFF inside geometry.
    pub states: wgpu::Buffer,
    /// A vec4 a probe: where lightfield/relocate moved it from its grid position.
    pub offsets: wgpu::Buffer,
}

impl ProbeMaps {
    /// The maps in the order the cache stores them, with their bytes a texel.
    pub fn in_cache_order(&self) -> [(&wgpu::Texture, u32); 5] {
        [
            (&self.radiance.texture, 4),
            (&self.geometry.texture, 4),
            (&self.low.texture, 4),
            (&self.irradiance.texture, 8),
            (&self.distance.texture, 8),
        ]
    }
}

pub struct LightfieldResources {
    pub params: wgpu::Buffer,
    pub maps: ProbeMaps,
    /// The maps averaged down for the prefilters (bake only).
    pub small_radiance: Texture,
    pub small_moments: Texture,
    /// DDGI's volume uniform describing the prefiltered atlases.
    pub volume: wgpu::Buffer,
    bilinear: wgpu::Sampler,
    gather: wgpu::Sampler,
    /// This frame's traced light.
    pub lambert: Texture,
    pub glossy: Texture,
    /// The separable filter's half-way image, and its outputs.
    pub filter_scratch: Texture,
    pub lambert_spatial: Texture,
    pub glossy_spatial: Texture,
    /// Filtered light and the geometry it was filtered on, [frame mod 2] written, the other read.
    pub lambert_history: [Texture; 2],
    pub glossy_history: [Texture; 2],
    pub geometry_history: [Texture; 2],
    /// The block irradiance (rgb, view depth) and the normals it was queried at, sized for the
    /// finest block (2); coarser blocks use its top-left part.
    pub coarse_irradiance: Texture,
    pub coarse_normal: Texture,
    /// The filter's four passes: Lambertian horizontal, vertical; glossy horizontal, vertical.
    pub filter_passes: [wgpu::Buffer; 4],
}

impl LightfieldResources {
    /// Allocates what [`plan`] lists (which the session checked against the adapter first).
    pub fn new(
        ctx: &GpuContext,
        grid: &ProbeGrid,
        settings: &LightfieldSettings,
        size: (u32, u32),
    ) -> Result<Self, RenderError> {
        ctx.check_allocations(&plan(grid, settings, size))?;
        let device = &ctx.device;
        let b = &settings.bake;
        let probes = grid.probe_count;
        let array = |label: &str, side: u32, format| {
            Texture::array(irradiant_gpu::texture_2d_array(
                device,
                label,
                (side, side),
                probes,
                format,
                USAGE,
            ))
        };
        let image = |label: &str, size: (u32, u32), format| {
            Texture::plain(irradiant_gpu::texture_2d(
                device, label, size, format, 1, USAGE,
            ))
        };
        let frame = |label: &str| image(label, size, wgpu::TextureFormat::Rgba16Float);
        let atlas = AtlasLayout::new(probes, &tile_sides(settings));
        let small = settings.prefilter_side();
        let uniform = |label: &str, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let zeros = |label: &str, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(16),
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let (bilinear, gather) = crate::probes::atlas::atlas_samplers(device, "lightfield");
        let filter_pass = |label| uniform(label, size_of::<GpuLightfieldFilterPass>() as u64);
        Ok(Self {
            params: uniform("lightfield/params", size_of::<GpuLightfieldParams>() as u64),
            maps: ProbeMaps {
                radiance: array(
                    "lightfield/radiance",
                    b.resolution,
                    wgpu::TextureFormat::R32Uint,
                ),
                geometry: array(
                    "lightfield/geometry",
                    b.resolution,
                    wgpu::TextureFormat::R32Uint,
                ),
                low: array(
                    "lightfield/low",
                    b.resolution / MIN_MIP_FACTOR,
                    wgpu::TextureFormat::R32Float,
                ),
                irradiance: image(
                    "lightfield/irradiance",
                    atlas.size(b.irradiance_texels),
                    wgpu::TextureFormat::Rgba16Float,
                ),
                distance: image(
                    "lightfield/distance",
                    atlas.size(b.distance_texels),
                    wgpu::TextureFormat::Rg32Float,
                ),
                states: zeros("lightfield/probe_states", probes as u64 * 4),
                offsets: zeros("lightfield/probe_offsets", probes as u64 * 16),
            },
            small_radiance: array(
                "lightfield/small_radiance",
                small,
                wgpu::TextureFormat::Rgba16Float,
            ),
            small_moments: array(
                "lightfield/small_moments",
                small,
                wgpu::TextureFormat::Rg32Float,
            ),
            volume: uniform("lightfield/volume", size_of::<GpuDdgiVolume>() as u64),
            bilinear,
            gather,
            lambert: frame("lightfield/lambert"),
            glossy: frame("lightfield/glossy"),
            filter_scratch: frame("lightfield/filter_scratch"),
            lambert_spatial: frame("lightfield/lambert_spatial"),
            glossy_spatial: frame("lightfield/glossy_spatial"),
            lambert_history: [
                frame("lightfield/lambert_history_0"),
                frame("lightfield/lambert_history_1"),
            ],
            glossy_history: [
                frame("lightfield/glossy_history_0"),
                frame("lightfield/glossy_history_1"),
            ],
            geometry_history: [
                image(
                    "lightfield/geometry_history_0",
                    size,
                    wgpu::TextureFormat::Rgba32Float,
                ),
                image(
                    "lightfield/geometry_history_1",
                    size,
                    wgpu::TextureFormat::Rgba32Float,
                ),
            ],
            coarse_irradiance: image(
                "lightfield/coarse_irradiance",
                (size.0.div_ceil(2), size.1.div_ceil(2)),
                wgpu::TextureFormat::Rgba16Float,
            ),
            coarse_normal: image(
                "lightfield/coarse_normal",
                (size.0.div_ceil(2), size.1.div_ceil(2)),
                wgpu::TextureFormat::Rgba16Float,
            ),
            filter_passes: [
                filter_pass("lightfield/filter_lambert_x"),
                filter_pass("lightfield/filter_lambert_y"),
                filter_pass("lightfield/filter_glossy_x"),
                filter_pass("lightfield/filter_glossy_y"),
            ],
        })
    }

    /// What every light-field pass may read: the parameters, the maps, and DDGI's query over
    /// the prefiltered atlases.
    pub fn table(&self) -> ResourceTable<'_> {
        ResourceTable::new()
            .buffer("lightfield", &self.params)
            .texture("lightfield_radiance", &self.maps.radiance.view)
            .texture("lightfield_geometry", &self.maps.geometry.view)
            .texture("lightfield_low", &self.maps.low.view)
            .buffer("volume", &self.volume)
            .buffer("probe_offsets", &self.maps.offsets)
            .buffer("lightfield_probe_offsets", &self.maps.offsets)
            .buffer("probe_states", &self.maps.states)
            .buffer("lightfield_probe_states", &self.maps.states)
            .texture("irradiance_texture", &self.maps.irradiance.view)
            .texture("distance_texture", &self.maps.distance.view)
            .sampler("atlas_bilinear", &self.bilinear)
            .sampler("atlas_gather", &self.gather)
    }
}
