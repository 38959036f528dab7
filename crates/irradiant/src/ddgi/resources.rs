//! A DDGI volume's GPU memory: the volume uniform, the ray buffers, the probe state and the two
//! probe atlases (storage buffers the blends write, and texture copies the query samples),
//! offered to the passes by the names their WGSL declares.

use irradiant_gpu::{Allocation, GpuContext, ResourceTable, wgpu};

use super::settings::DdgiSettings;
use super::types::{
    GpuDdgiBlendWeight, GpuDdgiDeferredRead, GpuDdgiRayHit, GpuDdgiRaySample, GpuDdgiShadowRay,
    GpuDdgiVolume,
};
use super::volume::DdgiDispatches;
use crate::RenderError;
use crate::probes::{AtlasLayout, ProbeGrid, atlas};

/// Bytes before the queued rays in `shadow_queue`; the indirect dispatch's (x, y, z) start
/// at byte 4.
pub const SHADOW_QUEUE_HEADER: u64 = 16;

/// Bytes before the probe indices in `active_probes`: two list headers of 48 bytes (every
/// updating probe, then the newly ones), each the count, the indirect dispatch of shade (x, y,
/// z at its byte 4), of the blends (at its byte 16) and of trace (at its byte 28). The lists'
/// probes follow, each `probe_count` long.
pub const ACTIVE_PROBES_HEADER: u64 = 96;
/// Where `active_probes` holds the indirect dispatch of ddgi/shade (a thread a probe ray).
pub const ACTIVE_RAY_GROUPS: u64 = 4;
/// Where `active_probes` holds the indirect dispatch of the blends.
pub const ACTIVE_BLEND_GROUPS: u64 = 16;
/// Where `active_probes` holds the indirect dispatch of ddgi/trace (shade's, or runs of rays
/// where its lanes fetch: `DdgiSettings::fetches_rays`).
pub const ACTIVE_TRACE_GROUPS: u64 = 28;
/// Where `active_probes` holds the newly probes' list (the convergence rounds').
pub const NEWLY_LIST: u64 = 48;

/// Bytes of `convergence` (DdgiConvergence): the round, padded.
pub const CONVERGENCE_BYTES: u64 = 16;

/// Wake boxes the buffer holds; further animated instances merge into the last box.
pub const MAX_WAKE_BOXES: usize = 64;

/// Bytes a texel of either atlas: irradiance as two packed f16 pairs (rgb, value^(1/gamma)),
/// distance as two f32 (mean, mean²) — so that the copies into rgba16float and rg32float
/// textures are byte for byte.
pub const ATLAS_TEXEL_BYTES: u32 = 8;

/// What sizes the probe buffers, for the messages that refuse too large a volume.
const PROBE_SETTING: &str = "the probe counts (the manifest's probe_volume counts, --probes) or technique.volume.rays_per_probe";
/// The same for cascades, whose probes the cascade settings place.
const CASCADE_SETTING: &str =
    "technique.volume.cascades / cascade_probes or technique.volume.rays_per_probe";

/// The tile sides (border included) every atlas row must align for.
pub fn tile_sides(settings: &DdgiSettings) -> [u32; 2] {
    [
        settings.volume.irradiance_texels + 2,
        settings.volume.distance_texels + 2,
    ]
}

