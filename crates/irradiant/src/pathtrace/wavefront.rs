//! The path tracer as a wavefront ([`PathSchedule::Wavefront`](super::PathSchedule)): one pass
//! a bounce over the paths still alive, each pass appending the survivors to a queue whose
//! header is the next pass's indirect dispatch. On a scene of one wide tree
//! ([`GpuScene::fetches_rays`]) a bounce's rays are traced apart from their shading, by lanes
//! that fetch their next ray. See `wavefront.wgsl`.

use std::sync::Arc;

use irradiant_gpu::{Allocation, ComputePass, GpuContext, PassDesc, Profiler, ResourceTable, wgpu};

use super::types::GpuPathTraceParams;
use crate::RenderError;
use crate::frame::IMAGE_TILE;
use crate::scene::GpuScene;

/// Bytes of a queue's header: its bounce pass's indirect dispatch (count, x, y, z), the
/// bounce, and `pathtrace/hits`' dispatch (x, y, z; zero where rays are not traced apart).
const QUEUE_HEADER_BYTES: u64 = 32;
/// Bytes of one path's state (`PathState` in path.wgsl).
const PATH_STATE_BYTES: u64 = 64;
/// Where a queue's dispatch (x, y, z) of its bounce pass, a thread a path, lies in it.
const QUEUE_DISPATCH_OFFSET: u64 = 4;
/// Where a queue's dispatch (x, y, z) of `pathtrace/hits`, a run of paths a workgroup, lies.
const QUEUE_RUNS_OFFSET: u64 = 20;
/// Bytes of one path's closest hit (`GpuPathHit` in wavefront.wgsl).
const PATH_HIT_BYTES: u64 = 16;

/// The bottom-level tree's SAH cost (`GpuSceneStats::sah_cost`: a ray's expected node visits
/// and triangle tests) from which the wavefront traces a bounce's rays apart from their
/// shading. Apart, a bounce pays a fixed cost a path (its origin, direction and hit through
/// memory, one more pass), while lanes that fetch gain in proportion to how long rays walk the
/// tree. Split on every tree (NVIDIA H200, 1920×1080, a sample; docs/notes/traversal.md,
/// 2026-11-28): Sponza (63.0) 12.40 → 11.09 ms and Sibenik (47.8) 17.00 → 15.91, but
/// `many-lights` (31.9) 7.45 → 7.62 and the Cornell box (14.2) 2.55 → 2.83.
pub(super) const TRACED_APART_FROM_SAH_COST: f32 = 40.0;

/// `WAVEFRONT_STAGE` of wavefront.wgsl: which of its passes a pipeline is.
#[derive(Clone, Copy)]
enum Stage {
    Camera = 0,
    Hits = 1,
    Bounce = 2,
}

/// The wavefront's passes and its two path queues (each pass reads one, fills the other).
pub(super) struct Wavefront {
    camera: Arc<ComputePass>,
    bounce: Arc<ComputePass>,
    /// Where a bounce's rays are traced apart: `pathtrace/hits`.
    hits: Option<Arc<ComputePass>>,
    /// The closest hit of each queued path where they are traced apart; else one hit's bytes,
    /// since pathtrace/bounce declares the binding either way.
    hit_buffer: wgpu::Buffer,
    queues: [wgpu::Buffer; 2],
}

impl Wavefront {
    /// The two queues of a `width`×`height` image, a path for every thread of its 8×8 tiles,
    /// and where `fetches` a hit for each.
    pub fn plan(width: u32, height: u32, fetches: bool) -> Vec<Allocation> {
        let paths = (width.div_ceil(IMAGE_TILE.0) * IMAGE_TILE.0) as u64
            * (height.div_ceil(IMAGE_TILE.1) * IMAGE_TILE.1) as u64;
        let bytes = QUEUE_HEADER_BYTES + paths * PATH_STATE_BYTES;
        let mut plan: Vec<Allocation> = ["pathtrace/paths_a", "pathtrace/paths_b"]
            .into_iter()
            .map(|label| Allocation::storage(label, bytes, "the image size (--size)"))
            .collect();
        if fetches {
            plan.push(Allocation::storage(
                "pathtrace/hits",
                paths * PATH_HIT_BYTES,
                "the image size (--size)",
            ));
        }
        plan
    }

