//! The final gather's history (`DdgiGatherSettings`): ddgi/temporal's running mean of the
//! gathered light, its second moment and the geometry it was taken on, two sets ping-ponged
//! (this frame's is the next frame's history), the pass bound to each, and ddgi/gather_filter's
//! passes from this frame's mean into the frame's `indirect`.

use std::sync::Arc;

use irradiant_gpu::{
    Allocation, BoundPass, ComputePass, GpuContext, Profiler, ResourceTable, Workgroups, wgpu,
};

use crate::RenderError;

/// What sizes the history, for the messages that refuse too large an image.
const HISTORY_SETTING: &str = "the image size (--size) or technique.gather.rays_per_pixel";

/// (mean, frames in it) and (normal, view depth) per pixel, rgba32float; the mean of the
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
/// Between two filter passes that do not write the frame's `indirect`: (light, variance).
const FILTER_SCRATCH: &str = "ddgi/gather_filtered";
const FILTER_SCRATCH_FORMAT: (wgpu::TextureFormat, u64) = (wgpu::TextureFormat::Rgba32Float, 16);

/// ddgi/temporal's workgroups at an image size: one thread a pixel, as ddgi/resolve.
pub fn workgroups((width, height): (u32, u32)) -> Workgroups {
    Workgroups::for_image(width, height, crate::frame::IMAGE_TILE)
}

/// The history's allocations at an image size, with the filter's scratch where
/// `filter_passes` needs one (two passes or more).
pub fn plan(size: (u32, u32), filter_passes: u32) -> Vec<Allocation> {
    let mut all: Vec<Allocation> = LABELS
        .iter()
        .flat_map(|set| set.iter().zip(FORMATS))
        .map(|(label, (_, bytes))| Allocation::texture(*label, size, bytes, 1, HISTORY_SETTING))
        .collect();
    if filter_passes >= 2 {
        all.push(Allocation::texture(
            FILTER_SCRATCH,
            size,
            FILTER_SCRATCH_FORMAT.1,
            1,
            "the image size (--size) or technique.gather.filter_passes",
        ));
    }
    all
}

/// Where each of `passes` filter passes writes: the last the frame's `indirect`, the ones
/// before it alternately the scratch and `indirect`, so that no pass reads what it writes.
/// true: `indirect`.
fn filter_targets(passes: u32) -> Vec<bool> {
    (0..passes)
        .map(|k| (passes - 1 - k).is_multiple_of(2))
        .collect()
}

pub struct GatherHistory {
    /// ddgi/temporal writing set 0 (reading set 1), and writing set 1.
    passes: [BoundPass; 2],
    /// ddgi/gather_filter's passes after each of them, in order.
    filters: [Vec<BoundPass>; 2],
    image: Workgroups,
    frames: u64,
    /// Kept alive for the passes' views.
    _textures: Vec<wgpu::Texture>,
}

impl GatherHistory {
    /// `tables`: the scene's, the frame's and the first volume's (ddgi/temporal reads its
    /// `gather_history_frames`); `filters`: ddgi/gather_filter's passes in order, the last
    /// writing `indirect`, the frame's view of the technique's light.
    pub fn new(
        ctx: &GpuContext,
        temporal: &Arc<ComputePass>,
        filters: &[Arc<ComputePass>],
        tables: &[&ResourceTable],
        indirect: &wgpu::TextureView,
        size: (u32, u32),
    ) -> Result<Self, RenderError> {
        ctx.check_allocations(&plan(size, filters.len() as u32))?;
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let texture = |label: &str, format| {
            irradiant_gpu::texture_2d(&ctx.device, label, size, format, 1, usage)
        };
        let mut textures: Vec<wgpu::Texture> = LABELS
            .iter()
            .flat_map(|set| set.iter().zip(FORMATS))
            .map(|(label, (format, _))| texture(label, format))
            .collect();
        if filters.len() >= 2 {
            textures.push(texture(FILTER_SCRATCH, FILTER_SCRATCH_FORMAT.0));
        }
        let views: Vec<wgpu::TextureView> = textures
            .iter()
            .map(|t| t.create_view(&Default::default()))
            .collect();
        // views: [mean 0, geometry 0, moment 0, mean 1, geometry 1, moment 1, scratch?].
        let set = |now: usize, item: usize| &views[3 * now + item];
        let scratch = views.get(LABELS.len() * LABELS[0].len());
        let bind = |now: usize| -> Result<BoundPass, RenderError> {
            let before = 1 - now;
            let own = ResourceTable::new()
                .texture("gather_history", set(before, 0))
                .texture("gather_history_geometry", set(before, 1))
                .texture("gather_history_moment", set(before, 2))
                .texture("gather_mean", set(now, 0))
                .texture("gather_mean_geometry", set(now, 1))
                .texture("gather_moment", set(now, 2));
            let mut all = tables.to_vec();
            all.push(&own);
            Ok(temporal.bind(ctx, &all)?)
        };
        let bind_filters = |now: usize| -> Result<Vec<BoundPass>, RenderError> {
            let targets = filter_targets(filters.len() as u32);
            let mut source = set(now, 0);
            let mut bound = Vec::new();
            for (pass, to_indirect) in filters.iter().zip(targets) {
                // filter_targets sends a pass to the scratch only where there are two or more,
                // and then the scratch exists.
                let target = match (to_indirect, scratch) {
                    (false, Some(scratch)) => scratch,
                    _ => indirect,
                };
                let own = ResourceTable::new()
                    .texture("filter_source", source)
                    .texture("filter_moment", set(now, 2))
                    .texture("filter_target", target);
                let mut all = tables.to_vec();
                all.push(&own);
                bound.push(pass.bind(ctx, &all)?);
                source = target;
            }
            Ok(bound)
        };
        Ok(Self {
            passes: [bind(0)?, bind(1)?],
            filters: [bind_filters(0)?, bind_filters(1)?],
            image: workgroups(size),
            frames: 0,
            _textures: textures,
        })
    }

    /// Records ddgi/temporal, after every volume's ddgi/resolve, and the filter's passes.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        let now = (self.frames % 2) as usize;
        self.passes[now].dispatch(encoder, profiler.as_deref_mut(), self.image);
        for filter in &self.filters[now] {
            filter.dispatch(encoder, profiler.as_deref_mut(), self.image);
        }
        self.frames += 1;
    }
}
