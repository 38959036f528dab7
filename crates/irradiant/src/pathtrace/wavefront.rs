//! The path tracer as a wavefront ([`PathSchedule::Wavefront`](super::PathSchedule)): one pass
//! a bounce over the paths still alive, each pass appending the survivors to a queue whose
//! header is the next pass's indirect dispatch, for a sample's first `WAVEFRONT_PASSES`; the
//! pass after them takes each path left to its end. On a scene of one wide tree
//! ([`GpuScene::fetches_rays`]) a bounce's rays, and in a sample's first passes its vertices'
//! shadow rays, are traced apart from their shading, by lanes that fetch their next ray. See
//! `wavefront.wgsl`.

use std::sync::Arc;

use irradiant_gpu::{Allocation, ComputePass, GpuContext, PassDesc, Profiler, ResourceTable, wgpu};

use super::types::GpuPathTraceParams;
use crate::RenderError;
use crate::frame::IMAGE_TILE;
use crate::scene::GpuScene;

/// Bytes of a queue's header: its bounce pass's indirect dispatch (count, x, y, z), the
/// bounce, `pathtrace/hits`' dispatch (x, y, z; zero where rays are not traced apart) and
/// `pathtrace/tail`'s (x, y, z; zero but in the tail's queue), then 4 bytes of padding.
const QUEUE_HEADER_BYTES: u64 = 48;
/// Bytes of one path's state (`PathState` in path.wgsl).
const PATH_STATE_BYTES: u64 = 64;
/// Where a queue's dispatch (x, y, z) of its bounce pass, a thread a path, lies in it.
const QUEUE_DISPATCH_OFFSET: u64 = 4;
/// Where a queue's dispatch (x, y, z) of `pathtrace/hits`, a run of paths a workgroup, lies.
const QUEUE_RUNS_OFFSET: u64 = 20;
/// Where a queue's dispatch (x, y, z) of `pathtrace/tail`, a run of paths a workgroup, lies.
const QUEUE_TAIL_OFFSET: u64 = 32;
/// Bytes of one path's closest hit (`GpuPathHit` in wavefront.wgsl).
const PATH_HIT_BYTES: u64 = 16;
/// Bytes of the shadow queue's header (`GpuShadowQueue` in wavefront.wgsl): the dispatches of
/// `pathtrace/shadows` (count, x, y, z) and of `pathtrace/shadow_resolve` (x, y, z), and its
/// spans' count.
const SHADOW_HEADER_BYTES: u64 = 32;
/// Where the shadow queue's dispatch of `pathtrace/shadows` (x, y, z) lies in it.
const SHADOW_RUNS_OFFSET: u64 = 4;
/// Where its dispatch of `pathtrace/shadow_resolve` (x, y, z) lies.
const SHADOW_RESOLVE_OFFSET: u64 = 16;
/// Bytes of one deferred shadow ray (`DeferredShadow` in path.wgsl).
const DEFERRED_SHADOW_BYTES: u64 = 48;
/// Bytes of one path's span of deferred rays (first, count, pixel, 0).
const SHADOW_SPAN_BYTES: u64 = 16;

/// The bottom-level tree's SAH cost (`GpuSceneStats::sah_cost`: a ray's expected node visits
/// and triangle tests) from which the wavefront traces a bounce's rays apart from their
/// shading. Apart, a bounce pays a fixed cost a path (its origin, direction and hit through
/// memory, one more pass), while lanes that fetch gain in proportion to how long rays walk the
/// tree. Split on every tree (NVIDIA H200, 1920×1080, a sample; docs/notes/traversal.md,
/// 2026-11-28): Sponza (63.0) 12.40 → 11.09 ms and Sibenik (47.8) 17.00 → 15.91, but
/// `many-lights` (31.9) 7.45 → 7.62 and the Cornell box (14.2) 2.55 → 2.83.
pub(super) const TRACED_APART_FROM_SAH_COST: f32 = 40.0;

