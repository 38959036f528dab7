//! The final gather's history (`DdgiGatherSettings`): ddgi/temporal's running mean of the
//! gathered light, its second moment and the geometry it was taken on, two sets ping-ponged
//! (this frame's is the next frame's history), the pass bound to each, and ddgi/gather_filter's
//! passes from this frame's mean into the frame's `indirect`. With `half_resolution` all of it
//! is on a half-size image: ddgi/gather traces there (a pass a volume, into `gathered`), the
//! filter's last pass writes a scratch image and ddgi/gather_upsample brings that to
//! `indirect`.

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
/// Between filter passes that do not write the frame's `indirect`: (light, variance). Half
/// size takes both (no pass writes `indirect`), full size the first from two passes on.
const FILTER_SCRATCH: [&str; 2] = ["ddgi/gather_filtered", "ddgi/gather_filtered_1"];
/// With `half_resolution`: ddgi/gather's light (weighted sum, weight) and the query at each
/// texel's pixel (ddgi/gather_upsample's scale).
const HALF_IMAGES: [&str; 2] = ["ddgi/gathered", "ddgi/gather_query"];
const RGBA32: (wgpu::TextureFormat, u64) = (wgpu::TextureFormat::Rgba32Float, 16);

/// The gather's image at an image size: the image, or half of it rounded up.
pub fn image_size((width, height): (u32, u32), half: bool) -> (u32, u32) {
    let scale = 1 + half as u32;
    (width.div_ceil(scale), height.div_ceil(scale))
}

/// ddgi/temporal's, ddgi/gather_filter's and ddgi/gather's workgroups: one thread a texel of
/// the gather's image.
pub fn workgroups(size: (u32, u32), half: bool) -> Workgroups {
    let (width, height) = image_size(size, half);
    Workgroups::for_image(width, height, crate::frame::IMAGE_TILE)
}

/// The scratch images `filter_passes` needs: see FILTER_SCRATCH.
fn scratch_count(filter_passes: u32, half: bool) -> usize {
    match half {
        true => filter_passes.min(2) as usize,
        false => (filter_passes >= 2) as usize,
    }
}

/// The history's allocations at an image size, with the filter's scratch and the half-size
/// gather's images where they are needed.
pub fn plan(size: (u32, u32), filter_passes: u32, half: bool) -> Vec<Allocation> {
    let own = image_size(size, half);
    let texture =
        |label: &str, bytes, setting: &str| Allocation::texture(label, own, bytes, 1, setting);
    let mut all: Vec<Allocation> = LABELS
        .iter()
        .flat_map(|set| set.iter().zip(FORMATS))
        .map(|(label, (_, bytes))| texture(label, bytes, HISTORY_SETTING))
        .collect();
    let scratch = FILTER_SCRATCH[..scratch_count(filter_passes, half)].iter();
    all.extend(scratch.map(|label| texture(label, RGBA32.1, FILTER_SETTING)));
    if half {
        all.extend(HALF_IMAGES.map(|label| texture(label, RGBA32.1, HISTORY_SETTING)));
    }
    all
}

/// The gather's passes, as DdgiPipelines compiled them.
pub struct GatherPipelines<'a> {
    pub temporal: &'a Arc<ComputePass>,
    pub filters: &'a [Arc<ComputePass>],
    /// ddgi/gather and ddgi/gather_upsample, with `half_resolution`.
    pub half: Option<&'a (Arc<ComputePass>, Arc<ComputePass>)>,
}

/// What one frame of the two ping-ponged sets records, in order.
struct FramePasses {
    temporal: BoundPass,
    filters: Vec<BoundPass>,
    upsample: Option<BoundPass>,
}

