//! Baked light-field probes on disk, keyed by everything that shapes them — the scene's
//! content and lights, the probe grid, the bake settings, every shader's text and this
//! crate's version — so that a stale bake is never read. An entry is written under a
//! temporary name and renamed into place (a half-written entry is never read; two processes
//! baking the same key write the same bytes, and the last rename wins). An entry that does
//! not match what is expected (truncated, another key, other sizes) is baked anew. An entry
//! holds the five maps (each with its sizes), then the probe states and offsets.

use std::hash::{Hash, Hasher};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use irradiant_gpu::{GpuContext, wgpu};
use irradiant_scene::Scene;

use super::resources::ProbeMaps;
use super::settings::LightfieldBakeSettings;
use crate::RenderError;
use crate::probes::ProbeGrid;

/// The first bytes of an entry, with the format's version.
const MAGIC: &[u8; 8] = b"IRLF\0\0\0\x03";

/// A hash of everything that shapes a bake.
pub fn bake_key(scene: &Scene, grid: &ProbeGrid, bake: &LightfieldBakeSettings) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    crate::shaders::library().hash_sources(&mut h);
    for source in super::BAKE_SOURCES {
        source.hash(&mut h);
    }
    scene.hash_content(&mut h);
    // Lights and transforms as they stand when the bake is made (the bake is static).
    let pose = scene.pose_at(0.0);
    format!("{:?}{:?}", pose.lights, pose.instance_transforms).hash(&mut h);
    format!("{grid:?}{bake:?}").hash(&mut h);
    h.finish()
}

pub fn entry_path(dir: &Path, key: u64) -> PathBuf {
    dir.join(format!("lightfield-{key:016x}.bin"))
}

fn layout(texture: &wgpu::Texture, texel_bytes: u32) -> [u32; 4] {
    let s = texture.size();
    [s.width, s.height, s.depth_or_array_layers, texel_bytes]
}

/// Uploads the entry at `file` into `maps` if it is there and matches; false otherwise.
pub fn load(
    ctx: &GpuContext,
    file: &Path,
    key: u64,
    maps: &ProbeMaps,
) -> Result<bool, RenderError> {
    let Ok(mut reader) = std::fs::File::open(file).map(std::io::BufReader::new) else {
        return Ok(false);
    };
    let mut header = [0u8; 16];
    if reader.read_exact(&mut header).is_err()
        || &header[..8] != MAGIC
        || header[8..] != key.to_le_bytes()
    {
        return Ok(false);
    }
    // Read everything before uploading anything: a short entry leaves the textures alone.
    let mut contents = Vec::new();
    for (texture, texel_bytes) in maps.in_cache_order() {
        let expected = layout(texture, texel_bytes);
        let mut stored = [0u8; 16];
        if reader.read_exact(&mut stored).is_err()
            || bytemuck::cast::<[u8; 16], [u32; 4]>(stored).map(u32::from_le) != expected
        {
            return Ok(false);
        }
        let [w, h, layers, texel] = expected;
        let mut data = vec![0u8; w as usize * h as usize * layers as usize * texel as usize];
        if reader.read_exact(&mut data).is_err() {
            return Ok(false);
        }
        contents.push((texture, expected, data));
    }
    let mut buffers = Vec::new();
    for buffer in [&maps.states, &maps.offsets] {
        let mut data = vec![0u8; buffer.size() as usize];
        if reader.read_exact(&mut data).is_err() {
            return Ok(false);
        }
        buffers.push((buffer, data));
    }
    for (buffer, data) in buffers {
        ctx.queue.write_buffer(buffer, 0, &data);
    }
    for (texture, [w, h, layers, texel], data) in contents {
        ctx.queue.write_texture(
            texture.as_image_copy(),
            &data,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(w * texel),
                rows_per_image: Some(h),
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: layers,
            },
        );
    }
    Ok(true)
}

/// Writes `maps` as the entry for `key`. A cache that cannot be written is not an error: the
/// bake stands, and the next run bakes again.
pub fn store(ctx: &GpuContext, file: &Path, key: u64, maps: &ProbeMaps) -> Result<(), RenderError> {
    let mut bytes = Vec::new();
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&key.to_le_bytes());
    for (texture, texel_bytes) in maps.in_cache_order() {
        for v in layout(texture, texel_bytes) {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        bytes.extend(irradiant_gpu::read_texture(ctx, texture, texel_bytes)?);
    }
    for buffer in [&maps.states, &maps.offsets] {
        bytes.extend(irradiant_gpu::read_buffer(ctx, buffer, 0, buffer.size())?);
    }
    let Some(dir) = file.parent() else {
        return Ok(());
    };
    if std::fs::create_dir_all(dir).is_err() {
        return Ok(());
    }
    // A temporary name of this process's, renamed into place once complete.
    let _ = crate::frame::write_atomically(file, |temporary| {
        std::fs::File::create(temporary)
            .and_then(|mut f| f.write_all(&bytes).and_then(|()| f.sync_all()))
            .map_err(|e| e.to_string())
    });
    Ok(())
}
