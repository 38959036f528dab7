//! The final gather's history (`DdgiGatherSettings`): ddgi/temporal's running mean of the
//! gathered light, its second moment and the geometry it was taken on, two sets ping-ponged
//! (this frame's is the next frame's history), the pass bound to each, and ddgi/gather_filter's
//! passes over this frame's mean, all on the gather's own image (the frame's, or half of it
//! with `half_resolution`): ddgi/gather traces there (a pass a volume, into `gathered`), and
//! ddgi/gather_upsample brings the filter's last pass into the frame's `indirect`.

use std::sync::Arc;

use irradiant_gpu::{
    Allocation, BoundPass, ComputePass, GpuContext, Profiler, ResourceTable, Workgroups, wgpu,
};

use crate::RenderError;

/// What sizes the history, for the messages that refuse too large an image.
const HISTORY_SETTING: &str = "the image size (--size) or technique.gather.rays_per_pixel";
const FILTER_SETTING: &str = "the image size (--size) or technique.gather.filter_passes";

/// (mean, frames in it) and (normal, view depth) per texel, rgba32float; the mean of the
/// gathers' squared luminance, r32float.
const LABELS: [[&str; 3]; 2] = [
    [
        "ddgi/gather_mean_0",
        "ddgi/gather_geometry_0",
        "ddgi/gather_moment_0",
    ],
    [
        "ddgi/gather_mean_1",
        "ddgi/gather_geometry_1",
        "ddgi/gather_moment_1",
    ],
];
const FORMATS: [(wgpu::TextureFormat, u64); 3] = [
    (wgpu::TextureFormat::Rgba32Float, 16),
    (wgpu::TextureFormat::Rgba32Float, 16),
    (wgpu::TextureFormat::R32Float, 4),
];
/// Between filter passes, and after the last (ddgi/gather_upsample's source): (light,
/// variance), the passes taking the two in turn.
const FILTER_SCRATCH: [&str; 2] = ["ddgi/gather_filtered", "ddgi/gather_filtered_1"];
/// ddgi/gather's light (weighted sum, weight) and the query at each texel's pixel (rgb, and
/// the luminance ddgi/gather_upsample scales by), the light arriving.
const GATHER_IMAGES: [&str; 2] = ["ddgi/gathered", "ddgi/gather_query"];
const RGBA32: (wgpu::TextureFormat, u64) = (wgpu::TextureFormat::Rgba32Float, 16);

/// The gather's image at an image size: the image, or half of it rounded up.
pub fn image_size((width, height): (u32, u32), half: bool) -> (u32, u32) {
    let scale = 1 + half as u32;
    (width.div_ceil(scale), height.div_ceil(scale))
}

/// One thread a texel of the gather's image (ddgi/gather, ddgi/temporal,
/// ddgi/gather_filter), or with `half` false of the frame's (ddgi/gather_upsample).
pub fn workgroups(size: (u32, u32), half: bool) -> Workgroups {
    let (width, height) = image_size(size, half);
    Workgroups::for_image(width, height, crate::frame::IMAGE_TILE)
}

/// The history's allocations at an image size, with the gather's images and the filter's
/// scratch.
pub fn plan(size: (u32, u32), filter_passes: u32, half: bool) -> Vec<Allocation> {
    let own = image_size(size, half);
    let texture =
        |label: &str, bytes, setting: &str| Allocation::texture(label, own, bytes, 1, setting);
    let mut all: Vec<Allocation> = LABELS
        .iter()
        .flat_map(|set| set.iter().zip(FORMATS))
        .map(|(label, (_, bytes))| texture(label, bytes, HISTORY_SETTING))
        .collect();
    let scratch = FILTER_SCRATCH[..filter_passes.min(2) as usize].iter();
    all.extend(scratch.map(|label| texture(label, RGBA32.1, FILTER_SETTING)));
    all.extend(GATHER_IMAGES.map(|label| texture(label, RGBA32.1, HISTORY_SETTING)));
    all
}

/// The gather's passes, as DdgiPipelines compiled them.
pub struct GatherPipelines<'a> {
    /// ddgi/gather and ddgi/gather_upsample.
    pub gather: &'a (Arc<ComputePass>, Arc<ComputePass>),
    pub temporal: &'a Arc<ComputePass>,
    pub filters: &'a [Arc<ComputePass>],
    /// `gather.half_resolution`: the gather's image is half the frame's.
    pub half: bool,
}

/// What one frame of the two ping-ponged sets records after ddgi/gather, in order.
struct FramePasses {
    temporal: BoundPass,
    filters: Vec<BoundPass>,
    upsample: BoundPass,
}