    /// What it holds.
    pub fn allocations(&self, width: u32, height: u32) -> Vec<Allocation> {
        Self::plan(width, height, self.hits.is_some())
    }

    /// The wavefront of a `width`×`height` image, or None where its buffers pass the adapter's
    /// largest storage binding (the path tracer then keeps to the megakernel). With `fetches`
    /// (only where the scene fetches rays) `pathtrace/hits` traces a bounce's rays apart, in a
    /// dispatch of at most `fetch_workgroups` workgroups.
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        width: u32,
        height: u32,
        fetches: bool,
        fetch_workgroups: u32,
    ) -> Result<Option<Self>, RenderError> {
        // Where the hits would not fit, the wavefront still traces, its rays in the bounce.
        let fetches = fetches
            && scene.fetches_rays()
            && ctx
                .check_allocations(&Self::plan(width, height, true))
                .is_ok();
        let plan = Self::plan(width, height, fetches);
        if ctx.check_allocations(&plan).is_err() {
            return Ok(None);
        }
        let stage = |label, stage: Stage| {
            crate::shaders::pass(
                ctx,
                &PassDesc::new(label, include_str!("wavefront.wgsl"))
                    .constants(scene.shader_constants())
                    .constants([
                        ("WAVEFRONT_STAGE", format!("{}u", stage as u32)),
                        ("FETCH_RAYS", format!("{}u", fetches as u32)),
                        ("FETCH_WORKGROUPS", format!("{}u", fetch_workgroups.max(1))),
                    ]),
            )
        };
        let buffer = |a: &Allocation| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&a.label),
                size: a.bytes,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::INDIRECT
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let (hits, hit_buffer) = match fetches {
            true => (
                Some(stage("pathtrace/hits", Stage::Hits)?),
                buffer(&plan[2]),
            ),
            false => (
                None,
                buffer(&Allocation::storage("pathtrace/hits", PATH_HIT_BYTES, "")),
            ),
        };
        Ok(Some(Self {
            camera: stage("pathtrace/camera", Stage::Camera)?,
            bounce: stage("pathtrace/bounce", Stage::Bounce)?,
            hits,
            hit_buffer,
            queues: [buffer(&plan[0]), buffer(&plan[1])],
        }))
    }

    /// Whether a bounce's rays are traced apart from their shading, by lanes that fetch
    /// (where more paths are alive than `fetch_workgroups` runs of 64).
    pub fn fetches_rays(&self) -> bool {
        self.hits.is_some()
    }

    /// Records `params.samples` samples a pixel from `params.sample_offset` on: for each, the
    /// camera pass, then a bounce pass for each bounce up to `max_bounces` (after its rays'
    /// `pathtrace/hits` where the scene fetches rays), each dispatched over exactly the paths
    /// the pass before left alive. The bounce passes read nothing of a sample's own, so they
    /// are bound once; the camera pass once a sample (its offset).
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
                .buffer("paths_out", &self.queues[1 - from])
                .buffer("hits", &self.hit_buffer);
            pass.bind(ctx, &[&scene.resources(), &own])
        };
        let shared = ctx.uniform_buffer("pathtrace/params", params);
        let bounces = [
            bound(&self.bounce, &shared, 0)?,
            bound(&self.bounce, &shared, 1)?,
        ];
        let hits = match &self.hits {
            Some(pass) => Some([bound(pass, &shared, 0)?, bound(pass, &shared, 1)?]),
            None => None,
        };
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
                if let Some(hits) = &hits {
                    hits[from].dispatch_indirect(
                        encoder,
                        profiler.as_deref_mut(),
                        &self.queues[from],
                        QUEUE_RUNS_OFFSET,
                    );
                }
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
