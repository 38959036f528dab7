//! Light-field probes (McGuire, Mara, Nowrouzezahrai and Luebke 2017): a grid of probes, each
//! holding octahedral maps of the radiance, normal and distance of what it sees, baked once on
//! the GPU with our own tracer; world-space rays are then traced through the probes alone.
//!
//! ```text
//! bake (once, or from the cache):
//! lightfield/bake_geometry   each probe texel's nearest surface: normal and radial distance
//! lightfield/min_mip         the nearest distance of each 16×16 block
//! lightfield/bake_radiance   light leaving each texel's surface (bounce n reads bounce n − 1's
//! lightfield/reduce          irradiance) → the maps averaged down
//! lightfield/prefilter       → irradiance and distance-moment tiles in DDGI's atlas layout
//! each frame:
//! lightfield/trace           Lambertian and glossy rays through the light field
//! lightfield/filter          cross-bilateral filters (traced and fast paths)
//! lightfield/temporal        reprojected exponential averages
//! lightfield/resolve         → the frame's indirect light
//! ```
//!
//! Three registry entries, one a shading algorithm of §5: `lightfield` (the fast path:
//! prefiltered irradiance with Chebyshev visibility through DDGI's query, one filtered glossy
//! ray), `lightfield-traced` (one Lambertian and one glossy ray, filtered) and
//! `lightfield-naive` (Monte Carlo through the light field). See docs/lightfield.md.

pub mod agreement;
mod bake;
pub mod cache;
pub mod constants;
mod inspect;
mod kind;
mod resources;
mod settings;
pub mod types;

pub use bake::BakeReport;
use bake::check_prefilter_loops;
pub use cache::{EntryLayout, bake_key, parse_entry};
pub use kind::{LightfieldKind, grid_of};
use kind::{bake_dispatches, block_image};
pub use resources::plan as plan_resources;
pub use settings::{
    LightfieldBakeSettings, LightfieldSettings, LightfieldShadeSettings, ShadingAlgorithm,
};

use std::any::Any;
use std::sync::Arc;
use std::time::Instant;

use bytemuck::Zeroable;
use glam::Vec3;
use irradiant_gpu::{
    Allocation, BoundPass, ComputePass, GpuContext, PassDesc, Profiler, ResourceTable, Workgroups,
    read_buffer_as, wgpu,
};
use irradiant_scene::{Camera, Scene};

use crate::RenderError;
use crate::ddgi::constants::{STATES_OFF, WEIGHT_BACKFACE, WEIGHT_CHEBYSHEV};
use crate::ddgi::types::GpuDdgiVolume;
use crate::frame::IMAGE_TILE;
use crate::probes::{AtlasLayout, ProbeGrid};
use crate::raycast::types::GpuRay;
use crate::settings::SettingsError;
use crate::settings::TechniqueSpec;
use crate::technique::{
    Counter, ProbeView, Technique, TechniqueContext, TechniqueKind, TechniquePasses, non_finite,
};
use constants::{ALGORITHM_FILTERED, ALGORITHM_NAIVE, ALGORITHM_PREFILTERED, MIN_MIP_FACTOR};
use resources::LightfieldResources;
use types::{GpuLightfieldFilterPass, GpuLightfieldHit, GpuLightfieldParams};

/// The fast path (§5.2): prefiltered irradiance with visibility, one filtered glossy ray.
pub static LIGHTFIELD: LightfieldKind = LightfieldKind {
    algorithm: ShadingAlgorithm::Prefiltered,
};
/// One Lambertian and one glossy ray a pixel through the light field, filtered (§5.1).
pub static LIGHTFIELD_TRACED: LightfieldKind = LightfieldKind {
    algorithm: ShadingAlgorithm::Filtered,
};
/// Monte Carlo through the light field, unfiltered (§5).
pub static LIGHTFIELD_NAIVE: LightfieldKind = LightfieldKind {
    algorithm: ShadingAlgorithm::Naive,
};

