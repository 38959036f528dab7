use glam::{Mat3, Quat};
use irradiant_gpu::{GpuContext, Profiler, read_buffer_as, wgpu};
use irradiant_scene::ProbeVolumeDesc;

use super::resources::{DdgiResources, SHADOW_QUEUE_HEADER, VolumeLayout};
use super::{DdgiSettings, ProbeWeights, RELOCATION_FRAMES};
use crate::RenderError;
use crate::frame::FrameBuffers;
use crate::gpu_scene::GpuScene;
use crate::gpu_types::GpuDdgiVolume;
use crate::pipeline::*;

const WEIGHT_BACKFACE: u32 = 1;
const WEIGHT_CHEBYSHEV: u32 = 2;
const WEIGHT_BACKFACE_HITS: u32 = 4;

/// Probes in each state (003 §6; see ddgi/states.wgsl).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProbeStateCounts {
    /// Near static geometry: trace and update every frame.
    pub vigilant: u32,
    /// Inside static geometry: never trace or shade.
    pub off: u32,
    /// No geometry within a cell: never trace or shade.
    pub sleeping: u32,
    /// Sleeping probes that an animated instance woke.
    pub awake: u32,
}

impl ProbeStateCounts {
    /// Probes that trace rays this frame.
    pub fn updating(&self) -> u32 {
        self.vigilant + self.awake
    }
}

/// One probe volume and its passes.
pub struct Ddgi {
    /// Fixed at creation: buffer sizes and shader constants follow from them
    /// ([`Ddgi::settings`] reads them; a new `Ddgi` takes new ones).
    settings: DdgiSettings,
    pub layout: VolumeLayout,
    pub resources: DdgiResources,
    max_ray_distance: f32,
    /// Frames blended so far; 0 means the next update starts the probes from scratch.
    pub frame: u32,
    ray_directions: ComputeStage,
    trace: ComputeStage,
    shade: ComputeStage,
    shadow: ComputeStage,
    relocate: ComputeStage,
    probe_states: ComputeStage,
    blend_weights: ComputeStage,
    blend_irradiance: ComputeStage,
    blend_distance: ComputeStage,
    resolve: ComputeStage,
    visualize: ComputeStage,
    groups: UpdateGroups,
    /// The atlas textures and their samplers: group 2 of the passes that query the probes.
    atlas_group: wgpu::BindGroup,
    frame_layout: wgpu::BindGroupLayout,
    visualize_layout: wgpu::BindGroupLayout,
    frame_groups: Option<(wgpu::BindGroup, wgpu::BindGroup)>,
    /// Active hysteresis reductions: (frames left, irradiance factor, distance factor).
    boosts: Vec<(u32, f32, f32)>,
    /// Offsets are cleared before the first relocation frame.
    relocation_pending: bool,
    /// States are cleared (every probe vigilant, nothing blended) before the first frame.
    states_pending: bool,
    /// Wake boxes to upload at the next prepare, after animation moved something.
    wake_boxes: Option<Vec<(glam::Vec3, glam::Vec3)>>,
    wake_box_count: u32,
}

struct UpdateGroups {
    ray_directions: wgpu::BindGroup,
    trace: wgpu::BindGroup,
    shade: wgpu::BindGroup,
    shadow: wgpu::BindGroup,
    relocate: wgpu::BindGroup,
    probe_states: wgpu::BindGroup,
    blend_weights: wgpu::BindGroup,
    blend_irradiance: wgpu::BindGroup,
    blend_distance: wgpu::BindGroup,
}