/// The passes of a sample run as a wavefront: the camera's, then a bounce's each, their
/// vertices' shadow rays deferred to `pathtrace/shadows` where the paths alive fill its runs.
/// The bounce pass after them is the tail (`pathtrace/tail`): its lanes take the paths left to
/// their ends, as the megakernel does, and no later pass is recorded. By then the paths that
/// are left are few, and a pass of each bounce would cost its clear, its dispatches and the
/// barriers between them for little work; deferred shadow passes there cost the same (every
/// pass deferring made Sponza 7 % slower). Once the tail's lanes fetched their paths, it paid
/// to start it earlier. NVIDIA H200, 1920×1080, a sample, ms, round 1 / 2 (the Cornell box's
/// round 2 alone: a process's first wavefront there reads slow)
/// (docs/notes/traversal.md, 2026-11-28 (late) and (end of day)):
///
/// | passes before the tail | Cornell box | Sponza | Sibenik |
/// | --- | ---: | ---: | ---: |
/// | none (a pass every bounce, 32) | 2.540 | 10.954 | 14.513 |
/// | 4, a path a thread in the tail | 1.913 | 9.867 | 13.191 |
/// | 6, a path a thread in the tail (before) | 1.857 | 9.385 | 12.660 |
/// | 10, a path a thread in the tail | 1.978 | 9.411 | 13.003 |
/// | 3, lanes that fetch in the tail (another call) | 1.782 | 9.969 / 9.980 | 13.895 / 13.886 |
/// | **4, lanes that fetch** | 1.826 | **8.901 / 8.880** | **12.280 / 12.291** |
/// | 5, lanes that fetch | 1.861 | 8.974 / 8.937 | 12.316 / 12.284 |
/// | 6, lanes that fetch | 1.872 | 9.060 / 9.041 | 12.504 / 12.501 |
const WAVEFRONT_PASSES: u32 = 4;

/// Workgroups `pathtrace/tail` takes its paths in at most, for `fetch_workgroups` of the ray
/// passes: a workgroup's run of the queue grows, in steps of 64, as the paths left outnumber 64
/// × this, and its lanes fetch from the run. Fewer workgroups give each lane more paths to
/// fetch, so that it idles less while its warp's longest path ends, but keep fewer warps on
/// the GPU. NVIDIA H200, 1920×1080, a sample, ms (`pathtrace/wavefront`, round 1 / 2;
/// docs/notes/traversal.md, 2026-11-28 (end of day)):
///
/// | | Cornell box | Sponza | Sibenik |
/// | --- | ---: | ---: | ---: |
/// | a path a thread (before) | 1.881 / 1.881 | 9.335 / 9.351 | 12.651 / 12.640 |
/// | **1 024 workgroups (an eighth)** | 1.874 | **9.057 / 9.044** | **12.513 / 12.508** |
/// | 2 048 | 1.869 | 9.271 / 9.262 | 12.542 / 12.540 |
/// | 8 192 | 1.869 | 9.297 / 9.262 | 12.522 / 12.550 |
fn tail_workgroups(fetch_workgroups: u32) -> u32 {
    (fetch_workgroups / 8).max(1)
}

/// `WAVEFRONT_STAGE` of wavefront.wgsl: which of its passes a pipeline is.
#[derive(Clone, Copy)]
enum Stage {
    Camera = 0,
    Hits = 1,
    Bounce = 2,
    Shadows = 3,
    Resolve = 4,
    Tail = 5,
}

/// The wavefront's passes and its two path queues (each pass reads one, fills the other).
pub(super) struct Wavefront {
    camera: Arc<ComputePass>,
    bounce: Arc<ComputePass>,
    /// The pass after the first `WAVEFRONT_PASSES`: it takes each path left to its end.
    tail: Arc<ComputePass>,
    /// Where a bounce's rays are traced apart: `pathtrace/hits`.
    hits: Option<Arc<ComputePass>>,
    /// The closest hit of each queued path where they are traced apart; else one hit's bytes,
    /// since pathtrace/bounce declares the binding either way.
    hit_buffer: wgpu::Buffer,
    queues: [wgpu::Buffer; 2],
    /// Where a vertex's shadow rays are traced apart: `pathtrace/shadows` and
    /// `pathtrace/shadow_resolve`.
    shadow_passes: Option<[Arc<ComputePass>; 2]>,
    /// The deferred shadow rays and each path's span of them (one entry each where none are).
    shadow_queue: wgpu::Buffer,
    shadow_spans: wgpu::Buffer,
    /// A copy of the shadow queue's header, the dispatches of the passes that bind the queue
    /// read-write (a dispatch may not read its own indirect arguments from such a binding).
    shadow_dispatch: wgpu::Buffer,
    /// Deferred shadow rays a vertex at most (0: none deferred).
    shadow_slots: u64,
}

