use std::sync::Arc;

use irradiant_gpu::{
    Allocation, ComputePass, GpuContext, PassDesc, Profiler, ResourceTable, Workgroups, wgpu,
};
use irradiant_scene::Camera;

use super::types::GpuPathTraceParams;
use super::wavefront::Wavefront;
use super::{PathSchedule, PathTraceSettings};
use crate::RenderError;
use crate::frame::{IMAGE_TILE, Image};
use crate::scene::GpuScene;
use crate::scene::types::GpuCamera;

/// pathtrace/trace with its accumulation buffer.
pub struct PathTracer {
    pass: Arc<ComputePass>,
    /// rgba32float: rgb sum, sample count.
    pub accumulation: wgpu::Texture,
    accumulation_view: wgpu::TextureView,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel accumulated since the last reset.
    pub samples_done: u32,
    /// The wavefront's passes and queues, made at its first use: None inside where they do
    /// not fit the adapter (the megakernel traces then).
    wavefront: Option<Option<Wavefront>>,
    /// The schedule the last samples were traced with.
    traced_with: PathSchedule,
    /// Set by [`PathTracer::with_fetch_workgroups`]: the wavefront traces a bounce's rays apart
    /// whatever the tree's cost, its `pathtrace/hits` in at most this many workgroups. None:
    /// from `TRACED_APART_FROM_SAH_COST` on, in at most `crate::shaders::FETCH_WORKGROUPS`.
    forced_fetch_workgroups: Option<u32>,
}

impl PathTracer {
    /// What a path tracer of this size allocates (checked before it is made).
    pub fn plan(width: u32, height: u32) -> Vec<Allocation> {
        vec![Allocation::texture(
            "pathtrace/accumulation",
            (width, height),
            16,
            1,
            "the image size (--size)",
        )]
    }

    /// What it holds now: the accumulation, and the wavefront's queues (and hits) once made.
    pub fn allocations(&self) -> Vec<Allocation> {
        let mut all = Self::plan(self.width, self.height);
        if let Some(Some(wavefront)) = &self.wavefront {
            all.extend(wavefront.allocations(self.width, self.height));
        }
        all
    }

    /// Checks its allocation, compiles the pass with the scene's traversal constants and
    /// makes the accumulation texture.
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        ctx.check_allocations(&Self::plan(width, height))?;
        let pass = crate::shaders::pass(
            ctx,
            &PassDesc::new("pathtrace/trace", include_str!("trace.wgsl"))
                .constants(scene.shader_constants()),
        )?;
        let accumulation = irradiant_gpu::texture_2d(
            &ctx.device,
            "pathtrace/accumulation",
            (width, height),
            wgpu::TextureFormat::Rgba32Float,
            1,
            // Sampled too: the viewer tonemaps the running mean on the GPU, without a readback.
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        Ok(Self {
            pass,
            accumulation_view: accumulation.create_view(&Default::default()),
            accumulation,
            width,
            height,
            samples_done: 0,
            wavefront: None,
            traced_with: PathSchedule::Megakernel,
            forced_fetch_workgroups: None,
        })
    }

    /// With the wavefront tracing a bounce's rays apart wherever the scene fetches rays,
    /// whatever its tree's cost, and its `pathtrace/hits` dispatching at most `workgroups`
    /// workgroups (a run of rays each: a test's few paths then take runs past 64). Call before
    /// the first samples.
    pub fn with_fetch_workgroups(self, workgroups: u32) -> Self {
        Self {
            forced_fetch_workgroups: Some(workgroups.max(1)),
            ..self
        }
    }

    /// The workgroups of one dispatch over a `width`×`height` image.
    pub fn workgroups(width: u32, height: u32) -> Workgroups {
        Workgroups::for_image(width, height, IMAGE_TILE)
    }

    /// Clears the accumulation: call whenever anything that changes the image changes.
    pub fn reset(&mut self, encoder: &mut wgpu::CommandEncoder) {
        encoder.clear_texture(&self.accumulation, &wgpu::ImageSubresourceRange::default());
        self.samples_done = 0;
    }

