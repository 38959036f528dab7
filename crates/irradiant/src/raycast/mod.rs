//! raycast/trace: closest or any hit for a buffer of rays. The GPU traversal's test harness
//! (against a CPU oracle) and the rays-per-second benchmark.

use irradiant_gpu::{GpuContext, Profiler, read_buffer_as, wgpu};
use wgpu::util::DeviceExt;

use crate::RenderError;
use crate::gpu_scene::GpuScene;
use crate::gpu_types::{GpuRay, GpuRayCastParams, GpuRayHit};
use crate::pipeline::*;

pub struct RayCaster {
    stage: ComputeStage,
    layout: wgpu::BindGroupLayout,
}

/// Rays and hits resident on the GPU, for repeated timed traces.
pub struct RayBatch {
    pub count: u32,
    group: wgpu::BindGroup,
    pub hits: wgpu::Buffer,
}

impl RayCaster {
    pub fn new(ctx: &GpuContext, scene: &GpuScene) -> Result<Self, RenderError> {
        let layout = ctx
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("raycast/trace"),
                entries: &[
                    buffer_entry(0, UNIFORM),       // params
                    buffer_entry(1, STORAGE_READ),  // rays
                    buffer_entry(2, STORAGE_WRITE), // hits
                ],
            });
        let stage = ComputeStage::tracing(
            ctx,
            scene,
            "raycast/trace",
            include_str!("trace.wgsl"),
            &[],
            &layout,
        )?;
        Ok(Self { stage, layout })
    }

    pub fn upload(&self, ctx: &GpuContext, rays: &[GpuRay], any_hit: bool) -> RayBatch {
        let params = GpuRayCastParams {
            ray_count: rays.len() as u32,
            any_hit: any_hit as u32,
            _pad0: 0,
            _pad1: 0,
        };
        let params = ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("raycast/params"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let ray_buffer = ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("raycast/rays"),
                contents: bytemuck::cast_slice(rays),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let hits = storage_buffer(
            &ctx.device,
            "raycast/hits",
            (rays.len() * size_of::<GpuRayHit>()) as u64,
        );
        let group = bind_buffers(
            &ctx.device,
            "raycast/trace",
            &self.layout,
            &[&params, &ray_buffer, &hits],
        );
        RayBatch {
            count: rays.len() as u32,
            group,
            hits,
        }
    }

    /// Records one trace of the batch.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        batch: &RayBatch,
        profiler: Option<&mut Profiler>,
    ) {
        let groups = batch.count.div_ceil(64);
        // Split into rows of at most 32768 workgroups (the limit is 65535 per dimension).
        let x = groups.min(32768);
        let y = groups.div_ceil(x.max(1));
        self.stage.dispatch(
            encoder,
            profiler,
            &[&scene.bind_group, &batch.group],
            [x.max(1), y.max(1), 1],
        );
    }

    /// Traces `rays` and returns their hits.
    pub fn trace(
        &self,
        ctx: &GpuContext,
        scene: &GpuScene,
        rays: &[GpuRay],
        any_hit: bool,
    ) -> Result<Vec<GpuRayHit>, RenderError> {
        let batch = self.upload(ctx, rays, any_hit);
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("raycast/trace"),
            });
        self.record(&mut encoder, scene, &batch, None);
        ctx.queue.submit([encoder.finish()]);
        let hits = read_buffer_as(ctx, &batch.hits)?;
        Ok(hits[..rays.len()].to_vec())
    }
}
