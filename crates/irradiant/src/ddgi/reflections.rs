//! GI in glossy reflections (003 §4.4, `[technique.reflections]`): at pixels glossy enough, a
//! ray sampled from the GGX lobe (ddgi/reflect), its hit lit directly and by the probes (the
//! second and later bounces), then filtered across neighbours of the same surface and lobe,
//! averaged over frames along the motion vectors and added to the frame's indirect light
//! (ddgi/reflect_filter). The running mean and the geometry it was taken on are two sets,
//! ping-ponged as the final gather's are.

use std::sync::Arc;

use documented::DocumentedFields;
use irradiant_gpu::{
    Allocation, BoundPass, ComputePass, GpuContext, Profiler, ResourceTable, Workgroups, wgpu,
};
use serde::{Deserialize, Serialize};

use crate::RenderError;
use crate::settings::{SettingsError, check_range};

/// Glossy reflections of the lit scene (`[technique.reflections]`). Without them a glossy
/// surface reflects only what `frame/direct` gives it: the lights' highlights, none of the
/// surfaces around it. Compiled in: a change rebuilds the technique.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct DdgiReflectionSettings {
    /// Trace a reflection ray at the glossy pixels (`max_roughness`): a mirror shows the room,
    /// a polished floor the walls and their light (the mirror Cornell box's tall box, FLIP
    /// against the path tracer, docs/ddgi.md). Costs a traced ray, a shadow ray and a probe
    /// query at each glossy pixel that traces, and two passes over the image; nothing is
    /// traced in scenes without glossy surfaces.
    pub enabled: bool,
    /// The roughest surface that traces (GGX roughness, 0 to 1). Rougher surfaces get no
    /// glossy indirect light (a metal rougher than this none at all: it has no diffuse term);
    /// each glossy pixel traced costs a ray.
    pub max_roughness: f32,
    /// Trace one pixel of each 2×2 a frame, in turn, and fill the others from it: a quarter of
    /// the rays, at the cost of detail in sharp reflections and four frames to refine them.
    pub half_resolution: bool,
    /// Frames the reflected light is averaged over at `max_roughness` (a running mean
    /// reprojected along the motion vectors); mirror-like surfaces keep fewer, down to 2,
    /// since their reflections move over the surface with the view. More: less noise on rough
    /// reflections, and as many frames of lag.
    pub history_frames: u32,
}

impl DdgiReflectionSettings {
    /// Off: the image of the paper's query, and the cost.
    pub fn off() -> Self {
        Self {
            enabled: false,
            max_roughness: 0.5,
            half_resolution: true,
            history_frames: 16,
        }
    }

    /// On, tracing a quarter of the glossy pixels a frame.
    pub fn half() -> Self {
        Self {
            enabled: true,
            ..Self::off()
        }
    }

    /// On, every glossy pixel tracing every frame.
    pub fn full() -> Self {
        Self {
            half_resolution: false,
            ..Self::half()
        }
    }

    /// Refuses settings that cannot work, naming the field.
    pub fn validate(&self) -> Result<(), SettingsError> {
        check_range(
            "technique.reflections.max_roughness",
            self.max_roughness,
            0.0,
            1.0,
        )?;
        check_range(
            "technique.reflections.history_frames",
            self.history_frames,
            2,
            256,
        )
    }

    /// The constants ddgi/reflect and ddgi/reflect_filter are compiled with.
    pub fn shader_constants(&self) -> Vec<(&'static str, String)> {
        vec![
            ("REFLECT_MAX_ROUGHNESS", format!("{:?}", self.max_roughness)),
            (
                "REFLECT_STEP",
                format!("{}u", if self.half_resolution { 2 } else { 1 }),
            ),
            (
                "REFLECT_HISTORY",
                format!("{:?}", self.history_frames as f32),
            ),
        ]
    }

    /// ddgi/reflect's workgroups at an image size: a thread for each block of pixels that
    /// traces one ray.
    pub fn trace_workgroups(&self, (width, height): (u32, u32)) -> Workgroups {
        let step = if self.half_resolution { 2 } else { 1 };
        Workgroups::for_image(
            width.div_ceil(step),
            height.div_ceil(step),
            crate::frame::IMAGE_TILE,
        )
    }
}

