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
pub mod cache;
pub mod constants;
mod resources;
mod settings;
pub mod types;

pub use cache::{EntryLayout, bake_key, parse_entry};
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
use crate::technique::{
    Counter, Technique, TechniqueContext, TechniqueKind, TechniquePasses, TechniqueSpec, non_finite,
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

pub struct LightfieldKind {
    algorithm: ShadingAlgorithm,
}

impl LightfieldKind {
    pub fn settings(
        &self,
        spec: &TechniqueSpec,
        warnings: &mut Vec<String>,
    ) -> Result<LightfieldSettings, RenderError> {
        Ok(LightfieldSettings::from_spec(
            spec,
            self.algorithm,
            warnings,
        )?)
    }
}

/// The probe grid the settings ask for: the scene's first probe volume (or the default one
/// over its bounds); with the bake's own probe counts, that many probes at the centres of as
/// many equal cells of the volume's box (or the scene's bounds), so that a coarse grid keeps
/// its probes off the walls the box touches.
pub fn grid_of(scene: &Scene, settings: &LightfieldSettings) -> Result<ProbeGrid, RenderError> {
    let mut desc = crate::probes::volumes_of(scene).remove(0);
    let counts = settings.bake.probe_counts;
    if counts != [0, 0, 0] {
        let (lo, hi) = match scene.probe_volumes.first() {
            Some(v) => (v.min, v.max),
            None => scene.bounds(),
        };
        let extent = (hi - lo).max(Vec3::splat(1e-3));
        let inset = extent / glam::UVec3::from(counts).as_vec3() * 0.5;
        desc.min = lo + inset;
        desc.max = hi - inset;
        desc.counts = counts;
    }
    let grid = ProbeGrid::new(&desc);
    if grid.probe_count > MAX_PROBES {
        return Err(RenderError::Settings(format!(
            "technique.bake.probe_counts: {} probes are more than one bake dispatch holds ({MAX_PROBES}); use fewer probes",
            grid.probe_count
        )));
    }
    Ok(grid)
}

fn map_groups(side: u32, probes: u32) -> Workgroups {
    Workgroups::for_layers(side, side, probes, MAP_TILE)
}

/// The bake's dispatches, each with its label, in order.
fn bake_dispatches(grid: &ProbeGrid, s: &LightfieldSettings) -> Vec<(&'static str, Workgroups)> {
    let b = &s.bake;
    let probes = grid.probe_count;
    let tile = b.irradiance_texels.max(b.distance_texels) + 2;
    let geometry = (BAKE[0], map_groups(b.resolution, probes));
    let per_probe = Workgroups::linear(probes as u64);
    let mut all = vec![geometry];
    for _ in 0..b.relocation_steps {
        all.extend([(BAKE[1], per_probe), geometry]);
    }
    all.extend([
        (BAKE[2], map_groups(b.resolution / MIN_MIP_FACTOR, probes)),
        (BAKE[3], per_probe),
    ]);
    for _ in 0..=b.bounces {
        all.extend([
            (BAKE[4], map_groups(b.resolution, probes)),
            (BAKE[5], map_groups(s.prefilter_side(), probes)),
            (BAKE[6], map_groups(tile, probes)),
        ]);
    }
    all
}

/// A thread a block of the fast path's irradiance.
fn block_image((width, height): (u32, u32), block: u32) -> Workgroups {
    Workgroups::for_image(width.div_ceil(block), height.div_ceil(block), IMAGE_TILE)
}

/// The frame's dispatches, each with its label, in order.
fn frame_dispatches(s: &LightfieldSettings, size: (u32, u32)) -> Vec<(&'static str, Workgroups)> {
    let image = Workgroups::for_image(size.0, size.1, IMAGE_TILE);
    let glossy = s.shade.glossy;
    let mut all = Vec::new();
    match s.shade.algorithm {
        ShadingAlgorithm::Naive => all.push((TRACE, image)),
        ShadingAlgorithm::Filtered => {
            all.push((TRACE, image));
            let filters = if glossy { 4 } else { 2 };
            all.extend(std::iter::repeat_n((FILTER, image), filters));
            all.push((TEMPORAL, image));
        }
        ShadingAlgorithm::Prefiltered if glossy => {
            all.extend([(TRACE, image), (FILTER, image), (FILTER, image)]);
            all.push((TEMPORAL, image));
        }
        ShadingAlgorithm::Prefiltered => {}
    }
    if s.shade.algorithm == ShadingAlgorithm::Prefiltered && s.shade.irradiance_block > 1 {
        all.push((IRRADIANCE, block_image(size, s.shade.irradiance_block)));
    }
    all.push((RESOLVE, image));
    all
}

impl TechniqueKind for LightfieldKind {
    fn name(&self) -> &'static str {
        match self.algorithm {
            ShadingAlgorithm::Prefiltered => "lightfield",
            ShadingAlgorithm::Filtered => "lightfield-traced",
            ShadingAlgorithm::Naive => "lightfield-naive",
        }
    }
    fn description(&self) -> &'static str {
        match self.algorithm {
            ShadingAlgorithm::Prefiltered => {
                "light-field probes: prefiltered irradiance with visibility, a filtered glossy ray"
            }
            ShadingAlgorithm::Filtered => {
                "light-field probes: a Lambertian and a glossy ray a pixel, filtered"
            }
            ShadingAlgorithm::Naive => "light-field probes: Monte Carlo rays, unfiltered",
        }
    }
    fn check(&self, spec: &TechniqueSpec) -> Result<Vec<String>, RenderError> {
        let mut warnings = Vec::new();
        self.settings(spec, &mut warnings)?;
        Ok(warnings)
    }
    fn plan(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<Allocation>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        Ok(resources::plan(
            &grid_of(scene, &settings)?,
            &settings,
            size,
        ))
    }
    fn dispatches(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<(&'static str, Workgroups)>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        let mut all = bake_dispatches(&grid_of(scene, &settings)?, &settings);
        all.extend(frame_dispatches(&settings, size));
        all.push((
            "lightfield/view",
            Workgroups::for_image(size.0, size.1, IMAGE_TILE),
        ));
        Ok(all)
    }
    fn build(
        &self,
        cx: &TechniqueContext,
        spec: &TechniqueSpec,
    ) -> Result<Box<dyn Technique>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        Ok(Box::new(Lightfield::new(cx, self.name(), &settings)?))
    }
}

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

