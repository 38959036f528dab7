use irradiant_gpu::{GpuContext, Profiler, wgpu};
use irradiant_scene::Camera;

use super::PathTraceSettings;
use crate::RenderError;
use crate::frame::{Image, read_radiance};
use crate::gpu_scene::GpuScene;
use crate::gpu_types::{GpuCamera, GpuPathTraceParams};
use crate::pipeline::*;

/// pathtrace/trace with its accumulation buffer.
pub struct PathTracer {
    stage: ComputeStage,
    layout: wgpu::BindGroupLayout,
    /// One vec4 a pixel: rgb sum, sample count.
    pub accumulation: wgpu::Buffer,
    pub width: u32,
    pub height: u32,
    /// Samples per pixel accumulated since the last reset.
    pub samples_done: u32,
}

impl PathTracer {
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        let layout = ctx
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("pathtrace/trace"),
                entries: &[
                    buffer_entry(0, UNIFORM),       // params
                    buffer_entry(1, STORAGE_WRITE), // accumulation
                ],
            });
        let stage = ComputeStage::tracing(
            ctx,
            scene,
            "pathtrace/trace",
            include_str!("trace.wgsl"),
            &[],
            &layout,
        )?;
        let accumulation = storage_buffer(
            &ctx.device,
            "pathtrace/accumulation",
            16 * width as u64 * height as u64,
        );
        Ok(Self {
            stage,
            layout,
            accumulation,
            width,
            height,
            samples_done: 0,
        })
    }

    /// Clears the accumulation: call whenever anything that changes the image changes.
    pub fn reset(&mut self, encoder: &mut wgpu::CommandEncoder) {
        encoder.clear_buffer(&self.accumulation, 0, None);
        self.samples_done = 0;
    }

    /// Records one dispatch of `samples` paths per pixel.
    pub fn record(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        camera: &Camera,
        settings: &PathTraceSettings,
        samples: u32,
        profiler: Option<&mut Profiler>,
    ) {
        let params = GpuPathTraceParams {
            camera: GpuCamera::new(camera, self.width, self.height),
            width: self.width,
            height: self.height,
            sample_offset: self.samples_done,
            samples,
            max_bounces: settings.max_bounces,
            seed: settings.seed,
            _pad0: 0,
            _pad1: 0,
        };
        // A fresh uniform per dispatch: write_buffer lands before the whole submission, so
        // several dispatches in one encoder must not share one.
        let uniform = uniform_buffer(
            &ctx.device,
            "pathtrace/params",
            size_of::<GpuPathTraceParams>(),
        );
        ctx.queue
            .write_buffer(&uniform, 0, bytemuck::bytes_of(&params));
        let group = bind_buffers(
            &ctx.device,
            "pathtrace/trace",
            &self.layout,
            &[&uniform, &self.accumulation],
        );
        self.stage.dispatch(
            encoder,
            profiler,
            &[&scene.bind_group, &group],
            [self.width.div_ceil(8), self.height.div_ceil(8), 1],
        );
        self.samples_done += samples;
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
        let per_dispatch = settings.samples_per_dispatch.max(1);
        while self.samples_done < settings.samples_per_pixel {
            let samples = per_dispatch.min(settings.samples_per_pixel - self.samples_done);
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("pathtrace/trace"),
                });
            self.record(ctx, &mut encoder, scene, camera, settings, samples, None);
            ctx.queue.submit([encoder.finish()]);
            ctx.wait()?;
            progress(self.samples_done, settings.samples_per_pixel);
        }
        read_radiance(ctx, &self.accumulation, self.width, self.height)
    }
}
