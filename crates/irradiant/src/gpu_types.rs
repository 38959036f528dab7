//! The Rust definitions of the GPU structs of `shaders/types.wgsl` and the passes' parameter
//! blocks. `tests/gpu_structs.rs` checks every one against its WGSL declaration.

use bytemuck::{Pod, Zeroable};
use irradiant_gpu::{Expected, gpu_layout};

pub use irradiant_bvh::{GpuBvhNode, GpuWideBvhNode};

/// Triangle flag: the material is alpha-masked and textured, so hits test the texture.
pub const TRIANGLE_ALPHA_TESTED: u32 = 1;

/// Intersection data in object space: v0 and the two edges (Möller–Trumbore needs no more).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuTriangle {
    pub v0: [f32; 3],
    pub material: u32,
    pub e1: [f32; 3],
    /// bit 0: [`TRIANGLE_ALPHA_TESTED`]
    pub flags: u32,
    pub e2: [f32; 3],
    pub _pad: u32,
}
const _: () = assert!(size_of::<GpuTriangle>() == 48);

/// Shading data: vertex normals (zero length: flat shading) and texture coordinates.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuTriangleShading {
    pub n0: [f32; 3],
    pub _pad0: u32,
    pub n1: [f32; 3],
    pub _pad1: u32,
    pub n2: [f32; 3],
    pub _pad2: u32,
    pub uv0: [f32; 2],
    pub uv1: [f32; 2],
    pub uv2: [f32; 2],
    pub _pad3: [f32; 2],
}
const _: () = assert!(size_of::<GpuTriangleShading>() == 80);

/// Rows of the 3×4 world-to-object, object-to-world and last frame's object-to-world
/// matrices, and the root of the mesh's BVH.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuInstance {
    pub world_to_object0: [f32; 4],
    pub world_to_object1: [f32; 4],
    pub world_to_object2: [f32; 4],
    pub object_to_world0: [f32; 4],
    pub object_to_world1: [f32; 4],
    pub object_to_world2: [f32; 4],
    pub previous_object_to_world0: [f32; 4],
    pub previous_object_to_world1: [f32; 4],
    pub previous_object_to_world2: [f32; 4],
    pub blas_root: u32,
    pub _pad0: u32,
    pub _pad1: u32,
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuInstance>() == 160);

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuMaterial {
    pub base_color: [f32; 4],
    pub emission: [f32; 3],
    /// Texture array layer, or -1.
    pub texture: i32,
    pub metallic: f32,
    pub roughness: f32,
    pub specular: f32,
    /// Alpha below this is a hole; -1 for opaque materials.
    pub alpha_cutoff: f32,
}
const _: () = assert!(size_of::<GpuMaterial>() == 48);

pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_SPOT: u32 = 1;
pub const LIGHT_DIRECTIONAL: u32 = 2;

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuLight {
    pub position: [f32; 3],
    /// [`LIGHT_POINT`], [`LIGHT_SPOT`] or [`LIGHT_DIRECTIONAL`]
    pub kind: u32,
    /// The direction light travels.
    pub direction: [f32; 3],
    pub cos_inner: f32,
    /// Colour × intensity, zero when off.
    pub power: [f32; 3],
    pub cos_outer: f32,
}
const _: () = assert!(size_of::<GpuLight>() == 48);

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuEmitter {
    pub triangle: u32,
    pub instance: u32,
    /// Cumulative selection probability up to and including this emitter.
    pub cdf: f32,
    pub _pad: u32,
}
const _: () = assert!(size_of::<GpuEmitter>() == 16);

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuSceneInfo {
    pub sky: [f32; 3],
    pub light_count: u32,
    pub emitter_count: u32,
    /// Σ luminance(emission) × world area over the emitters.
    pub emissive_power: f32,
    pub tlas_root: u32,
    pub instance_count: u32,
}
const _: () = assert!(size_of::<GpuSceneInfo>() == 32);

/// A pinhole camera as an orthonormal frame; image y goes down.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuCamera {
    pub position: [f32; 3],
    pub tan_half_fov_y: f32,
    pub right: [f32; 3],
    pub aspect: f32,
    pub up: [f32; 3],
    pub _pad0: f32,
    pub forward: [f32; 3],
    pub _pad1: f32,
}
const _: () = assert!(size_of::<GpuCamera>() == 64);

