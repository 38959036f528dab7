//! Probe atlases: every probe's octahedral tile (its interior plus a 1-texel border) side by
//! side in one 2D image, rows of probes; and the copy of an atlas buffer into a texture that
//! the queries sample with hardware filtering.

use irradiant_gpu::wgpu;

/// How probe tiles are laid out in an atlas.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AtlasLayout {
    /// Probe tiles in each row of the atlas.
    pub probes_per_row: u32,
    /// Rows of tiles (the last may be partly empty).
    pub rows: u32,
}

impl AtlasLayout {
    /// Rows about as long as the atlas is tall, each a whole number of 256-byte copy rows for
    /// every tile side listed (tiles of `side` texels, border included, 8 bytes a texel): a
    /// buffer-to-texture copy's row alignment.
    pub fn new(probe_count: u32, tile_sides: &[u32]) -> Self {
        // Tiles a row must be a multiple of for each tile side: 32 texels ÷ gcd(side, 32).
        let multiple = tile_sides
            .iter()
            .map(|&side| 32 / gcd(side, 32))
            .fold(1, lcm);
        let probes_per_row = ((probe_count as f32).sqrt().ceil() as u32)
            .max(1)
            .next_multiple_of(multiple);
        Self {
            probes_per_row,
            rows: probe_count.div_ceil(probes_per_row).max(1),
        }
    }

    /// Atlas size in texels for tiles of `texels` interior texels.
    pub fn size(&self, texels: u32) -> (u32, u32) {
        (self.probes_per_row * (texels + 2), self.rows * (texels + 2))
    }

    /// The atlas texel of texel (x, y) of probe `probe`'s tile (border included): the CPU twin
    /// of probes/atlas.wgsl's atlas_tile_origin.
    pub fn texel(&self, probe: u32, texels: u32, x: u32, y: u32) -> (u32, u32) {
        let tile = texels + 2;
        (
            (probe % self.probes_per_row) * tile + x,
            (probe / self.probes_per_row) * tile + y,
        )
    }
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

fn lcm(a: u32, b: u32) -> u32 {
    a / gcd(a, b) * b
}

/// Records the copy of an atlas kept in a storage buffer (rows of `texel_bytes`-byte texels,
/// 256-byte aligned by [`AtlasLayout`]) into the texture of the same size that queries sample.
pub fn copy_atlas_to_texture(
    encoder: &mut wgpu::CommandEncoder,
    buffer: &wgpu::Buffer,
    texture: &wgpu::Texture,
    texel_bytes: u32,
) {
    let size = texture.size();
    debug_assert_eq!(
        size.width * texel_bytes % wgpu::COPY_BYTES_PER_ROW_ALIGNMENT,
        0,
        "atlas rows are aligned"
    );
    encoder.copy_buffer_to_texture(
        wgpu::TexelCopyBufferInfo {
            buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(size.width * texel_bytes),
                rows_per_image: Some(size.height),
            },
        },
        texture.as_image_copy(),
        size,
    );
}

/// The two samplers DDGI's query reads the atlases with: bilinear for irradiance, nearest for
/// the distance moments' gathers. Labelled `<technique>/atlas_bilinear` and `…/atlas_gather`.
pub fn atlas_samplers(device: &wgpu::Device, technique: &str) -> (wgpu::Sampler, wgpu::Sampler) {
    let sampler = |name: &str, filter| {
        device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some(&format!("{technique}/{name}")),
            mag_filter: filter,
            min_filter: filter,
            ..Default::default()
        })
    };
    (
        sampler("atlas_bilinear", wgpu::FilterMode::Linear),
        sampler("atlas_gather", wgpu::FilterMode::Nearest),
    )
}

/// A texture for an atlas of `size` texels that buffers are copied into and queries sample.
pub fn atlas_texture(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    irradiant_gpu::texture_2d(
        device,
        label,
        (width, height),
        format,
        1,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_align_for_every_tile_side() {
        for count in [1, 6, 64, 343, 8192] {
            let layout = AtlasLayout::new(count, &[8, 16]);
            assert!(layout.probes_per_row * layout.rows >= count);
            for side in [6, 14] {
                let (w, _) = layout.size(side);
                assert_eq!(w * 8 % 256, 0, "{count} probes, side {side}: {w}");
            }
        }
        let layout = AtlasLayout::new(6, &[8, 16]);
        assert_eq!(
            layout.texel(5, 6, 1, 2),
            (
                (5 % layout.probes_per_row) * 8 + 1,
                (5 / layout.probes_per_row) * 8 + 2
            )
        );
    }
}