pub struct GatherHistory {
    /// ddgi/gather for each volume, finest first (half size only).
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
    /// `tables`: the scene's and the frame's; `volumes`: each volume's own, finest first (the
    /// first's `gather_history_frames` is ddgi/temporal's); `indirect`: the frame's view of
    /// the technique's light.
    pub fn new(
        ctx: &GpuContext,
        pipelines: GatherPipelines,
        tables: &[&ResourceTable],
        volumes: &[ResourceTable],
        indirect: &wgpu::TextureView,
        size: (u32, u32),
    ) -> Result<Self, RenderError> {
        let half = pipelines.half.is_some();
        let passes = pipelines.filters.len() as u32;
        ctx.check_allocations(&plan(size, passes, half))?;
        let own = image_size(size, half);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let texture = |label: &str, format| {
            irradiant_gpu::texture_2d(&ctx.device, label, own, format, 1, usage)
        };
        let sets: Vec<Vec<wgpu::Texture>> = LABELS
            .iter()
            .map(|set| {
                set.iter()
                    .zip(FORMATS)
                    .map(|(l, (f, _))| texture(l, f))
                    .collect()
            })
            .collect();
        let scratch: Vec<wgpu::Texture> = FILTER_SCRATCH[..scratch_count(passes, half)]
            .iter()
            .map(|label| texture(label, RGBA32.0))
            .collect();
        let half_images: Vec<wgpu::Texture> = match half {
            true => HALF_IMAGES.iter().map(|l| texture(l, RGBA32.0)).collect(),
            false => Vec::new(),
        };
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let set_views: Vec<Vec<wgpu::TextureView>> = sets
            .iter()
            .map(|set| set.iter().map(view).collect())
            .collect();
        let scratch_views: Vec<wgpu::TextureView> = scratch.iter().map(view).collect();
        let half_views: Vec<wgpu::TextureView> = half_images.iter().map(view).collect();
        let bind = |pass: &Arc<ComputePass>, own: ResourceTable, volume: &ResourceTable| {
            let mut all = tables.to_vec();
            all.push(volume);
            all.push(&own);
            pass.bind(ctx, &all)
        };
        let first = &volumes[0];
        // The temporal's source: ddgi/gather's image, or the frame's light.
        let source = half_views.first().unwrap_or(indirect);
        let frame_passes = |now: usize| -> Result<FramePasses, RenderError> {
            let before = 1 - now;
            let temporal = bind(
                pipelines.temporal,
                ResourceTable::new()
                    .texture("gather_source", source)
                    .texture("gather_history", &set_views[before][0])
                    .texture("gather_history_geometry", &set_views[before][1])
                    .texture("gather_history_moment", &set_views[before][2])
                    .texture("gather_mean", &set_views[now][0])
                    .texture("gather_mean_geometry", &set_views[now][1])
                    .texture("gather_moment", &set_views[now][2]),
                first,
            )?;
            let mut from = &set_views[now][0];
            let mut filters = Vec::new();
            for (k, pass) in pipelines.filters.iter().enumerate() {
                let target = filter_target(k, passes as usize, half, &scratch_views, indirect);
                let own = ResourceTable::new()
                    .texture("filter_source", from)
                    .texture("filter_moment", &set_views[now][2])
                    .texture("filter_target", target);
                filters.push(bind(pass, own, first)?);
                from = target;
            }
            let upsample = match (pipelines.half, half_views.get(1)) {
                (Some((_, upsample)), Some(query)) => Some(bind(
                    upsample,
                    ResourceTable::new()
                        .texture("upsample_source", from)
                        .texture("upsample_query", query),
                    first,
                )?),
                _ => None,
            };
            Ok(FramePasses {
                temporal,
                filters,
                upsample,
            })
        };
        let gathers = match (pipelines.half, half_views.as_slice()) {
            (Some((gather, _)), [gathered, query]) => volumes
                .iter()
                .map(|volume| {
                    let own = ResourceTable::new()
                        .texture("gathered", gathered)
                        .texture("gather_query", query);
                    bind(gather, own, volume)
                })
                .collect::<Result<_, _>>()?,
            _ => Vec::new(),
        };
        let frames = [frame_passes(0)?, frame_passes(1)?];
        Ok(Self {
            gathers,
            frames,
            image: workgroups(size, false),
            own_image: workgroups(size, half),
            count: 0,
            _textures: sets
                .into_iter()
                .flatten()
                .chain(scratch)
                .chain(half_images)
                .collect(),
        })
    }

    /// Records, after every volume's ddgi/resolve: ddgi/gather for each volume (half size),
    /// ddgi/temporal, the filter's passes and ddgi/gather_upsample (half size).
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
        if let Some(upsample) = &now.upsample {
            upsample.dispatch(encoder, profiler, self.image);
        }
        self.count += 1;
    }
}

/// Where filter pass `k` of `passes` writes. Full size: the last `indirect`, the ones before
/// it alternately the scratch and `indirect`, so that no pass reads what it writes. Half size:
/// the two scratch images in turn (ddgi/gather_upsample writes `indirect`).
fn filter_target<'v>(
    k: usize,
    passes: usize,
    half: bool,
    scratch: &'v [wgpu::TextureView],
    indirect: &'v wgpu::TextureView,
) -> &'v wgpu::TextureView {
    if half {
        return &scratch[k % 2];
    }
    match (passes - 1 - k).is_multiple_of(2) {
        true => indirect,
        // A pass goes to the scratch only where there are two or more, and then it exists.
        false => &scratch[0],
    }
}