impl GpuCamera {
    pub fn new(camera: &irradiant_scene::Camera, width: u32, height: u32) -> Self {
        let forward = (camera.target - camera.position).normalize();
        let right = forward.cross(camera.up).normalize_or(glam::Vec3::X);
        let up = right.cross(forward);
        Self {
            position: camera.position.into(),
            tan_half_fov_y: (camera.fov_y_degrees.to_radians() * 0.5).tan(),
            right: right.into(),
            aspect: width as f32 / height as f32,
            up: up.into(),
            _pad0: 0.0,
            forward: forward.into(),
            _pad1: 0.0,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuPathTraceParams {
    pub camera: GpuCamera,
    pub width: u32,
    pub height: u32,
    pub sample_offset: u32,
    pub samples: u32,
    pub max_bounces: u32,
    pub seed: u32,
    pub _pad0: u32,
    pub _pad1: u32,
}
const _: () = assert!(size_of::<GpuPathTraceParams>() == 96);

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuTonemapParams {
    pub width: u32,
    pub height: u32,
    pub exposure: f32,
    /// 0: filmic; 1: clamp only.
    pub curve: u32,
}

/// A ray for the ray-cast pass (tests, benchmarks).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuRay {
    pub origin: [f32; 3],
    pub t_max: f32,
    pub dir: [f32; 3],
    pub _pad: u32,
}

/// The closest hit of a [`GpuRay`]: triangle and instance are `u32::MAX` on a miss.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuRayHit {
    pub t: f32,
    pub triangle: u32,
    pub instance: u32,
    pub _pad: u32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuRayCastParams {
    pub ray_count: u32,
    /// 1: stop at the first hit (shadow rays).
    pub any_hit: u32,
    pub _pad0: u32,
    pub _pad1: u32,
}

/// The real-time frame's parameters (`frame/frame_types.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuFrameParams {
    pub camera: GpuCamera,
    pub previous_camera: GpuCamera,
    pub width: u32,
    pub height: u32,
    pub frame_index: u32,
    /// Emitter samples per pixel per frame for direct light from emissive surfaces.
    pub area_light_samples: u32,
    pub seed: u32,
    /// Frames already in the direct-light running mean; 0 restarts it.
    pub accumulated_frames: u32,
    pub _pad0: u32,
    pub _pad1: u32,
}
const _: () = assert!(size_of::<GpuFrameParams>() == 160);

/// One G-buffer pixel. `depth` < 0 where the camera ray left the scene.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGBufferTexel {
    pub position: [f32; 3],
    pub depth: f32,
    pub normal: [f32; 3],
    pub roughness: f32,
    pub geometric_normal: [f32; 3],
    pub metallic: f32,
    pub albedo: [f32; 3],
    pub specular: f32,
    pub emission: [f32; 3],
    pub _pad0: f32,
    /// Previous position minus current, in pixels.
    pub motion: [f32; 2],
    pub _pad1: [f32; 2],
}
const _: () = assert!(size_of::<GpuGBufferTexel>() == 96);

/// A DDGI probe volume's parameters (`ddgi/volume.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuDdgiVolume {
    pub origin: [f32; 3],
    pub probe_count: u32,
    pub spacing: [f32; 3],
    pub rays_per_probe: u32,
    pub counts: [u32; 3],
    pub probes_per_row: u32,
    pub ray_rotation0: [f32; 4],
    pub ray_rotation1: [f32; 4],
    pub ray_rotation2: [f32; 4],
    pub irradiance_texels: u32,
    pub distance_texels: u32,
    pub irradiance_hysteresis: f32,
    pub distance_hysteresis: f32,
    pub max_ray_distance: f32,
    pub self_shadow_bias: f32,
    pub distance_exponent: f32,
    pub irradiance_gamma: f32,
    /// `WEIGHT_*` bits of `ddgi/volume.wgsl`.
    pub weights: u32,
    pub frame: u32,
    pub min_spacing: f32,
    pub convergence_heuristics: u32,
    /// 1 while probes are being relocated (the volume's first frames).
    pub relocating: u32,
    /// 1: probe rays shade every punctual light; 0: one chosen at random.
    pub all_lights: u32,
    /// `STATES_*` of `ddgi/states.wgsl`: off, classifying, classifying for the last time, or
    /// classified (probes sleep and wake).
    pub state_phase: u32,
    /// Boxes in the wake-box buffer (around animated instances).
    pub wake_box_count: u32,
}
const _: () = assert!(size_of::<GpuDdgiVolume>() == 160);

/// A probe ray's closest hit; `t` < 0 for a miss; `bary` is `pack2x16unorm`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuDdgiRayHit {
    pub t: f32,
    pub triangle: u32,
    pub instance: u32,
    pub bary: u32,
}

/// The radiance a probe ray brought back and the distance it travelled (negative: a backface).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiRaySample {
    pub radiance: [f32; 3],
    pub distance: f32,
}

