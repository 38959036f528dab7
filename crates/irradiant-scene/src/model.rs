//! The in-memory scene: what every loader produces and every renderer consumes.
//!
//! Units are linear RGB radiometry with no photometric conversion: a point light's
//! `intensity` is radiant intensity (irradiance at 1 unit is `intensity`), a directional
//! light's is the irradiance on a surface facing it, emission is radiance.

use glam::{Mat4, Vec2, Vec3, Vec4};

/// A triangle mesh in object space; one bottom-level BVH on the GPU.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub name: String,
    pub positions: Vec<Vec3>,
    /// Per-vertex shading normals; empty means flat shading from the geometric normal.
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates; empty means (0, 0) everywhere.
    pub uvs: Vec<Vec2>,
    /// Three vertex indices per triangle.
    pub indices: Vec<u32>,
    /// One material index (into [`Scene::materials`]) per triangle.
    pub triangle_materials: Vec<u32>,
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Edges that bound only one triangle: where the mesh is not closed (watertight). Vertices
    /// are matched by position, since loaders split a vertex wherever its normal or texture
    /// coordinate changes.
    pub fn open_edges(&self) -> usize {
        self.edges().open
    }

    /// The mesh's distinct edges, and how many of them bound only one triangle.
    pub fn edges(&self) -> EdgeCount {
        let key = |p: Vec3| p.to_array().map(f32::to_bits);
        let mut edges: std::collections::HashMap<([u32; 3], [u32; 3]), u32> =
            std::collections::HashMap::new();
        for t in 0..self.triangle_count() {
            let [a, b, c] = self.triangle(t).map(key);
            for (u, v) in [(a, b), (b, c), (c, a)] {
                *edges
                    .entry(if u < v { (u, v) } else { (v, u) })
                    .or_default() += 1;
            }
        }
        EdgeCount {
            total: edges.len(),
            open: edges.values().filter(|&&n| n == 1).count(),
        }
    }

    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let i = &self.indices[3 * t..3 * t + 3];
        [
            self.positions[i[0] as usize],
            self.positions[i[1] as usize],
            self.positions[i[2] as usize],
        ]
    }
}

/// A mesh's distinct edges (vertices matched by position) and those that bound one triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EdgeCount {
    pub total: usize,
    pub open: usize,
}

/// A placed copy of a mesh: the unit of the top-level BVH, and what animation moves.
#[derive(Clone, Debug)]
pub struct Instance {
    pub name: String,
    pub mesh: u32,
    pub transform: Mat4,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlphaMode {
    Opaque,
    /// Texels whose alpha is below the cutoff are holes: rays pass through them.
    Mask {
        cutoff: f32,
    },
}

/// glTF-style metallic-roughness material.
#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    /// Linear base colour; alpha is coverage for [`AlphaMode::Mask`].
    pub base_color: Vec4,
    /// Index into [`Scene::textures`]; multiplies `base_color`.
    pub base_color_texture: Option<u32>,
    /// Emitted radiance (glTF emissive factor × KHR_materials_emissive_strength, or MTL `Ke`).
    pub emission: Vec3,
    pub metallic: f32,
    /// Perceptual roughness (GGX alpha = roughness²).
    pub roughness: f32,
    /// Scale of the dielectric specular lobe (F0 = 0.04 × specular). OBJ materials with
    /// `Ks 0 0 0` are pure Lambertian (0); glTF materials use 1.
    pub specular: f32,
    pub alpha_mode: AlphaMode,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
            base_color_texture: None,
            emission: Vec3::ZERO,
            metallic: 0.0,
            roughness: 1.0,
            specular: 0.0,
            alpha_mode: AlphaMode::Opaque,
        }
    }
}

/// An sRGB-encoded RGBA8 image, rows top to bottom.
#[derive(Clone, Debug)]
pub struct Texture {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub rgba8: Vec<u8>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    Point,
    /// Cone angles in radians, measured from the axis.
    Spot {
        inner_angle: f32,
        outer_angle: f32,
    },
    Directional,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub name: String,
    pub kind: LightKind,
    pub position: Vec3,
    /// The direction light travels (for spot and directional lights).
    pub direction: Vec3,
    pub color: Vec3,
    pub intensity: f32,
    /// Lights that are off still exist so that animation can switch them on.
    pub enabled: bool,
}

impl Light {
    /// A point light, on.
    pub fn point(name: &str, position: Vec3, color: Vec3, intensity: f32) -> Self {
        Self {
            name: name.into(),
            kind: LightKind::Point,
            position,
            direction: -Vec3::Y,
            color,
            intensity,
            enabled: true,
        }
    }