/// The prefiltered irradiance's encoding (value^(1/gamma), as DDGI stores it). DDGI's 5 serves
/// its hysteresis, which blends in the encoded space; a baked atlas never blends over time, and
/// at 2 the query blends probes in the same gamma-2 space as DDGI's without decoding each one.
const IRRADIANCE_GAMMA: f32 = 2.0;
/// The map passes' workgroup (8×8 texels of one probe's map).
const MAP_TILE: (u32, u32) = (8, 8);
/// Probes a bake dispatch may cover: a dispatch's z.
const MAX_PROBES: u32 = 65_535;
/// The bake passes' WGSL, in BAKE's order (the cache key hashes it).
const BAKE_SOURCES: [&str; 7] = [
    include_str!("bake_geometry.wgsl"),
    include_str!("relocate.wgsl"),
    include_str!("min_mip.wgsl"),
    include_str!("probe_states.wgsl"),
    include_str!("bake_radiance.wgsl"),
    include_str!("reduce.wgsl"),
    include_str!("prefilter.wgsl"),
];
/// Pass labels.
const TRACE: &str = "lightfield/trace";
const FILTER: &str = "lightfield/filter";
const TEMPORAL: &str = "lightfield/temporal";
const RESOLVE: &str = "lightfield/resolve";
const IRRADIANCE: &str = "lightfield/irradiance";
const BAKE: [&str; 7] = [
    "lightfield/bake_geometry",
    "lightfield/relocate",
    "lightfield/min_mip",
    "lightfield/probe_states",
    "lightfield/bake_radiance",
    "lightfield/reduce",
    "lightfield/prefilter",
];

/// The compiled passes.
struct Pipelines {
    bake_geometry: Arc<ComputePass>,
    relocate: Arc<ComputePass>,
    min_mip: Arc<ComputePass>,
    probe_states: Arc<ComputePass>,
    bake_radiance: Arc<ComputePass>,
    reduce: Arc<ComputePass>,
    prefilter: Arc<ComputePass>,
    trace: Arc<ComputePass>,
    filter: Arc<ComputePass>,
    temporal: Arc<ComputePass>,
    resolve: Arc<ComputePass>,
    irradiance: Arc<ComputePass>,
    view: Arc<ComputePass>,
    trace_rays: Arc<ComputePass>,
}

impl Pipelines {
    fn new(cx: &TechniqueContext, settings: &LightfieldSettings) -> Result<Self, RenderError> {
        let exact = (settings.shade.irradiance_block == 1) as u32;
        let compile = |label: &'static str, source: &str, tracing: bool, query: bool| {
            let mut desc =
                PassDesc::new(label, source).constants([("EXACT_IRRADIANCE", format!("{exact}u"))]);
            if tracing {
                desc = desc.constants(cx.gpu_scene.shader_constants());
            }
            if query {
                desc = desc.unfilterable(crate::ddgi::QUERY_UNFILTERABLE);
            }
            crate::shaders::pass(cx.ctx, &desc).map_err(RenderError::from)
        };
        Ok(Self {
            bake_geometry: compile(BAKE[0], BAKE_SOURCES[0], true, false)?,
            relocate: compile(BAKE[1], BAKE_SOURCES[1], false, false)?,
            min_mip: compile(BAKE[2], BAKE_SOURCES[2], false, false)?,
            probe_states: compile(BAKE[3], BAKE_SOURCES[3], false, false)?,
            bake_radiance: compile(BAKE[4], BAKE_SOURCES[4], true, true)?,
            reduce: compile(BAKE[5], BAKE_SOURCES[5], false, false)?,
            prefilter: compile(BAKE[6], BAKE_SOURCES[6], false, false)?,
            trace: compile(TRACE, include_str!("trace.wgsl"), false, false)?,
            filter: compile(FILTER, include_str!("filter.wgsl"), false, false)?,
            temporal: compile(TEMPORAL, include_str!("temporal.wgsl"), false, false)?,
            resolve: compile(RESOLVE, include_str!("resolve.wgsl"), false, true)?,
            irradiance: compile(IRRADIANCE, include_str!("irradiance.wgsl"), false, true)?,
            view: compile("lightfield/view", include_str!("view.wgsl"), false, false)?,
            trace_rays: compile(
                "lightfield/trace_rays",
                include_str!("trace_rays.wgsl"),
                false,
                false,
            )?,
        })
    }
}

