//! Hierarchical screen-space indirect illumination (Soler, Hoel, Rochet and Holzschuch 2009):
//! the light of what the camera sees, gathered over the frame's G-buffer pyramid. Each frame:
//!
//! ```text
//! ssil/voxelize      the view frustum, 128 depth slices a texel, solid inside closed objects
//! ssil/voxel_down    each level's grid from the one below (AND)
//! ssil/gather_<n>    each level's disc or ring of samples: point-to-disc form factors,
//!                    visibility by marching the level's grid, glossy importance sampling
//! ssil/upsample      the levels combined coarsest first, joint-bilaterally upsampled
//! ssil/bounce        (more bounces) the light of bounce n for bounce n + 1 to gather
//! ssil/temporal      blended with last frame's light where the same surface was there, into
//!                    the frame's indirect light (with ssil+ddgi, over the probes' light)
//! ```
//!
//! See docs/ssil.md. Two registry entries: `ssil` alone, and `ssil+ddgi`, where DDGI's probes
//! supply the light the screen cannot see.

pub mod constants;
mod hybrid;
mod kind;
mod resources;
mod settings;
pub mod types;

pub use hybrid::{HybridSettings, SsilDdgi};
pub use kind::{SsilKind, dispatches};
pub use resources::plan;
pub use settings::{SsilSettings, StartResolution};

use std::any::Any;
use std::sync::Arc;

use glam::Vec3;
use irradiant_gpu::{
    BoundPass, ComputePass, GpuContext, PassDesc, Profiler, ResourceTable, Workgroups,
    read_buffer_as, wgpu,
};
use irradiant_scene::Camera;

use crate::RenderError;
use crate::settings::TechniqueSpec;
use crate::technique::{Counter, Technique, TechniqueContext, TechniquePasses, non_finite};
use kind::{gather_groups, level_groups};
use resources::SsilResources;
use types::{GpuSsilParams, GpuSsilPass};

/// The registry entry `ssil`.
pub static SSIL: SsilKind = SsilKind { hybrid: false };
/// The registry entry `ssil+ddgi`: DDGI supplies what the screen cannot see.
pub static SSIL_DDGI: SsilKind = SsilKind { hybrid: true };

/// Per-level labels, so that bench times each level as the paper's table does.
const GATHER_LABELS: [&str; 6] = [
    "ssil/gather_1",
    "ssil/gather_2",
    "ssil/gather_3",
    "ssil/gather_4",
    "ssil/gather_5",
    "ssil/gather_6",
];

/// The compiled passes.
struct Pipelines {
    voxelize: Arc<ComputePass>,
    voxel_down: Arc<ComputePass>,
    gather: Arc<ComputePass>,
    upsample: Arc<ComputePass>,
    bounce: Arc<ComputePass>,
    probe_light: Arc<ComputePass>,
    bounce_down: Arc<ComputePass>,
    temporal: Arc<ComputePass>,
}

/// One bounce's dispatches, in order: its light (after the first), the gathers finest first,
/// the upsamples coarsest first.
struct BouncePasses {
    light: Vec<(BoundPass, Workgroups)>,
    gathers: Vec<(BoundPass, Workgroups)>,
    upsamples: Vec<(BoundPass, Workgroups)>,
}

/// Hierarchical screen-space indirect illumination over the frame's G-buffer pyramid.
pub struct Ssil {
    settings: SsilSettings,
    hybrid: bool,
    /// In ssil+ddgi, the farthest a sender may lie (scene units); below 0: no limit.
    reach: f32,
    /// In ssil+ddgi with DDGI's reflections, the roughest surface they trace: the glossy
    /// gather only above it (`HybridPart::probes_reflect_up_to`).
    probes_reflect_up_to: Option<f32>,
    resources: SsilResources,
    voxels: Vec<(BoundPass, Workgroups)>,
    bounces: Vec<BouncePasses>,
    /// To full resolution.
    upsample: (BoundPass, Workgroups),
    /// Temporal filtering into the frame's indirect light: [frame n mod 2] writes that set of
    /// filtered textures and reads the other.
    temporal: [(BoundPass, Workgroups); 2],
    /// Scene bounds (grown for animation) for the voxel grid's depth range.
    bounds: (Vec3, Vec3),
    frames: u32,
}