pub struct GatherHistory {
    /// ddgi/gather for each volume, finest first.
    gathers: Vec<BoundPass>,
    /// Writing set 0 (reading set 1), and writing set 1.
    frames: [FramePasses; 2],
    image: Workgroups,
    own_image: Workgroups,
    count: u64,
    /// Kept alive for the passes' views.
    _textures: Vec<wgpu::Texture>,
}

impl GatherHistory {
    /// `tables`: the scene's and the frame's (whose `indirect` ddgi/resolve has written the
    /// query into); `volumes`: each volume's own, finest first (the first's
    /// `gather_history_frames` is ddgi/temporal's).
    pub fn new(
        ctx: &GpuContext,
        pipelines: GatherPipelines,
        tables: &[&ResourceTable],
        volumes: &[ResourceTable],
        size: (u32, u32),
    ) -> Result<Self, RenderError> {
        let passes = pipelines.filters.len();
        ctx.check_allocations(&plan(size, passes as u32, pipelines.half))?;
        let own = image_size(size, pipelines.half);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let texture = |label: &str, format| {
            irradiant_gpu::texture_2d(&ctx.device, label, own, format, 1, usage)
        };
        // [mean, geometry, moment] of each set, then the scratch, then the gather's images.
        let textures: Vec<wgpu::Texture> = LABELS
            .iter()
            .flat_map(|set| set.iter().zip(FORMATS))
            .map(|(label, (format, _))| texture(label, format))
            .chain(
                FILTER_SCRATCH[..passes.min(2)]
                    .iter()
                    .map(|l| texture(l, RGBA32.0)),
            )
            .chain(GATHER_IMAGES.iter().map(|l| texture(l, RGBA32.0)))
            .collect();
        let views: Vec<wgpu::TextureView> = textures
            .iter()
            .map(|t| t.create_view(&Default::default()))
            .collect();
        let set = |now: usize, item: usize| &views[3 * now + item];
        let scratch = &views[6..6 + passes.min(2)];
        let (gathered, query) = (&views[views.len() - 2], &views[views.len() - 1]);
        let bind = |pass: &Arc<ComputePass>, own: ResourceTable, volume: &ResourceTable| {
            let mut all = tables.to_vec();
            all.push(volume);
            all.push(&own);
            pass.bind(ctx, &all)
        };
        let first = &volumes[0];
        let frame_passes = |now: usize| -> Result<FramePasses, RenderError> {
            let before = 1 - now;
            let temporal = bind(
                pipelines.temporal,
                ResourceTable::new()
                    .texture("gather_source", gathered)
                    .texture("gather_history", set(before, 0))
                    .texture("gather_history_geometry", set(before, 1))
                    .texture("gather_history_moment", set(before, 2))
                    .texture("gather_mean", set(now, 0))
                    .texture("gather_mean_geometry", set(now, 1))
                    .texture("gather_moment", set(now, 2)),
                first,
            )?;
            let mut from = set(now, 0);
            let mut filters = Vec::new();
            for (k, pass) in pipelines.filters.iter().enumerate() {
                let own = ResourceTable::new()
                    .texture("filter_source", from)
                    .texture("filter_moment", set(now, 2))
                    .texture("filter_target", &scratch[k % 2]);
                filters.push(bind(pass, own, first)?);
                from = &scratch[k % 2];
            }
            let upsample = ResourceTable::new()
                .texture("upsample_source", from)
                .texture("upsample_query", query);
            Ok(FramePasses {
                temporal,
                filters,
                upsample: bind(&pipelines.gather.1, upsample, first)?,
            })
        };
        let gathers = volumes
            .iter()
            .map(|volume| {
                let own = ResourceTable::new()
                    .texture("gathered", gathered)
                    .texture("gather_query", query);
                bind(&pipelines.gather.0, own, volume)
            })
            .collect::<Result<_, _>>()?;
        Ok(Self {
            gathers,
            frames: [frame_passes(0)?, frame_passes(1)?],
            image: workgroups(size, false),
            own_image: workgroups(size, pipelines.half),
            count: 0,
            _textures: textures,
        })
    }

    /// Records, after every volume's ddgi/resolve: ddgi/gather for each volume, ddgi/temporal,
    /// the filter's passes and ddgi/gather_upsample.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        for gather in &self.gathers {
            gather.dispatch(encoder, profiler.as_deref_mut(), self.own_image);
        }
        let now = &self.frames[(self.count % 2) as usize];
        now.temporal
            .dispatch(encoder, profiler.as_deref_mut(), self.own_image);
        for filter in &now.filters {
            filter.dispatch(encoder, profiler.as_deref_mut(), self.own_image);
        }
        now.upsample.dispatch(encoder, profiler, self.image);
        self.count += 1;
    }
}
