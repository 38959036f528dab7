//! The scene's GPU structs (`shaders/types.wgsl`): one Rust definition each, checked against the
//! WGSL by `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

pub use irradiant_bvh::{GpuBvhNode, GpuWideBvhNode};

/// Intersection data in object space: v0 and the two edges (Möller–Trumbore needs no more).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuTriangle {
    /// First vertex, in the mesh's object space.
    pub v0: [f32; 3],
    /// Index into the materials buffer.
    pub material: u32,
    /// Second vertex minus the first.
    pub e1: [f32; 3],
    /// bit 0: [`TRIANGLE_ALPHA_TESTED`](super::constants::TRIANGLE_ALPHA_TESTED)
    pub flags: u32,
    /// Third vertex minus the first.
    pub e2: [f32; 3],
    /// Padding to a 16-byte multiple; 0.
    pub _pad: u32,
}
const _: () = assert!(size_of::<GpuTriangle>() == 48);

/// Shading data: vertex normals (zero length: flat shading) and texture coordinates.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuTriangleShading {
    /// Normal at the first vertex, object space.
    pub n0: [f32; 3],
    /// For an emissive triangle, its place among its mesh's emissive triangles: an instance's
    /// `emitter_base` plus this is its entry of the emitters buffer. 0 otherwise.
    pub emitter_ordinal: u32,
    /// Normal at the second vertex.
    pub n1: [f32; 3],
    /// Padding after a vec3; 0.
    pub _pad1: u32,
    /// Normal at the third vertex.
    pub n2: [f32; 3],
    /// Padding after a vec3; 0.
    pub _pad2: u32,
    /// Texture coordinates of the first vertex.
    pub uv0: [f32; 2],
    /// Texture coordinates of the second vertex.
    pub uv1: [f32; 2],
    /// Texture coordinates of the third vertex.
    pub uv2: [f32; 2],
    /// Padding to a 16-byte multiple; 0.
    pub _pad3: [f32; 2],
}
const _: () = assert!(size_of::<GpuTriangleShading>() == 80);

/// Rows of the 3×4 world-to-object, object-to-world and last frame's object-to-world
/// matrices, and the root of the mesh's BVH.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuInstance {
    /// Row 0 of the world-to-object matrix.
    pub world_to_object0: [f32; 4],
    /// Row 1 of the world-to-object matrix.
    pub world_to_object1: [f32; 4],
    /// Row 2 of the world-to-object matrix.
    pub world_to_object2: [f32; 4],
    /// Row 0 of the object-to-world matrix.
    pub object_to_world0: [f32; 4],
    /// Row 1 of the object-to-world matrix.
    pub object_to_world1: [f32; 4],
    /// Row 2 of the object-to-world matrix.
    pub object_to_world2: [f32; 4],
    /// Row 0 of last frame's object-to-world matrix (motion vectors).
    pub previous_object_to_world0: [f32; 4],
    /// Row 1 of last frame's object-to-world matrix.
    pub previous_object_to_world1: [f32; 4],
    /// Row 2 of last frame's object-to-world matrix.
    pub previous_object_to_world2: [f32; 4],
    /// Root node of the mesh's bottom-level tree, in the binary or the wide node buffer as
    /// [`BlasLayout`](super::BlasLayout) picks.
    pub blas_root: u32,
    /// Its first entry of the emitters buffer (its mesh's emissive triangles follow in order).
    pub emitter_base: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuInstance>() == 160);

/// A material: metallic-roughness, as glTF.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuMaterial {
    /// Linear base colour; alpha is coverage for alpha-masked materials.
    pub base_color: [f32; 4],
    /// Emitted radiance.
    pub emission: [f32; 3],
    /// Texture array layer, or -1.
    pub texture: i32,
    /// 0: dielectric, 1: metal.
    pub metallic: f32,
    /// Perceptual roughness (GGX alpha = roughness²).
    pub roughness: f32,
    /// Scale of the dielectric specular lobe (F0 = 0.04 × specular).
    pub specular: f32,
    /// Alpha below this is a hole; -1 for opaque materials.
    pub alpha_cutoff: f32,
}
const _: () = assert!(size_of::<GpuMaterial>() == 48);

/// A punctual light: point, spot or directional.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuLight {
    /// World position (unused by directional lights).
    pub position: [f32; 3],
    /// [`LIGHT_POINT`](super::constants::LIGHT_POINT),
    /// [`LIGHT_SPOT`](super::constants::LIGHT_SPOT) or
    /// [`LIGHT_DIRECTIONAL`](super::constants::LIGHT_DIRECTIONAL)
    pub kind: u32,
    /// The direction light travels.
    pub direction: [f32; 3],
    /// Spot lights: cosine of the cone's inner angle (full power inside); 1 otherwise.
    pub cos_inner: f32,
    /// Colour × intensity, zero when off.
    pub power: [f32; 3],
    /// Spot lights: cosine of the cone's outer angle (no light outside); 1 otherwise.
    pub cos_outer: f32,
}
const _: () = assert!(size_of::<GpuLight>() == 48);