impl Ddgi {
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        desc: &ProbeVolumeDesc,
        settings: &DdgiSettings,
    ) -> Result<Self, RenderError> {
        settings.validate().map_err(RenderError::Settings)?;
        let layout = VolumeLayout::new(
            desc,
            &[settings.irradiance_texels + 2, settings.distance_texels + 2],
        );
        let resources = DdgiResources::new(ctx, &layout, settings)?;
        let device = &ctx.device;
        let max_ray_distance = settings
            .max_ray_distance
            .unwrap_or((desc.max - desc.min).length().max(1e-3) * 1.5);
        let r = &resources;
        let ddgi_constants = ddgi_shader_constants(settings);
        // Bindings, by the names in the WGSL: 0 volume, 3 directions, 4 hits, 6 samples,
        // 7 irradiance (write), 8 distance (write), 9 gbuffer, 10 indirect, 11 frame,
        // 12 radiance, 13 offsets (write), 14 ray set, 15 states (read), 16 states (write),
        // 17 wake boxes, 18 blend weights, 19 shadow queue. Passes that query the probes
        // (ddgi_query) also take the atlas textures as group 2.
        let (atlas_layout, atlas_group) = atlas_textures(device, r);
        let make_with = |label: &'static str,
                         source: &str,
                         entries: &[(u32, wgpu::BufferBindingType)],
                         constants: &[(&str, String)],
                         queries: bool| {
            let group_layout = buffer_layout(device, label, entries);
            let mut all = ddgi_constants.clone();
            all.extend(constants.iter().cloned());
            let groups: &[&wgpu::BindGroupLayout] = if queries {
                &[&group_layout, &atlas_layout]
            } else {
                &[&group_layout]
            };
            let stage = ComputeStage::tracing_with_groups(ctx, scene, label, source, &all, groups)?;
            Ok::<_, RenderError>((stage, group_layout))
        };
        let make = |label: &'static str,
                    source: &str,
                    entries: &[(u32, wgpu::BufferBindingType)],
                    constants: &[(&str, String)]| {
            make_with(label, source, entries, constants, false)
        };
        let (ray_directions, l_dirs) = make(
            "ddgi/ray_directions",
            include_str!("ray_directions.wgsl"),
            &[(0, UNIFORM), (3, STORAGE_WRITE), (14, STORAGE_READ)],
            &[],
        )?;
        let (trace, l_trace) = make(
            "ddgi/trace",
            include_str!("trace.wgsl"),
            &[
                (0, UNIFORM),
                (3, STORAGE_READ),
                (4, STORAGE_WRITE),
                (5, STORAGE_READ),
                (15, STORAGE_READ),
            ],
            &[],
        )?;
        let (shade, l_shade) = make_with(
            if settings.fuse_trace_and_shade {
                "ddgi/trace_shade"
            } else {
                "ddgi/shade"
            },
            include_str!("shade.wgsl"),
            &[
                (0, UNIFORM),
                (3, STORAGE_READ),
                (4, STORAGE_READ),
                (5, STORAGE_READ),
                (6, STORAGE_WRITE),
                (15, STORAGE_READ),
                (19, STORAGE_WRITE),
            ],
            &[
                (
                    "FUSED_TRACE",
                    format!("{}u", settings.fuse_trace_and_shade as u32),
                ),
                (
                    "SHADOW_QUEUE",
                    format!("{}u", settings.queues_shadow_rays() as u32),
                ),
            ],
            true,
        )?;
        let (shadow, l_shadow) = make(
            "ddgi/shadow",
            include_str!("shadow.wgsl"),
            &[(0, UNIFORM), (6, STORAGE_WRITE), (19, STORAGE_READ)],
            &[],
        )?;
        let (relocate, l_relocate) = make(
            "ddgi/relocate",
            include_str!("relocate.wgsl"),
            &[
                (0, UNIFORM),
                (3, STORAGE_READ),
                (6, STORAGE_READ),
                (13, STORAGE_WRITE),
            ],
            &[],
        )?;
        let (probe_states, l_states) = make(
            "ddgi/probe_states",
            include_str!("probe_states.wgsl"),
            &[
                (0, UNIFORM),
                (3, STORAGE_READ),
                (5, STORAGE_READ),
                (6, STORAGE_READ),
                (16, STORAGE_WRITE),
                (17, STORAGE_READ),
            ],
            &[],
        )?;
        let (blend_weights, l_bw) = make(
            "ddgi/blend_weights",
            include_str!("blend_weights.wgsl"),
            &[(0, UNIFORM), (3, STORAGE_READ), (18, STORAGE_WRITE)],
            &[],
        )?;
        let (blend_irradiance, l_bi) = make(
            "ddgi/blend_irradiance",
            include_str!("blend_irradiance.wgsl"),
            &[
                (0, UNIFORM),
                (6, STORAGE_READ),
                (7, STORAGE_WRITE),
                (15, STORAGE_READ),
                (18, STORAGE_READ),
            ],
            &blend_constants(settings.irradiance_texels),
        )?;
        let (blend_distance, l_bd) = make(
            "ddgi/blend_distance",
            include_str!("blend_distance.wgsl"),
            &[
                (0, UNIFORM),
                (6, STORAGE_READ),
                (8, STORAGE_WRITE),
                (15, STORAGE_READ),
                (18, STORAGE_READ),
            ],
            &blend_constants(settings.distance_texels),
        )?;
        let (resolve, frame_layout) = make_with(
            "ddgi/resolve",
            include_str!("resolve.wgsl"),
            &[
                (0, UNIFORM),
                (5, STORAGE_READ),
                (9, STORAGE_READ),
                (10, STORAGE_WRITE),
                (11, UNIFORM),
                (15, STORAGE_READ),
            ],
            &[],
            true,
        )?;
        let (visualize, visualize_layout) = make_with(
            "ddgi/visualize",
            include_str!("visualize.wgsl"),
            &[
                (0, UNIFORM),
                (5, STORAGE_READ),
                (9, STORAGE_READ),
                (11, UNIFORM),
                (12, STORAGE_WRITE),
                (15, STORAGE_READ),
            ],
            &[],
            true,
        )?;
        let groups = UpdateGroups {
            ray_directions: bind_at(
                device,
                "ddgi/ray_directions",
                &l_dirs,
                &[(0, &r.volume), (3, &r.directions), (14, &r.ray_set)],
            ),
            trace: bind_at(
                device,
                "ddgi/trace",
                &l_trace,
                &[
                    (0, &r.volume),
                    (3, &r.directions),
                    (4, &r.hits),
                    (5, &r.offsets),
                    (15, &r.states),
                ],
            ),
            shade: bind_at(
                device,
                "ddgi/shade",
                &l_shade,
                &[
                    (0, &r.volume),
                    (3, &r.directions),
                    (4, &r.hits),
                    (5, &r.offsets),
                    (6, &r.samples),
                    (15, &r.states),
                    (19, &r.shadow_queue),
                ],
            ),
            shadow: bind_at(
                device,
                "ddgi/shadow",
                &l_shadow,
                &[(0, &r.volume), (6, &r.samples), (19, &r.shadow_queue)],
            ),
            relocate: bind_at(
                device,
                "ddgi/relocate",
                &l_relocate,
                &[
                    (0, &r.volume),
                    (3, &r.directions),
                    (6, &r.samples),
                    (13, &r.offsets),
                ],
            ),
            probe_states: bind_at(
                device,
                "ddgi/probe_states",
                &l_states,
                &[
                    (0, &r.volume),
                    (3, &r.directions),
                    (5, &r.offsets),
                    (6, &r.samples),
                    (16, &r.states),
                    (17, &r.wake_boxes),
                ],
            ),
            blend_weights: bind_at(
                device,
                "ddgi/blend_weights",
                &l_bw,
                &[(0, &r.volume), (3, &r.directions), (18, &r.blend_weights)],
            ),
            blend_irradiance: bind_at(
                device,
                "ddgi/blend_irradiance",
                &l_bi,
                &[
                    (0, &r.volume),
                    (6, &r.samples),
                    (7, &r.irradiance),
                    (15, &r.states),
                    (18, &r.blend_weights),
                ],
            ),
            blend_distance: bind_at(
                device,
                "ddgi/blend_distance",
                &l_bd,
                &[
                    (0, &r.volume),
                    (6, &r.samples),
                    (8, &r.distance),
                    (15, &r.states),
                    (18, &r.blend_weights),
                ],
            ),
        };
        Ok(Self {
            settings: settings.clone(),
            layout,
            resources,
            max_ray_distance,
            frame: 0,
            ray_directions,
            trace,
            shade,
            shadow,
            relocate,
            probe_states,
            blend_weights,
            blend_irradiance,
            blend_distance,
            resolve,
            visualize,
            groups,
            atlas_group,
            frame_layout,
            visualize_layout,
            frame_groups: None,
            boosts: Vec::new(),
            relocation_pending: true,
            states_pending: true,
            wake_boxes: Some(scene.dynamic_bounds()),
            wake_box_count: 0,
        })
    }

    /// The settings the volume was created with.
    pub fn settings(&self) -> &DdgiSettings {
        &self.settings
    }

    /// Starts the probes over (the next update blends with hysteresis 0, relocation reruns).
    pub fn reset(&mut self) {
        self.frame = 0;
        self.relocation_pending = true;
        self.states_pending = true;
    }

    /// STATES_* of ddgi/states.wgsl for this frame: probes are classified on the relocation
    /// frames (the optimiser has moved them by the last one) and sleep or wake after.
    fn state_phase(&self) -> u32 {
        if !self.settings.probe_states {
            0
        } else if self.frame + 1 < RELOCATION_FRAMES {
            1
        } else if self.frame + 1 == RELOCATION_FRAMES {
            2
        } else {
            3
        }
    }

    fn relocating(&self) -> bool {
        self.settings.relocation && self.frame < RELOCATION_FRAMES
    }

    pub fn max_ray_distance(&self) -> f32 {
        self.max_ray_distance
    }

    /// 003 §4.3's scene-level heuristics: a small lighting change lowers the irradiance
    /// hysteresis by 15 % for 4 frames, a large one by 50 % for 10 frames; an object that moves
    /// lowers irradiance hysteresis by 50 % for 10 frames and visibility's by 50 % for 7.
    pub fn scene_changed(&mut self, change: &crate::frame::SceneChange) {
        use crate::frame::LightingChange;
        self.wake_boxes = Some(change.dynamic_bounds.clone());
        if !self.settings.convergence_heuristics {
            return;
        }
        match change.lighting {
            LightingChange::Small => self.boosts.push((4, 0.85, 1.0)),
            LightingChange::Large => self.boosts.push((10, 0.5, 1.0)),
            LightingChange::None => {}
        }
        if change.geometry {
            self.boosts.push((10, 0.5, 1.0));
            self.boosts.push((7, 1.0, 0.5));
        }
    }

    /// This frame's hysteresis multipliers (irradiance, distance) from the active boosts.
    fn boost_factors(&self) -> (f32, f32) {
        self.boosts
            .iter()
            .fold((1.0f32, 1.0f32), |(i, d), b| (i.min(b.1), d.min(b.2)))
    }

    fn volume_uniform(&self) -> GpuDdgiVolume {
        let s = &self.settings;
        let l = &self.layout;
        let weights = match s.weights {
            ProbeWeights::Classic => 0,
            ProbeWeights::Backface => WEIGHT_BACKFACE,
            ProbeWeights::Chebyshev => WEIGHT_BACKFACE | WEIGHT_CHEBYSHEV,
            ProbeWeights::Full => WEIGHT_BACKFACE | WEIGHT_CHEBYSHEV | WEIGHT_BACKFACE_HITS,
        };
        let rotation = Mat3::from_quat(random_rotation(s.seed, self.frame));
        let row = |i: usize| rotation.row(i).extend(0.0).to_array();
        GpuDdgiVolume {
            origin: l.origin.into(),
            probe_count: l.probe_count,
            spacing: l.spacing.into(),
            rays_per_probe: s.rays_per_probe,
            counts: l.counts.into(),
            probes_per_row: l.probes_per_row,
            ray_rotation0: row(0),
            ray_rotation1: row(1),
            ray_rotation2: row(2),
            irradiance_texels: s.irradiance_texels,
            distance_texels: s.distance_texels,
            irradiance_hysteresis: s.hysteresis * self.boost_factors().0,
            distance_hysteresis: s.distance_hysteresis * self.boost_factors().1,
            max_ray_distance: self.max_ray_distance,
            self_shadow_bias: if s.weights == ProbeWeights::Full {
                s.self_shadow_bias
            } else {
                0.0
            },
            distance_exponent: s.distance_exponent,
            irradiance_gamma: s.irradiance_gamma,
            weights,
            frame: self.frame,
            min_spacing: l.min_spacing(),
            convergence_heuristics: s.convergence_heuristics as u32,
            relocating: self.relocating() as u32,
            all_lights: s.shade_all_lights as u32,
            state_phase: self.state_phase(),
            wake_box_count: self.wake_box_count,
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
    fn upload_wake_boxes(&mut self, ctx: &GpuContext, bounds: &[(glam::Vec3, glam::Vec3)]) {
        let grow = self.layout.spacing
            + glam::Vec3::splat(0.75 * self.layout.min_spacing() * self.settings.self_shadow_bias);
        let mut boxes: Vec<(glam::Vec3, glam::Vec3)> = Vec::new();
        for &(lo, hi) in bounds {
            let grown = (lo - grow, hi + grow);
            if boxes.len() < super::resources::MAX_WAKE_BOXES {
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

    /// Records the probe update: trace, shade, blend weights, blends (borders included).
    pub fn update(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        mut profiler: Option<&mut Profiler>,
    ) {
        if self.states_pending {
            encoder.clear_buffer(&self.resources.states, 0, None);
            self.states_pending = false;
        }
        let g = &self.groups;
        let per_group = self.settings.probes_per_group;
        let ray_groups = self.layout.probe_count.div_ceil(per_group)
            * self.settings.rays_per_probe.div_ceil(64 / per_group);
        let s = &scene.bind_group;
        self.ray_directions.dispatch(
            encoder,
            profiler.as_deref_mut(),
            &[s, &g.ray_directions],
            [self.settings.rays_per_probe.div_ceil(64), 1, 1],
        );
        if !self.settings.fuse_trace_and_shade {
            self.trace.dispatch(
                encoder,
                profiler.as_deref_mut(),
                &[s, &g.trace],
                fold_groups(ray_groups),
            );
        }
        let shadow_queue = self.settings.queues_shadow_rays();
        if shadow_queue {
            encoder.clear_buffer(&self.resources.shadow_queue, 0, Some(SHADOW_QUEUE_HEADER));
        }
        self.shade.dispatch(
            encoder,
            profiler.as_deref_mut(),
            &[s, &g.shade, &self.atlas_group],
            fold_groups(ray_groups),
        );
        if shadow_queue {
            self.shadow.dispatch_indirect(
                encoder,
                profiler.as_deref_mut(),
                &[s, &g.shadow],
                &self.resources.shadow_queue,
                4,
            );
        }
        if self.relocating() {
            if self.relocation_pending {
                encoder.clear_buffer(&self.resources.offsets, 0, None);
                self.relocation_pending = false;
            }
            self.relocate.dispatch(
                encoder,
                profiler.as_deref_mut(),
                &[s, &g.relocate],
                fold_groups(self.layout.probe_count.div_ceil(64)),
            );
        }
        self.record_blend(encoder, scene, profiler.as_deref_mut());
        self.probe_states.dispatch(
            encoder,
            profiler,
            &[s, &g.probe_states],
            fold_groups(self.layout.probe_count.div_ceil(64)),
        );
        self.frame += 1;
        for boost in &mut self.boosts {
            boost.0 -= 1;
        }
        self.boosts.retain(|b| b.0 > 0);
    }

    /// Records only the blend passes, borders included (tests feed the rays themselves).
    pub fn record_blend(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        mut profiler: Option<&mut Profiler>,
    ) {
        let g = &self.groups;
        let s = &scene.bind_group;
        let texels = self.settings.irradiance_texels.pow(2) + self.settings.distance_texels.pow(2);
        self.blend_weights.dispatch(
            encoder,
            profiler.as_deref_mut(),
            &[s, &g.blend_weights],
            [texels, 1, 1],
        );
        let probes = fold_groups(self.layout.probe_count);
        self.blend_irradiance.dispatch(
            encoder,
            profiler.as_deref_mut(),
            &[s, &g.blend_irradiance],
            probes,
        );
        self.blend_distance
            .dispatch(encoder, profiler, &[s, &g.blend_distance], probes);
        // The query samples texture copies of the atlases (DdgiResources::irradiance_texture).
        let r = &self.resources;
        for (label, buffer, texture) in [
            ("irradiance", &r.irradiance, &r.irradiance_texture),
            ("distance", &r.distance, &r.distance_texture),
        ] {
            let size = texture.size();
            debug_assert_eq!(size.width * 8 % 256, 0, "{label} atlas rows are aligned");
            encoder.copy_buffer_to_texture(
                wgpu::TexelCopyBufferInfo {
                    buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(size.width * 8),
                        rows_per_image: Some(size.height),
                    },
                },
                texture.as_image_copy(),
                size,
            );
        }
    }

    /// Binds the frame's G-buffer and outputs; call again when they are recreated.
    pub fn bind_frame(&mut self, ctx: &GpuContext, frame: &FrameBuffers) {
        let r = &self.resources;
        let resolve = bind_at(
            &ctx.device,
            "ddgi/resolve",
            &self.frame_layout,
            &[
                (0, &r.volume),
                (5, &r.offsets),
                (9, &frame.gbuffer),
                (10, &frame.indirect),
                (11, &frame.params),
                (15, &r.states),
            ],
        );
        let visualize = bind_at(
            &ctx.device,
            "ddgi/visualize",
            &self.visualize_layout,
            &[
                (0, &r.volume),
                (5, &r.offsets),
                (9, &frame.gbuffer),
                (11, &frame.params),
                (12, &frame.radiance),
                (15, &r.states),
            ],
        );
        self.frame_groups = Some((resolve, visualize));
    }

    /// Records ddgi/resolve: the G-buffer's indirect diffuse light into `frame.indirect`.
    pub fn resolve(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        frame: &FrameBuffers,
        profiler: Option<&mut Profiler>,
    ) {
        let (group, _) = self
            .frame_groups
            .as_ref()
            .expect("Ddgi::bind_frame before resolve");
        self.resolve.dispatch(
            encoder,
            profiler,
            &[&scene.bind_group, group, &self.atlas_group],
            [frame.width.div_ceil(8), frame.height.div_ceil(8), 1],
        );
    }

    /// Records ddgi/visualize: probes drawn as spheres into the composed radiance.
    pub fn visualize(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        frame: &FrameBuffers,
    ) {
        let (_, group) = self
            .frame_groups
            .as_ref()
            .expect("Ddgi::bind_frame before visualize");
        self.visualize.dispatch(
            encoder,
            None,
            &[&scene.bind_group, group, &self.atlas_group],
            [frame.width.div_ceil(8), frame.height.div_ceil(8), 1],
        );
    }

    /// Shadow rays ddgi/shade queued in the last update (0 without the shadow queue).
    pub fn read_queued_shadow_rays(&self, ctx: &GpuContext) -> Result<u32, RenderError> {
        if !self.settings.queues_shadow_rays() {
            return Ok(0);
        }
        let count = irradiant_gpu::read_buffer(ctx, &self.resources.shadow_queue, 0, 4)?;
        Ok(u32::from_le_bytes([count[0], count[1], count[2], count[3]]))
    }

    /// How many probes are in each state (003 §6), read back from the GPU.
    pub fn read_state_counts(&self, ctx: &GpuContext) -> Result<ProbeStateCounts, RenderError> {
        let words: Vec<u32> = read_buffer_as(ctx, &self.resources.states)?;
        let mut counts = ProbeStateCounts::default();
        for word in &words[..self.layout.probe_count as usize] {
            match word & 3 {
                0 => counts.vigilant += 1,
                1 => counts.off += 1,
                2 => counts.sleeping += 1,
                _ => counts.awake += 1,
            }
        }
        Ok(counts)
    }

    /// Each probe's relocation offset and the share of its rays that hit backfaces.
    pub fn read_offsets(&self, ctx: &GpuContext) -> Result<Vec<[f32; 4]>, RenderError> {
        let offsets: Vec<[f32; 4]> = read_buffer_as(ctx, &self.resources.offsets)?;
        Ok(offsets[..self.layout.probe_count as usize].to_vec())
    }

    /// The atlases, decoded: irradiance as cosine-weighted mean radiance (rgb), distance as
    /// (mean, mean²); each with its width and height in texels.
    pub fn read_atlases(&self, ctx: &GpuContext) -> Result<Atlases, RenderError> {
        let packed: Vec<[u32; 2]> = read_buffer_as(ctx, &self.resources.irradiance)?;
        let distance: Vec<[f32; 2]> = read_buffer_as(ctx, &self.resources.distance)?;
        let gamma = self.settings.irradiance_gamma;
        let unpack = |v: u32| [half_to_f32(v as u16), half_to_f32((v >> 16) as u16)];
        let irradiance = packed
            .iter()
            .map(|p| {
                let [r, g] = unpack(p[0]);
                let [b, _] = unpack(p[1]);
                [r, g, b].map(|c| c.max(0.0).powf(gamma))
            })
            .collect();
        let (iw, ih) = self.layout.atlas_size(self.settings.irradiance_texels);
        let (dw, dh) = self.layout.atlas_size(self.settings.distance_texels);
        Ok(Atlases {
            irradiance,
            irradiance_size: (iw, ih),
            distance,
            distance_size: (dw, dh),
        })
    }
}

/// Decoded probe atlases (see [`Ddgi::read_atlases`]).
pub struct Atlases {
    pub irradiance: Vec<[f32; 3]>,
    pub irradiance_size: (u32, u32),
    pub distance: Vec<[f32; 2]>,
    pub distance_size: (u32, u32),
}

/// Group 2 of the passes that query the probes (ddgi_query): the irradiance atlas texture
/// with a bilinear sampler, and the distance atlas texture (f32, so not filterable on every
/// adapter) with a sampler for gathering.
fn atlas_textures(
    device: &wgpu::Device,
    r: &DdgiResources,
) -> (wgpu::BindGroupLayout, wgpu::BindGroup) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("ddgi/atlas_textures"),
        entries: &[
            texture_entry(0, wgpu::TextureViewDimension::D2, true),
            texture_entry(1, wgpu::TextureViewDimension::D2, false),
            sampler_entry(2, wgpu::SamplerBindingType::Filtering),
            sampler_entry(3, wgpu::SamplerBindingType::NonFiltering),
        ],
    });
    let make_sampler = |label, filter| {
        device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some(label),
            mag_filter: filter,
            min_filter: filter,
            ..Default::default()
        })
    };
    let bilinear = make_sampler("ddgi/atlas_bilinear", wgpu::FilterMode::Linear);
    let gather = make_sampler("ddgi/atlas_gather", wgpu::FilterMode::Nearest);
    let irradiance = r.irradiance_texture.create_view(&Default::default());
    let distance = r.distance_texture.create_view(&Default::default());
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("ddgi/atlas_textures"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&irradiance),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&distance),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::Sampler(&bilinear),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Sampler(&gather),
            },
        ],
    });
    (layout, group)
}