/// Light-field probes (McGuire et al. 2017): baked (or loaded from the cache) once, then
/// traced through each frame with the registry entry's shading algorithm.
pub struct Lightfield {
    name: &'static str,
    settings: LightfieldSettings,
    grid: ProbeGrid,
    atlas: AtlasLayout,
    resources: LightfieldResources,
    pipelines: Pipelines,
    /// (pass, workgroups) of the frame, in order; temporal and resolve by frame parity.
    trace: (BoundPass, Workgroups),
    filters: Vec<(BoundPass, Workgroups)>,
    temporal: [(BoundPass, Workgroups); 2],
    resolve: [(BoundPass, Workgroups); 2],
    /// The half-resolution irradiance query (the fast path).
    irradiance: (BoundPass, Workgroups),
    view: (BoundPass, Workgroups),
    /// Longest distance the moments count: the scene's diagonal.
    max_distance: f32,
    frames: u32,
    bake: BakeReport,
}

impl Lightfield {
    /// Validates the settings, allocates the probe maps and the frame buffers, builds the
    /// passes, then bakes the probes or loads them from the cache.
    pub fn new(
        cx: &TechniqueContext,
        name: &'static str,
        settings: &LightfieldSettings,
    ) -> Result<Self, RenderError> {
        settings.validate()?;
        let ctx = cx.ctx;
        check_prefilter_loops(settings, &ctx.info)?;
        let size = cx.frame.size();
        let grid = grid_of(cx.scene, settings)?;
        let atlas = AtlasLayout::new(grid.probe_count, &resources::tile_sides(settings));
        let resources = LightfieldResources::new(ctx, &grid, settings, size)?;
        let pipelines = Pipelines::new(cx, settings)?;
        let (lo, hi) = cx.scene.bounds();
        let max_distance = (hi - lo).length().max(grid.spacing.length()).max(1e-3);
        let scene_table = cx.gpu_scene.resources();
        let frame_table = cx.frame.resources.table();
        let shared = resources.table();
        let r = &resources;
        let image = Workgroups::for_image(size.0, size.1, IMAGE_TILE);
        let bind =
            |pass: &Arc<ComputePass>, own: ResourceTable| -> Result<BoundPass, RenderError> {
                Ok(pass.bind(ctx, &[&scene_table, &frame_table, &shared, &own])?)
            };
        let trace = (
            bind(
                &pipelines.trace,
                ResourceTable::new()
                    .texture("target_lambert", &r.lambert.view)
                    .texture("target_glossy", &r.glossy.view),
            )?,
            image,
        );
        let filter = |pass: usize, source: &wgpu::TextureView, target: &wgpu::TextureView| {
            bind(
                &pipelines.filter,
                ResourceTable::new()
                    .buffer("filter_pass", &r.filter_passes[pass])
                    .texture("filter_source", source)
                    .texture("filter_target", target),
            )
            .map(|p| (p, image))
        };
        let scratch = &r.filter_scratch.view;
        let s = &settings.shade;
        let mut filters = Vec::new();
        if s.algorithm == ShadingAlgorithm::Filtered {
            filters.push(filter(0, &r.lambert.view, scratch)?);
            filters.push(filter(1, scratch, &r.lambert_spatial.view)?);
        }
        if s.algorithm != ShadingAlgorithm::Naive && s.glossy {
            filters.push(filter(2, &r.glossy.view, scratch)?);
            filters.push(filter(3, scratch, &r.glossy_spatial.view)?);
        }
        let temporal = |now: usize| {
            let before = 1 - now;
            bind(
                &pipelines.temporal,
                ResourceTable::new()
                    .texture("lambert_now", &r.lambert_spatial.view)
                    .texture("glossy_now", &r.glossy_spatial.view)
                    .texture("lambert_history", &r.lambert_history[before].view)
                    .texture("glossy_history", &r.glossy_history[before].view)
                    .texture("geometry_history", &r.geometry_history[before].view)
                    .texture("lambert_filtered", &r.lambert_history[now].view)
                    .texture("glossy_filtered", &r.glossy_history[now].view)
                    .texture("geometry_filtered", &r.geometry_history[now].view),
            )
            .map(|p| (p, image))
        };
        let resolve = |now: usize| {
            // The naive renderer resolves its traced light as it is; the others their filtered
            // light (the fast path without glossy rays: a glossy buffer never written, zeros).
            let (lambert, glossy) = if s.algorithm == ShadingAlgorithm::Naive {
                (&r.lambert.view, &r.glossy.view)
            } else {
                (&r.lambert_history[now].view, &r.glossy_history[now].view)
            };
            bind(
                &pipelines.resolve,
                ResourceTable::new()
                    .texture("lambert_light", lambert)
                    .texture("glossy_light", glossy)
                    .texture("coarse_irradiance", &r.coarse_irradiance.view)
                    .texture("coarse_normal", &r.coarse_normal.view),
            )
            .map(|p| (p, image))
        };
        let view = (bind(&pipelines.view, ResourceTable::new())?, image);
        let irradiance = (
            bind(
                &pipelines.irradiance,
                ResourceTable::new()
                    .texture("target_coarse_irradiance", &r.coarse_irradiance.view)
                    .texture("target_coarse_normal", &r.coarse_normal.view),
            )?,
            block_image(size, settings.shade.irradiance_block.max(1)),
        );
        let mut lightfield = Self {
            name,
            settings: settings.clone(),
            atlas,
            trace,
            filters,
            temporal: [temporal(0)?, temporal(1)?],
            resolve: [resolve(0)?, resolve(1)?],
            irradiance,
            view,
            max_distance,
            frames: 0,
            bake: BakeReport {
                milliseconds: 0.0,
                bytes: 0,
                cached: false,
            },
            grid,
            resources,
            pipelines,
        };
        lightfield.write_filter_passes(ctx);
        lightfield.bake = lightfield.bake_or_load(cx)?;
        Ok(lightfield)
    }