/// One emissive triangle of one instance for next-event estimation, picked through the emitter
/// grid (`scene::emitter_grid`): its cluster by the cell, then itself ∝ luminance × world area.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuEmitter {
    /// Its first vertex in world space (at the last uploaded pose).
    pub v0: [f32; 3],
    /// Its triangle slot.
    pub triangle: u32,
    /// Its first edge (v1 − v0) in world space.
    pub e1: [f32; 3],
    /// Its instance, in instance-buffer (top-level leaf) order.
    pub instance: u32,
    /// Its second edge (v2 − v0) in world space.
    pub e2: [f32; 3],
    /// Its cluster of the emitter grid.
    pub cluster: u32,
    /// Its front face's world normal (unit length).
    pub normal: [f32; 3],
    /// Padding after a vec3; 0.
    pub _pad: u32,
    /// Emitted radiance (front face).
    pub radiance: [f32; 3],
    /// The area pdf of a point on it given its cluster: luminance(radiance) / the cluster's
    /// Σ luminance × area (× the cell's probability of the cluster: the pdf at a point).
    pub pdf_area: f32,
}
const _: () = assert!(size_of::<GpuEmitter>() == 80);

/// Scene-wide figures, uploaded with each pose (the `scene_info` uniform).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuSceneInfo {
    /// Radiance of rays that leave the scene.
    pub sky: [f32; 3],
    /// Entries of the lights buffer.
    pub light_count: u32,
    /// Entries of the emitters buffer.
    pub emitter_count: u32,
    /// Clusters of the emitter grid: texels of a cell's row.
    pub grid_clusters: u32,
    /// Root node of the top-level tree, in the binary node buffer after every mesh's nodes.
    pub tlas_root: u32,
    /// Entries of the instances buffer.
    pub instance_count: u32,
    /// The emitter grid's low corner.
    pub grid_min: [f32; 3],
    /// Texels a row of the emitter grid's texture.
    pub grid_width: u32,
    /// The emitter grid's cells per unit of length along each axis.
    pub grid_inverse_cell: [f32; 3],
    /// The emitter grid texture's first row of cluster members (the cell count).
    pub grid_member_row: u32,
    /// The emitter grid's cells along each axis.
    pub grid_dims: [u32; 3],
    /// Padding to a 16-byte multiple; 0.
    pub _pad: u32,
}
const _: () = assert!(size_of::<GpuSceneInfo>() == 80);

/// A pinhole camera as an orthonormal frame; image y goes down.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuCamera {
    /// World position of the eye.
    pub position: [f32; 3],
    /// tan of half the vertical field of view.
    pub tan_half_fov_y: f32,
    /// Unit vector to the image's right.
    pub right: [f32; 3],
    /// Width over height.
    pub aspect: f32,
    /// Unit vector up the image.
    pub up: [f32; 3],
    /// Padding after a vec3; 0.
    pub _pad0: f32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// Padding after a vec3; 0.
    pub _pad1: f32,
}
const _: () = assert!(size_of::<GpuCamera>() == 64);

impl GpuCamera {
    /// The camera's frame for a `width`×`height` image.
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

    /// The primary ray's direction through a point of a `width`×`height` image (in pixels,
    /// y down): the CPU twin of `camera_ray_dir` in shaders/camera.wgsl.
    pub fn ray_dir(&self, pixel: glam::Vec2, width: u32, height: u32) -> glam::Vec3 {
        let ndc = glam::Vec2::new(
            pixel.x / width as f32 * 2.0 - 1.0,
            1.0 - pixel.y / height as f32 * 2.0,
        );
        (glam::Vec3::from(self.forward)
            + glam::Vec3::from(self.right) * (ndc.x * self.tan_half_fov_y * self.aspect)
            + glam::Vec3::from(self.up) * (ndc.y * self.tan_half_fov_y))
            .normalize()
    }

    /// The pixel (y down) a world point is seen at, and its distance along the view; None
    /// behind the camera: the inverse of [`GpuCamera::ray_dir`].
    pub fn project(&self, point: glam::Vec3, width: u32, height: u32) -> Option<(glam::Vec2, f32)> {
        let v = point - glam::Vec3::from(self.position);
        let depth = v.dot(glam::Vec3::from(self.forward));
        if depth <= 0.0 {
            return None;
        }
        let ndc = glam::Vec2::new(
            v.dot(glam::Vec3::from(self.right)) / (depth * self.tan_half_fov_y * self.aspect),
            v.dot(glam::Vec3::from(self.up)) / (depth * self.tan_half_fov_y),
        );
        let pixel = glam::Vec2::new(
            (ndc.x + 1.0) * 0.5 * width as f32,
            (1.0 - ndc.y) * 0.5 * height as f32,
        );
        Some((pixel, depth))
    }
}