/// Constants of a blend pass over tiles of `texels` interior texels: TILE_TEXELS (the tile's
/// texels, border included), BLEND_SPLIT (threads sharing one texel: enough to fill 256
/// threads), BLEND_THREADS (a workgroup's threads: BLEND_SPLIT for each tile texel, up to
/// 256) and BLEND_CHUNK (rays held in workgroup memory at once).
fn blend_constants(texels: u32) -> Vec<(&'static str, String)> {
    let tile_texels = (texels + 2) * (texels + 2);
    let split = (256 / tile_texels).max(1);
    vec![
        (
            "BLEND_THREADS",
            format!("{}u", (split * tile_texels).min(256)),
        ),
        ("BLEND_SPLIT", format!("{split}u")),
        ("TILE_TEXELS", format!("{tile_texels}u")),
        ("BLEND_CHUNK", format!("{BLEND_CHUNK}u")),
    ]
}

/// Rays the blend passes hold in workgroup memory at once: 4 KiB of radiance.
const BLEND_CHUNK: u32 = 256;

/// Constants every DDGI shader sees: PROBES_PER_GROUP (ray_slot in rays.wgsl) and
/// LIGHT_PER_WARP (ddgi/shade).
fn ddgi_shader_constants(settings: &DdgiSettings) -> Vec<(&'static str, String)> {
    vec![
        (
            "PROBES_PER_GROUP",
            format!("{}u", settings.probes_per_group),
        ),
        (
            "LIGHT_PER_WARP",
            format!("{}u", settings.light_per_warp as u32),
        ),
    ]
}