/// Every allocation of one volume, from its grid and settings, and whether the technique has
/// several volumes (whose probe rays then leave their hits' probe light to
/// ddgi/between_volumes, through `deferred_reads`).
pub fn plan(grid: &ProbeGrid, settings: &DdgiSettings, several_volumes: bool) -> Vec<Allocation> {
    let v = &settings.volume;
    let probes = grid.probe_count as u64;
    let rays = probes * v.rays_per_probe as u64;
    let atlas = AtlasLayout::new(grid.probe_count, &tile_sides(settings));
    let texel = ATLAS_TEXEL_BYTES as u64;
    let (probe_setting, atlas_setting) = if v.cascades > 0 {
        (
            CASCADE_SETTING,
            "technique.volume.cascade_probes or technique.volume.irradiance_texels / distance_texels",
        )
    } else {
        (
            PROBE_SETTING,
            "the probe counts or technique.volume.irradiance_texels / distance_texels",
        )
    };
    vec![
        Allocation::storage(
            "ddgi/hits",
            rays * size_of::<GpuDdgiRayHit>() as u64,
            probe_setting,
        ),
        Allocation::storage(
            "ddgi/samples",
            rays * size_of::<GpuDdgiRaySample>() as u64,
            probe_setting,
        ),
        Allocation::storage(
            "ddgi/deferred_reads",
            if several_volumes { rays } else { 1 } * size_of::<GpuDdgiDeferredRead>() as u64,
            probe_setting,
        ),
        Allocation::storage(
            "ddgi/shadow_queue",
            SHADOW_QUEUE_HEADER
                + if settings.queues_shadow_rays() {
                    rays * size_of::<GpuDdgiShadowRay>() as u64
                } else {
                    size_of::<GpuDdgiShadowRay>() as u64
                },
            probe_setting,
        ),
        Allocation::storage(
            "ddgi/blend_weights",
            (v.irradiance_texels.pow(2) + v.distance_texels.pow(2)) as u64
                * (v.rays_per_probe as u64 + 1)
                * size_of::<GpuDdgiBlendWeight>() as u64,
            "technique.volume.rays_per_probe or the texel counts",
        ),
        Allocation::storage(
            "ddgi/irradiance_atlas",
            area(atlas.size(v.irradiance_texels)) * texel,
            atlas_setting,
        ),
        Allocation::storage(
            "ddgi/irradiance_bounce_atlas",
            area(atlas.size(v.irradiance_texels)) * texel,
            atlas_setting,
        ),
        Allocation::storage(
            "ddgi/irradiance_history",
            probes * v.irradiance_texels.pow(2) as u64 * 16,
            atlas_setting,
        ),
        Allocation::storage(
            "ddgi/distance_atlas",
            area(atlas.size(v.distance_texels)) * texel,
            atlas_setting,
        ),
        Allocation::texture(
            "ddgi/irradiance_texture",
            atlas.size(v.irradiance_texels),
            texel,
            1,
            atlas_setting,
        ),
        Allocation::texture(
            "ddgi/irradiance_bounce_texture",
            atlas.size(v.irradiance_texels),
            texel,
            1,
            atlas_setting,
        ),
        Allocation::texture(
            "ddgi/distance_texture",
            atlas.size(v.distance_texels),
            texel,
            1,
            atlas_setting,
        ),
        Allocation::storage("ddgi/probe_offsets", probes * 16, probe_setting),
        Allocation::storage("ddgi/probe_states", probes * 4, probe_setting),
        Allocation::storage(
            "ddgi/active_probes",
            ACTIVE_PROBES_HEADER + 2 * probes * 4,
            probe_setting,
        ),
        Allocation::storage("ddgi/convergence", CONVERGENCE_BYTES, probe_setting),
        Allocation::storage(
            "ddgi/every_probe",
            ACTIVE_PROBES_HEADER + 2 * probes * 4,
            probe_setting,
        ),
    ]
}

fn area((w, h): (u32, u32)) -> u64 {
    w as u64 * h as u64
}

pub struct DdgiResources {
    pub volume: wgpu::Buffer,
    /// The ray set before rotation, uploaded once (vec4 a ray, in trace order).
    pub ray_set: wgpu::Buffer,
    /// The rotated ray set of this frame (vec4 a ray).
    pub directions: wgpu::Buffer,
    pub hits: wgpu::Buffer,
    pub samples: wgpu::Buffer,
    /// A GpuDdgiDeferredRead a probe ray with several volumes (one otherwise): the hits whose
    /// probe light ddgi/between_volumes adds.
    pub deferred_reads: wgpu::Buffer,
    /// Two packed f16 pairs a texel (rgb, value^(1/gamma)): what the query samples, through
    /// its texture copy.
    pub irradiance: wgpu::Buffer,
    /// The bounce copy: irradiance blended at `bounce_hysteresis`, which probe rays read at
    /// their hits (packed as `irradiance`), so that multi-bounce light converges quickly.
    pub irradiance_bounce: wgpu::Buffer,
    /// The blend's running value of each interior texel, linear and f32 (16 bytes a texel):
    /// f16 loses updates below half its rounding step (ddgi/blend_irradiance).
    pub irradiance_history: wgpu::Buffer,
    /// Two f32 a texel: mean distance and mean squared distance.
    pub distance: wgpu::Buffer,
    /// Copies of the two atlases that the query samples (rgba16float and rg32float: the
    /// buffers' bytes as they are), copied after each blend. Hardware bilinear filtering and
    /// gathers take one or two fetches where loading texels took four.
    pub irradiance_texture: wgpu::Texture,
    pub irradiance_bounce_texture: wgpu::Texture,
    pub distance_texture: wgpu::Texture,
    irradiance_view: wgpu::TextureView,
    irradiance_bounce_view: wgpu::TextureView,
    distance_view: wgpu::TextureView,
    bilinear: wgpu::Sampler,
    gather: wgpu::Sampler,
    /// vec4 a probe: relocation offset (xyz) and 1 if relocation found it tied (w; ddgi/relocate).
    pub offsets: wgpu::Buffer,
    /// u32 a probe: state, near-geometry flag and blends since it started (ddgi::constants).
    pub states: wgpu::Buffer,
    /// The probes that update this frame, and the indirect dispatches over them
    /// (DdgiActiveProbes in ddgi/states.wgsl): written by ddgi/probe_states for the next
    /// frame, copied from `every_probe` when the states start over.
    pub active_probes: wgpu::Buffer,
    /// `active_probes` as it is when every probe updates (each volume's first frames).
    pub every_probe: wgpu::Buffer,
    /// Two vec4 (min, max) a box: where animated instances may wake sleeping probes.
    pub wake_boxes: wgpu::Buffer,
    /// GpuDdgiBlendWeight lists: per tile texel, the rays of its blend and their weights, the
    /// same for every probe (layout in ddgi/blend_weights.wgsl).
    pub blend_weights: wgpu::Buffer,
    /// ddgi/shade's queue of shadow rays for ddgi/shadow: a 16-byte header (count, then the
    /// shadow pass's indirect dispatch) and a GpuDdgiShadowRay a probe ray. Header only when
    /// no shadow ray is queued (DdgiSettings::queues_shadow_rays).
    pub shadow_queue: wgpu::Buffer,
    /// The convergence pass's round and indirect dispatches (DdgiConvergence in states.wgsl).
    pub convergence: wgpu::Buffer,
}

