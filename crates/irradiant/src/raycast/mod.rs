//! raycast/trace: closest or any hit for a buffer of rays. The GPU traversal's test harness
//! (against a CPU oracle) and the rays-per-second benchmark.

pub mod types;

use std::sync::Arc;

use irradiant_gpu::{
    BoundPass, ComputePass, GpuContext, PassDesc, Profiler, ResourceTable, Workgroups,
    read_buffer_as, wgpu,
};
use wgpu::util::DeviceExt;

use crate::RenderError;
use crate::scene::GpuScene;
use types::{GpuRay, GpuRayCastParams, GpuRayHit};

/// The mean work of a batch of rays, from the counting variant ([`RayCaster::counting`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayWork {
    /// Node visits a ray (wide nodes where the bottom level is wide; top-level nodes too).
    pub node_visits: f64,
    /// Triangle tests a ray.
    pub triangle_tests: f64,
}

impl RayWork {
    /// The mean over the counting variant's hits.
    pub fn of(hits: &[GpuRayHit]) -> Self {
        let n = hits.len().max(1) as f64;
        Self {
            node_visits: hits.iter().map(|h| f64::from(h.node_visits())).sum::<f64>() / n,
            triangle_tests: hits
                .iter()
                .map(|h| f64::from(h.triangle_tests()))
                .sum::<f64>()
                / n,
        }
    }
}

/// The compiled `raycast/trace` passes (a ray a thread, and where the scene allows lanes that
/// fetch), for one scene's traversal settings.
pub struct RayCaster {
    /// A ray a thread.
    pass: Arc<ComputePass>,
    /// Where the scene is one wide tree: lanes that fetch their workgroup's next ray
    /// (bvh_fetch.wgsl).
    fetching: Option<Arc<ComputePass>>,
    /// The most workgroups a fetching dispatch holds before its runs pass 64 rays.
    fetch_workgroups: u32,
}

/// How a batch's rays lie, which picks how they are traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayOrder {
    /// Neighbouring rays walk the same nodes (a camera's rays in pixel order): a ray a thread.
    /// Fetching would scatter a warp's lanes over rays at different depths of the tree: 5–7 %
    /// slower on primary rays (H200, BENCHMARKS.md).
    Coherent,
    /// Rays in no useful order (bounces, shadow rays): where the scene is one wide tree, a
    /// workgroup's lanes fetch its next ray as theirs ends (H200, BENCHMARKS.md: 15 % less
    /// time on Sibenik's diffuse rays, 36 % on Sponza's any-hit rays, 5 % on `many-lights`'
    /// diffuse rays).
    Incoherent,
}

/// Rays and hits resident on the GPU, for repeated timed traces.
pub struct RayBatch {
    /// Rays in the batch.
    pub count: u32,
    bound: BoundPass,
    /// Traced by lanes that fetch: a run of rays a workgroup.
    fetching: bool,
    /// One [`GpuRayHit`] a ray, written by each trace.
    pub hits: wgpu::Buffer,
}

impl RayCaster {
    /// Compiles the passes with the scene's traversal constants.
    pub fn new(ctx: &GpuContext, scene: &GpuScene) -> Result<Self, RenderError> {
        Self::compile(
            ctx,
            scene,
            "raycast/trace",
            false,
            crate::shaders::FETCH_WORKGROUPS,
        )
    }

    /// As [`RayCaster::new`], with fetching dispatches of at most `workgroups` workgroups
    /// (a run of rays each; a test's few rays then take runs past 64).
    pub fn with_fetch_workgroups(
        ctx: &GpuContext,
        scene: &GpuScene,
        workgroups: u32,
    ) -> Result<Self, RenderError> {
        Self::compile(ctx, scene, "raycast/trace", false, workgroups.max(1))
    }

    /// The counting variant: the same traversal, each hit's `work` holding the ray's node
    /// visits and triangle tests (slower; for the work per ray, not for timing).
    pub fn counting(ctx: &GpuContext, scene: &GpuScene) -> Result<Self, RenderError> {
        Self::compile(
            ctx,
            scene,
            "raycast/count",
            true,
            crate::shaders::FETCH_WORKGROUPS,
        )
    }

    fn compile(
        ctx: &GpuContext,
        scene: &GpuScene,
        label: &'static str,
        count_work: bool,
        fetch_workgroups: u32,
    ) -> Result<Self, RenderError> {
        let pass = |fetch: bool| {
            let mut constants = scene.shader_constants();
            for (name, value) in &mut constants {
                if *name == "COUNT_WORK" {
                    *value = format!("{}u", count_work as u32);
                }
            }
            constants.push(("FETCH_RAYS", format!("{}u", fetch as u32)));
            constants.push(("FETCH_WORKGROUPS", format!("{fetch_workgroups}u")));
            crate::shaders::pass(
                ctx,
                &PassDesc::new(label, include_str!("trace.wgsl")).constants(constants),
            )
        };
        // The counting variant counts a ray a thread: its counters live in trace()'s loops.
        let fetching = match scene.fetches_rays() && !count_work {
            true => Some(pass(true)?),
            false => None,
        };
        Ok(Self {
            pass: pass(false)?,
            fetching,
            fetch_workgroups,
        })
    }

    /// Uploads `rays` and binds them with a hit buffer, ready for [`RayCaster::record`];
    /// `any_hit` stops each ray at its first hit (shadow rays); `order` picks how they are
    /// traced.
    pub fn upload(
        &self,
        ctx: &GpuContext,
        scene: &GpuScene,
        rays: &[GpuRay],
        any_hit: bool,
        order: RayOrder,
    ) -> Result<RayBatch, RenderError> {
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
        let hits = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("raycast/hits"),
            size: (rays.len() * size_of::<GpuRayHit>()).max(16) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let own = ResourceTable::new()
            .buffer("params", &params)
            .buffer("rays", &ray_buffer)
            .buffer("hits", &hits);
        let (pass, fetching) = match (&self.fetching, order) {
            (Some(pass), RayOrder::Incoherent) => (pass, true),
            _ => (&self.pass, false),
        };
        Ok(RayBatch {
            count: rays.len() as u32,
            bound: pass.bind(ctx, &[&scene.resources(), &own])?,
            fetching,
            hits,
        })
    }

    /// The workgroups of a trace of `rays` rays with a ray a thread (64 a workgroup, folded).
    pub fn workgroups(rays: u64) -> Workgroups {
        Workgroups::for_threads(rays, 64)
    }

    /// The workgroups a batch takes: a run of rays each where its lanes fetch.
    fn batch_workgroups(&self, batch: &RayBatch) -> Workgroups {
        let rays = u64::from(batch.count);
        match batch.fetching {
            true => crate::shaders::fetch_dispatch(rays, self.fetch_workgroups),
            false => Self::workgroups(rays),
        }
    }

    /// Records one trace of the batch.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        batch: &RayBatch,
        profiler: Option<&mut Profiler>,
    ) {
        batch
            .bound
            .dispatch(encoder, profiler, self.batch_workgroups(batch));
    }

    /// Traces `rays` and returns their hits.
    pub fn trace(
        &self,
        ctx: &GpuContext,
        scene: &GpuScene,
        rays: &[GpuRay],
        any_hit: bool,
        order: RayOrder,
    ) -> Result<Vec<GpuRayHit>, RenderError> {
        let batch = self.upload(ctx, scene, rays, any_hit, order)?;
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("raycast/trace"),
            });
        self.record(&mut encoder, &batch, None);
        ctx.queue.submit([encoder.finish()]);
        let hits = read_buffer_as(ctx, &batch.hits)?;
        Ok(hits[..rays.len()].to_vec())
    }
}
