//! The reference path tracer: the ground truth every technique is measured against.
//! See docs/pathtrace.md.

pub mod constants;
pub mod gather;
mod passes;
pub mod reference_cache;
pub mod types;
mod wavefront;

pub use gather::{GatherKind, GatherQuery, Gathered, gather};
pub use passes::PathTracer;

/// Path tracer settings. Every figure it produces is deterministic for a given seed.
#[derive(Clone, Debug, PartialEq)]
pub struct PathTraceSettings {
    /// Samples per pixel. Noise falls as 1/√spp: 64 previews, 1024 converges most scenes,
    /// references for comparisons use 4096+.
    pub samples_per_pixel: u32,
    /// Samples each pixel takes per GPU dispatch. More per dispatch means fewer submissions
    /// (faster) but longer single dispatches, which some drivers kill (Windows TDR at 2 s).
    pub samples_per_dispatch: u32,
    /// Longest path, in bounces after the camera ray. Russian roulette ends most paths long
    /// before; the cap only bounds the worst case. Lower it to see fewer bounces of light.
    pub max_bounces: u32,
    /// Random seed: change it for an independent image.
    pub seed: u32,
    /// How emitted light is found: both ways weighed by multiple importance (the truth), or
    /// one alone — a diagnostic: each alone must converge to the same image, so a difference
    /// between them shows where one of them is wrong.
    pub light_sampling: LightSampling,
    /// How the paths are laid out on the GPU: see [`PathSchedule`].
    pub schedule: PathSchedule,
}

/// How the path tracer's work is laid out on the GPU. Both trace the same paths from the same
/// random numbers (one shared `path_step`, or `path_step_at` from a hit traced apart), so they
/// render the same image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PathSchedule {
    /// The wavefront on a GPU, the megakernel on a CPU adapter (lavapipe), where every pass
    /// costs about half a millisecond of its own: the wavefront's 33 passes a sample (before
    /// the tail) made a 32×32 image 6 times slower.
    #[default]
    Auto,
    /// One thread a pixel traces its paths from start to end (`pathtrace/trace`): no memory
    /// beyond the image and one dispatch a batch of samples, but a warp runs as long as the
    /// longest of its 32 paths, its other lanes idle once theirs end.
    Megakernel,
    /// One pass a bounce over the paths still alive (`pathtrace/camera`, `pathtrace/bounce`):
    /// ended paths leave the warps (a sample on Sibenik at 1920×1080 17.1 ms against 20.2, on
    /// an H100), against two queues of 64 bytes a pixel each (265 MB at 1920×1080) and a pass
    /// a bounce for a sample's first four passes, the fifth (`pathtrace/tail`) taking the paths
    /// left to their ends, its lanes fetching them (12.29 ms on Sibenik on an H200,
    /// docs/pathtrace.md). On a costly tree of one mesh a
    /// bounce's rays are traced apart first (`pathtrace/hits`, lanes that fetch: Sibenik 17.0
    /// → 15.9 ms on an H200), for 16 bytes a pixel more. Where the buffers pass the adapter's
    /// largest storage binding, the megakernel traces instead.
    Wavefront,
}

impl PathSchedule {
    /// The schedule this adapter runs: `Auto` made definite.
    pub fn on(self, ctx: &irradiant_gpu::GpuContext) -> Self {
        match self {
            // GpuInfo's device type, as wgpu's Debug writes it: no adapter query a frame.
            Self::Auto if ctx.info.device_type == "Cpu" => Self::Megakernel,
            Self::Auto => Self::Wavefront,
            definite => definite,
        }
    }
}

/// The ways the path tracer finds emissive triangles' light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LightSampling {
    /// The emitter sample and BRDF-sampled rays that hit an emitter, weighed by the power
    /// heuristic: low noise wherever emitters are small or large.
    #[default]
    Both,
    /// The emitter sample alone (what DDGI's probe rays take): noisy where emitters are large
    /// and near.
    Emitters,
    /// BRDF-sampled rays alone: noisy where emitters are small.
    Brdf,
}

impl LightSampling {
    /// The value the shaders read (`path_radiance`'s `light_sampling`).
    pub fn gpu(self) -> u32 {
        match self {
            Self::Both => constants::LIGHT_SAMPLING_BOTH,
            Self::Emitters => constants::LIGHT_SAMPLING_EMITTERS,
            Self::Brdf => constants::LIGHT_SAMPLING_BRDF,
        }
    }
}

impl Default for PathTraceSettings {
    fn default() -> Self {
        Self::balanced()
    }
}

/// Samples of one path-tracer invocation a dispatch takes at most where the adapter limits an
/// invocation's loop iterations (`GpuInfo::loop_iteration_limit`, llvmpipe's 65 535 shared by
/// every loop): each sample's BVH traversals run hundreds of iterations a ray. A closed box of
/// 43 200 emitting triangles read a third of its light short at 64 a dispatch on lavapipe, and
/// right at this many.
const SAMPLES_PER_DISPATCH_UNDER_A_LOOP_LIMIT: u32 = 4;

impl PathTraceSettings {
    /// Samples a dispatch takes on this adapter: `samples_per_dispatch`, fewer where the adapter
    /// ends loops past a limit.
    pub fn samples_per_dispatch_on(&self, info: &irradiant_gpu::GpuInfo) -> u32 {
        let cap = info
            .loop_iteration_limit
            .map_or(u32::MAX, |_| SAMPLES_PER_DISPATCH_UNDER_A_LOOP_LIMIT);
        self.samples_per_dispatch.clamp(1, cap)
    }

    /// Light that bounced at most `bounces` times between the emitters and the surface seen
    /// (0: direct light only; 1: the one indirect bounce that SSIL's first bounce models):
    /// `max_bounces` counts the hop to the emitter too.
    pub fn with_indirect_bounces(self, bounces: u32) -> Self {
        Self {
            max_bounces: bounces + 1,
            ..self
        }
    }

    /// 64 samples a pixel, at most 8 bounces: a preview.
    pub fn fast() -> Self {
        Self {
            samples_per_pixel: 64,
            samples_per_dispatch: 8,
            max_bounces: 8,
            seed: 0,
            light_sampling: LightSampling::Both,
            schedule: PathSchedule::Auto,
        }
    }
    /// 1024 samples a pixel, at most 32 bounces: converges most scenes.
    pub fn balanced() -> Self {
        Self {
            samples_per_pixel: 1024,
            samples_per_dispatch: 16,
            max_bounces: 32,
            seed: 0,
            light_sampling: LightSampling::Both,
            schedule: PathSchedule::Auto,
        }
    }
    /// 8192 samples a pixel, at most 64 bounces: references for comparisons.
    pub fn quality() -> Self {
        Self {
            samples_per_pixel: 8192,
            samples_per_dispatch: 32,
            max_bounces: 64,
            seed: 0,
            light_sampling: LightSampling::Both,
            schedule: PathSchedule::Auto,
        }
    }
}