    /// Radiant intensity (point, spot) or irradiance (directional), zero when off.
    pub fn power(&self) -> Vec3 {
        if self.enabled {
            self.color * self.intensity
        } else {
            Vec3::ZERO
        }
    }
}

/// A pinhole camera. Image y goes down; the vertical field of view is fixed.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub fov_y_degrees: f32,
}

impl Camera {
    /// A camera at `position` looking at `target`, y up.
    pub fn looking_at(position: Vec3, target: Vec3, fov_y_degrees: f32) -> Self {
        Self {
            position,
            target,
            up: Vec3::Y,
            fov_y_degrees,
        }
    }
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: Vec3::new(0.0, 1.0, 3.5),
            target: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            fov_y_degrees: 40.0,
        }
    }
}

/// A box that a probe volume fills with a regular grid of probes.
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeVolumeDesc {
    pub name: String,
    pub min: Vec3,
    pub max: Vec3,
    /// Probes per axis (any count ≥ 2, not only powers of two).
    pub counts: [u32; 3],
}

impl ProbeVolumeDesc {
    pub fn new(name: &str, min: Vec3, max: Vec3, counts: [u32; 3]) -> Self {
        Self {
            name: name.into(),
            min,
            max,
            counts,
        }
    }
}

/// A named box of the scene, measured by the comparison lab (e.g. the dark room).
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub name: String,
    pub min: Vec3,
    pub max: Vec3,
}

impl Region {
    pub fn new(name: &str, min: Vec3, max: Vec3) -> Self {
        Self {
            name: name.into(),
            min,
            max,
        }
    }
}

/// What an animation track drives.
#[derive(Clone, Debug, PartialEq)]
pub enum AnimationTarget {
    Light(String),
    Instance(String),
    /// The scene's camera: translation moves its position and target together (a dolly),
    /// rotation turns its view about its position (a pan).
    Camera,
}

/// Keyframed tracks, linearly interpolated and clamped at both ends.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Tracks {
    /// (time in seconds, offset added to the rest position)
    pub translation: Vec<(f32, Vec3)>,
    /// (time, multiplier of the light's intensity; 0 switches it off)
    pub intensity_scale: Vec<(f32, f32)>,
    /// (time, rotation about the y axis in degrees, about the instance's own origin)
    pub rotation_y_degrees: Vec<(f32, f32)>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    pub target: AnimationTarget,
    pub tracks: Tracks,
}

/// A complete scene, validated: every index is in range and every number finite.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub name: String,
    pub meshes: Vec<Mesh>,
    pub instances: Vec<Instance>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub lights: Vec<Light>,
    pub camera: Camera,
    /// Radiance of rays that leave the scene.
    pub sky: Vec3,
    pub probe_volumes: Vec<ProbeVolumeDesc>,
    pub regions: Vec<Region>,
    pub animations: Vec<Animation>,
    /// Renderer settings a manifest carries (its `[frame]` and `[technique]` tables), passed
    /// through unread: the renderer owns their meaning.
    pub settings: toml::Table,
}

impl Scene {
    /// Feeds everything that shapes what the scene looks like into `h`: geometry, materials,
    /// textures, instances and sky (lights and transforms come with a pose). Caches of
    /// rendered or baked data key on it, so that a changed scene never reads a stale entry.
    pub fn hash_content<H: std::hash::Hasher>(&self, h: &mut H) {
        use std::hash::Hash;
        for mesh in &self.meshes {
            for p in &mesh.positions {
                p.to_array().map(f32::to_bits).hash(h);
            }
            for n in &mesh.normals {
                n.to_array().map(f32::to_bits).hash(h);
            }
            for t in &mesh.uvs {
                t.to_array().map(f32::to_bits).hash(h);
            }
            mesh.indices.hash(h);
            mesh.triangle_materials.hash(h);
        }
        for t in &self.textures {
            t.rgba8.hash(h);
        }
        format!("{:?}{:?}{:?}", self.instances, self.materials, self.sky).hash(h);
    }

    pub fn triangle_count(&self) -> usize {
        self.instances
            .iter()
            .map(|i| self.meshes[i.mesh as usize].triangle_count())
            .sum()
    }

    /// World-space bounds of every instance.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for inst in &self.instances {
            for p in &self.meshes[inst.mesh as usize].positions {
                let w = inst.transform.transform_point3(*p);
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
        (lo, hi)
    }

    pub fn region(&self, name: &str) -> Option<&Region> {
        self.regions.iter().find(|r| r.name == name)
    }

    /// Whether anything changes over time (drives accumulation resets and re-renders).
    pub fn is_animated(&self) -> bool {
        !self.animations.is_empty()
    }
}
