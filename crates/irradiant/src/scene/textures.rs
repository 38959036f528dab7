//! The scene's textures on the GPU: every texture resampled to one square size with a full mip
//! chain, in one texture array (lavapipe has no binding arrays).

use irradiant_gpu::{Allocation, AllocationKind, GpuContext, wgpu};
use irradiant_scene::Scene;

use crate::RenderError;

/// The texture array's side: the setting, or 1 when the scene has no textures.
fn side(ctx: &GpuContext, scene: &Scene, size: u32) -> u32 {
    if scene.textures.is_empty() {
        1
    } else {
        size.clamp(1, ctx.device.limits().max_texture_dimension_2d)
    }
}

/// The texture array, as an allocation to check before anything is made.
pub(super) fn plan(ctx: &GpuContext, scene: &Scene, size: u32) -> Allocation {
    let side = side(ctx, scene, size);
    let layers = scene.textures.len().max(1) as u32;
    let mut a = Allocation::texture(
        "scene/textures",
        (side, side),
        4,
        32 - side.leading_zeros(),
        "the texture size (GpuSceneSettings::texture_size) or the scene's texture count",
    );
    a.bytes *= layers as u64;
    a.kind = AllocationKind::Texture {
        width: side,
        height: side,
        layers,
    };
    a
}

/// Resamples every texture to one square size with a full mip chain, into one array.
pub(super) fn upload_textures(
    ctx: &GpuContext,
    scene: &Scene,
    size: u32,
) -> Result<(wgpu::TextureView, u32, u64), RenderError> {
    let limits = ctx.device.limits();
    let size = side(ctx, scene, size);
    let layers = scene.textures.len().max(1) as u32;
    if layers > limits.max_texture_array_layers {
        return Err(RenderError::Scene(format!(
            "the scene has {layers} textures; this adapter's texture arrays hold {}",
            limits.max_texture_array_layers
        )));
    }
    let mip_levels = 32 - size.leading_zeros();
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("scene/textures"),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        },
        mip_level_count: mip_levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let mut bytes = 0u64;
    for layer in 0..layers {
        let mut level_image = match scene.textures.get(layer as usize) {
            Some(t) => {
                let img = image::RgbaImage::from_raw(t.width, t.height, t.rgba8.clone())
                    .ok_or_else(|| {
                        RenderError::Scene(format!(
                            "texture '{}' has the wrong number of bytes",
                            t.name
                        ))
                    })?;
                image::imageops::resize(&img, size, size, image::imageops::FilterType::Triangle)
            }
            None => image::RgbaImage::from_pixel(1, 1, image::Rgba([255; 4])),
        };
        for level in 0..mip_levels {
            let s = (size >> level).max(1);
            if level > 0 {
                level_image = image::imageops::resize(
                    &level_image,
                    s,
                    s,
                    image::imageops::FilterType::Triangle,
                );
            }
            ctx.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: level,
                    origin: wgpu::Origin3d {
                        x: 0,
                        y: 0,
                        z: layer,
                    },
                    aspect: wgpu::TextureAspect::All,
                },
                level_image.as_raw(),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * s),
                    rows_per_image: Some(s),
                },
                wgpu::Extent3d {
                    width: s,
                    height: s,
                    depth_or_array_layers: 1,
                },
            );
            bytes += 4 * s as u64 * s as u64;
        }
    }
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("scene/textures_view"),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    });
    Ok((view, layers, bytes))
}
