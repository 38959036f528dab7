//! The real-time frame: G-buffer from primary rays → direct light → the technique's indirect
//! light → compose → tonemap (ARCHITECTURE.md, "The frame").

mod image_io;
mod renderer;

pub use renderer::{
    FrameBuffers, FrameRenderer, FrameSettings, LightingChange, SceneChange, Technique, apply_pose,
};

pub use image_io::{Image, write_png};

use irradiant_gpu::{GpuContext, read_buffer_as, wgpu};

use crate::RenderError;
use crate::gpu_types::GpuTonemapParams;
use crate::pipeline::*;

/// How linear radiance becomes display values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToneSettings {
    /// Multiplier before the curve; raise it for dim scenes.
    pub exposure: f32,
    /// Filmic (ACES fit) rolls highlights off; plain clamps them (for side-by-side checks
    /// with renderers that clamp).
    pub filmic: bool,
}

impl Default for ToneSettings {
    fn default() -> Self {
        Self {
            exposure: 1.0,
            filmic: true,
        }
    }
}

/// frame/tonemap: radiance sums and counts → packed sRGB RGBA8.
pub struct Tonemapper {
    stage: ComputeStage,
    layout: wgpu::BindGroupLayout,
    params: wgpu::Buffer,
}

impl Tonemapper {
    pub fn new(ctx: &GpuContext) -> Result<Self, RenderError> {
        let layout = ctx
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("frame/tonemap"),
                entries: &[
                    buffer_entry(0, UNIFORM),       // params
                    buffer_entry(1, STORAGE_READ),  // radiance
                    buffer_entry(2, STORAGE_WRITE), // output
                ],
            });
        let stage = ComputeStage::new(
            ctx,
            "frame/tonemap",
            include_str!("tonemap.wgsl"),
            &[],
            &[&layout],
        )?;
        let params = uniform_buffer(
            &ctx.device,
            "frame/tonemap_params",
            size_of::<GpuTonemapParams>(),
        );
        Ok(Self {
            stage,
            layout,
            params,
        })
    }

    /// Tonemaps `radiance` (one vec4 per pixel: rgb sum, sample count) into RGBA8 bytes.
    pub fn run(
        &self,
        ctx: &GpuContext,
        radiance: &wgpu::Buffer,
        width: u32,
        height: u32,
        tone: &ToneSettings,
    ) -> Result<Vec<u8>, RenderError> {
        let params = GpuTonemapParams {
            width,
            height,
            exposure: tone.exposure,
            curve: if tone.filmic { 0 } else { 1 },
        };
        ctx.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let output = storage_buffer(
            &ctx.device,
            "frame/tonemap_output",
            4 * width as u64 * height as u64,
        );
        let group = bind_buffers(
            &ctx.device,
            "frame/tonemap",
            &self.layout,
            &[&self.params, radiance, &output],
        );
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame/tonemap"),
            });
        self.stage.dispatch(
            &mut encoder,
            None,
            &[&group],
            [(width * height).div_ceil(64), 1, 1],
        );
        ctx.queue.submit([encoder.finish()]);
        let packed: Vec<u32> = read_buffer_as(ctx, &output)?;
        Ok(bytemuck::cast_slice(&packed[..(width * height) as usize]).to_vec())
    }
}

/// Reads a radiance accumulation buffer (rgb sum, count) as a linear image.
pub fn read_radiance(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
    width: u32,
    height: u32,
) -> Result<Image, RenderError> {
    let sums: Vec<[f32; 4]> = read_buffer_as(ctx, buffer)?;
    let pixels = sums[..(width * height) as usize].iter().map(|s| {
        let n = s[3].max(1.0);
        [s[0] / n, s[1] / n, s[2] / n]
    });
    Ok(Image {
        width,
        height,
        pixels: pixels.collect(),
    })
}
