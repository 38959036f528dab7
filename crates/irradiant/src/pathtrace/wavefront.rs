//! The path tracer as a wavefront ([`PathSchedule::Wavefront`](super::PathSchedule)): one pass
//! a bounce over the paths still alive, each pass appending the survivors to a queue whose
//! header is the next pass's indirect dispatch. See `wavefront.wgsl`.

use std::sync::Arc;

use irradiant_gpu::{Allocation, ComputePass, GpuContext, PassDesc, Profiler, ResourceTable, wgpu};

use super::types::GpuPathTraceParams;
use crate::RenderError;
use crate::frame::IMAGE_TILE;
use crate::scene::GpuScene;

/// Bytes of a queue's header: its indirect dispatch (count, x, y, z), the bounce, padding.
const QUEUE_HEADER_BYTES: u64 = 32;
/// Bytes of one path's state (`PathState` in path.wgsl).
const PATH_STATE_BYTES: u64 = 64;
/// Where a queue's dispatch (x, y, z) lies in it.
const QUEUE_DISPATCH_OFFSET: u64 = 4;

/// The wavefront's two passes and its two path queues (each pass reads one, fills the other).
pub(super) struct Wavefront {
    camera: Arc<ComputePass>,
    bounce: Arc<ComputePass>,
    queues: [wgpu::Buffer; 2],
}

impl Wavefront {
    /// The two queues of a `width`×`height` image: a path for every thread of its 8×8 tiles.
    pub fn plan(width: u32, height: u32) -> Vec<Allocation> {
        let paths = (width.div_ceil(IMAGE_TILE.0) * IMAGE_TILE.0) as u64
            * (height.div_ceil(IMAGE_TILE.1) * IMAGE_TILE.1) as u64;
        let bytes = QUEUE_HEADER_BYTES + paths * PATH_STATE_BYTES;
        ["pathtrace/paths_a", "pathtrace/paths_b"]
            .into_iter()
            .map(|label| Allocation::storage(label, bytes, "the image size (--size)"))
            .collect()
    }

    /// The wavefront of a `width`×`height` image, or None where its queues pass the adapter's
    /// largest storage binding (the path tracer then keeps to the megakernel).
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        width: u32,
        height: u32,
    ) -> Result<Option<Self>, RenderError> {
        let plan = Self::plan(width, height);
        if ctx.check_allocations(&plan).is_err() {
            return Ok(None);
        }
        let stage = |label, camera: bool| {
            crate::shaders::pass(
                ctx,
                &PassDesc::new(label, include_str!("wavefront.wgsl"))
                    .constants(scene.shader_constants())
                    .constants([("WAVEFRONT_CAMERA", format!("{}u", camera as u32))]),
            )
        };
        let queue = |a: &Allocation| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&a.label),
                size: a.bytes,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::INDIRECT
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Ok(Some(Self {
            camera: stage("pathtrace/camera", true)?,
            bounce: stage("pathtrace/bounce", false)?,
            queues: [queue(&plan[0]), queue(&plan[1])],
        }))
    }

    /// Records `params.samples` samples a pixel from `params.sample_offset` on: for each, the
    /// camera pass, then a bounce pass for each bounce up to `max_bounces`, each dispatched
    /// over exactly the paths the pass before left alive. The bounce passes read nothing of a
    /// sample's own, so they are bound once; the camera pass once a sample (its offset).
    pub fn record(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        accumulation: &wgpu::TextureView,
        params: &GpuPathTraceParams,
        mut profiler: Option<&mut Profiler>,
    ) -> Result<(), RenderError> {
        let bound = |pass: &Arc<ComputePass>, uniform: &wgpu::Buffer, from: usize| {
            let own = ResourceTable::new()
                .buffer("params", uniform)
                .texture("accumulation", accumulation)
                .buffer("paths_in", &self.queues[from])
                .buffer("paths_out", &self.queues[1 - from]);
            pass.bind(ctx, &[&scene.resources(), &own])
        };
        let shared = ctx.uniform_buffer("pathtrace/params", params);
        let bounces = [
            bound(&self.bounce, &shared, 0)?,
            bound(&self.bounce, &shared, 1)?,
        ];
        for sample in 0..params.samples {
            let uniform = ctx.uniform_buffer(
                "pathtrace/params",
                &GpuPathTraceParams {
                    sample_offset: params.sample_offset + sample,
                    samples: 1,
                    ..*params
                },
            );
            // Filled from queue 1 (the camera pass reads none); bounces alternate from there.
            let camera = bound(&self.camera, &uniform, 1)?;
            encoder.clear_buffer(&self.queues[0], 0, Some(QUEUE_HEADER_BYTES));
            camera.dispatch(
                encoder,
                profiler.as_deref_mut(),
                super::PathTracer::workgroups(params.width, params.height),
            );
            for bounce in 1..=params.max_bounces as usize {
                let from = (bounce + 1) % 2;
                encoder.clear_buffer(&self.queues[1 - from], 0, Some(QUEUE_HEADER_BYTES));
                bounces[from].dispatch_indirect(
                    encoder,
                    profiler.as_deref_mut(),
                    &self.queues[from],
                    QUEUE_DISPATCH_OFFSET,
                );
            }
        }
        Ok(())
    }
}
