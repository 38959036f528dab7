//! DDGI: dynamic diffuse global illumination with ray-traced irradiance fields (Majercik et
//! al. 2019, as evaluated in seed 001), with the production rules of seed 003 (self-shadow
//! bias, perceptual encoding, convergence heuristics, backface hits, probe relocation and
//! probe states). See docs/ddgi.md.
//!
//! Each frame every volume records `ddgi/ray_directions → ddgi/trace → ddgi/shade →
//! (ddgi/shadow) → (ddgi/relocate) → ddgi/blend_weights → ddgi/blend_irradiance →
//! ddgi/blend_distance → ddgi/probe_states` (the blends fill their tiles' borders; trace, shade
//! and the blends are dispatched indirectly over the probes that update, which
//! ddgi/probe_states lists for the next frame), and `ddgi/resolve` blends its indirect diffuse
//! light into the frame's, finest volume first. With the final gather (`gather.rays_per_pixel`)
//! `ddgi/gather` traces rays from the pixels (or one pixel of each 2×2 block) whose hits the
//! probes light, `ddgi/temporal` averages them over frames, `ddgi/gather_filter` across the
//! image and `ddgi/gather_upsample` writes them over the query (gather.rs). The pipelines are
//! compiled once (pipelines.rs) and shared by every volume ([`DdgiVolume`]).

mod cascades;
pub mod constants;
mod gather;
pub mod oracle;
mod pipelines;
mod reflections;
mod resources;
pub mod saved;
mod settings;
pub mod types;
mod volume;

pub(crate) use pipelines::QUERY_UNFILTERABLE;
pub use resources::{
    ACTIVE_BLEND_GROUPS, ACTIVE_PROBES_HEADER, ACTIVE_RAY_GROUPS, ACTIVE_TRACE_GROUPS,
    ATLAS_TEXEL_BYTES, MAX_WAKE_BOXES, NEWLY_LIST, SHADOW_QUEUE_HEADER,
};
pub use settings::{
    DdgiGatherSettings, DdgiReflectionSettings, DdgiSettings, DdgiSpeedSettings,
    DdgiUpdateSettings, DdgiVolumeSettings, ProbeWeights, RELOCATION_FRAMES,
};
pub use volume::{Atlases, DdgiDispatches, DdgiVolume, ProbeStateCounts, VolumePlace};

use std::any::Any;

use irradiant_gpu::{Allocation, BoundPass, GpuContext, Profiler, ResourceTable, Workgroups, wgpu};
use irradiant_scene::{ProbeVolumeDesc, Scene};

use crate::RenderError;
use crate::frame::SceneChange;
use crate::settings::TechniqueSpec;
use crate::technique::{
    Counter, ProbeView, Technique, TechniqueContext, TechniqueKind, TechniquePasses,
};
use pipelines::DdgiPipelines;

/// The registry entry `ddgi`: the full method.
pub static DDGI: DdgiKind = DdgiKind { classic: false };
/// The registry entry `classic-probes`: DDGI's probes with trilinear weights only (no
/// visibility) and the cage clamped at the outermost probes, the classic irradiance probes the
/// paper improves on.
pub static CLASSIC_PROBES: DdgiKind = DdgiKind { classic: true };

/// A DDGI registry entry: the full method or classic probes.
pub struct DdgiKind {
    classic: bool,
}

impl DdgiKind {
    /// The settings a spec asks for (classic probes force trilinear weights, no extrapolation
    /// past the outermost probes, no traced bounce and no final gather: the baseline the paper
    /// improves on).
    pub fn settings(
        &self,
        spec: &TechniqueSpec,
        warnings: &mut Vec<String>,
    ) -> Result<DdgiSettings, RenderError> {
        let mut settings = DdgiSettings::from_spec(spec, warnings)?;
        if self.classic {
            settings.update.weights = ProbeWeights::Classic;
            settings.update.extrapolation = 0.0;
            settings.update.traced_bounce = false;
            settings.update.blind_bounces = 0;
            settings.gather.rays_per_pixel = 0;
            settings.reflections.enabled = false;
            settings.update.light_between_volumes = false;
        }
        Ok(settings)
    }
}

