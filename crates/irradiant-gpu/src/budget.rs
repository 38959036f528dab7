//! Sizes checked before allocation: every buffer and texture a run will make is listed with
//! the setting that sizes it, and compared with the adapter's limits and memory first, so that
//! a run too large for the adapter stops at once with a message naming the setting to change —
//! never after minutes of work, never as a raw wgpu message.

use crate::{GpuContext, GpuError};

/// What kind of GPU memory an allocation is, for the limit that applies to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AllocationKind {
    /// A buffer bound whole as a storage buffer: limited by the adapter's largest binding.
    StorageBuffer,
    /// A buffer that is only copied or bound as a uniform: limited by the largest buffer.
    Buffer,
    /// A 2D texture (or array of `layers` layers).
    Texture {
        /// Width in texels (of level 0).
        width: u32,
        /// Height in texels (of level 0).
        height: u32,
        /// Array layers; 1 for a plain 2D texture.
        layers: u32,
    },
}

/// One allocation a run will make, known before it is made.
#[derive(Clone, Debug, PartialEq)]
pub struct Allocation {
    /// `owner/name`, as the resource's label.
    pub label: String,
    /// Size in bytes; for a texture, every layer and mip level.
    pub bytes: u64,
    /// What it is, which decides the limit it is checked against.
    pub kind: AllocationKind,
    /// The setting that sizes it (`--size`, `ddgi probe counts`): the message names it.
    pub setting: String,
}

impl Allocation {
    /// A storage buffer of `bytes` bytes, bound whole.
    pub fn storage(label: impl Into<String>, bytes: u64, setting: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            bytes,
            kind: AllocationKind::StorageBuffer,
            setting: setting.into(),
        }
    }

    /// A buffer of `bytes` bytes that is only copied or bound as a uniform.
    pub fn buffer(label: impl Into<String>, bytes: u64, setting: impl Into<String>) -> Self {
        Self {
            kind: AllocationKind::Buffer,
            ..Self::storage(label, bytes, setting)
        }
    }

    /// A 2D texture of `texel_bytes` a texel, with `mip_levels` levels (a full chain adds a third).
    pub fn texture(
        label: impl Into<String>,
        (width, height): (u32, u32),
        texel_bytes: u64,
        mip_levels: u32,
        setting: impl Into<String>,
    ) -> Self {
        let mut texture = Self::texture_array(label, (width, height), 1, texel_bytes, setting);
        texture.bytes = (0..mip_levels.max(1))
            .map(|level| {
                (width >> level).max(1) as u64 * (height >> level).max(1) as u64 * texel_bytes
            })
            .sum();
        texture
    }

    /// A 2D texture array of `layers` layers of one level, `texel_bytes` a texel.
    pub fn texture_array(
        label: impl Into<String>,
        (width, height): (u32, u32),
        layers: u32,
        texel_bytes: u64,
        setting: impl Into<String>,
    ) -> Self {
        Self {
            label: label.into(),
            bytes: width as u64 * height as u64 * layers as u64 * texel_bytes,
            kind: AllocationKind::Texture {
                width,
                height,
                layers,
            },
            setting: setting.into(),
        }
    }
}

/// The limits allocations are checked against: the device's, and its memory.
#[derive(Clone, Debug)]
pub struct Budget {
    /// Largest storage-buffer binding, in bytes.
    pub max_storage_buffer_binding_size: u64,
    /// Largest buffer, in bytes.
    pub max_buffer_size: u64,
    /// Largest side of a 2D texture, in texels.
    pub max_texture_dimension_2d: u32,
    /// Most layers of a texture array.
    pub max_texture_array_layers: u32,
    /// The largest device-local memory heap, where the driver reports it.
    pub memory: Option<u64>,
}

impl Budget {
    /// The limits of `ctx`'s device, and the memory its adapter reports.
    pub fn of(ctx: &GpuContext) -> Self {
        let limits = ctx.device.limits();
        Self {
            max_storage_buffer_binding_size: limits.max_storage_buffer_binding_size,
            max_buffer_size: limits.max_buffer_size,
            max_texture_dimension_2d: limits.max_texture_dimension_2d,
            max_texture_array_layers: limits.max_texture_array_layers,
            memory: ctx.info.memory,
        }
    }