    /// The settings it runs with.
    pub fn settings(&self) -> &LightfieldSettings {
        &self.settings
    }

    /// The probe grid, before relocation.
    pub fn grid(&self) -> &ProbeGrid {
        &self.grid
    }

    /// What the bake cost (or the cache's upload).
    pub fn bake_report(&self) -> BakeReport {
        self.bake
    }

    /// The parameters of a pass: the bake's `bounce`, or the frame's.
    pub fn params(&self, bounce: u32) -> GpuLightfieldParams {
        let b = &self.settings.bake;
        let s = &self.settings.shade;
        let spacing = self.grid.min_spacing();
        let (algorithm, lambert_rays, glossy_rays) = match s.algorithm {
            ShadingAlgorithm::Naive => (ALGORITHM_NAIVE, s.naive_rays, s.naive_rays),
            ShadingAlgorithm::Filtered => (ALGORITHM_FILTERED, 1, 1),
            ShadingAlgorithm::Prefiltered => (ALGORITHM_PREFILTERED, 0, 1),
        };
        let valid = self.frames > 0;
        GpuLightfieldParams {
            origin: self.grid.origin.to_array(),
            probe_count: self.grid.probe_count,
            spacing: self.grid.spacing.to_array(),
            resolution: b.resolution,
            counts: self.grid.counts.to_array(),
            low_resolution: b.resolution / MIN_MIP_FACTOR,
            min_thickness: s.min_thickness * spacing,
            max_thickness: s.max_thickness * spacing,
            thickness_distance: spacing,
            max_probe_visits: s.max_probe_visits,
            max_distance: self.max_distance,
            prefilter_resolution: self.settings.prefilter_side(),
            emitter_samples: b.emitter_samples,
            bounce,
            algorithm,
            lambert_rays,
            glossy_rays: if s.glossy { glossy_rays } else { 0 },
            frame: self.frames,
            lambert_hysteresis: if valid { s.lambert_hysteresis } else { 0.0 },
            glossy_hysteresis: if valid { s.glossy_hysteresis } else { 0.0 },
            history_valid: valid as u32,
            irradiance_block: s.irradiance_block,
            glossy_max_roughness: s.glossy_max_roughness,
            _pad0: 0,
            _pad1: 0,
            _pad2: 0,
        }
    }