/// The volumes of a scene with the settings' probe counts applied (or the settings'
/// cascades in their place), finest first.
pub fn volume_descs(scene: &Scene, settings: &DdgiSettings) -> Vec<ProbeVolumeDesc> {
    let v = &settings.volume;
    if v.cascades > 0 {
        return cascades::descs(scene.camera.position, v);
    }
    let mut volumes = crate::probes::volumes_of(scene);
    if settings.volume.probe_counts != [0; 3] {
        for v in &mut volumes {
            v.counts = settings.volume.probe_counts;
        }
    }
    if let Some(follow) = irradiant_scene::Follow::parse(&settings.volume.follow) {
        for v in &mut volumes {
            v.follow = Some(follow.clone());
        }
    }
    let spacing = |v: &ProbeVolumeDesc| crate::probes::ProbeGrid::new(v).min_spacing();
    volumes.sort_by(|a, b| spacing(a).total_cmp(&spacing(b)));
    volumes
}

impl TechniqueKind for DdgiKind {
    fn name(&self) -> &'static str {
        if self.classic {
            "classic-probes"
        } else {
            "ddgi"
        }
    }
    fn description(&self) -> &'static str {
        if self.classic {
            "DDGI's probes with trilinear weights only (no visibility)"
        } else {
            "DDGI, full method"
        }
    }
    fn check(&self, spec: &TechniqueSpec) -> Result<Vec<String>, RenderError> {
        let mut warnings = Vec::new();
        self.settings(spec, &mut warnings)?;
        Ok(warnings)
    }
    fn resolved_settings(&self, spec: &TechniqueSpec) -> Result<toml::Table, RenderError> {
        Ok(crate::settings::as_table(
            &self.settings(spec, &mut Vec::new())?,
        ))
    }
    fn setting_doc(&self, _spec: &TechniqueSpec, path: &[&str]) -> Option<&'static str> {
        <DdgiSettings as crate::settings::SettingDocs>::setting_doc(path)
    }
    fn scene_warnings(&self, spec: &TechniqueSpec, scene: &Scene) -> Vec<String> {
        let Ok(settings) = self.settings(spec, &mut Vec::new()) else {
            return Vec::new();
        };
        let descs = volume_descs(scene, &settings);
        let mut warnings = cascades::window_warnings(scene, &descs, settings.volume.cascades);
        warnings.extend(cascades::overlap_warnings(&descs));
        warnings
    }
    fn plan(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<Allocation>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        let descs = volume_descs(scene, &settings);
        let several = descs.len() > 1;
        let mut all: Vec<Allocation> = descs
            .iter()
            .flat_map(|desc| {
                resources::plan(&crate::probes::ProbeGrid::new(desc), &settings, several)
            })
            .collect();
        if settings.gather.rays_per_pixel > 0 {
            let g = &settings.gather;
            all.extend(gather::plan(size, g.filter_passes, g.half_resolution));
        }
        if settings.reflections.enabled {
            all.extend(reflections::plan(size));
        }
        Ok(all)
    }
    fn dispatches(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<(&'static str, Workgroups)>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        let mut all: Vec<(&'static str, Workgroups)> = volume_descs(scene, &settings)
            .iter()
            .flat_map(|desc| {
                // A ray a thread: the most workgroups ddgi/trace can take.
                let grid = crate::probes::ProbeGrid::new(desc);
                DdgiDispatches::new(&grid, &settings, size, false).all()
            })
            .collect();
        let g = &settings.gather;
        if g.rays_per_pixel > 0 {
            let own = gather::workgroups(size, g.half_resolution);
            all.extend([("ddgi/gather", own), ("ddgi/temporal", own)]);
            for _ in 0..g.filter_passes {
                all.push(("ddgi/gather_filter", own));
            }
            all.push(("ddgi/gather_upsample", gather::workgroups(size, false)));
        }
        if settings.reflections.enabled {
            all.push(("ddgi/reflect", settings.reflections.trace_workgroups(size)));
            all.push(("ddgi/reflect_filter", gather::workgroups(size, false)));
        }
        Ok(all)
    }
    fn build(
        &self,
        cx: &TechniqueContext,
        spec: &TechniqueSpec,
    ) -> Result<Box<dyn Technique>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        Ok(Box::new(Ddgi::new(cx, self.name(), &settings)?))
    }
}

