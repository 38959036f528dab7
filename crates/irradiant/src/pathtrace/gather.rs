//! pathtrace/gather: the path tracer's truth at arbitrary points and lobes rather than pixels —
//! what the probe oracle and the query oracle (`ddgi::oracle`) measure DDGI against.

use glam::Vec3;
use irradiant_gpu::{Allocation, GpuContext, PassDesc, ResourceTable, Workgroups, wgpu};
use wgpu::util::DeviceExt;

use super::PathTraceSettings;
use super::types::{GpuGatherParams, GpuGatherQuery};
use crate::RenderError;
use crate::scene::GpuScene;

/// Threads a workgroup of pathtrace/gather (its THREADS).
const GATHER_THREADS: u32 = 64;

/// What a query gathers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GatherKind {
    /// Path-traced radiance arriving along each sample, the first surface's emission left out.
    Radiance,
    /// The first hit's distance and its square, misses and longer hits counted as `far`.
    Distance {
        /// The distance misses and longer hits count as.
        far: f32,
    },
}

/// A point, and the lobe cos^exponent about `axis` whose samples it averages.
#[derive(Clone, Copy, Debug)]
pub struct GatherQuery {
    /// World-space point the samples start from.
    pub origin: Vec3,
    /// Axis of the lobe (normalised on upload; zero becomes +z).
    pub axis: Vec3,
    /// The lobe's exponent: 1 is cosine-weighted, so a radiance query's mean is E/π.
    pub exponent: f32,
    /// Radiance or distance.
    pub kind: GatherKind,
    /// The origin lies on a surface whose normal is `axis`: rays start just off it.
    pub on_surface: bool,
}

impl GatherQuery {
    fn gpu(&self) -> GpuGatherQuery {
        let (kind, far) = match self.kind {
            GatherKind::Radiance => (0, 0.0),
            GatherKind::Distance { far } => (1, far),
        };
        GpuGatherQuery {
            origin: self.origin.to_array(),
            far,
            axis: self.axis.normalize_or(Vec3::Z).to_array(),
            exponent: self.exponent,
            kind,
            on_surface: self.on_surface as u32,
            _pad0: 0,
            _pad1: 0,
        }
    }
}

/// The sums of every query after `samples` samples each.
pub struct Gathered {
    /// Radiance: (rgb sum, sum of luminance²); distance: (sum, sum of squares, 0, 0).
    pub sums: Vec<[f32; 4]>,
    /// Samples each query took.
    pub samples: u32,
}

impl Gathered {
    /// Mean radiance of a radiance query (with exponent 1: E/π).
    pub fn radiance(&self, i: usize) -> [f32; 3] {
        let n = self.samples.max(1) as f32;
        let s = self.sums[i];
        [s[0] / n, s[1] / n, s[2] / n]
    }

    /// Standard error of a radiance query's mean luminance: how far the truth itself may be off.
    pub fn luminance_standard_error(&self, i: usize) -> f32 {
        let n = self.samples.max(1) as f32;
        let mean = luminance(self.radiance(i));
        let mean_square = self.sums[i][3] / n;
        ((mean_square - mean * mean).max(0.0) / n).sqrt()
    }

    /// (mean, mean square) of a distance query.
    pub fn distance_moments(&self, i: usize) -> [f32; 2] {
        let n = self.samples.max(1) as f32;
        [self.sums[i][0] / n, self.sums[i][1] / n]
    }
}

/// Rec. 709 luminance, as the shaders' `luminance`.
pub fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// What gathering `count` queries allocates.
pub fn plan(count: usize) -> Vec<Allocation> {
    let setting = "the oracle's probe count or image size";
    vec![
        Allocation::storage(
            "pathtrace/gather_queries",
            (count * size_of::<GpuGatherQuery>()) as u64,
            setting,
        ),
        Allocation::storage("pathtrace/gather_sums", (count * 16) as u64, setting),
    ]
}

/// Gathers `settings.samples_per_pixel` samples at every query, `samples_per_dispatch` at a
/// time, reporting progress as (samples done, samples wanted).
pub fn gather(
    ctx: &GpuContext,
    scene: &GpuScene,
    queries: &[GatherQuery],
    settings: &PathTraceSettings,
    mut progress: impl FnMut(u32, u32),
) -> Result<Gathered, RenderError> {
    if queries.is_empty() {
        return Ok(Gathered {
            sums: Vec::new(),
            samples: settings.samples_per_pixel,
        });
    }
    ctx.check_allocations(&plan(queries.len()))?;
    let pass = crate::shaders::pass(
        ctx,
        &PassDesc::new("pathtrace/gather", include_str!("gather.wgsl"))
            .constants(scene.shader_constants()),
    )?;
    let gpu_queries: Vec<GpuGatherQuery> = queries.iter().map(GatherQuery::gpu).collect();
    let query_buffer = ctx
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("pathtrace/gather_queries"),
            contents: bytemuck::cast_slice(&gpu_queries),
            usage: wgpu::BufferUsages::STORAGE,
        });
    let sums = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("pathtrace/gather_sums"),
        size: (queries.len() * 16).max(16) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        // Zeroed by wgpu: the sums start at nothing.
        mapped_at_creation: false,
    });
    let per_dispatch = settings.samples_per_dispatch_on(&ctx.info);
    // One uniform and one binding for every dispatch: each is submitted and waited for before
    // the next writes the uniform (on llvmpipe there are hundreds of small dispatches).
    let uniform = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("pathtrace/gather_params"),
        size: size_of::<GpuGatherParams>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let own = ResourceTable::new()
        .buffer("params", &uniform)
        .buffer("queries", &query_buffer)
        .buffer("sums", &sums);
    let bound = pass.bind(ctx, &[&scene.resources(), &own])?;
    let mut done = 0;
    while done < settings.samples_per_pixel {
        let samples = per_dispatch.min(settings.samples_per_pixel - done);
        let params = GpuGatherParams {
            count: queries.len() as u32,
            sample_offset: done,
            samples,
            max_bounces: settings.max_bounces,
            seed: settings.seed,
            light_sampling: settings.light_sampling.gpu(),
            _pad1: 0,
            _pad2: 0,
        };
        ctx.queue
            .write_buffer(&uniform, 0, bytemuck::bytes_of(&params));
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("pathtrace/gather"),
            });
        bound.dispatch(
            &mut encoder,
            None,
            Workgroups::for_threads(queries.len() as u64, GATHER_THREADS),
        );
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        done += samples;
        progress(done, settings.samples_per_pixel);
    }
    let sums: Vec<[f32; 4]> = irradiant_gpu::read_buffer_as(ctx, &sums)?;
    Ok(Gathered {
        sums: sums[..queries.len()].to_vec(),
        samples: done,
    })
}