    /// DDGI's volume uniform for the prefiltered atlases: no relocation, every probe live,
    /// backface and Chebyshev weights.
    fn volume(&self) -> GpuDdgiVolume {
        let b = &self.settings.bake;
        let mut v = GpuDdgiVolume::zeroed();
        v.origin = self.grid.origin.to_array();
        v.probe_count = self.grid.probe_count;
        v.spacing = self.grid.spacing.to_array();
        v.counts = self.grid.counts.to_array();
        v.probes_per_row = self.atlas.probes_per_row;
        v.irradiance_texels = b.irradiance_texels;
        v.distance_texels = b.distance_texels;
        v.max_ray_distance = self.max_distance;
        v.self_shadow_bias = self.settings.shade.self_shadow_bias;
        v.distance_exponent = b.distance_exponent;
        v.irradiance_gamma = IRRADIANCE_GAMMA;
        v.weights = WEIGHT_BACKFACE | WEIGHT_CHEBYSHEV;
        v.min_spacing = self.grid.min_spacing();
        v.state_phase = STATES_OFF;
        v.volume_is_last = 1;
        // lightfield/relocate marks no probe tied (w of its offsets stays 0): moving the light
        // field's swallowed probes towards the middle as DDGI's made box-cylinders' FLIP
        // 0.1869 → 0.1921 on the H100 (docs/lightfield.md).
        v.tied_probe_weight = 1.0;
        v
    }

    fn write_filter_passes(&self, ctx: &GpuContext) {
        let s = &self.settings.shade;
        let passes = [
            ([1, 0], s.lambert_radius, s.lambert_stride),
            ([0, 1], s.lambert_radius, s.lambert_stride),
            ([1, 0], s.glossy_radius, 1),
            ([0, 1], s.glossy_radius, 1),
        ];
        for (buffer, (direction, radius, stride)) in self.resources.filter_passes.iter().zip(passes)
        {
            let pass = GpuLightfieldFilterPass {
                direction,
                radius,
                stride,
            };
            ctx.queue.write_buffer(buffer, 0, bytemuck::bytes_of(&pass));
        }
    }

    /// Bytes of the baked data.
    fn baked_bytes(&self) -> u64 {
        let maps = &self.resources.maps;
        let textures: u64 = maps
            .in_cache_order()
            .iter()
            .map(|(t, texel)| {
                let s = t.size();
                s.width as u64 * s.height as u64 * s.depth_or_array_layers as u64 * *texel as u64
            })
            .sum();
        textures + maps.states.size()
    }

    /// Every probe's position: its grid position moved by lightfield/relocate.
    pub fn probe_positions(&self, ctx: &GpuContext) -> Result<Vec<Vec3>, RenderError> {
        let offsets: Vec<[f32; 4]> = read_buffer_as(ctx, &self.resources.maps.offsets)?;
        Ok((0..self.grid.probe_count)
            .map(|p| self.grid.probe_position(p) + Vec3::from_slice(&offsets[p as usize][..3]))
            .collect())
    }