impl DdgiResources {
    /// Allocates what [`plan`] lists (which the session checked against the adapter first).
    pub fn new(
        ctx: &GpuContext,
        grid: &ProbeGrid,
        atlas_layout: &AtlasLayout,
        settings: &DdgiSettings,
        dispatches: &DdgiDispatches,
        several_volumes: bool,
    ) -> Result<Self, RenderError> {
        let allocations = plan(grid, settings, several_volumes);
        ctx.check_allocations(&allocations)?;
        let size = |label: &str| {
            allocations
                .iter()
                .find(|a| a.label == label)
                .map(|a| a.bytes)
                .expect("every buffer is planned")
        };
        let device = &ctx.device;
        let storage = |label: &str, size: u64| {
            storage_buffer(device, label, size, wgpu::BufferUsages::empty())
        };
        let v = &settings.volume;
        let ray_set: Vec<[f32; 4]> =
            crate::probes::rays::probe_ray_set(v.rays_per_probe, settings.speed.coherent_rays)
                .iter()
                .map(|d| d.extend(0.0).to_array())
                .collect();
        let ray_set_buffer = storage("ddgi/ray_set", v.rays_per_probe as u64 * 16);
        ctx.queue
            .write_buffer(&ray_set_buffer, 0, bytemuck::cast_slice(&ray_set));
        let irradiance_texture = atlas::atlas_texture(
            device,
            "ddgi/irradiance_texture",
            atlas_layout.size(v.irradiance_texels),
            wgpu::TextureFormat::Rgba16Float,
        );
        let irradiance_bounce_texture = atlas::atlas_texture(
            device,
            "ddgi/irradiance_bounce_texture",
            atlas_layout.size(v.irradiance_texels),
            wgpu::TextureFormat::Rgba16Float,
        );
        let distance_texture = atlas::atlas_texture(
            device,
            "ddgi/distance_texture",
            atlas_layout.size(v.distance_texels),
            wgpu::TextureFormat::Rg32Float,
        );
        let (bilinear, gather) = atlas::atlas_samplers(device, "ddgi");
        Ok(Self {
            irradiance_view: irradiance_texture.create_view(&Default::default()),
            irradiance_bounce_view: irradiance_bounce_texture.create_view(&Default::default()),
            irradiance_bounce_texture,
            distance_view: distance_texture.create_view(&Default::default()),
            irradiance_texture,
            distance_texture,
            bilinear,
            gather,
            ray_set: ray_set_buffer,
            volume: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ddgi/volume"),
                size: size_of::<GpuDdgiVolume>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            directions: storage("ddgi/directions", v.rays_per_probe as u64 * 16),
            hits: storage("ddgi/hits", size("ddgi/hits")),
            samples: storage("ddgi/samples", size("ddgi/samples")),
            deferred_reads: storage("ddgi/deferred_reads", size("ddgi/deferred_reads")),
            irradiance: storage("ddgi/irradiance_atlas", size("ddgi/irradiance_atlas")),
            irradiance_bounce: storage(
                "ddgi/irradiance_bounce_atlas",
                size("ddgi/irradiance_bounce_atlas"),
            ),
            irradiance_history: storage("ddgi/irradiance_history", size("ddgi/irradiance_history")),
            distance: storage("ddgi/distance_atlas", size("ddgi/distance_atlas")),
            offsets: storage("ddgi/probe_offsets", size("ddgi/probe_offsets")),
            states: storage("ddgi/probe_states", size("ddgi/probe_states")),
            active_probes: every_probe_list(
                ctx,
                "ddgi/active_probes",
                grid,
                dispatches,
                wgpu::BufferUsages::INDIRECT,
            ),
            every_probe: every_probe_list(
                ctx,
                "ddgi/every_probe",
                grid,
                dispatches,
                wgpu::BufferUsages::empty(),
            ),
            wake_boxes: storage("ddgi/wake_boxes", MAX_WAKE_BOXES as u64 * 32),
            shadow_queue: storage_buffer(
                device,
                "ddgi/shadow_queue",
                size("ddgi/shadow_queue"),
                wgpu::BufferUsages::INDIRECT,
            ),
            blend_weights: storage("ddgi/blend_weights", size("ddgi/blend_weights")),
            convergence: storage_buffer(
                device,
                "ddgi/convergence",
                CONVERGENCE_BYTES,
                wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::UNIFORM,
            ),
        })
    }

