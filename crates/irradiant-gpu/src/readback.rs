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
    map_staging(ctx, &staging, |mapped| mapped.to_vec())
}

/// Waits for the submitted copy into `staging`, maps it and reads it with `read`.
fn map_staging(
    ctx: &GpuContext,
    staging: &wgpu::Buffer,
    read: impl FnOnce(&[u8]) -> Vec<u8>,
) -> Result<Vec<u8>, GpuError> {
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
    let data = read(
        &slice
            .get_mapped_range()
            .map_err(|e| GpuError::Poll(e.to_string()))?,
    );
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

/// Copies mip level 0 of a 2D texture and waits for it: `texel_bytes` a texel, rows packed
/// (the copy's 256-byte row padding removed).
pub fn read_texture(
    ctx: &GpuContext,
    texture: &wgpu::Texture,
    texel_bytes: u32,
) -> Result<Vec<u8>, GpuError> {
    read_texture_level(ctx, texture, 0, texel_bytes)
}

/// [`read_texture`] of mip level `level`; of an array texture, every layer, one after another.
pub fn read_texture_level(
    ctx: &GpuContext,
    texture: &wgpu::Texture,
    level: u32,
    texel_bytes: u32,
) -> Result<Vec<u8>, GpuError> {
    if level >= texture.mip_level_count() {
        return Err(GpuError::Poll(format!(
            "the texture has no mip level {level}"
        )));
    }
    let size = texture.size().mip_level_size(level, texture.dimension());
    let layers = size.depth_or_array_layers;
    let row = size.width * texel_bytes;
    let padded = row.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback/texture_staging"),
        size: padded as u64 * size.height as u64 * layers as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("readback/texture_copy"),
        });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: level,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &staging,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(size.height),
            },
        },
        wgpu::Extent3d {
            width: size.width,
            height: size.height,
            depth_or_array_layers: layers,
        },
    );
    ctx.queue.submit([encoder.finish()]);
    map_staging(ctx, &staging, |mapped| {
        let rows = size.height as usize * layers as usize;
        let mut data = Vec::with_capacity(row as usize * rows);
        for y in 0..rows {
            let start = y * padded as usize;
            data.extend_from_slice(&mapped[start..start + row as usize]);
        }
        data
    })
}