    /// Every probe's state word (ddgi::constants: PROBE_OFF for probes inside geometry).
    pub fn read_probe_states(&self, ctx: &GpuContext) -> Result<Vec<u32>, RenderError> {
        let mut states: Vec<u32> = read_buffer_as(ctx, &self.resources.maps.states)?;
        states.truncate(self.grid.probe_count as usize);
        Ok(states)
    }

    /// Traces `rays` through the light field alone (tests and the agreement figures).
    pub fn trace_rays(
        &self,
        ctx: &GpuContext,
        gpu_scene: &crate::scene::GpuScene,
        frame: &crate::frame::Frame,
        rays: &[GpuRay],
    ) -> Result<Vec<GpuLightfieldHit>, RenderError> {
        use wgpu::util::DeviceExt;
        let device = &ctx.device;
        let ray_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("lightfield/test_rays"),
            contents: bytemuck::cast_slice(rays),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let hits = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lightfield/test_hits"),
            size: (rays.len().max(1) * size_of::<GpuLightfieldHit>()) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let scene_table = gpu_scene.resources();
        let frame_table = frame.resources.table();
        let shared = self.resources.table();
        let own = ResourceTable::new()
            .buffer("test_rays", &ray_buffer)
            .buffer("test_hits", &hits);
        let pass = self
            .pipelines
            .trace_rays
            .bind(ctx, &[&scene_table, &frame_table, &shared, &own])?;
        ctx.queue.write_buffer(
            &self.resources.params,
            0,
            bytemuck::bytes_of(&self.params(0)),
        );
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("lightfield/trace_rays"),
            });
        pass.dispatch(
            &mut encoder,
            None,
            Workgroups::for_threads(rays.len() as u64, 64),
        );
        ctx.queue.submit([encoder.finish()]);
        let mut out: Vec<GpuLightfieldHit> = read_buffer_as(ctx, &hits)?;
        out.truncate(rays.len());
        Ok(out)
    }

    fn record_frame(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        let now = self.frames as usize % 2;
        let s = &self.settings.shade;
        let traces = s.algorithm != ShadingAlgorithm::Prefiltered || s.glossy;
        if traces {
            let (pass, groups) = &self.trace;
            pass.dispatch(encoder, profiler.as_deref_mut(), *groups);
            for (pass, groups) in &self.filters {
                pass.dispatch(encoder, profiler.as_deref_mut(), *groups);
            }
            if s.algorithm != ShadingAlgorithm::Naive {
                let (pass, groups) = &self.temporal[now];
                pass.dispatch(encoder, profiler.as_deref_mut(), *groups);
            }
        }
        if s.algorithm == ShadingAlgorithm::Prefiltered && s.irradiance_block > 1 {
            let (pass, groups) = &self.irradiance;
            pass.dispatch(encoder, profiler.as_deref_mut(), *groups);
        }
        let (pass, groups) = &self.resolve[now];
        pass.dispatch(encoder, profiler, *groups);
        self.frames += 1;
    }
}

/// One texel of a probe's baked maps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeTexel {
    /// Radiance leaving the nearest surface towards the probe (emission excluded).
    pub radiance: Vec3,
    /// That surface's normal.
    pub normal: Vec3,
    /// Radial distance from the probe to that surface.
    pub distance: f32,
}

impl ProbeTexel {
    /// The CPU twin of lightfield.wgsl's unpacking.
    pub fn unpack(radiance: u32, geometry: u32) -> Self {
        let channel = |bits: u32| half::f16::from_bits(bits as u16).to_f32();
        let radiance = Vec3::new(
            channel((radiance & 0x7ff) << 4),
            channel(((radiance >> 11) & 0x7ff) << 4),
            channel(((radiance >> 22) & 0x3ff) << 5),
        );
        let oct = glam::Vec2::new(
            (geometry & 0xff) as f32 / 255.0,
            ((geometry >> 8) & 0xff) as f32 / 255.0,
        ) * 2.0
            - 1.0;
        Self {
            radiance,
            normal: crate::probes::octahedral::oct_decode(oct),
            distance: half::f16::from_bits((geometry >> 16) as u16).to_f32(),
        }
    }
}