    /// Every resource by the name its passes declare.
    pub fn table(&self) -> ResourceTable<'_> {
        self.table_sampling(&self.irradiance_view)
    }

    /// The table of the passes that shade probe rays: their query samples the bounce copy.
    pub fn bounce_table(&self) -> ResourceTable<'_> {
        self.table_sampling(&self.irradiance_bounce_view)
    }

    /// The updating volume's rays, as ddgi/between_volumes names them beside another volume's
    /// table.
    pub fn owner_table(&self) -> ResourceTable<'_> {
        ResourceTable::new()
            .buffer("owner", &self.volume)
            .buffer("owner_active_probes", &self.active_probes)
            .buffer("owner_samples", &self.samples)
            .buffer("owner_deferred_reads", &self.deferred_reads)
    }

    fn table_sampling<'a>(&'a self, irradiance: &'a wgpu::TextureView) -> ResourceTable<'a> {
        ResourceTable::new()
            .buffer("volume", &self.volume)
            .buffer("ray_set", &self.ray_set)
            .buffer("directions", &self.directions)
            .buffer("hits", &self.hits)
            .buffer("samples", &self.samples)
            .buffer("deferred_reads", &self.deferred_reads)
            .buffer("irradiance_atlas", &self.irradiance)
            .buffer("irradiance_bounce_atlas", &self.irradiance_bounce)
            .buffer("irradiance_history", &self.irradiance_history)
            .buffer("distance_atlas", &self.distance)
            .buffer("probe_offsets", &self.offsets)
            .buffer("probe_states", &self.states)
            .buffer("wake_boxes", &self.wake_boxes)
            .buffer("active_probes", &self.active_probes)
            .buffer("blend_weights", &self.blend_weights)
            .buffer("shadow_queue", &self.shadow_queue)
            .buffer("convergence", &self.convergence)
            .texture("irradiance_texture", irradiance)
            .texture("distance_texture", &self.distance_view)
            .sampler("atlas_bilinear", &self.bilinear)
            .sampler("atlas_gather", &self.gather)
    }
}

/// Lists of the active probes (DdgiActiveProbes) whose first holds every probe of the grid,
/// with the dispatches that cover them all, and whose second (the newly probes) is empty.
fn every_probe_list(
    ctx: &GpuContext,
    label: &str,
    grid: &ProbeGrid,
    dispatches: &DdgiDispatches,
    extra: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let mut words = vec![grid.probe_count];
    words.extend(dispatches.rays.counts());
    words.extend(dispatches.blends.counts());
    words.extend(dispatches.trace.counts());
    words.extend([0; 2]);
    words.extend([0; 12]);
    words.extend(0..grid.probe_count);
    words.extend(std::iter::repeat_n(0, grid.probe_count as usize));
    let buffer = storage_buffer(&ctx.device, label, words.len() as u64 * 4, extra);
    ctx.queue
        .write_buffer(&buffer, 0, bytemuck::cast_slice(&words));
    buffer
}

fn storage_buffer(
    device: &wgpu::Device,
    label: &str,
    size: u64,
    extra: wgpu::BufferUsages,
) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC
            | extra,
        mapped_at_creation: false,
    })
}