/// IEEE half to f32 (the atlases pack f16 pairs with WGSL's pack2x16float).
pub fn half_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exponent = ((h >> 10) & 0x1f) as i32;
    let mantissa = (h & 0x3ff) as f32;
    match exponent {
        0 => sign * mantissa * 2f32.powi(-24),
        31 => {
            if mantissa == 0.0 {
                sign * f32::INFINITY
            } else {
                f32::NAN
            }
        }
        e => sign * (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

/// A uniformly random rotation for frame `frame` (Shoemake's method from three hashed numbers).
fn random_rotation(seed: u32, frame: u32) -> Quat {
    let hash = |mut x: u32| {
        x ^= x >> 16;
        x = x.wrapping_mul(0x7feb352d);
        x ^= x >> 15;
        x = x.wrapping_mul(0x846ca68b);
        x ^= x >> 16;
        x
    };
    let base = hash(seed.wrapping_mul(0x9e3779b9) ^ hash(frame));
    let u = [hash(base), hash(base ^ 0x68e31da4), hash(base ^ 0xb5297a4d)]
        .map(|v| (v >> 8) as f32 / 16_777_216.0);
    let (a, b) = ((1.0 - u[0]).sqrt(), u[0].sqrt());
    let (t1, t2) = (std::f32::consts::TAU * u[1], std::f32::consts::TAU * u[2]);
    Quat::from_xyzw(a * t1.sin(), a * t1.cos(), b * t2.sin(), b * t2.cos()).normalize()
}

impl crate::frame::Technique for Ddgi {
    fn name(&self) -> &'static str {
        "ddgi"
    }
    fn bind_frame(&mut self, ctx: &GpuContext, frame: &FrameBuffers) {
        Ddgi::bind_frame(self, ctx, frame);
    }
    fn prepare(&mut self, ctx: &GpuContext) {
        Ddgi::prepare(self, ctx);
    }
    fn update(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        profiler: Option<&mut Profiler>,
    ) {
        Ddgi::update(self, encoder, scene, profiler);
    }
    fn resolve(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        frame: &FrameBuffers,
        profiler: Option<&mut Profiler>,
    ) {
        Ddgi::resolve(self, encoder, scene, frame, profiler);
    }
    fn visualize(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        frame: &FrameBuffers,
    ) {
        Ddgi::visualize(self, encoder, scene, frame);
    }
    fn reset(&mut self) {
        Ddgi::reset(self);
    }
    fn scene_changed(&mut self, change: &crate::frame::SceneChange) {
        Ddgi::scene_changed(self, change);
    }
}
