//! Screen-space indirect illumination's textures: the voxel grid and the per-level light at the
//! start level's resolution (with a mip a level), and the full-resolution light and its
//! filtered value with the geometry it was filtered on, this frame's and last frame's.

use irradiant_gpu::{Allocation, GpuContext, wgpu};

use super::settings::SsilSettings;
use super::types::GpuSsilParams;
use crate::RenderError;

const SETTING: &str = "the image size (--size), technique.start or technique.levels";

/// A texture and its views: the whole chain, and each mip alone (a pass writes one mip while it
/// reads another).
pub struct LevelTexture {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub levels: Vec<wgpu::TextureView>,
}

impl LevelTexture {
    fn new(
        device: &wgpu::Device,
        label: &str,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        mips: u32,
    ) -> Self {
        let texture = irradiant_gpu::texture_2d(
            device,
            label,
            size,
            format,
            mips,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
        );
        let levels = (0..mips)
            .map(|level| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    base_mip_level: level,
                    mip_level_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        Self {
            view: texture.create_view(&Default::default()),
            texture,
            levels,
        }
    }
}

/// (name, format, bytes a texel, at the start level with a mip a level?)
const TEXTURES: &[(&str, wgpu::TextureFormat, u64, bool)] = &[
    ("ssil/voxels", wgpu::TextureFormat::Rgba32Uint, 16, true),
    ("ssil/gather", wgpu::TextureFormat::Rgba16Float, 8, true),
    (
        "ssil/gather_specular",
        wgpu::TextureFormat::Rgba16Float,
        8,
        true,
    ),
    ("ssil/combined", wgpu::TextureFormat::Rgba16Float, 8, true),
    (
        "ssil/combined_specular",
        wgpu::TextureFormat::Rgba16Float,
        8,
        true,
    ),
    ("ssil/full", wgpu::TextureFormat::Rgba16Float, 8, false),
    (
        "ssil/full_specular",
        wgpu::TextureFormat::Rgba16Float,
        8,
        false,
    ),
    // Two of each: this frame's filtered light is next frame's history (ping-pong).
    (
        "ssil/filtered_0",
        wgpu::TextureFormat::Rgba16Float,
        8,
        false,
    ),
    (
        "ssil/filtered_1",
        wgpu::TextureFormat::Rgba16Float,
        8,
        false,
    ),
    (
        "ssil/filtered_specular_0",
        wgpu::TextureFormat::Rgba16Float,
        8,
        false,
    ),
    (
        "ssil/filtered_specular_1",
        wgpu::TextureFormat::Rgba16Float,
        8,
        false,
    ),
    // normal and view depth the light was filtered on
    (
        "ssil/filtered_geometry_0",
        wgpu::TextureFormat::Rgba32Float,
        16,
        false,
    ),
    (
        "ssil/filtered_geometry_1",
        wgpu::TextureFormat::Rgba32Float,
        16,
        false,
    ),
];

/// The covered directions beside the gathers', the combined, the full and the filtered light
/// (covered_directions.wgsl), with ssil+ddgi's bent fill only: (name, at the start level with a
/// mip a level?), in COVERED_FORMAT.
const COVERED: &[(&str, bool)] = &[
    ("ssil/gather_covered", true),
    ("ssil/combined_covered", true),
    ("ssil/full_covered", false),
    ("ssil/filtered_covered_0", false),
    ("ssil/filtered_covered_1", false),
];
const COVERED_FORMAT: (wgpu::TextureFormat, u64) = (wgpu::TextureFormat::Rgba16Float, 8);

/// The light the gathers read when it is not the frame's pyramid: more than one bounce, or
/// the probes' light in it (ssil+ddgi).
const BOUNCE: (&str, wgpu::TextureFormat, u64) =
    ("ssil/bounce", wgpu::TextureFormat::Rgba16Float, 8);

fn start_size(settings: &SsilSettings, (width, height): (u32, u32)) -> (u32, u32) {
    let s = settings.start.level();
    ((width >> s).max(1), (height >> s).max(1))
}

/// Whether the gathers read the bounce chain.
fn needs_bounce_chain(settings: &SsilSettings, hybrid: bool) -> bool {
    settings.bounces > 1 || hybrid
}

/// Every allocation, from the settings and the image size alone; `covered`: with the covered
/// directions (ssil+ddgi's bent fill).
pub fn plan(
    settings: &SsilSettings,
    size: (u32, u32),
    hybrid: bool,
    covered: bool,
) -> Vec<Allocation> {
    let start = start_size(settings, size);
    let covered_textures = COVERED
        .iter()
        .filter(|_| covered)
        .map(|&(name, chain)| (name, COVERED_FORMAT.1, chain));
    let mut plan: Vec<Allocation> = TEXTURES
        .iter()
        .map(|&(name, _, texel, chain)| (name, texel, chain))
        .chain(covered_textures)
        .map(|(name, texel, chain)| {
            if chain {
                Allocation::texture(name, start, texel, settings.levels, SETTING)
            } else {
                Allocation::texture(name, size, texel, 1, SETTING)
            }
        })
        .collect();
    if needs_bounce_chain(settings, hybrid) {
        plan.push(Allocation::texture(
            BOUNCE.0,
            start,
            BOUNCE.2,
            settings.levels,
            SETTING,
        ));
    }
    plan
}

/// The covered directions beside the gathers', the combined, the full and the filtered light.
pub struct CoveredTextures {
    pub gather: LevelTexture,
    pub combined: LevelTexture,
    pub full: LevelTexture,
    /// Frame n writes set n mod 2 and reads the other, as the filtered light.
    pub filtered: [LevelTexture; 2],
}

pub struct SsilResources {
    pub params: wgpu::Buffer,
    /// Open and total voxelization rays of the last frame (two u32).
    pub counters: wgpu::Buffer,
    pub voxels: LevelTexture,
    pub gather: LevelTexture,
    pub gather_specular: LevelTexture,
    pub combined: LevelTexture,
    pub combined_specular: LevelTexture,
    pub full: LevelTexture,
    pub full_specular: LevelTexture,
    /// The filtered light, its glossy part and the geometry it was filtered on, twice: frame
    /// n writes set n mod 2 and reads the other as its history.
    pub filtered: [LevelTexture; 2],
    pub filtered_specular: [LevelTexture; 2],
    pub filtered_geometry: [LevelTexture; 2],
    /// The covered directions, with ssil+ddgi's bent fill.
    pub covered: Option<CoveredTextures>,
    pub bounce: Option<LevelTexture>,
}

impl SsilResources {
    pub fn new(
        ctx: &GpuContext,
        settings: &SsilSettings,
        size: (u32, u32),
        hybrid: bool,
        covered: bool,
    ) -> Result<Self, RenderError> {
        ctx.check_allocations(&plan(settings, size, hybrid, covered))?;
        let device = &ctx.device;
        let start = start_size(settings, size);
        let make = |name: &str| {
            let &(_, format, _, chain) = TEXTURES
                .iter()
                .find(|t| t.0 == name)
                .expect("a planned texture");
            if chain {
                LevelTexture::new(device, name, start, format, settings.levels)
            } else {
                LevelTexture::new(device, name, size, format, 1)
            }
        };
        Ok(Self {
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ssil/params"),
                size: size_of::<GpuSsilParams>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            counters: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ssil/counters"),
                size: 16,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            voxels: make("ssil/voxels"),
            gather: make("ssil/gather"),
            gather_specular: make("ssil/gather_specular"),
            combined: make("ssil/combined"),
            combined_specular: make("ssil/combined_specular"),
            full: make("ssil/full"),
            full_specular: make("ssil/full_specular"),
            filtered: [make("ssil/filtered_0"), make("ssil/filtered_1")],
            filtered_specular: [
                make("ssil/filtered_specular_0"),
                make("ssil/filtered_specular_1"),
            ],
            filtered_geometry: [
                make("ssil/filtered_geometry_0"),
                make("ssil/filtered_geometry_1"),
            ],
            covered: covered.then(|| {
                let make_covered = |name: &str| {
                    let &(_, chain) = COVERED
                        .iter()
                        .find(|t| t.0 == name)
                        .expect("a planned texture");
                    let (size, mips) = if chain {
                        (start, settings.levels)
                    } else {
                        (size, 1)
                    };
                    LevelTexture::new(device, name, size, COVERED_FORMAT.0, mips)
                };
                CoveredTextures {
                    gather: make_covered("ssil/gather_covered"),
                    combined: make_covered("ssil/combined_covered"),
                    full: make_covered("ssil/full_covered"),
                    filtered: [
                        make_covered("ssil/filtered_covered_0"),
                        make_covered("ssil/filtered_covered_1"),
                    ],
                }
            }),
            bounce: needs_bounce_chain(settings, hybrid)
                .then(|| LevelTexture::new(device, BOUNCE.0, start, BOUNCE.1, settings.levels)),
        })
    }
}
