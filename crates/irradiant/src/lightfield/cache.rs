//! Baked light-field probes on disk, keyed by everything that shapes them — the scene's
//! content and lights, the probe grid, the bake settings, every shader's text and this
//! crate's version — so that a stale bake is never read. An entry is written under a
//! temporary name and renamed into place (a half-written entry is never read; two processes
//! baking the same key write the same bytes, and the last rename wins). An entry that does
//! not match what is expected (truncated, another key, other sizes) is baked anew. An entry
//! holds the five maps (each with its sizes), then the probe states and offsets.

use std::hash::{Hash, Hasher};
use std::io::Write;
use std::path::{Path, PathBuf};

use irradiant_gpu::{GpuContext, wgpu};
use irradiant_scene::Scene;

use super::resources::ProbeMaps;
use super::settings::LightfieldBakeSettings;
use crate::RenderError;
use crate::probes::ProbeGrid;

/// The first bytes of an entry, with the format's version.
const MAGIC: &[u8; 8] = b"IRLF\0\0\0\x03";

/// A hash of everything that shapes a bake: the bake settings and the one shading setting
/// the bake reads, the irradiance query's `self_shadow_bias` (its bounces gather with it).
pub fn bake_key(
    scene: &Scene,
    grid: &ProbeGrid,
    bake: &LightfieldBakeSettings,
    self_shadow_bias: f32,
) -> u64 {
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
    self_shadow_bias.to_bits().hash(&mut h);
    h.finish()
}

/// The file of the entry for `key` in the cache folder `dir`.
pub fn entry_path(dir: &Path, key: u64) -> PathBuf {
    dir.join(format!("lightfield-{key:016x}.bin"))
}

fn layout(texture: &wgpu::Texture, texel_bytes: u32) -> [u32; 4] {
    let s = texture.size();
    [s.width, s.height, s.depth_or_array_layers, texel_bytes]
}

/// What an entry must hold after its header: each map's [width, height, layers, bytes a
/// texel] with its texels, then each buffer's bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct EntryLayout {
    /// Each map's [width, height, layers, bytes a texel], in the entry's order.
    pub maps: Vec<[u32; 4]>,
    /// Each buffer's bytes: the probe states, then the offsets.
    pub buffers: Vec<u64>,
}

impl EntryLayout {
    fn of(maps: &ProbeMaps) -> Self {
        Self {
            maps: maps
                .in_cache_order()
                .iter()
                .map(|(texture, texel)| layout(texture, *texel))
                .collect(),
            buffers: vec![maps.states.size(), maps.offsets.size()],
        }
    }

    fn map_bytes([w, h, layers, texel]: [u32; 4]) -> u64 {
        w as u64 * h as u64 * layers as u64 * texel as u64
    }

    /// The whole entry's length in bytes.
    pub fn entry_bytes(&self) -> u64 {
        16 + self
            .maps
            .iter()
            .map(|&m| 16 + Self::map_bytes(m))
            .sum::<u64>()
            + self.buffers.iter().sum::<u64>()
    }
}

/// The chunks of an entry — each map's texels, then each buffer's bytes — when `bytes` is the
/// entry for `key` of exactly `layout`; None for anything else (truncated, foreign, of other
/// sizes, with bytes left over). Fuzzed by `fuzz/fuzz_targets/bake_cache.rs`.
pub fn parse_entry<'a>(bytes: &'a [u8], key: u64, layout: &EntryLayout) -> Option<Vec<&'a [u8]>> {
    if bytes.len() as u64 != layout.entry_bytes()
        || &bytes[..8] != MAGIC
        || bytes[8..16] != key.to_le_bytes()
    {
        return None;
    }
    let mut rest = &bytes[16..];
    let mut chunks = Vec::new();
    for &map in &layout.maps {
        let (stored, after) = rest.split_at(16);
        let stored: [u8; 16] = stored.try_into().ok()?;
        if bytemuck::cast::<[u8; 16], [u32; 4]>(stored).map(u32::from_le) != map {
            return None;
        }
        let (texels, after) = after.split_at(EntryLayout::map_bytes(map) as usize);
        chunks.push(texels);
        rest = after;
    }
    for &size in &layout.buffers {
        let (data, after) = rest.split_at(size as usize);
        chunks.push(data);
        rest = after;
    }
    rest.is_empty().then_some(chunks)
}

/// Uploads the entry at `file` into `maps` if it is there and matches; false otherwise. A file
/// of any other length is passed over before it is read.
pub fn load(
    ctx: &GpuContext,
    file: &Path,
    key: u64,
    maps: &ProbeMaps,
) -> Result<bool, RenderError> {
    let layout = EntryLayout::of(maps);
    if std::fs::metadata(file).map(|m| m.len()).ok() != Some(layout.entry_bytes()) {
        return Ok(false);
    }
    let Ok(bytes) = std::fs::read(file) else {
        return Ok(false);
    };
    let Some(chunks) = parse_entry(&bytes, key, &layout) else {
        return Ok(false);
    };
    let textures = maps.in_cache_order();
    for ((texture, _), (data, &[w, h, layers, texel])) in
        textures.iter().zip(chunks.iter().zip(&layout.maps))
    {
        ctx.queue.write_texture(
            texture.as_image_copy(),
            data,
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
    for (buffer, data) in [&maps.states, &maps.offsets]
        .into_iter()
        .zip(&chunks[layout.maps.len()..])
    {
        ctx.queue.write_buffer(buffer, 0, data);
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
