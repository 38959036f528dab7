//! The final gather's history (`DdgiGatherSettings`): ddgi/temporal's running mean of the
//! gathered light and the geometry it was taken on, two sets ping-ponged (this frame's is the
//! next frame's history), and the pass bound to each.

use std::sync::Arc;

use irradiant_gpu::{
    Allocation, BoundPass, ComputePass, GpuContext, Profiler, ResourceTable, Workgroups, wgpu,
};

use crate::RenderError;

/// What sizes the history, for the messages that refuse too large an image.
const HISTORY_SETTING: &str = "the image size (--size) or technique.gather.rays_per_pixel";

/// (mean, frames in it) and (normal, view depth) per pixel: rgba32float, both.
const LABELS: [[&str; 2]; 2] = [
    ["ddgi/gather_mean_0", "ddgi/gather_geometry_0"],
    ["ddgi/gather_mean_1", "ddgi/gather_geometry_1"],
];
const TEXEL_BYTES: u64 = 16;

/// ddgi/temporal's workgroups at an image size: one thread a pixel, as ddgi/resolve.
pub fn workgroups((width, height): (u32, u32)) -> Workgroups {
    Workgroups::for_image(width, height, crate::frame::IMAGE_TILE)
}

/// The history's allocations at an image size.
pub fn plan(size: (u32, u32)) -> Vec<Allocation> {
    LABELS
        .iter()
        .flatten()
        .map(|label| Allocation::texture(*label, size, TEXEL_BYTES, 1, HISTORY_SETTING))
        .collect()
}

pub struct GatherHistory {
    /// ddgi/temporal writing set 0 (reading set 1), and writing set 1.
    passes: [BoundPass; 2],
    image: Workgroups,
    frames: u64,
    /// Kept alive for the passes' views.
    _textures: Vec<wgpu::Texture>,
}

impl GatherHistory {
    /// `tables`: the scene's, the frame's and the first volume's (ddgi/temporal reads its
    /// `gather_history_frames`).
    pub fn new(
        ctx: &GpuContext,
        temporal: &Arc<ComputePass>,
        tables: &[&ResourceTable],
        size: (u32, u32),
    ) -> Result<Self, RenderError> {
        ctx.check_allocations(&plan(size))?;
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let textures: Vec<wgpu::Texture> = LABELS
            .iter()
            .flatten()
            .map(|label| {
                irradiant_gpu::texture_2d(
                    &ctx.device,
                    label,
                    size,
                    wgpu::TextureFormat::Rgba32Float,
                    1,
                    usage,
                )
            })
            .collect();
        let views: Vec<wgpu::TextureView> = textures
            .iter()
            .map(|t| t.create_view(&Default::default()))
            .collect();
        // views: [mean 0, geometry 0, mean 1, geometry 1].
        let bind = |now: usize| -> Result<BoundPass, RenderError> {
            let before = 1 - now;
            let own = ResourceTable::new()
                .texture("gather_history", &views[2 * before])
                .texture("gather_history_geometry", &views[2 * before + 1])
                .texture("gather_mean", &views[2 * now])
                .texture("gather_mean_geometry", &views[2 * now + 1]);
            let mut all = tables.to_vec();
            all.push(&own);
            Ok(temporal.bind(ctx, &all)?)
        };
        Ok(Self {
            passes: [bind(0)?, bind(1)?],
            image: workgroups(size),
            frames: 0,
            _textures: textures,
        })
    }

    /// Records ddgi/temporal, after every volume's ddgi/resolve.
    pub fn record(&mut self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut Profiler>) {
        self.passes[(self.frames % 2) as usize].dispatch(encoder, profiler, self.image);
        self.frames += 1;
    }
}