    /// Checks every allocation, then their sum against the memory; the first refusal names the
    /// allocation, what it needs, what the adapter allows and the setting to change.
    pub fn check(&self, allocations: &[Allocation]) -> Result<(), GpuError> {
        for a in allocations {
            let refuse = |needs: String, allows: String| GpuError::TooLarge {
                what: a.label.clone(),
                needs,
                allows,
                setting: a.setting.clone(),
            };
            match a.kind {
                AllocationKind::StorageBuffer if a.bytes > self.max_storage_buffer_binding_size => {
                    return Err(refuse(
                        bytes(a.bytes),
                        format!(
                            "{} in one storage buffer",
                            bytes(self.max_storage_buffer_binding_size)
                        ),
                    ));
                }
                AllocationKind::StorageBuffer | AllocationKind::Buffer
                    if a.bytes > self.max_buffer_size =>
                {
                    return Err(refuse(
                        bytes(a.bytes),
                        format!("{} in one buffer", bytes(self.max_buffer_size)),
                    ));
                }
                AllocationKind::Texture {
                    width,
                    height,
                    layers,
                } => {
                    if width.max(height) > self.max_texture_dimension_2d {
                        return Err(refuse(
                            format!("a {width}×{height} texture"),
                            format!("{} texels a side", self.max_texture_dimension_2d),
                        ));
                    }
                    if layers > self.max_texture_array_layers {
                        return Err(refuse(
                            format!("{layers} texture layers"),
                            format!("{}", self.max_texture_array_layers),
                        ));
                    }
                }
                _ => {}
            }
        }
        let total: u64 = allocations.iter().map(|a| a.bytes).sum();
        if let Some(memory) = self.memory
            && total > memory
        {
            let mut largest: Vec<&Allocation> = allocations.iter().collect();
            largest.sort_by_key(|a| std::cmp::Reverse(a.bytes));
            let top: Vec<String> = largest
                .iter()
                .take(3)
                .map(|a| format!("{} {} ({})", a.label, bytes(a.bytes), a.setting))
                .collect();
            return Err(GpuError::TooLarge {
                what: "this run".into(),
                needs: format!(
                    "{} of GPU memory in all, the most for {}",
                    bytes(total),
                    top.join(", ")
                ),
                allows: format!("{} (its largest device-local memory heap)", bytes(memory)),
                setting: largest[0].setting.clone(),
            });
        }
        Ok(())
    }
}

/// A 2D texture of one layer: the one place textures are described (usage decides where it
/// binds: storage, sampled, copies).
pub fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    mip_levels: u32,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: mip_levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// A 2D texture array of `layers` layers and one level (probe maps: a layer a probe).
pub fn texture_2d_array(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    layers: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// A byte count for people: KiB, MiB or GiB.
pub fn bytes(n: u64) -> String {
    const K: f64 = 1024.0;
    let v = n as f64;
    if v >= K * K * K {
        format!("{:.1} GiB", v / (K * K * K))
    } else if v >= K * K {
        format!("{:.1} MiB", v / (K * K))
    } else if v >= K {
        format!("{:.1} KiB", v / K)
    } else {
        format!("{n} bytes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn budget() -> Budget {
        Budget {
            max_storage_buffer_binding_size: 1 << 31,
            max_buffer_size: 1 << 32,
            max_texture_dimension_2d: 16384,
            max_texture_array_layers: 2048,
            memory: Some(8 << 30),
        }
    }

    #[test]
    fn each_limit_refuses_with_the_setting_named() {
        let b = budget();
        assert!(
            b.check(&[Allocation::storage(
                "ddgi/samples",
                1 << 30,
                "ddgi probe counts"
            )])
            .is_ok()
        );
        let e = b
            .check(&[Allocation::storage(
                "ddgi/samples",
                3 << 30,
                "ddgi probe counts",
            )])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("ddgi/samples") && e.contains("ddgi probe counts") && e.contains("3.0 GiB"),
            "{e}"
        );
        let e = b
            .check(&[Allocation::texture(
                "frame/radiance",
                (20000, 10),
                16,
                1,
                "--size",
            )])
            .unwrap_err()
            .to_string();
        assert!(e.contains("20000×10") && e.contains("--size"), "{e}");
        // Each fits alone; together they pass the 8 GiB of memory.
        let many: Vec<Allocation> = (0..5)
            .map(|i| Allocation::texture(format!("frame/t{i}"), (16384, 16384), 8, 1, "--size"))
            .collect();
        let e = b.check(&many).unwrap_err().to_string();
        assert!(e.contains("10.0 GiB") && e.contains("--size"), "{e}");
    }

    #[test]
    fn mip_chains_add_a_third() {
        let a = Allocation::texture("t", (256, 256), 4, 9, "x");
        assert!(a.bytes > 256 * 256 * 4 && a.bytes < 256 * 256 * 4 * 4 / 3 + 64);
    }
}