/// What `ssil+ddgi` gives its screen part: how far senders count, and the probes it fills with.
pub struct HybridPart<'a> {
    /// The near field's reach (scene units).
    pub reach: f32,
    /// The roughest surface DDGI traces reflections at (`reflections.max_roughness`), None
    /// without them: there the screen's glossy gather steps aside, as its diffuse light does
    /// where the pixels trace.
    pub probes_reflect_up_to: Option<f32>,
    /// The finest probe volume's resources (`DdgiResources::table`), for the fill read around
    /// the uncovered directions (`HybridSettings::bent_fill`); None: the probes' light at the
    /// pixel as it is.
    pub bent_fill: Option<ResourceTable<'a>>,
}

impl Ssil {
    /// Validates the settings, allocates its textures and binds its passes to the frame;
    /// `hybrid` builds it as `ssil+ddgi`'s part, over the probes' light, gathering senders up
    /// to its reach (scene units, the near field).
    pub fn new(
        cx: &TechniqueContext,
        settings: &SsilSettings,
        hybrid_part: Option<HybridPart>,
    ) -> Result<Self, RenderError> {
        settings.validate()?;
        let hybrid = hybrid_part.is_some();
        let hybrid_reach = hybrid_part.as_ref().map(|part| part.reach);
        let probes_reflect_up_to = hybrid_part
            .as_ref()
            .and_then(|part| part.probes_reflect_up_to);
        let bent_fill = hybrid_part.and_then(|part| part.bent_fill);
        let ctx = cx.ctx;
        let size = cx.frame.size();
        let resources = SsilResources::new(ctx, settings, size, hybrid, bent_fill.is_some())?;
        let compile = |label: &'static str, source: &str, tracing: bool| {
            let mut desc = PassDesc::new(label, source);
            if tracing {
                desc = desc.constants(cx.gpu_scene.shader_constants());
            }
            crate::shaders::pass(ctx, &desc).map_err(RenderError::from)
        };
        // The covered directions are summed, stored and bound only for the bent fill.
        let covered = if bent_fill.is_some() {
            include_str!("covered_directions.wgsl")
        } else {
            include_str!("covered_none.wgsl")
        };
        let with_covered = |source: &str| format!("{source}\n{covered}");
        let p = Pipelines {
            voxelize: compile("ssil/voxelize", include_str!("voxelize.wgsl"), true)?,
            voxel_down: compile("ssil/voxel_down", include_str!("voxel_down.wgsl"), false)?,
            gather: compile(
                "ssil/gather",
                &with_covered(include_str!("gather.wgsl")),
                false,
            )?,
            upsample: compile(
                "ssil/upsample",
                &with_covered(include_str!("upsample.wgsl")),
                false,
            )?,
            bounce: compile("ssil/bounce", include_str!("bounce.wgsl"), false)?,
            probe_light: compile("ssil/probe_light", include_str!("probe_light.wgsl"), false)?,
            bounce_down: compile("ssil/bounce", include_str!("bounce_down.wgsl"), false)?,
            temporal: {
                // The light for what the screen leaves uncovered: read from the probes around
                // the bent normal (DDGI's query, with its unfilterable atlas), or the probes'
                // light as it is.
                let (uncovered, unfilterable) = if bent_fill.is_some() {
                    (
                        include_str!("uncovered_bent.wgsl"),
                        crate::ddgi::QUERY_UNFILTERABLE,
                    )
                } else {
                    (include_str!("uncovered_even.wgsl"), &[][..])
                };
                let source = format!(
                    "{}\n{uncovered}",
                    with_covered(include_str!("temporal.wgsl"))
                );
                let desc = PassDesc::new("ssil/temporal", &source).unfilterable(unfilterable);
                crate::shaders::pass(ctx, &desc)?
            },
        };
        let scene_table = cx.gpu_scene.resources();
        let frame_table = cx.frame.resources.table();
        let r = &resources;
        let s = settings.start.level();
        let levels = settings.levels;
        let group = |k: u32| level_groups(size, k);
        // One uniform a dispatch: each holds its own level.
        let pass_uniform = |pass: GpuSsilPass| ctx.uniform_buffer("ssil/pass", &pass);
        let bind =
            |pipeline: &Arc<ComputePass>, own: ResourceTable| -> Result<BoundPass, RenderError> {
                Ok(pipeline.bind(ctx, &[&scene_table, &frame_table, &own])?)
            };
        // The voxel grid: level 0 by tracing, each further level by AND.
        let mut voxels = vec![(
            bind(
                &p.voxelize,
                ResourceTable::new()
                    .buffer("ssil", &r.params)
                    .buffer("ssil_counters", &r.counters)
                    .texture("target_voxels", &r.voxels.levels[0]),
            )?,
            group(s),
        )];
        for j in 1..levels as usize {
            let own = ResourceTable::new()
                .texture("source_voxels", &r.voxels.levels[j - 1])
                .texture("target_voxels", &r.voxels.levels[j]);
            voxels.push((p.voxel_down.bind(ctx, &[&own])?, group(s + j as u32)));
        }
        let pyramid_radiance = cx.frame.resources.view("pyramid_radiance");
        let mut bounces = Vec::new();
        let mut uniforms = Vec::new();
        for bounce in 0..settings.bounces {
            let last = bounce + 1 == settings.bounces;
            let mut light = Vec::new();
            if bounce > 0 || hybrid {
                let b = r
                    .bounce
                    .as_ref()
                    .expect("a bounce chain with more than one bounce or probes");
                // The start level: the last bounce's light reflected, or (the hybrid's first
                // bounce) the probes' light added.
                let start_light = if bounce > 0 {
                    bind(
                        &p.bounce,
                        ResourceTable::new()
                            .buffer("ssil", &r.params)
                            .texture("combined_light", &r.combined.levels[0])
                            .texture("target_radiance", &b.levels[0]),
                    )?
                } else {
                    bind(
                        &p.probe_light,
                        ResourceTable::new()
                            .buffer("ssil", &r.params)
                            .texture("target_radiance", &b.levels[0]),
                    )?
                };
                light.push((start_light, group(s)));
                for j in 1..levels {
                    uniforms.push(pass_uniform(GpuSsilPass {
                        level: s + j,
                        ..Default::default()
                    }));
                    let own = ResourceTable::new()
                        .buffer("ssil", &r.params)
                        .buffer("ssil_pass", uniforms.last().unwrap())
                        .texture("source_radiance", &b.levels[j as usize - 1])
                        .texture("target_radiance", &b.levels[j as usize]);
                    light.push((bind(&p.bounce_down, own)?, group(s + j)));
                }
            }
            let mut gathers = Vec::new();
            for j in 0..levels {
                let (source, radiance_level) = match &r.bounce {
                    Some(b) if bounce > 0 || hybrid => (&b.view, j),
                    _ => (pyramid_radiance, s + j),
                };
                uniforms.push(pass_uniform(GpuSsilPass {
                    level: s + j,
                    first: (j == 0) as u32,
                    last_bounce: last as u32,
                    radiance_level,
                    ..Default::default()
                }));
                let own = ResourceTable::new()
                    .buffer("ssil", &r.params)
                    .buffer("ssil_pass", uniforms.last().unwrap())
                    .texture("source_radiance", source)
                    .texture("ssil_voxels", &r.voxels.view)
                    .texture("target_light", &r.gather.levels[j as usize])
                    .texture("target_specular", &r.gather_specular.levels[j as usize]);
                let own = match &r.covered {
                    Some(c) => own.texture("target_direction", &c.gather.levels[j as usize]),
                    None => own,
                };
                gathers.push((
                    bind(&p.gather, own)?.labelled(GATHER_LABELS[j as usize]),
                    gather_groups(size, s + j),
                ));
            }
            let mut upsamples = Vec::new();
            for j in (0..levels).rev() {
                let coarsest = j + 1 == levels;
                // The coarsest level has nothing above: its own gather stands in, unread.
                let above = if coarsest { j } else { j + 1 } as usize;
                let (coarse, coarse_specular) = if coarsest {
                    (&r.gather.levels[above], &r.gather_specular.levels[above])
                } else {
                    (
                        &r.combined.levels[above],
                        &r.combined_specular.levels[above],
                    )
                };
                uniforms.push(pass_uniform(GpuSsilPass {
                    level: s + j,
                    coarse_level: if coarsest { 0 } else { s + j + 1 },
                    with_gather: 1,
                    ..Default::default()
                }));
                let own = ResourceTable::new()
                    .buffer("ssil", &r.params)
                    .buffer("ssil_pass", uniforms.last().unwrap())
                    .texture("source_light", &r.gather.levels[j as usize])
                    .texture("source_specular", &r.gather_specular.levels[j as usize])
                    .texture("coarse_light", coarse)
                    .texture("coarse_specular", coarse_specular)
                    .texture("target_light", &r.combined.levels[j as usize])
                    .texture("target_specular", &r.combined_specular.levels[j as usize]);
                let own = match &r.covered {
                    Some(c) => {
                        let coarse = if coarsest { &c.gather } else { &c.combined };
                        own.texture("source_direction", &c.gather.levels[j as usize])
                            .texture("coarse_direction", &coarse.levels[above])
                            .texture("target_direction", &c.combined.levels[j as usize])
                    }
                    None => own,
                };
                upsamples.push((bind(&p.upsample, own)?, group(s + j)));
            }
            bounces.push(BouncePasses {
                light,
                gathers,
                upsamples,
            });
        }
        // To full resolution: the start level joint-bilaterally upsampled (at a full start, the
        // combined level 0 itself).
        uniforms.push(pass_uniform(GpuSsilPass {
            level: 0,
            coarse_level: s,
            with_gather: (s == 0) as u32,
            ..Default::default()
        }));
        let own = ResourceTable::new()
            .buffer("ssil", &r.params)
            .buffer("ssil_pass", uniforms.last().unwrap())
            .texture("source_light", &r.combined.levels[0])
            .texture("source_specular", &r.combined_specular.levels[0])
            .texture("coarse_light", &r.combined.levels[0])
            .texture("coarse_specular", &r.combined_specular.levels[0])
            .texture("target_light", &r.full.view)
            .texture("target_specular", &r.full_specular.view);
        let own = match &r.covered {
            Some(c) => own
                .texture("source_direction", &c.combined.levels[0])
                .texture("coarse_direction", &c.combined.levels[0])
                .texture("target_direction", &c.full.view),
            None => own,
        };
        let upsample = (bind(&p.upsample, own)?, group(0));
        let temporal = |now: usize| -> Result<(BoundPass, Workgroups), RenderError> {
            let before = 1 - now;
            let own = ResourceTable::new()
                .buffer("ssil", &r.params)
                .texture("ssil_full", &r.full.view)
                .texture("ssil_full_specular", &r.full_specular.view)
                .texture("ssil_history", &r.filtered[before].view)
                .texture("ssil_history_specular", &r.filtered_specular[before].view)
                .texture("ssil_history_geometry", &r.filtered_geometry[before].view)
                .texture("ssil_filtered", &r.filtered[now].view)
                .texture("ssil_filtered_specular", &r.filtered_specular[now].view)
                .texture("ssil_filtered_geometry", &r.filtered_geometry[now].view);
            let own = match &r.covered {
                Some(c) => own
                    .texture("source_direction", &c.full.view)
                    .texture("history_direction", &c.filtered[before].view)
                    .texture("target_direction", &c.filtered[now].view),
                None => own,
            };
            let mut tables = vec![&scene_table, &frame_table, &own];
            if let Some(probes) = &bent_fill {
                tables.push(probes);
            }
            Ok((p.temporal.bind(ctx, &tables)?, group(0)))
        };
        let temporal = [temporal(0)?, temporal(1)?];
        // The pass uniforms stay alive through the bind groups that hold them.
        drop(uniforms);
        let (lo, hi) = cx.scene.bounds();
        let grow = (hi - lo).max(Vec3::splat(1e-3)) * 0.1;
        Ok(Self {
            settings: settings.clone(),
            hybrid,
            reach: hybrid_reach.unwrap_or(-1.0),
            probes_reflect_up_to,
            resources,
            voxels,
            bounces,
            upsample,
            temporal,
            bounds: (lo - grow, hi + grow),
            frames: 0,
        })
    }

    /// The settings it runs with.
    pub fn settings(&self) -> &SsilSettings {
        &self.settings
    }

    /// The view depths the voxel grid's slices span: the scene's bounds seen from the camera.
    pub fn depth_range(&self, camera: &Camera) -> (f32, f32) {
        let forward = (camera.target - camera.position).normalize_or(Vec3::NEG_Z);
        let (lo, hi) = self.bounds;
        let depths = (0..8).map(|c| {
            let corner = Vec3::new(
                if c & 1 == 0 { lo.x } else { hi.x },
                if c & 2 == 0 { lo.y } else { hi.y },
                if c & 4 == 0 { lo.z } else { hi.z },
            );
            (corner - camera.position).dot(forward)
        });
        let (near, far) = depths.fold((f32::MAX, f32::MIN), |(n, f), d| (n.min(d), f.max(d)));
        let far = far.max(1e-3);
        (near.max(far * 1e-3), far)
    }

    /// Voxelization rays of the last frame that ended inside a solid (crossed an odd number of
    /// surfaces), and all of them: the share of open geometry the camera sees.
    pub fn read_open_rays(&self, ctx: &GpuContext) -> Result<(u32, u32), RenderError> {
        let c: Vec<u32> = read_buffer_as(ctx, &self.resources.counters)?;
        Ok((c[0], c[1]))
    }

    /// The last frame's filtered light at full resolution: (E rgb, coverage) a pixel, E being
    /// ∫ L cos dω (a Lambertian surface of albedo ρ reflects ρ/π × E).
    pub fn read_light(&self, ctx: &GpuContext) -> Result<Vec<[f32; 4]>, RenderError> {
        // The set the last frame wrote.
        let last = (self.frames + 1) as usize % 2;
        read_rgba16(ctx, &self.resources.filtered[last].texture, 0)
    }

    /// One level of the last bounce's gathers (level 0: the start level), as [`Self::read_light`].
    pub fn read_gather(&self, ctx: &GpuContext, level: u32) -> Result<Vec<[f32; 4]>, RenderError> {
        read_rgba16(ctx, &self.resources.gather.texture, level)
    }

    /// One level of the voxel grid (level 0: the start level's resolution): 128 slice bits a
    /// texel, as four u32.
    pub fn read_voxels(&self, ctx: &GpuContext, level: u32) -> Result<Vec<[u32; 4]>, RenderError> {
        let bytes =
            irradiant_gpu::read_texture_level(ctx, &self.resources.voxels.texture, level, 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    fn record_frame(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        if self.settings.visibility {
            encoder.clear_buffer(&self.resources.counters, 0, None);
            for (pass, groups) in &self.voxels {
                pass.dispatch(encoder, profiler.as_deref_mut(), *groups);
            }
        }
        for bounce in &self.bounces {
            for (pass, groups) in bounce
                .light
                .iter()
                .chain(&bounce.gathers)
                .chain(&bounce.upsamples)
            {
                pass.dispatch(encoder, profiler.as_deref_mut(), *groups);
            }
        }
        let (upsample, groups) = &self.upsample;
        upsample.dispatch(encoder, profiler.as_deref_mut(), *groups);
        let (temporal, groups) = &self.temporal[self.frames as usize % 2];
        temporal.dispatch(encoder, profiler, *groups);
        // Wrapping keeps the ping-pong's parity (2³² is even).
        self.frames = self.frames.wrapping_add(1);
    }
}

impl Technique for Ssil {
    fn name(&self) -> &'static str {
        if self.hybrid { "ssil+ddgi" } else { "ssil" }
    }
    fn passes(&self) -> TechniquePasses {
        let mut update = vec!["ssil/voxelize", "ssil/voxel_down"];
        update.extend(&GATHER_LABELS[..self.settings.levels as usize]);
        update.extend(["ssil/upsample", "ssil/probe_light", "ssil/bounce"]);
        TechniquePasses {
            update,
            resolve: vec!["ssil/temporal"],
        }
    }
    fn prepare(&mut self, ctx: &GpuContext, camera: &Camera) {
        let s = &self.settings;
        // Glossy reflection at surfaces rougher than this; above 1 at none.
        let glossy_above = match (s.glossy, self.probes_reflect_up_to) {
            (false, _) => 2.0,
            (true, Some(traced)) => traced,
            (true, None) => -1.0,
        };
        let (near, far) = self.depth_range(camera);
        let height = self.resources.full.texture.size().height;
        let params = GpuSsilParams {
            start_level: s.start.level(),
            levels: s.levels,
            samples: s.samples,
            visibility: s.visibility as u32,
            radius: s.radius_at(height),
            near,
            far,
            visibility_steps: s.visibility_steps,
            visibility_bias: s.visibility_bias,
            importance_alpha: if s.glossy { s.importance_alpha } else { 1e9 },
            hysteresis: s.hysteresis,
            motion_pixels: s.motion_pixels,
            depth_tolerance: s.depth_tolerance,
            normal_tolerance: s.normal_tolerance,
            history_frames: self.frames,
            hybrid: self.hybrid as u32,
            reach: self.reach,
            glossy_above,
            _pad1: 0,
            _pad2: 0,
        };
        ctx.queue
            .write_buffer(&self.resources.params, 0, bytemuck::bytes_of(&params));
    }
    fn update(&mut self, _encoder: &mut wgpu::CommandEncoder, _profiler: Option<&mut Profiler>) {}
    /// The whole technique runs at resolve time: it gathers the frame's own direct light.
    fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut Profiler>) {
        self.record_frame(encoder, profiler);
    }
    fn invalidate(&mut self) {
        self.frames = 0;
    }
    fn reconfigure(
        &mut self,
        _ctx: &GpuContext,
        spec: &TechniqueSpec,
    ) -> Result<bool, RenderError> {
        if spec.name != Technique::name(self) {
            return Ok(false);
        }
        let kind = if self.hybrid { &SSIL_DDGI } else { &SSIL };
        let (settings, _) = kind.settings(spec, &mut Vec::new())?;
        // Sizes, levels, bounces and the samples' layout shape the passes: only the filter's
        // and the march's numbers change live.
        let live = SsilSettings {
            hysteresis: self.settings.hysteresis,
            motion_pixels: self.settings.motion_pixels,
            depth_tolerance: self.settings.depth_tolerance,
            normal_tolerance: self.settings.normal_tolerance,
            visibility_bias: self.settings.visibility_bias,
            importance_alpha: self.settings.importance_alpha,
            ..settings.clone()
        };
        if live != self.settings || self.hybrid {
            return Ok(false);
        }
        self.settings = settings;
        Ok(true)
    }
    fn check_state(&self, ctx: &GpuContext) -> Result<Vec<String>, RenderError> {
        let light = self.read_light(ctx)?;
        Ok(
            non_finite("ssil filtered light", light.iter().flatten().copied())
                .into_iter()
                .collect(),
        )
    }
    /// Each level of the pyramid's gathers (irradiance ÷ π, as radiance) and of the voxel grid
    /// (the share of its 128 depth slices that are solid, as grey).
    fn inspect(&self, ctx: &GpuContext) -> Result<crate::inspect::Inspection, RenderError> {
        use crate::inspect::{DebugImage, grey_pixel, radiance_pixel};
        let mut out = crate::inspect::Inspection::default();
        let pi = std::f32::consts::PI;
        for level in 0..self.resources.gather.levels.len() as u32 {
            let size = self
                .resources
                .gather
                .texture
                .size()
                .mip_level_size(level, wgpu::TextureDimension::D2);
            let gather = self.read_gather(ctx, level)?;
            out.images.push(DebugImage::from_texels(
                format!("ssil/gather, level {level}"),
                (size.width, size.height),
                &gather,
                |e| radiance_pixel([e[0] / pi, e[1] / pi, e[2] / pi]),
            ));
        }
        for level in 0..self.resources.voxels.levels.len() as u32 {
            let size = self
                .resources
                .voxels
                .texture
                .size()
                .mip_level_size(level, wgpu::TextureDimension::D2);
            let voxels = self.read_voxels(ctx, level)?;
            out.images.push(DebugImage::from_texels(
                format!("ssil/voxels, level {level}"),
                (size.width, size.height),
                &voxels,
                |bits| grey_pixel(bits.iter().map(|b| b.count_ones()).sum::<u32>() as f32 / 128.0),
            ));
        }
        Ok(out)
    }
    fn counters(&self, ctx: &GpuContext) -> Result<Vec<Counter>, RenderError> {
        let (open, total) = self.read_open_rays(ctx)?;
        Ok(vec![
            Counter {
                name: "voxel_rays",
                value: total as f64,
            },
            Counter {
                name: "open_voxel_rays",
                value: open as f64,
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

fn read_rgba16(
    ctx: &GpuContext,
    texture: &wgpu::Texture,
    level: u32,
) -> Result<Vec<[f32; 4]>, RenderError> {
    let bytes = irradiant_gpu::read_texture_level(ctx, texture, level, 8)?;
    let halves: &[half::f16] = bytemuck::cast_slice(&bytes);
    Ok(halves
        .chunks_exact(4)
        .map(|c| [c[0].to_f32(), c[1].to_f32(), c[2].to_f32(), c[3].to_f32()])
        .collect())
}