impl Technique for Lightfield {
    fn name(&self) -> &'static str {
        self.name
    }
    fn passes(&self) -> TechniquePasses {
        TechniquePasses {
            update: Vec::new(),
            resolve: vec![TRACE, FILTER, TEMPORAL, IRRADIANCE, RESOLVE],
        }
    }
    fn prepare(&mut self, ctx: &GpuContext, _camera: &Camera) {
        ctx.queue.write_buffer(
            &self.resources.params,
            0,
            bytemuck::bytes_of(&self.params(0)),
        );
    }
    /// The probes are baked: each frame traces and resolves at resolve time.
    fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut Profiler>) {
        self.record_frame(encoder, profiler);
    }
    /// Light-field probes have no states: both views draw them lit by their radiance.
    fn visualize(&self, encoder: &mut wgpu::CommandEncoder, _view: ProbeView) {
        let (pass, groups) = &self.view;
        pass.dispatch(encoder, None, *groups);
    }
    fn invalidate(&mut self) {
        self.frames = 0;
    }
    fn reconfigure(&mut self, ctx: &GpuContext, spec: &TechniqueSpec) -> Result<bool, RenderError> {
        if spec.name != self.name {
            return Ok(false);
        }
        let kind = match self.settings.shade.algorithm {
            ShadingAlgorithm::Prefiltered => &LIGHTFIELD,
            ShadingAlgorithm::Filtered => &LIGHTFIELD_TRACED,
            ShadingAlgorithm::Naive => &LIGHTFIELD_NAIVE,
        };
        let settings = kind.settings(spec, &mut Vec::new())?;
        // The bake and the passes' shapes (algorithm, glossy, irradiance blocks) need
        // a rebuild; the shading
        // numbers change live.
        let same_shape = settings.bake == self.settings.bake
            && settings.shade.algorithm == self.settings.shade.algorithm
            && settings.shade.glossy == self.settings.shade.glossy
            && settings.shade.irradiance_block == self.settings.shade.irradiance_block;
        if !same_shape {
            return Ok(false);
        }
        self.settings = settings;
        self.write_filter_passes(ctx);
        // The irradiance query's self-shadow bias.
        ctx.queue.write_buffer(
            &self.resources.volume,
            0,
            bytemuck::bytes_of(&self.volume()),
        );
        Ok(true)
    }
    fn check_state(&self, ctx: &GpuContext) -> Result<Vec<String>, RenderError> {
        // The set the last frame wrote: its filtered light is next frame's history.
        let last = (self.frames + 1) as usize % 2;
        let r = &self.resources;
        let mut all = Vec::new();
        for (label, texture) in [
            (
                "lightfield lambertian history",
                &r.lambert_history[last].texture,
            ),
            ("lightfield glossy history", &r.glossy_history[last].texture),
        ] {
            let bytes = irradiant_gpu::read_texture(ctx, texture, 8)?;
            let halves: &[half::f16] = bytemuck::cast_slice(&bytes);
            all.extend(non_finite(label, halves.iter().map(|h| h.to_f32())));
        }
        Ok(all)
    }
    fn inspect(&self, ctx: &GpuContext) -> Result<crate::inspect::Inspection, RenderError> {
        self.inspect_maps(ctx)
    }
    fn counters(&self, _ctx: &GpuContext) -> Result<Vec<Counter>, RenderError> {
        Ok(vec![
            Counter {
                name: "bake_ms",
                value: self.bake.milliseconds,
            },
            Counter {
                name: "bake_bytes",
                value: self.bake.bytes as f64,
            },
            Counter {
                name: "bake_cached",
                value: self.bake.cached as u32 as f64,
            },
            Counter {
                name: "probes",
                value: self.grid.probe_count as f64,
            },
        ])
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}