/// DDGI over every probe volume of the scene, sharing one set of pipelines.
pub struct Ddgi {
    name: &'static str,
    settings: DdgiSettings,
    /// Finest first: the order ddgi/resolve blends them in.
    pub volumes: Vec<DdgiVolume>,
    /// The final gather's running mean, with `gather.rays_per_pixel` > 0.
    gather: Option<gather::GatherHistory>,
    /// The scene as the probes see it (saved.rs), and the volumes placed in it: what a saved
    /// probe file's key covers besides the settings.
    scene_key: u64,
    descs: Vec<ProbeVolumeDesc>,
    /// Frames updated, for the cascades' schedule.
    frames: u64,
    /// GI in glossy reflections (`reflections.enabled`), read from the finest volume.
    reflections: Option<reflections::Reflections>,
    /// With several volumes, for each volume its rays' ddgi/between_volumes passes: one bound
    /// to each volume, finest first.
    between: Vec<Vec<BoundPass>>,
}

/// ddgi/between_volumes bound for each volume's rays (the owner) to each volume's probes,
/// finest first.
fn bind_between_volumes(
    ctx: &GpuContext,
    pass: &std::sync::Arc<irradiant_gpu::ComputePass>,
    tables: &[&ResourceTable],
    volumes: &[DdgiVolume],
) -> Result<Vec<Vec<BoundPass>>, RenderError> {
    volumes
        .iter()
        .map(|owner| {
            let rays = owner.resources.owner_table();
            volumes
                .iter()
                .map(|source| {
                    let probes = source.resources.bounce_table();
                    let mut all = tables.to_vec();
                    all.extend([&probes, &rays]);
                    pass.bind(ctx, &all).map_err(RenderError::from)
                })
                .collect()
        })
        .collect()
}

impl Ddgi {
    /// The spacing of the finest volume's probes along its closest axis (scene units): the
    /// smallest detail of the light the probes resolve.
    pub fn finest_spacing(&self) -> f32 {
        self.descs
            .first()
            .map_or(0.0, |d| crate::probes::ProbeGrid::new(d).min_spacing())
    }

    /// Records the diffuse light into the frame's `indirect`: every volume's ddgi/resolve
    /// (finest first), and the final gather's passes (gather.rs).
    pub fn resolve_diffuse(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        for v in &self.volumes {
            v.record_resolve(encoder, profiler.as_deref_mut());
        }
        if let Some(gather) = &mut self.gather {
            gather.record(encoder, profiler);
        }
    }

    /// Records the glossy reflections (`reflections.enabled`), added to the frame's `indirect`
    /// after the diffuse light.
    pub fn resolve_reflections(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
    ) {
        if let Some(reflections) = &mut self.reflections {
            reflections.record(encoder, profiler);
        }
    }