/// What sizes the reflections' textures, for the messages that refuse too large an image.
const SIZE_SETTING: &str = "the image size (--size) or technique.reflections.enabled";

/// This frame's rays (rgb the reflected light, a the hit distance; a < 0 where the pixel did
/// not trace), then the running mean (rgb, frames in it) and the geometry it was taken on
/// (normal, view depth), two sets. rgba16float each.
const LABELS: [&str; 5] = [
    "ddgi/reflection_rays",
    "ddgi/reflection_mean_0",
    "ddgi/reflection_geometry_0",
    "ddgi/reflection_mean_1",
    "ddgi/reflection_geometry_1",
];
const TEXEL_BYTES: u64 = 8;

/// The reflections' allocations at an image size.
pub fn plan(size: (u32, u32)) -> Vec<Allocation> {
    LABELS
        .iter()
        .map(|label| Allocation::texture(*label, size, TEXEL_BYTES, 1, SIZE_SETTING))
        .collect()
}

/// The reflections' textures and passes.
pub struct Reflections {
    trace: BoundPass,
    /// ddgi/reflect_filter writing set 0 (reading set 1), and writing set 1.
    filters: [BoundPass; 2],
    trace_groups: Workgroups,
    image: Workgroups,
    frames: u64,
    /// Kept alive for the passes' views.
    _textures: Vec<wgpu::Texture>,
}

impl Reflections {
    /// `tables`: the scene's, the frame's (whose `indirect` the filter adds the reflections to)
    /// and the finest volume's, whose probes light the reflection rays' hits.
    pub fn new(
        ctx: &GpuContext,
        (trace, filter): (&Arc<ComputePass>, &Arc<ComputePass>),
        tables: &[&ResourceTable],
        settings: &DdgiReflectionSettings,
        size: (u32, u32),
    ) -> Result<Self, RenderError> {
        ctx.check_allocations(&plan(size))?;
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let textures: Vec<wgpu::Texture> = LABELS
            .iter()
            .map(|label| {
                irradiant_gpu::texture_2d(
                    &ctx.device,
                    label,
                    size,
                    wgpu::TextureFormat::Rgba16Float,
                    1,
                    usage,
                )
            })
            .collect();
        let views: Vec<wgpu::TextureView> = textures
            .iter()
            .map(|t| t.create_view(&Default::default()))
            .collect();
        let rays = &views[0];
        let bind =
            |pass: &Arc<ComputePass>, own: ResourceTable| -> Result<BoundPass, RenderError> {
                let mut all = tables.to_vec();
                all.push(&own);
                Ok(pass.bind(ctx, &all)?)
            };
        let bind_filter = |now: usize| {
            let (mean, geometry) = (&views[1 + 2 * now], &views[2 + 2 * now]);
            let before = 1 - now;
            let (old_mean, old_geometry) = (&views[1 + 2 * before], &views[2 + 2 * before]);
            bind(
                filter,
                ResourceTable::new()
                    .texture("reflection_rays_read", rays)
                    .texture("reflection_history", old_mean)
                    .texture("reflection_history_geometry", old_geometry)
                    .texture("reflection_mean", mean)
                    .texture("reflection_mean_geometry", geometry),
            )
        };
        Ok(Self {
            trace: bind(trace, ResourceTable::new().texture("reflection_rays", rays))?,
            filters: [bind_filter(0)?, bind_filter(1)?],
            trace_groups: settings.trace_workgroups(size),
            image: Workgroups::for_image(size.0, size.1, crate::frame::IMAGE_TILE),
            frames: 0,
            _textures: textures,
        })
    }

    /// Records ddgi/reflect and ddgi/reflect_filter, after the diffuse light is in `indirect`.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        self.trace
            .dispatch(encoder, profiler.as_deref_mut(), self.trace_groups);
        let now = (self.frames % 2) as usize;
        self.filters[now].dispatch(encoder, profiler, self.image);
        self.frames += 1;
    }
}
