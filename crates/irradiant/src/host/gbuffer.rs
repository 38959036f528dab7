//! A host's G-buffer as Irradiant reads it: which texture holds which channel, in which
//! convention, each checked (size, format, usage) before wgpu sees it, so that a wrong texture
//! is an error naming the channel and the fix, never a validation panic.

use irradiant_gpu::{ResourceTable, wgpu};

use super::constants::*;
use crate::RenderError;

/// How the host's depth texture measures depth. The projection must be Irradiant's camera's:
/// symmetric, with the camera's vertical field of view and the image's aspect.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthConvention {
    /// The distance along the ray from the eye through the pixel centre; negative for the sky
    /// (Irradiant's own).
    RayDistance,
    /// Positive view-space z: the distance along the view direction; 0 or less for the sky.
    ViewZ,
    /// A hardware depth buffer of a perspective projection: 0 at `near`, 1 at `far` (the sky).
    Hardware {
        /// The near plane's distance.
        near: f32,
        /// The far plane's distance.
        far: f32,
    },
    /// Reversed: 1 at `near`, 0 at `far` (the sky). The common choice for precision.
    HardwareReversed {
        /// The near plane's distance.
        near: f32,
        /// The far plane's distance.
        far: f32,
    },
    /// Reversed with the far plane at infinity: depth = near ÷ view z, 0 for the sky.
    HardwareReversedInfinite {
        /// The near plane's distance.
        near: f32,
    },
}

/// How the host's normal texture holds the shading normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalEncoding {
    /// World space, xyz in −1…1 (float or snorm formats).
    WorldSigned,
    /// World space as (n + 1) ÷ 2 (unorm formats).
    WorldUnorm,
    /// View space (x right, y up, z towards the viewer), xyz in −1…1.
    ViewSigned,
    /// View space as (n + 1) ÷ 2.
    ViewUnorm,
    /// World space, octahedral in xy (Irradiant's own).
    Octahedral,
}

/// How the host's motion texture holds where each surface was last frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotionConvention {
    /// Previous position minus current, in pixels (Irradiant's own).
    PixelsToPrevious,
    /// Previous minus current, in UV (0…1 across the image, y down).
    UvToPrevious,
    /// Current minus previous, in UV (y down).
    UvFromPrevious,
}

/// Which channels (0 r … 3 a) of the material texture hold what; None: not in it (roughness 1,
/// metallic 0, specular scale 1). glTF's metallic-roughness texture is `GLTF`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialChannels {
    /// Perceptual roughness, 0…1.
    pub roughness: Option<u8>,
    /// Metalness, 0…1.
    pub metallic: Option<u8>,
    /// Scale of the dielectric specular lobe (F0 = 0.04 × it).
    pub specular: Option<u8>,
}

impl MaterialChannels {
    /// glTF's metallicRoughness texture: roughness in green, metallic in blue.
    pub const GLTF: Self = Self {
        roughness: Some(1),
        metallic: Some(2),
        specular: None,
    };
}

/// The host's G-buffer of one frame: each a texture of the frame's size with TEXTURE_BINDING
/// usage, readable as float (a depth texture as Depth32Float).
#[derive(Clone, Copy, Debug)]
pub struct HostGBuffer<'a> {
    /// Depth, in `depth_convention`: Depth32Float, or the red channel of a float format.
    pub depth: &'a wgpu::Texture,
    /// How `depth` measures depth.
    pub depth_convention: DepthConvention,
    /// The shading normal, in `normal_encoding`.
    pub normal: &'a wgpu::Texture,
    /// How `normal` holds it.
    pub normal_encoding: NormalEncoding,
    /// Base colour (albedo) in rgb, linear (an sRGB format is decoded as it is read).
    pub base_colour: &'a wgpu::Texture,
    /// Roughness, metalness and specular scale, in the channels `material_channels` names.
    pub material: Option<&'a wgpu::Texture>,
    /// Where `material` holds what.
    pub material_channels: MaterialChannels,
    /// Emitted radiance in rgb, linear.
    pub emission: Option<&'a wgpu::Texture>,
    /// Motion in xy, in the convention given; without it the scene is taken as still.
    pub motion: Option<(&'a wgpu::Texture, MotionConvention)>,
}