    /// The finest volume's resources by name, for a pass of another technique that queries its
    /// probes (`ddgi_query`); None without volumes.
    pub fn finest_table(&self) -> Option<irradiant_gpu::ResourceTable<'_>> {
        self.volumes.first().map(|v| v.resources.table())
    }

    /// Validates the settings, compiles the pipelines once and builds a volume for each of the
    /// scene's probe volumes, bound to the frame.
    pub fn new(
        cx: &TechniqueContext,
        name: &'static str,
        settings: &DdgiSettings,
    ) -> Result<Self, RenderError> {
        settings.validate()?;
        let descs = volume_descs(cx.scene, settings);
        cascades::check_follow(cx.scene, &descs)?;
        let most_probe_rays = descs
            .iter()
            .map(|desc| {
                let probes = crate::probes::ProbeGrid::new(desc).probe_count;
                u64::from(probes) * u64::from(settings.volume.rays_per_probe)
            })
            .max()
            .unwrap_or(0);
        let pipelines =
            DdgiPipelines::new(cx.ctx, cx.gpu_scene, settings, descs.len(), most_probe_rays)?;
        let scene_table = cx.gpu_scene.resources();
        let frame_table = cx.frame.resources.table();
        let count = descs.len();
        let volumes = descs
            .iter()
            .enumerate()
            .map(|(i, desc)| {
                DdgiVolume::new(
                    cx.ctx,
                    &pipelines,
                    &[&scene_table, &frame_table],
                    desc,
                    settings,
                    VolumePlace {
                        index: i as u32,
                        is_last: i + 1 == count,
                    },
                    cx.frame.size(),
                    cx.gpu_scene.dynamic_bounds(),
                )
            })
            .collect::<Result<Vec<DdgiVolume>, _>>()?;
        let between = match &pipelines.between_volumes {
            Some(pass) => {
                bind_between_volumes(cx.ctx, pass, &[&scene_table, &frame_table], &volumes)?
            }
            None => Vec::new(),
        };
        let gather = match (&pipelines.gather, &pipelines.temporal) {
            (Some(gather), Some(temporal)) => {
                let tables: Vec<_> = volumes.iter().map(|v| v.resources.table()).collect();
                let passes = gather::GatherPipelines {
                    gather,
                    temporal,
                    filters: &pipelines.gather_filter,
                    half: settings.gather.half_resolution,
                };
                Some(gather::GatherHistory::new(
                    cx.ctx,
                    passes,
                    &[&scene_table, &frame_table],
                    &tables,
                    cx.frame.size(),
                )?)
            }
            _ => None,
        };
        let reflections = match &pipelines.reflections {
            Some((trace, filter)) => {
                let first = volumes[0].resources.table();
                Some(reflections::Reflections::new(
                    cx.ctx,
                    (trace, filter),
                    &[&scene_table, &frame_table, &first],
                    &settings.reflections,
                    cx.frame.size(),
                )?)
            }
            None => None,
        };
        Ok(Self {
            name,
            reflections,
            settings: settings.clone(),
            volumes,
            gather,
            scene_key: saved::scene_key(cx.scene, &cx.scene.pose_at(0.0)),
            descs,
            frames: 0,
            between,
        })
    }

    /// The settings it runs with.
    pub fn settings(&self) -> &DdgiSettings {
        &self.settings
    }

    /// The first (finest) volume: the only one where the scene has one.
    pub fn volume(&self) -> &DdgiVolume {
        &self.volumes[0]
    }

    /// The first (finest) volume, mutably.
    pub fn volume_mut(&mut self) -> &mut DdgiVolume {
        &mut self.volumes[0]
    }

    /// Probe states summed over the volumes.
    pub fn read_state_counts(&self, ctx: &GpuContext) -> Result<ProbeStateCounts, RenderError> {
        let mut total = ProbeStateCounts::default();
        for v in &self.volumes {
            let c = v.read_state_counts(ctx)?;
            total.vigilant += c.vigilant;
            total.off += c.off;
            total.sleeping += c.sleeping;
            total.awake += c.awake;
            total.newly_vigilant += c.newly_vigilant;
            total.newly_awake += c.newly_awake;
        }
        Ok(total)
    }

    /// Window steps taken so far, summed over the volumes (`DdgiVolume::window_steps`): a
    /// frame in which this grows brought probe planes in somewhere.
    pub fn window_steps(&self) -> u64 {
        self.volumes.iter().map(DdgiVolume::window_steps).sum()
    }

    /// Shadow rays queued in the last update, summed over the volumes.
    pub fn read_queued_shadow_rays(&self, ctx: &GpuContext) -> Result<u32, RenderError> {
        self.volumes
            .iter()
            .map(|v| v.read_queued_shadow_rays(ctx))
            .sum()
    }
}

