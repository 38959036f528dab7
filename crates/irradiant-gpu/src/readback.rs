//! Copying GPU buffers back to the CPU (images, test results, timestamps).

use crate::{GpuContext, GpuError};

/// Copies `size` bytes from `buffer` at `offset` and waits for them.
pub fn read_buffer(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
    offset: u64,
    size: u64,
) -> Result<Vec<u8>, GpuError> {
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback/staging"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("readback/copy"),
        });
    encoder.copy_buffer_to_buffer(buffer, offset, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let slice = staging.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = sender.send(r);
    });
    ctx.wait()?;
    receiver
        .recv()
        .map_err(|e| GpuError::Poll(e.to_string()))?
        .map_err(|e| GpuError::Poll(format!("mapping the readback buffer failed: {e}")))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| GpuError::Poll(e.to_string()))?
        .to_vec();
    staging.unmap();
    Ok(data)
}

/// [`read_buffer`] of a whole buffer, cast to `T`.
pub fn read_buffer_as<T: bytemuck::Pod>(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
) -> Result<Vec<T>, GpuError> {
    let bytes = read_buffer(ctx, buffer, 0, buffer.size())?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