/// host/import's uniforms (WGSL `GpuHostImport`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuHostImport {
    /// DEPTH_*.
    pub depth_convention: u32,
    /// NORMAL_*.
    pub normal_encoding: u32,
    /// MOTION_*.
    pub motion_convention: u32,
    /// 1 with a material texture.
    pub has_material: u32,
    /// Channels of roughness, metallic and specular (CHANNEL_NONE: none).
    pub roughness_channel: u32,
    /// See `roughness_channel`.
    pub metallic_channel: u32,
    /// See `roughness_channel`.
    pub specular_channel: u32,
    /// 1 with an emission texture.
    pub has_emission: u32,
    /// The hardware depth's near plane.
    pub near: f32,
    /// The hardware depth's far plane.
    pub far: f32,
    /// Padding; 0.
    pub _pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuHostImport>() == 48);

impl HostGBuffer<'_> {
    /// Checks every texture against the frame's `size` and the conventions' numbers; the error
    /// names the channel, the problem and the fix.
    pub fn check(&self, size: (u32, u32)) -> Result<(), RenderError> {
        let mut channels = vec![
            ("depth", self.depth),
            ("normal", self.normal),
            ("base_colour", self.base_colour),
        ];
        channels.extend(self.material.map(|t| ("material", t)));
        channels.extend(self.emission.map(|t| ("emission", t)));
        channels.extend(self.motion.map(|(t, _)| ("motion", t)));
        for (name, texture) in channels {
            check_texture(name, texture, size, name == "depth")?;
        }
        let planes = match self.depth_convention {
            DepthConvention::Hardware { near, far }
            | DepthConvention::HardwareReversed { near, far } => Some((near, far)),
            DepthConvention::HardwareReversedInfinite { near } => Some((near, f32::INFINITY)),
            _ => None,
        };
        if let Some((near, far)) = planes
            && !(near.is_finite() && near > 0.0 && far > near)
        {
            return Err(host_error(format!(
                "gbuffer.depth_convention: near = {near}, far = {far}: give a near plane above 0 and a far plane beyond it, as the projection that wrote the depth has"
            )));
        }
        for (name, channel) in [
            ("roughness", self.material_channels.roughness),
            ("metallic", self.material_channels.metallic),
            ("specular", self.material_channels.specular),
        ] {
            if channel.is_some_and(|c| c > 3) {
                return Err(host_error(format!(
                    "gbuffer.material_channels.{name} = {}: name a channel 0 (r) to 3 (a), or None",
                    channel.unwrap_or(0)
                )));
            }
        }
        Ok(())
    }

    /// host/import's uniforms for these conventions.
    pub fn params(&self) -> GpuHostImport {
        let (depth_convention, near, far) = match self.depth_convention {
            DepthConvention::RayDistance => (DEPTH_RAY_DISTANCE, 0.0, 0.0),
            DepthConvention::ViewZ => (DEPTH_VIEW_Z, 0.0, 0.0),
            DepthConvention::Hardware { near, far } => (DEPTH_HARDWARE, near, far),
            DepthConvention::HardwareReversed { near, far } => (DEPTH_HARDWARE_REVERSED, near, far),
            DepthConvention::HardwareReversedInfinite { near } => {
                (DEPTH_HARDWARE_REVERSED_INFINITE, near, 0.0)
            }
        };
        let channel = |c: Option<u8>| c.map_or(CHANNEL_NONE, u32::from);
        GpuHostImport {
            depth_convention,
            normal_encoding: match self.normal_encoding {
                NormalEncoding::WorldSigned => NORMAL_WORLD_SIGNED,
                NormalEncoding::WorldUnorm => NORMAL_WORLD_UNORM,
                NormalEncoding::ViewSigned => NORMAL_VIEW_SIGNED,
                NormalEncoding::ViewUnorm => NORMAL_VIEW_UNORM,
                NormalEncoding::Octahedral => NORMAL_OCTAHEDRAL,
            },
            motion_convention: match self.motion {
                None => MOTION_NONE,
                Some((_, MotionConvention::PixelsToPrevious)) => MOTION_PIXELS_TO_PREVIOUS,
                Some((_, MotionConvention::UvToPrevious)) => MOTION_UV_TO_PREVIOUS,
                Some((_, MotionConvention::UvFromPrevious)) => MOTION_UV_FROM_PREVIOUS,
            },
            has_material: self.material.is_some() as u32,
            roughness_channel: channel(self.material_channels.roughness),
            metallic_channel: channel(self.material_channels.metallic),
            specular_channel: channel(self.material_channels.specular),
            has_emission: self.emission.is_some() as u32,
            near,
            far,
            _pad: [0; 2],
        }
    }

    /// The textures host/import binds, in [`HostGBuffer::views`]' order: an absent channel's
    /// place is the base colour's.
    pub fn textures(&self) -> [wgpu::Texture; 6] {
        let or_base = |t: Option<&wgpu::Texture>| t.unwrap_or(self.base_colour).clone();
        [
            self.depth.clone(),
            self.normal.clone(),
            self.base_colour.clone(),
            or_base(self.material),
            or_base(self.emission),
            or_base(self.motion.map(|m| m.0)),
        ]
    }

    /// The views host/import binds: each channel's, an absent one standing in as the base
    /// colour (its flag keeps it unread).
    pub fn views(&self) -> [(&'static str, wgpu::TextureView); 6] {
        let view = |t: &wgpu::Texture| {
            t.create_view(&wgpu::TextureViewDescriptor {
                aspect: if t.format().is_depth_stencil_format() {
                    wgpu::TextureAspect::DepthOnly
                } else {
                    wgpu::TextureAspect::All
                },
                ..Default::default()
            })
        };
        let or_base = |t: Option<&wgpu::Texture>| view(t.unwrap_or(self.base_colour));
        [
            ("host_depth", view(self.depth)),
            ("host_normal", view(self.normal)),
            ("host_base_colour", view(self.base_colour)),
            ("host_material", or_base(self.material)),
            ("host_emission", or_base(self.emission)),
            ("host_motion", or_base(self.motion.map(|m| m.0))),
        ]
    }
}