/// A probe ray's shadow ray, queued by ddgi/shade for ddgi/shadow (`DdgiSettings::shadow_queue`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiShadowRay {
    pub origin: [f32; 3],
    /// Index of the probe ray's [`GpuDdgiRaySample`].
    pub sample: u32,
    /// The light's f · L · cos if nothing blocks it.
    pub contribution: [f32; 3],
    /// Index into the scene's lights.
    pub light: u32,
}
const _: () = assert!(size_of::<GpuDdgiShadowRay>() == 32);

/// One ray's weight in one texel's blend (ddgi/blend_weights.wgsl); a texel's header entry
/// holds its entry count in `ray` and their weight sum in `weight`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiBlendWeight {
    pub ray: u32,
    pub weight: f32,
}

/// Every GPU struct with its expected layout, for the WGSL check.
pub fn all_layouts() -> Vec<Expected> {
    vec![
        gpu_layout!(GpuBvhNode {
            a_min,
            a_first,
            a_max,
            a_count,
            b_min,
            b_first,
            b_max,
            b_count
        }),
        gpu_layout!(GpuWideBvhNode {
            origin,
            exponents_imask,
            child_base,
            primitive_base,
            child_meta,
            q_min_x,
            q_max_x,
            q_min_y,
            q_max_y,
            q_min_z,
            q_max_z
        }),
        gpu_layout!(GpuTriangle {
            v0,
            material,
            e1,
            flags,
            e2,
            _pad
        }),
        gpu_layout!(GpuTriangleShading {
            n0,
            _pad0,
            n1,
            _pad1,
            n2,
            _pad2,
            uv0,
            uv1,
            uv2,
            _pad3
        }),
        gpu_layout!(GpuInstance {
            world_to_object0,
            world_to_object1,
            world_to_object2,
            object_to_world0,
            object_to_world1,
            object_to_world2,
            previous_object_to_world0,
            previous_object_to_world1,
            previous_object_to_world2,
            blas_root,
            _pad0,
            _pad1,
            _pad2
        }),
        gpu_layout!(GpuMaterial {
            base_color,
            emission,
            texture,
            metallic,
            roughness,
            specular,
            alpha_cutoff
        }),
        gpu_layout!(GpuLight {
            position,
            kind,
            direction,
            cos_inner,
            power,
            cos_outer
        }),
        gpu_layout!(GpuEmitter {
            triangle,
            instance,
            cdf,
            _pad
        }),
        gpu_layout!(GpuSceneInfo {
            sky,
            light_count,
            emitter_count,
            emissive_power,
            tlas_root,
            instance_count
        }),
        gpu_layout!(GpuCamera {
            position,
            tan_half_fov_y,
            right,
            aspect,
            up,
            _pad0,
            forward,
            _pad1
        }),
        gpu_layout!(GpuPathTraceParams {
            camera,
            width,
            height,
            sample_offset,
            samples,
            max_bounces,
            seed,
            _pad0,
            _pad1
        }),
        gpu_layout!(GpuTonemapParams {
            width,
            height,
            exposure,
            curve
        }),
        gpu_layout!(GpuRay {
            origin,
            t_max,
            dir,
            _pad
        }),
        gpu_layout!(GpuRayHit {
            t,
            triangle,
            instance,
            _pad
        }),
        gpu_layout!(GpuRayCastParams {
            ray_count,
            any_hit,
            _pad0,
            _pad1
        }),
        gpu_layout!(GpuFrameParams {
            camera,
            previous_camera,
            width,
            height,
            frame_index,
            area_light_samples,
            seed,
            accumulated_frames,
            _pad0,
            _pad1
        }),
        gpu_layout!(GpuGBufferTexel {
            position,
            depth,
            normal,
            roughness,
            geometric_normal,
            metallic,
            albedo,
            specular,
            emission,
            _pad0,
            motion,
            _pad1
        }),
        gpu_layout!(GpuDdgiVolume {
            origin,
            probe_count,
            spacing,
            rays_per_probe,
            counts,
            probes_per_row,
            ray_rotation0,
            ray_rotation1,
            ray_rotation2,
            irradiance_texels,
            distance_texels,
            irradiance_hysteresis,
            distance_hysteresis,
            max_ray_distance,
            self_shadow_bias,
            distance_exponent,
            irradiance_gamma,
            weights,
            frame,
            min_spacing,
            convergence_heuristics,
            relocating,
            all_lights,
            state_phase,
            wake_box_count
        }),
        gpu_layout!(GpuDdgiRayHit {
            t,
            triangle,
            instance,
            bary
        }),
        gpu_layout!(GpuDdgiRaySample { radiance, distance }),
        gpu_layout!(GpuDdgiBlendWeight { ray, weight }),
        gpu_layout!(GpuDdgiShadowRay {
            origin,
            sample,
            contribution,
            light
        }),
    ]
}
