//! One DDGI probe volume: its grid, its buffers and atlases, the shared pipelines bound to them,
//! and its per-frame state (frames blended, relocation, probe states, hysteresis boosts).

use glam::{Mat3, Vec3};
use irradiant_gpu::{
    BoundPass, GpuContext, Profiler, ResourceTable, Workgroups, read_buffer_as, wgpu,
};
use irradiant_scene::ProbeVolumeDesc;

use super::constants::*;
use super::pipelines::DdgiPipelines;
use super::resources::{
    ACTIVE_BLEND_GROUPS, ACTIVE_PROBES_HEADER, ACTIVE_RAY_GROUPS, ACTIVE_TRACE_GROUPS,
    ATLAS_TEXEL_BYTES, DdgiResources, MAX_WAKE_BOXES, NEWLY_LIST, SHADOW_QUEUE_HEADER, tile_sides,
};
use super::settings::{DdgiSettings, ProbeWeights, RELOCATION_FRAMES};
use super::types::GpuDdgiVolume;
use crate::RenderError;
use crate::frame::{LightingChange, SceneChange};
use crate::probes::{AtlasLayout, ProbeGrid, atlas::copy_atlas_to_texture, rays::random_rotation};
use crate::technique::{ProbeView, non_finite};

mod dispatches;
mod readback;
mod saved;
mod window;
pub use dispatches::DdgiDispatches;
pub use readback::{Atlases, ProbeStateCounts};

/// A hysteresis reduction after a scene change (003 §4.3): the factors hold for `hold` frames,
/// then fade back to 1 over as many frames again. 003's reductions end abruptly; the fade keeps
/// draining light that a change removed (a lamp switched off in a closed room, where the
/// probes feed on their own last values) instead of letting it linger at full hysteresis.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Boost {
    age: u32,
    hold: u32,
    irradiance: f32,
    distance: f32,
}

impl Boost {
    fn new(hold: u32, irradiance: f32, distance: f32) -> Self {
        Self {
            age: 0,
            hold,
            irradiance,
            distance,
        }
    }

    /// This frame's (irradiance, distance) multipliers.
    fn factors(&self) -> (f32, f32) {
        let fade = self.age.saturating_sub(self.hold) as f32 / self.hold as f32;
        let f = |x: f32| x + (1.0 - x) * fade.min(1.0);
        (f(self.irradiance), f(self.distance))
    }

    fn expired(&self) -> bool {
        self.age >= 2 * self.hold
    }
}

/// Which pass of the update a dispatch belongs to: a convergence round (over the list of newly
/// probes) or the normal update (over every updating probe).
#[derive(Clone, Copy)]
enum Round {
    Convergence,
    Update,
}

impl Round {
    /// Where its list's header starts in `active_probes`.
    fn list(self) -> u64 {
        match self {
            Round::Update => 0,
            Round::Convergence => NEWLY_LIST,
        }
    }
}

/// The pipelines bound to one volume's buffers.
struct VolumePasses {
    ray_directions: BoundPass,
    trace: Option<BoundPass>,
    shade: BoundPass,
    shadow: Option<BoundPass>,
    relocate: BoundPass,
    window_enter: BoundPass,
    probe_states: BoundPass,
    converge_step: BoundPass,
    blend_weights: BoundPass,
    blend_irradiance: BoundPass,
    blend_distance: BoundPass,
    resolve: BoundPass,
    visualize: BoundPass,
    visualize_states: BoundPass,
    visualize_volumes: BoundPass,
}

/// One DDGI probe volume: its grid, atlases and buffers, the passes bound to them, and its
/// per-frame state.
pub struct DdgiVolume {
    settings: DdgiSettings,
    /// Where the probes sit before relocation.
    pub grid: ProbeGrid,
    /// How probe tiles are laid out in its atlases.
    pub atlas: AtlasLayout,
    /// Its buffers and textures.
    pub resources: DdgiResources,
    passes: VolumePasses,
    dispatches: DdgiDispatches,
    /// ddgi/trace's lanes fetch their rays (DdgiPipelines::fetches_rays): its dispatch in the
    /// list header is a run of rays a workgroup.
    fetches_rays: bool,
    max_ray_distance: f32,
    /// The volume's extent, for the default ray length.
    diagonal: f32,
    /// This volume's place among the technique's, finest first.
    place: VolumePlace,
    /// Frames blended so far; 0 means the next update starts the probes from scratch.
    pub frame: u32,
    /// Active hysteresis reductions.
    boosts: Vec<Boost>,
    /// Offsets are cleared before the first relocation frame.
    relocation_pending: bool,
    /// States are cleared (every probe vigilant, nothing blended) before the first frame.
    states_pending: bool,
    /// Wake boxes to upload at the next prepare, after animation moved something.
    wake_boxes: Option<Vec<(Vec3, Vec3)>>,
    wake_box_count: u32,
    /// Whether it follows the camera, and its last step.
    window: window::Window,
    /// Whether last frame's states pass may have made a probe newly awake or vigilant: this
    /// frame then records the convergence rounds (`convergence_rounds`).
    newly_possible: bool,
}