    /// Records `samples` paths a pixel: one dispatch with the megakernel; with the wavefront,
    /// a camera pass and a pass a bounce for each sample up to the tail, which takes each path
    /// left to its end (`Wavefront::record`), each bounce after its rays' `pathtrace/hits`
    /// where they are traced apart, and the passes before the tail each followed by
    /// `pathtrace/shadows` and `pathtrace/shadow_resolve` where shadow rays are deferred.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        camera: &Camera,
        settings: &PathTraceSettings,
        samples: u32,
        profiler: Option<&mut Profiler>,
    ) -> Result<(), RenderError> {
        let params = GpuPathTraceParams {
            camera: GpuCamera::new(camera, self.width, self.height),
            width: self.width,
            height: self.height,
            sample_offset: self.samples_done,
            samples,
            max_bounces: settings.max_bounces,
            seed: settings.seed,
            light_sampling: settings.light_sampling.gpu(),
            _pad1: 0,
        };
        if settings.schedule.on(ctx) == PathSchedule::Wavefront {
            if self.wavefront.is_none() {
                let apart = self.forced_fetch_workgroups.is_some()
                    || scene.stats.sah_cost >= super::wavefront::TRACED_APART_FROM_SAH_COST;
                self.wavefront = Some(Wavefront::new(
                    ctx,
                    scene,
                    self.width,
                    self.height,
                    apart,
                    self.forced_fetch_workgroups
                        .unwrap_or(crate::shaders::FETCH_WORKGROUPS),
                )?);
            }
            if let Some(Some(wavefront)) = &self.wavefront {
                wavefront.record(
                    ctx,
                    encoder,
                    scene,
                    &self.accumulation_view,
                    &params,
                    profiler,
                )?;
                self.samples_done += samples;
                self.traced_with = PathSchedule::Wavefront;
                return Ok(());
            }
        }
        let uniform = ctx.uniform_buffer("pathtrace/params", &params);
        let own = ResourceTable::new()
            .buffer("params", &uniform)
            .texture("accumulation", &self.accumulation_view);
        let bound = self.pass.bind(ctx, &[&scene.resources(), &own])?;
        bound.dispatch(
            encoder,
            profiler,
            Workgroups::for_image(self.width, self.height, IMAGE_TILE),
        );
        self.samples_done += samples;
        self.traced_with = PathSchedule::Megakernel;
        Ok(())
    }

    /// The schedule the last samples were traced with: the settings' on this adapter, unless
    /// the wavefront's queues did not fit it.
    pub fn traced_with(&self) -> PathSchedule {
        self.traced_with
    }

    /// Whether the last samples were traced by a wavefront that traces a bounce's rays apart
    /// from their shading, by lanes that fetch their next ray (on a scene of one wide tree),
    /// wherever more paths are alive than its `pathtrace/hits` holds in runs of 64.
    pub fn fetched_rays(&self) -> bool {
        self.traced_with == PathSchedule::Wavefront
            && matches!(&self.wavefront, Some(Some(w)) if w.fetches_rays())
    }

    /// Whether the last samples were traced by a wavefront whose first passes defer their
    /// vertices' shadow rays to `pathtrace/shadows` (where it fetches rays, and a vertex's lights
    /// and emitter sample take at most `DEFERRED_SHADOWS_MAX` rays).
    pub fn deferred_shadows(&self) -> bool {
        self.traced_with == PathSchedule::Wavefront
            && matches!(&self.wavefront, Some(Some(w)) if w.defers_shadows())
    }

    /// Renders `settings.samples_per_pixel` samples from scratch, reporting progress after each
    /// dispatch as (samples done, samples wanted).
    pub fn render(
        &mut self,
        ctx: &GpuContext,
        scene: &GpuScene,
        camera: &Camera,
        settings: &PathTraceSettings,
        mut progress: impl FnMut(u32, u32),
    ) -> Result<Image, RenderError> {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("pathtrace/reset"),
            });
        self.reset(&mut encoder);
        ctx.queue.submit([encoder.finish()]);
        let per_dispatch = settings.samples_per_dispatch_on(&ctx.info);
        while self.samples_done < settings.samples_per_pixel {
            let samples = per_dispatch.min(settings.samples_per_pixel - self.samples_done);
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("pathtrace/trace"),
                });
            self.record(ctx, &mut encoder, scene, camera, settings, samples, None)?;
            ctx.queue.submit([encoder.finish()]);
            ctx.wait()?;
            progress(self.samples_done, settings.samples_per_pixel);
        }
        self.image(ctx)
    }

    /// The accumulation as a sampled view: rgb sums over the count in alpha.
    pub fn accumulation_view(&self) -> &wgpu::TextureView {
        &self.accumulation_view
    }

    /// The accumulated mean radiance so far.
    pub fn image(&self, ctx: &GpuContext) -> Result<Image, RenderError> {
        let sums: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&irradiant_gpu::read_texture(
            ctx,
            &self.accumulation,
            16,
        )?);
        let pixels = sums.iter().map(|s| {
            let n = s[3].max(1.0);
            [s[0] / n, s[1] / n, s[2] / n]
        });
        Ok(Image {
            width: self.width,
            height: self.height,
            pixels: pixels.collect(),
        })
    }
}