/// DDGI's query reads the distance atlas (rg32float) by gathers: not filterable everywhere.
const UNFILTERABLE: &[&str] = &["distance_texture"];

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
                desc = desc.unfilterable(UNFILTERABLE);
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

/// What the bake cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakeReport {
    /// Wall-clock milliseconds from the first bake pass to the GPU's finishing the last (or to
    /// the cache entry's upload).
    pub milliseconds: f64,
    /// Bytes of the baked probe data (the maps and the prefiltered atlases).
    pub bytes: u64,
    /// Read from the disk cache.
    pub cached: bool,
}

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

/// lightfield/prefilter sums every texel of a probe's reduced map, twice (irradiance and
/// distance), in one invocation: 2 × prefilter_resolution² loop iterations. Where the adapter
/// ends an invocation's loops past a limit (llvmpipe), a larger map would be summed only in
/// part, silently; it is refused instead, naming the setting.
fn check_prefilter_loops(
    settings: &LightfieldSettings,
    info: &irradiant_gpu::GpuInfo,
) -> Result<(), RenderError> {
    let Some(limit) = info.loop_iteration_limit else {
        return Ok(());
    };
    let size = settings.prefilter_side() as u64;
    if 2 * size * size < limit as u64 {
        return Ok(());
    }
    // The largest power of two under the limit.
    let root = (limit as f64 / 2.0).sqrt() as u32;
    let largest = 1u32 << (31 - root.leading_zeros());
    Err(SettingsError::invalid(
        "technique.bake.prefilter_resolution",
        size,
        format!(
            "{largest} or less on {}, which ends a shader invocation's loops after {limit} \
             iterations and would sum only part of each map (2 × {size}² texels); or pick a \
             hardware GPU with --adapter",
            info.name
        ),
    )
    .into())
}

impl Lightfield {
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

    pub fn settings(&self) -> &LightfieldSettings {
        &self.settings
    }

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

    fn bake_or_load(&mut self, cx: &TechniqueContext) -> Result<BakeReport, RenderError> {
        let ctx = cx.ctx;
        let start = Instant::now();
        let key = bake_key(
            cx.scene,
            &self.grid,
            &self.settings.bake,
            self.settings.shade.self_shadow_bias,
        );
        let file = cx.cache_dir.map(|dir| cache::entry_path(dir, key));
        let bytes = self.baked_bytes();
        if let Some(file) = &file
            && cache::load(ctx, file, key, &self.resources.maps)?
        {
            ctx.queue.write_buffer(
                &self.resources.volume,
                0,
                bytemuck::bytes_of(&self.volume()),
            );
            ctx.check("uploading cached light-field probes")?;
            return Ok(BakeReport {
                milliseconds: start.elapsed().as_secs_f64() * 1e3,
                bytes,
                cached: true,
            });
        }
        self.bake_now(cx)?;
        let report = BakeReport {
            milliseconds: start.elapsed().as_secs_f64() * 1e3,
            bytes,
            cached: false,
        };
        if let Some(file) = &file {
            cache::store(ctx, file, key, &self.resources.maps)?;
        }
        Ok(report)
    }