/// The table host/import binds the host's views and uniforms from.
pub fn import_table<'a>(
    views: &'a [(&'static str, wgpu::TextureView); 6],
    params: &'a wgpu::Buffer,
) -> ResourceTable<'a> {
    views.iter().fold(
        ResourceTable::new().buffer("import_params", params),
        |t, (name, view)| t.texture(*name, view),
    )
}

fn host_error(problem: String) -> RenderError {
    RenderError::Settings(format!("the host's G-buffer: {problem}"))
}

fn check_texture(
    name: &str,
    texture: &wgpu::Texture,
    (width, height): (u32, u32),
    depth: bool,
) -> Result<(), RenderError> {
    let format = texture.format();
    if (texture.width(), texture.height()) != (width, height) {
        return Err(host_error(format!(
            "gbuffer.{name} is {}×{} where the frame is {width}×{height}: hand textures of the frame's size, or resize Irradiant's frame to the host's (HostGi::resize)",
            texture.width(),
            texture.height()
        )));
    }
    if !texture
        .usage()
        .contains(wgpu::TextureUsages::TEXTURE_BINDING)
    {
        return Err(host_error(format!(
            "gbuffer.{name} was created without TEXTURE_BINDING usage: add it where the host creates the texture"
        )));
    }
    if texture.dimension() != wgpu::TextureDimension::D2 || texture.sample_count() != 1 {
        return Err(host_error(format!(
            "gbuffer.{name} must be a 2D texture of one sample (resolve a multisampled G-buffer first)"
        )));
    }
    let readable = if format.is_depth_stencil_format() {
        depth && format == wgpu::TextureFormat::Depth32Float
    } else {
        matches!(
            format.sample_type(None, None),
            Some(wgpu::TextureSampleType::Float { .. })
        )
    };
    if !readable {
        return Err(host_error(format!(
            "gbuffer.{name} has format {format:?}, which Irradiant cannot read as float: use {}",
            if depth {
                "Depth32Float or a float colour format (R32Float)"
            } else {
                "a float, unorm or snorm colour format (Rgba16Float, Rgba8Unorm)"
            }
        )));
    }
    Ok(())
}