impl Wavefront {
    /// The two queues of a `width`×`height` image, a path for every thread of its 8×8 tiles,
    /// where `fetches` a hit for each, and where `shadow_slots` is not 0 that many deferred
    /// shadow rays a path and its span.
    pub fn plan(width: u32, height: u32, fetches: bool, shadow_slots: u64) -> Vec<Allocation> {
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
        if shadow_slots > 0 {
            plan.push(Allocation::storage(
                "pathtrace/shadows",
                SHADOW_HEADER_BYTES + paths * shadow_slots * DEFERRED_SHADOW_BYTES,
                "the image size (--size)",
            ));
            plan.push(Allocation::storage(
                "pathtrace/shadow_spans",
                paths * SHADOW_SPAN_BYTES,
                "the image size (--size)",
            ));
        }
        plan
    }

    /// What it holds.
    pub fn allocations(&self, width: u32, height: u32) -> Vec<Allocation> {
        Self::plan(width, height, self.hits.is_some(), self.shadow_slots)
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
        // Where the hits would not fit, the wavefront still traces, its rays in the bounce; where
        // the deferred shadow rays would not, it traces those in the bounce.
        let fetches = fetches
            && scene.fetches_rays()
            && ctx
                .check_allocations(&Self::plan(width, height, true, 0))
                .is_ok();
        // A vertex's shadow rays: one a punctual light, one for the emitter sample. A scene
        // with more than DEFERRED_SHADOWS_MAX traces them in the bounce.
        let lights_a_vertex = scene.light_count() as u64 + u64::from(scene.has_emitters());
        let slots = match lights_a_vertex <= u64::from(super::constants::DEFERRED_SHADOWS_MAX) {
            true => lights_a_vertex,
            false => 0,
        };
        let shadow_slots = match fetches
            && ctx
                .check_allocations(&Self::plan(width, height, true, slots))
                .is_ok()
        {
            true => slots,
            false => 0,
        };
        let plan = Self::plan(width, height, fetches, shadow_slots);
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
                        ("SHADOWS_APART", format!("{}u", (shadow_slots > 0) as u32)),
                        ("SHADOW_SLOTS", format!("{shadow_slots}u")),
                        ("WAVEFRONT_PASSES", format!("{WAVEFRONT_PASSES}u")),
                        (
                            "TAIL_WORKGROUPS",
                            format!("{}u", tail_workgroups(fetch_workgroups)),
                        ),
                    ]),
            )
        };
        let buffer = |a: &Allocation| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&a.label),
                size: a.bytes,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::INDIRECT
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
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
        // The least the bindings take where no ray is deferred: a header and one entry.
        let least = |label, bytes| buffer(&Allocation::storage(label, bytes, ""));
        let (shadow_passes, shadow_queue, shadow_spans) = match shadow_slots > 0 {
            true => (
                Some([
                    stage("pathtrace/shadows", Stage::Shadows)?,
                    stage("pathtrace/shadow_resolve", Stage::Resolve)?,
                ]),
                buffer(&plan[3]),
                buffer(&plan[4]),
            ),
            false => (
                None,
                least(
                    "pathtrace/shadows",
                    SHADOW_HEADER_BYTES + DEFERRED_SHADOW_BYTES,
                ),
                least("pathtrace/shadow_spans", SHADOW_SPAN_BYTES),
            ),
        };
        let shadow_dispatch = least("pathtrace/shadow_dispatch", SHADOW_HEADER_BYTES);
        Ok(Some(Self {
            camera: stage("pathtrace/camera", Stage::Camera)?,
            bounce: stage("pathtrace/bounce", Stage::Bounce)?,
            tail: stage("pathtrace/tail", Stage::Tail)?,
            hits,
            hit_buffer,
            queues: [buffer(&plan[0]), buffer(&plan[1])],
            shadow_passes,
            shadow_queue,
            shadow_spans,
            shadow_dispatch,
            shadow_slots,
        }))
    }

    /// Whether a bounce's rays are traced apart from their shading, by lanes that fetch
    /// (where more paths are alive than `fetch_workgroups` runs of 64).
    pub fn fetches_rays(&self) -> bool {
        self.hits.is_some()
    }

    /// Whether a sample's first passes defer their vertices' shadow rays to `pathtrace/shadows`.
    pub fn defers_shadows(&self) -> bool {
        self.shadow_passes.is_some()
    }

    /// Records `params.samples` samples a pixel from `params.sample_offset` on: for each, the
    /// camera pass, then a bounce pass for each bounce up to `max_bounces` or
    /// `WAVEFRONT_PASSES`, whichever is fewer (the `WAVEFRONT_PASSES`th is `pathtrace/tail`,
    /// which takes its paths to their ends), each after
    /// its rays' `pathtrace/hits` where the scene fetches rays and dispatched over exactly the
    /// paths the pass before left alive. Where shadow rays are deferred, each pass before the
    /// tail clears the shadow queue's header before it and is followed by a copy of the header,
    /// `pathtrace/shadows` and `pathtrace/shadow_resolve`. The bounce passes read nothing of a
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
                .buffer("paths_out", &self.queues[1 - from])
                .buffer("hits", &self.hit_buffer)
                .buffer("shadows", &self.shadow_queue)
                .buffer("shadow_spans", &self.shadow_spans);
            pass.bind(ctx, &[&scene.resources(), &own])
        };
        let shared = ctx.uniform_buffer("pathtrace/params", params);
        let bounces = [
            bound(&self.bounce, &shared, 0)?,
            bound(&self.bounce, &shared, 1)?,
        ];
        // The tail reads queue (WAVEFRONT_PASSES + 1) % 2, as its bounce would.
        let tail_from = (WAVEFRONT_PASSES as usize + 1) % 2;
        let tail = bound(&self.tail, &shared, tail_from)?;
        let hits = match &self.hits {
            Some(pass) => Some([bound(pass, &shared, 0)?, bound(pass, &shared, 1)?]),
            None => None,
        };
        let shadow_passes = match &self.shadow_passes {
            Some([trace, resolve]) => {
                Some([bound(trace, &shared, 0)?, bound(resolve, &shared, 0)?])
            }
            None => None,
        };
        // After a pass that may have deferred its shadow rays: trace them, then add what
        // arrived; both dispatches are empty where it did not.
        let shadows =
            |encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut Profiler>, pass: u32| {
                if let Some([trace, resolve]) = &shadow_passes
                    && pass < WAVEFRONT_PASSES
                {
                    let mut profiler = profiler;
                    encoder.copy_buffer_to_buffer(
                        &self.shadow_queue,
                        0,
                        &self.shadow_dispatch,
                        0,
                        SHADOW_HEADER_BYTES,
                    );
                    trace.dispatch_indirect(
                        encoder,
                        profiler.as_deref_mut(),
                        &self.shadow_dispatch,
                        SHADOW_RUNS_OFFSET,
                    );
                    resolve.dispatch_indirect(
                        encoder,
                        profiler,
                        &self.shadow_dispatch,
                        SHADOW_RESOLVE_OFFSET,
                    );
                }
            };
        let clear_shadows = |encoder: &mut wgpu::CommandEncoder, pass: u32| {
            if self.shadow_passes.is_some() && pass < WAVEFRONT_PASSES {
                encoder.clear_buffer(&self.shadow_queue, 0, Some(SHADOW_HEADER_BYTES));
            }
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
            clear_shadows(encoder, 0);
            camera.dispatch(
                encoder,
                profiler.as_deref_mut(),
                super::PathTracer::workgroups(params.width, params.height),
            );
            shadows(encoder, profiler.as_deref_mut(), 0);
            // The last pass recorded takes its paths to their end (wavefront.wgsl's tail).
            for bounce in 1..=params.max_bounces.min(WAVEFRONT_PASSES) as usize {
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
                clear_shadows(encoder, bounce as u32);
                let (pass, args) = match bounce as u32 == WAVEFRONT_PASSES {
                    true => (&tail, QUEUE_TAIL_OFFSET),
                    false => (&bounces[from], QUEUE_DISPATCH_OFFSET),
                };
                pass.dispatch_indirect(encoder, profiler.as_deref_mut(), &self.queues[from], args);
                shadows(encoder, profiler.as_deref_mut(), bounce as u32);
            }
        }
        Ok(())
    }
}