    /// Bakes the probes: one submission a step, each waited on, so that progress is real.
    fn bake_now(&mut self, cx: &TechniqueContext) -> Result<(), RenderError> {
        let ctx = cx.ctx;
        let r = &self.resources;
        let p = &self.pipelines;
        let scene_table = cx.gpu_scene.resources();
        let frame_table = cx.frame.resources.table();
        let shared = r.table();
        let bind =
            |pass: &Arc<ComputePass>, own: ResourceTable| -> Result<BoundPass, RenderError> {
                Ok(pass.bind(ctx, &[&scene_table, &frame_table, &shared, &own])?)
            };
        ctx.queue
            .write_buffer(&r.volume, 0, bytemuck::bytes_of(&self.volume()));
        let geometry = bind(
            &p.bake_geometry,
            ResourceTable::new().texture("target_geometry", &r.maps.geometry.view),
        )?;
        let relocate = bind(
            &p.relocate,
            ResourceTable::new().buffer("target_probe_offsets", &r.maps.offsets),
        )?;
        let min_mip = bind(
            &p.min_mip,
            ResourceTable::new().texture("target_low", &r.maps.low.view),
        )?;
        let states = bind(
            &p.probe_states,
            ResourceTable::new().buffer("target_probe_states", &r.maps.states),
        )?;
        let radiance = bind(
            &p.bake_radiance,
            ResourceTable::new().texture("target_radiance", &r.maps.radiance.view),
        )?;
        let reduce = bind(
            &p.reduce,
            ResourceTable::new()
                .texture("target_small_radiance", &r.small_radiance.view)
                .texture("target_small_moments", &r.small_moments.view),
        )?;
        let prefilter = bind(
            &p.prefilter,
            ResourceTable::new()
                .texture("small_radiance", &r.small_radiance.view)
                .texture("small_moments", &r.small_moments.view)
                .texture("target_irradiance", &r.maps.irradiance.view)
                .texture("target_distance", &r.maps.distance.view),
        )?;
        let dispatches = bake_dispatches(&self.grid, &self.settings);
        let passes = [
            &geometry, &relocate, &min_mip, &states, &radiance, &reduce, &prefilter,
        ];
        // Bounce n's radiance, reduce and prefilter come after everything else.
        let first_bounce_step = dispatches.len() - 3 * (self.settings.bake.bounces as usize + 1);
        let steps = dispatches.len() as u32;
        let progress = cx.progress;
        let report = |done: u32| {
            if let Some(progress) = progress {
                progress.report("baking light-field probes", done, steps);
            }
        };
        report(0);
        for (step, (label, groups)) in dispatches.iter().enumerate() {
            let bounce = (step.saturating_sub(first_bounce_step) / 3) as u32;
            ctx.queue
                .write_buffer(&r.params, 0, bytemuck::bytes_of(&self.params(bounce)));
            let pass = passes[BAKE.iter().position(|b| b == label).expect("a bake pass")];
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
            pass.dispatch(&mut encoder, None, *groups);
            ctx.queue.submit([encoder.finish()]);
            ctx.wait()?;
            report(step as u32 + 1);
        }
        ctx.check("baking light-field probes")?;
        Ok(())
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

    /// One probe's maps as baked: (radiance rgb, normal, distance) a texel, rows of
    /// `resolution` texels.
    pub fn read_probe(&self, ctx: &GpuContext, probe: u32) -> Result<Vec<ProbeTexel>, RenderError> {
        let res = self.settings.bake.resolution as usize;
        let layer = res * res * 4;
        let at = probe as usize * layer;
        let radiance = irradiant_gpu::read_texture(ctx, &self.resources.maps.radiance.texture, 4)?;
        let geometry = irradiant_gpu::read_texture(ctx, &self.resources.maps.geometry.texture, 4)?;
        let words =
            |bytes: &[u8]| -> Vec<u32> { bytemuck::pod_collect_to_vec(&bytes[at..at + layer]) };
        Ok(words(&radiance)
            .into_iter()
            .zip(words(&geometry))
            .map(|(r, g)| ProbeTexel::unpack(r, g))
            .collect())
    }

    /// Every probe's min-mip, layer after layer: the nearest distance of each 16×16 block.
    pub fn read_min_mip(&self, ctx: &GpuContext) -> Result<Vec<f32>, RenderError> {
        let bytes = irradiant_gpu::read_texture(ctx, &self.resources.maps.low.texture, 4)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
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
    pub radiance: Vec3,
    pub normal: Vec3,
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
    fn visualize(&self, encoder: &mut wgpu::CommandEncoder) {
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