impl Technique for Ddgi {
    fn name(&self) -> &'static str {
        self.name
    }
    fn passes(&self) -> TechniquePasses {
        let s = &self.settings;
        let mut update = vec!["ddgi/ray_directions"];
        if s.speed.fuse_trace_and_shade {
            update.push("ddgi/trace_shade");
        } else {
            update.extend(["ddgi/trace", "ddgi/shade"]);
        }
        if s.queues_shadow_rays() {
            update.push("ddgi/shadow");
        }
        if self.volumes.iter().any(DdgiVolume::reads_between_volumes) {
            update.push("ddgi/between_volumes");
        }
        update.extend([
            "ddgi/relocate",
            "ddgi/blend_weights",
            "ddgi/blend_irradiance",
            "ddgi/blend_distance",
            "ddgi/probe_states",
        ]);
        let mut resolve = vec!["ddgi/resolve"];
        if s.gather.rays_per_pixel > 0 {
            resolve.extend(["ddgi/gather", "ddgi/temporal"]);
            if s.gather.filter_passes > 0 {
                resolve.push("ddgi/gather_filter");
            }
            resolve.push("ddgi/gather_upsample");
        }
        if s.reflections.enabled {
            resolve.extend(["ddgi/reflect", "ddgi/reflect_filter"]);
        }
        TechniquePasses { update, resolve }
    }
    fn prepare(&mut self, ctx: &GpuContext, camera: &irradiant_scene::Camera) {
        for v in &mut self.volumes {
            v.follow(camera.position);
            v.prepare(ctx);
        }
    }
    fn update(&mut self, encoder: &mut wgpu::CommandEncoder, mut profiler: Option<&mut Profiler>) {
        let cascades = self.settings.volume.cascades;
        // Every window's entered planes start over first, updating or not: a finer volume's
        // rays read the coarser ones (ddgi/between_volumes), whose uniforms already hold this
        // frame's step, before those volumes' own turn.
        for v in &mut self.volumes {
            v.record_window_enter(encoder, profiler.as_deref_mut());
        }
        for (i, v) in self.volumes.iter_mut().enumerate() {
            if cascades == 0 || cascades::updates(i as u32, cascades, self.frames) {
                let between = self.between.get(i).map_or(&[][..], Vec::as_slice);
                v.record_update(encoder, profiler.as_deref_mut(), between);
            }
        }
        self.frames += 1;
    }
    fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, mut profiler: Option<&mut Profiler>) {
        self.resolve_diffuse(encoder, profiler.as_deref_mut());
        self.resolve_reflections(encoder, profiler);
    }
    fn visualize(&self, encoder: &mut wgpu::CommandEncoder, view: ProbeView) {
        for v in &self.volumes {
            v.record_visualize(encoder, view);
        }
    }
    fn invalidate(&mut self) {
        for v in &mut self.volumes {
            v.reset();
        }
    }
    fn scene_changed(&mut self, change: &SceneChange) {
        for v in &mut self.volumes {
            v.scene_changed(change);
        }
    }
    fn pose_changed(&mut self, scene: &Scene, pose: &irradiant_scene::Pose) {
        for v in &mut self.volumes {
            v.follow_pose(scene, pose);
        }
    }
    fn reconfigure(
        &mut self,
        _ctx: &GpuContext,
        spec: &TechniqueSpec,
    ) -> Result<bool, RenderError> {
        let kind = match spec.name.as_str() {
            name if name == CLASSIC_PROBES.name() => &CLASSIC_PROBES,
            name if name == DDGI.name() => &DDGI,
            _ => return Ok(false),
        };
        let settings = kind.settings(spec, &mut Vec::new())?;
        if !settings.same_build(&self.settings) {
            return Ok(false);
        }
        for v in &mut self.volumes {
            v.set_settings(&settings);
        }
        self.settings = settings;
        Ok(true)
    }
    fn check_state(&self, ctx: &GpuContext) -> Result<Vec<String>, RenderError> {
        let mut all = Vec::new();
        for volume in &self.volumes {
            all.extend(volume.check_state(ctx)?);
        }
        Ok(all)
    }
    fn inspect(&self, ctx: &GpuContext) -> Result<crate::inspect::Inspection, RenderError> {
        let mut out = crate::inspect::Inspection::default();
        for (i, volume) in self.volumes.iter().enumerate() {
            let label = if self.volumes.len() > 1 {
                format!(", volume {i}")
            } else {
                String::new()
            };
            volume.inspect(ctx, &label, &mut out)?;
        }
        Ok(out)
    }
    fn counters(&self, ctx: &GpuContext) -> Result<Vec<Counter>, RenderError> {
        let probes: u32 = self.volumes.iter().map(|v| v.grid.probe_count).sum();
        let rays = self.settings.volume.rays_per_probe as f64;
        let mut updating = 0;
        for v in &self.volumes {
            updating += v.read_updating_probes(ctx)?;
        }
        let states = self.read_state_counts(ctx)?;
        let counters = [
            ("probes_vigilant", states.vigilant as f64),
            ("probes_awake", states.awake as f64),
            ("probes_newly_vigilant", states.newly_vigilant as f64),
            ("probes_newly_awake", states.newly_awake as f64),
            ("probes_sleeping", states.sleeping as f64),
            ("probes_off", states.off as f64),
            ("probes", probes as f64),
            ("updating_probes", updating as f64),
            // The paper's Table 2 counts every probe's rays; sleeping probes trace none.
            ("probe_rays", probes as f64 * rays),
            ("traced_rays", updating as f64 * rays),
            (
                "queued_shadow_rays",
                self.read_queued_shadow_rays(ctx)? as f64,
            ),
        ];
        Ok(counters
            .into_iter()
            .map(|(name, value)| Counter { name, value })
            .collect())
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::Preset;

    /// Classic probes are the baseline the paper improves on: whatever the preset asks, they
    /// trace no bounce at their rays' hits and no gather at the pixels.
    #[test]
    fn classic_probes_trace_neither_a_bounce_nor_a_gather_nor_reflections() {
        let spec = TechniqueSpec::new("classic-probes", Preset::Quality);
        let full = DDGI.settings(&spec, &mut Vec::new()).unwrap();
        assert!(full.update.traced_bounce && full.gather.rays_per_pixel > 0);
        assert!(full.update.blind_bounces > 0);
        let classic = CLASSIC_PROBES.settings(&spec, &mut Vec::new()).unwrap();
        assert!(!classic.update.traced_bounce);
        assert_eq!(classic.update.blind_bounces, 0);
        assert_eq!(classic.gather.rays_per_pixel, 0);
        assert!(full.reflections.enabled && !classic.reflections.enabled);
        assert!(!classic.update.light_between_volumes);
    }

    /// The traced bounce and the blind bounces are compiled into DDGI's passes: switching one
    /// rebuilds the volumes, while the rest of `update` changes live.
    #[test]
    fn switching_the_traced_or_the_blind_bounces_rebuilds() {
        let balanced = DdgiSettings::balanced();
        let switches: [fn(&mut DdgiUpdateSettings); 3] = [
            |u| u.traced_bounce = true,
            |u| u.blind_bounces = 2,
            |u| u.blind_threshold = 0.75,
        ];
        for switch in switches {
            let mut switched = balanced.clone();
            switch(&mut switched.update);
            assert!(!balanced.same_build(&switched), "{:?}", switched.update);
        }
        let mut live = balanced.clone();
        live.update.hysteresis = 0.9;
        assert!(balanced.same_build(&live));
    }
}