/// The final gather's history this frame: `history_frames`, shortened after a scene change as
/// the probes' memory is (the boosted hysteresis's time constant, 1/(1 − h·boost), against the
/// set one's), so that the gathered light follows a switched-off lamp as fast as the probes
/// its rays read.
fn gather_history(history_frames: u32, hysteresis: f32, boost: f32) -> u32 {
    let memory = (1.0 - hysteresis) / (1.0 - hysteresis * boost).max(1e-6);
    ((history_frames as f32 * memory).round() as u32).max(1)
}

/// Where a volume sits among its technique's volumes.
#[derive(Clone, Copy, Debug)]
pub struct VolumePlace {
    /// Its place among the volumes, finest first (0: the finest).
    pub index: u32,
    /// Whether it is the coarsest, which fills whatever weight the finer ones left.
    pub is_last: bool,
}

impl VolumePlace {
    /// Whether the technique has other volumes than this one.
    pub fn has_neighbours(&self) -> bool {
        self.index > 0 || !self.is_last
    }
}

impl DdgiVolume {
    /// Allocates the volume for `desc`, binds the shared pipelines to its resources and the
    /// given tables (scene, frame), and starts its probes from scratch; `dynamic_bounds` are
    /// the boxes around animated instances, where sleeping probes wake.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        ctx: &GpuContext,
        pipelines: &DdgiPipelines,
        tables: &[&ResourceTable],
        desc: &ProbeVolumeDesc,
        settings: &DdgiSettings,
        place: VolumePlace,
        frame_size: (u32, u32),
        dynamic_bounds: Vec<(Vec3, Vec3)>,
    ) -> Result<Self, RenderError> {
        let grid = ProbeGrid::new(desc);
        let atlas = AtlasLayout::new(grid.probe_count, &tile_sides(settings));
        let dispatches = DdgiDispatches::new(&grid, settings, frame_size, pipelines.fetches_rays);
        let resources = DdgiResources::new(
            ctx,
            &grid,
            &atlas,
            settings,
            &dispatches,
            place.has_neighbours(),
        )?;
        let passes = {
            let own = resources.table();
            let mut all: Vec<&ResourceTable> = tables.to_vec();
            all.push(&own);
            let bind = |pass: &std::sync::Arc<irradiant_gpu::ComputePass>| pass.bind(ctx, &all);
            // Probe rays read the bounce copy of irradiance.
            let bounce = resources.bounce_table();
            let mut shading: Vec<&ResourceTable> = tables.to_vec();
            shading.push(&bounce);
            let bind_shading =
                |pass: &std::sync::Arc<irradiant_gpu::ComputePass>| pass.bind(ctx, &shading);
            VolumePasses {
                ray_directions: bind(&pipelines.ray_directions)?,
                trace: pipelines.trace.as_ref().map(bind).transpose()?,
                shade: bind_shading(&pipelines.shade)?,
                shadow: pipelines.shadow.as_ref().map(bind).transpose()?,
                relocate: bind(&pipelines.relocate)?,
                window_enter: bind(&pipelines.window_enter)?,
                probe_states: bind(&pipelines.probe_states)?,
                converge_step: bind(&pipelines.converge_step)?,
                blend_weights: bind(&pipelines.blend_weights)?,
                blend_irradiance: bind(&pipelines.blend_irradiance)?,
                blend_distance: bind(&pipelines.blend_distance)?,
                resolve: bind(&pipelines.resolve)?,
                visualize: bind(&pipelines.visualize)?,
                visualize_states: bind(&pipelines.visualize_states)?,
                visualize_volumes: bind(&pipelines.visualize_volumes)?,
            }
        };
        let diagonal = (desc.max - desc.min).length().max(1e-3);
        let mut volume = Self {
            dispatches,
            fetches_rays: pipelines.fetches_rays,
            settings: settings.clone(),
            grid,
            atlas,
            resources,
            passes,
            max_ray_distance: 0.0,
            diagonal,
            place,
            frame: 0,
            boosts: Vec::new(),
            relocation_pending: true,
            states_pending: true,
            wake_boxes: Some(dynamic_bounds),
            wake_box_count: 0,
            window: window::Window::new(desc.follow.clone()),
            newly_possible: false,
        };
        volume.set_settings(settings);
        Ok(volume)
    }

    /// The settings the volume runs with.
    pub fn settings(&self) -> &DdgiSettings {
        &self.settings
    }

    /// Takes settings that differ from the current ones only in `update` (the caller checks
    /// [`DdgiSettings::same_build`]); switching relocation, or whether probes in geometry
    /// shade, restarts the probes (both act on the first frames' classification).
    pub fn set_settings(&mut self, settings: &DdgiSettings) {
        let (new, old) = (&settings.update, &self.settings.update);
        if new.relocation != old.relocation
            || new.shade_probes_in_geometry != old.shade_probes_in_geometry
        {
            self.reset();
        }
        self.settings = settings.clone();
        let u = &settings.update;
        self.max_ray_distance = if u.max_ray_distance > 0.0 {
            u.max_ray_distance
        } else {
            self.diagonal * 1.5
        };
    }

    /// Starts the probes over (the next update blends with hysteresis 0, relocation reruns).
    pub fn reset(&mut self) {
        self.frame = 0;
        self.relocation_pending = true;
        self.states_pending = true;
    }

    /// Whether its probes' light is still provisional: in the first `RELOCATION_FRAMES` frames
    /// after a start or a reset the probes are relocated and classified, and at the end of it
    /// the ones near geometry drop what they held and start over (the convergence rounds).
    /// Until then their light comes from unplaced probes, some in walls. ssil+ddgi's screen
    /// reaches past its near field while this holds.
    pub fn probes_provisional(&self) -> bool {
        self.frame < RELOCATION_FRAMES
    }

    /// Longest probe ray, in scene units: the setting, or 1.5 × the volume's diagonal.
    pub fn max_ray_distance(&self) -> f32 {
        self.max_ray_distance
    }

    /// The workgroups of its dispatches.
    pub fn dispatches(&self) -> &DdgiDispatches {
        &self.dispatches
    }

    /// STATES_* of ddgi::constants for this frame: probes are classified on the relocation
    /// frames (the optimiser has moved them by the last one) and sleep or wake after. With
    /// `speed.probe_states` off too: the states then decide only what the query reads, and
    /// every probe still updates (`every_probe_updates`).
    fn state_phase(&self) -> u32 {
        if self.frame + 1 < RELOCATION_FRAMES {
            STATES_CLASSIFYING
        } else if self.frame + 1 == RELOCATION_FRAMES {
            STATES_CLASSIFY_LAST
        } else {
            STATES_CLASSIFIED
        }
    }

    /// Convergence rounds this frame records: `update.convergence_rounds` where last frame
    /// may have made a probe newly awake or vigilant, else none. Newly probes come only from
    /// the end of a classification (the volume's, or an entered plane's) and from wake boxes,
    /// so a still scene pays nothing.
    fn convergence_rounds(&self) -> u32 {
        if self.newly_possible {
            self.settings.update.convergence_rounds
        } else {
            0
        }
    }

    fn relocating(&self) -> bool {
        self.settings.update.relocation && self.frame < RELOCATION_FRAMES
    }

    /// `GpuDdgiVolume::relocating`: every probe in the volume's first frames, those that
    /// entered a window's step for a few frames after it, or none.
    fn relocation_mode(&self) -> u32 {
        if self.relocating() {
            1
        } else if self.settings.update.relocation && self.window.fresh_frames > 0 {
            RELOCATING_FRESH
        } else {
            0
        }
    }

    /// 003 §4.3's scene-level heuristics: a small lighting change lowers the irradiance
    /// hysteresis by 15 % for 4 frames, a large one by 50 % for 10 frames; an object that moves
    /// lowers irradiance hysteresis by 50 % for 10 frames and visibility's by 50 % for 7 — each
    /// then fading back over as many frames (see `Boost`).
    pub fn scene_changed(&mut self, change: &SceneChange) {
        self.wake_boxes = Some(change.dynamic_bounds.clone());
        if !self.settings.update.convergence_heuristics {
            return;
        }
        match change.lighting {
            LightingChange::Small => self.boosts.push(Boost::new(4, 0.85, 1.0)),
            LightingChange::Large => self.boosts.push(Boost::new(10, 0.5, 1.0)),
            LightingChange::None => {}
        }
        if change.geometry {
            self.boosts.push(Boost::new(10, 0.5, 1.0));
            self.boosts.push(Boost::new(7, 1.0, 0.5));
        }
    }

    /// This frame's hysteresis multipliers (irradiance, distance) from the active boosts.
    fn boost_factors(&self) -> (f32, f32) {
        self.boosts
            .iter()
            .map(Boost::factors)
            .fold((1.0f32, 1.0f32), |(i, d), (bi, bd)| (i.min(bi), d.min(bd)))
    }

    /// Whether its probe rays leave their hits' probe light to ddgi/between_volumes, which
    /// reads every volume that covers them (`update.light_between_volumes`).
    pub fn reads_between_volumes(&self) -> bool {
        self.place.has_neighbours() && self.settings.update.light_between_volumes
    }

    fn volume_uniform(&self) -> GpuDdgiVolume {
        let (v, u) = (&self.settings.volume, &self.settings.update);
        let g = &self.grid;
        let weights = match u.weights {
            ProbeWeights::Classic => 0,
            ProbeWeights::Backface => WEIGHT_BACKFACE,
            ProbeWeights::Chebyshev => WEIGHT_BACKFACE | WEIGHT_CHEBYSHEV,
            ProbeWeights::Full => WEIGHT_BACKFACE | WEIGHT_CHEBYSHEV | WEIGHT_BACKFACE_HITS,
        };
        let rotation = Mat3::from_quat(random_rotation(u.seed, self.frame));
        let row = |i: usize| rotation.row(i).extend(0.0).to_array();
        let (irradiance_boost, distance_boost) = self.boost_factors();
        GpuDdgiVolume {
            origin: g.origin.into(),
            probe_count: g.probe_count,
            spacing: g.spacing.into(),
            rays_per_probe: v.rays_per_probe,
            counts: g.counts.into(),
            probes_per_row: self.atlas.probes_per_row,
            ray_rotation0: row(0),
            ray_rotation1: row(1),
            ray_rotation2: row(2),
            irradiance_texels: v.irradiance_texels,
            distance_texels: v.distance_texels,
            irradiance_hysteresis: u.hysteresis * irradiance_boost,
            distance_hysteresis: u.distance_hysteresis * distance_boost,
            max_ray_distance: self.max_ray_distance,
            self_shadow_bias: if u.weights == ProbeWeights::Full {
                u.self_shadow_bias
            } else {
                0.0
            },
            distance_exponent: u.distance_exponent,
            irradiance_gamma: v.irradiance_gamma,
            weights,
            frame: self.frame,
            min_spacing: g.min_spacing(),
            convergence_heuristics: u.convergence_heuristics as u32,
            relocating: self.relocation_mode(),
            all_lights: v.shade_all_lights as u32,
            state_phase: self.state_phase(),
            wake_box_count: self.wake_box_count,
            volume_index: self.place.index,
            volume_is_last: self.place.is_last as u32,
            bounce_hysteresis: u.bounce_hysteresis * irradiance_boost,
            extrapolation: u.extrapolation,
            tied_probe_weight: u.tied_probe_weight,
            every_probe_updates: !self.settings.speed.probe_states as u32,
            shade_probes_in_geometry: u.shade_probes_in_geometry as u32,
            gather_history_frames: gather_history(
                self.settings.gather.history_frames,
                u.hysteresis,
                irradiance_boost,
            ),
            gather_interval: self.settings.gather.pixel_interval,
            phase_x: g.phase.x,
            phase_y: g.phase.y,
            phase_z: g.phase.z,
            entering_start: self.window.entering_start(),
            entering_end: self.window.entering_end(),
            blend_centre: self.window.blend_centre(),
            convergence_rounds: self.convergence_rounds(),
            light_between_volumes: self.reads_between_volumes() as u32,
            padding1: 0,
            padding2: 0,
        }
    }

    /// Writes this frame's volume parameters; call before recording the frame's passes, once a
    /// submission (the queue applies the write before the submission runs).
    pub fn prepare(&mut self, ctx: &GpuContext) {
        if let Some(boxes) = self.wake_boxes.take() {
            self.upload_wake_boxes(ctx, &boxes);
        }
        ctx.queue.write_buffer(
            &self.resources.volume,
            0,
            bytemuck::bytes_of(&self.volume_uniform()),
        );
    }

    /// Boxes where geometry may come and go (animated instances), grown by a grid cell and the
    /// self-shadow bias (003 §6.3): sleeping probes inside wake up.
    fn upload_wake_boxes(&mut self, ctx: &GpuContext, bounds: &[(Vec3, Vec3)]) {
        let grow = self.grid.spacing
            + Vec3::splat(0.75 * self.grid.min_spacing() * self.settings.update.self_shadow_bias);
        let mut boxes: Vec<(Vec3, Vec3)> = Vec::new();
        for &(lo, hi) in bounds {
            let grown = (lo - grow, hi + grow);
            if boxes.len() < MAX_WAKE_BOXES {
                boxes.push(grown);
            } else if let Some(last) = boxes.last_mut() {
                *last = (last.0.min(grown.0), last.1.max(grown.1));
            }
        }
        let data: Vec<[f32; 4]> = boxes
            .iter()
            .flat_map(|(lo, hi)| [lo.extend(0.0).to_array(), hi.extend(0.0).to_array()])
            .collect();
        if !data.is_empty() {
            ctx.queue
                .write_buffer(&self.resources.wake_boxes, 0, bytemuck::cast_slice(&data));
        }
        self.wake_box_count = boxes.len() as u32;
    }

    /// Records the probe update: ray directions, trace, shade, (shadow), (the light of every
    /// volume at the rays' hits: `between`, ddgi/between_volumes bound to each volume, finest
    /// first, and to this one's rays), (relocate), blend weights, blends (borders included),
    /// probe states.
    pub fn record_update(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
        between: &[BoundPass],
    ) {
        if self.states_pending {
            // Every probe starts vigilant, so every probe is listed.
            let r = &self.resources;
            encoder.clear_buffer(&r.states, 0, None);
            encoder.copy_buffer_to_buffer(&r.every_probe, 0, &r.active_probes, 0, None);
            self.states_pending = false;
        }
        self.record_window_enter(encoder, profiler.as_deref_mut());
        let rounds = self.convergence_rounds();
        for _ in 0..rounds {
            self.passes.converge_step.dispatch(
                encoder,
                profiler.as_deref_mut(),
                Workgroups::linear(1),
            );
            self.record_rays(encoder, profiler.as_deref_mut(), Round::Convergence);
            self.record_blend_of(encoder, profiler.as_deref_mut(), Round::Convergence);
        }
        if rounds > 0 {
            // Back to round 0 for the normal update.
            self.passes.converge_step.dispatch(
                encoder,
                profiler.as_deref_mut(),
                Workgroups::linear(1),
            );
        }
        self.record_rays(encoder, profiler.as_deref_mut(), Round::Update);
        if self.reads_between_volumes() {
            let offset = Round::Update.list() + ACTIVE_RAY_GROUPS;
            for pass in between {
                pass.dispatch_indirect(
                    encoder,
                    profiler.as_deref_mut(),
                    &self.resources.active_probes,
                    offset,
                );
            }
        }
        if self.relocation_mode() != 0 {
            if self.relocating() && self.relocation_pending {
                encoder.clear_buffer(&self.resources.offsets, 0, None);
                self.relocation_pending = false;
            }
            self.passes
                .relocate
                .dispatch(encoder, profiler.as_deref_mut(), self.dispatches.probes);
        }
        self.record_blend(encoder, profiler.as_deref_mut());
        self.record_probe_states(encoder, profiler);
        // This frame's states pass ends a classification on its last frame (the volume's, or
        // an entered plane's), and wakes probes while a wake box stands.
        self.newly_possible = self.state_phase() == STATES_CLASSIFY_LAST
            || self.window.fresh_frames > 0
            || self.wake_box_count > 0;
        self.frame += 1;
        self.window.fresh_frames = self.window.fresh_frames.saturating_sub(1);
        for boost in &mut self.boosts {
            boost.age += 1;
        }
        self.boosts.retain(|b| !b.expired());
    }

    /// Records a round's rays: directions, trace, shade, (shadow).
    fn record_rays(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
        round: Round,
    ) {
        let (p, d, r) = (&self.passes, &self.dispatches, &self.resources);
        // The list of updating probes' dispatch, or in a convergence round the newly ones'.
        let (groups, offset) = (&r.active_probes, round.list() + ACTIVE_RAY_GROUPS);
        p.ray_directions
            .dispatch(encoder, profiler.as_deref_mut(), d.ray_directions);
        if let Some(trace) = &p.trace {
            let trace_offset = round.list() + ACTIVE_TRACE_GROUPS;
            trace.dispatch_indirect(encoder, profiler.as_deref_mut(), groups, trace_offset);
        }
        if p.shadow.is_some() {
            encoder.clear_buffer(&r.shadow_queue, 0, Some(SHADOW_QUEUE_HEADER));
        }
        p.shade
            .dispatch_indirect(encoder, profiler.as_deref_mut(), groups, offset);
        if let Some(shadow) = &p.shadow {
            shadow.dispatch_indirect(encoder, profiler, &r.shadow_queue, 4);
        }
    }

    /// Records ddgi/probe_states (the end of every update; tests also record it alone, over
    /// states and rays they wrote): each probe's next state, and the next frame's lists of
    /// updating and newly probes, made afresh.
    pub fn record_probe_states(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
    ) {
        encoder.clear_buffer(&self.resources.active_probes, 0, Some(ACTIVE_PROBES_HEADER));
        self.passes
            .probe_states
            .dispatch(encoder, profiler, self.dispatches.probes);
    }

    /// Records only the blend passes, borders included, and the atlases' copies into the
    /// textures the query samples (tests feed the rays themselves).
    pub fn record_blend(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
    ) {
        self.record_blend_of(encoder, profiler, Round::Update);
    }

    fn record_blend_of(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
        round: Round,
    ) {
        let (p, d, r) = (&self.passes, &self.dispatches, &self.resources);
        let (groups, offset) = (&r.active_probes, round.list() + ACTIVE_BLEND_GROUPS);
        p.blend_weights
            .dispatch(encoder, profiler.as_deref_mut(), d.blend_weights);
        p.blend_irradiance
            .dispatch_indirect(encoder, profiler.as_deref_mut(), groups, offset);
        p.blend_distance
            .dispatch_indirect(encoder, profiler, groups, offset);
        copy_atlas_to_texture(
            encoder,
            &r.irradiance,
            &r.irradiance_texture,
            ATLAS_TEXEL_BYTES,
        );
        copy_atlas_to_texture(
            encoder,
            &r.irradiance_bounce,
            &r.irradiance_bounce_texture,
            ATLAS_TEXEL_BYTES,
        );
        copy_atlas_to_texture(encoder, &r.distance, &r.distance_texture, ATLAS_TEXEL_BYTES);
    }

    /// Records ddgi/resolve: this volume's share of the G-buffer's indirect diffuse light.
    pub fn record_resolve(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
    ) {
        self.passes
            .resolve
            .dispatch(encoder, profiler, self.dispatches.image);
    }

    /// Records ddgi/visualize: probes drawn as spheres into the composed radiance, lit by
    /// their irradiance or coloured by their state, or each pixel coloured by the volumes that
    /// light it (`view`; the technique records its volumes finest first).
    pub fn record_visualize(&self, encoder: &mut wgpu::CommandEncoder, view: ProbeView) {
        let pass = match view {
            ProbeView::Light => &self.passes.visualize,
            ProbeView::States => &self.passes.visualize_states,
            ProbeView::Volumes => &self.passes.visualize_volumes,
        };
        pass.dispatch(encoder, None, self.dispatches.image);
    }
}

#[cfg(test)]
mod tests {
    use super::Boost;

    #[test]
    fn boosts_hold_then_fade_back() {
        let mut b = Boost::new(10, 0.5, 1.0);
        let mut seen = Vec::new();
        while !b.expired() {
            seen.push(b.factors().0);
            b.age += 1;
        }
        assert_eq!(seen.len(), 20);
        assert!(seen[..=10].iter().all(|&f| f == 0.5), "{seen:?}");
        assert!(seen.windows(2).all(|w| w[1] >= w[0]) && seen[19] < 1.0 && seen[19] > 0.9);
    }
}
