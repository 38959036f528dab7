//! The in-memory scene: what every loader produces and every renderer consumes.
//!
//! Units are linear RGB radiometry with no photometric conversion: a point light's
//! `intensity` is radiant intensity (irradiance at 1 unit is `intensity`), a directional
//! light's is the irradiance on a surface facing it, emission is radiance.

use glam::{Mat4, Vec2, Vec3, Vec4};

/// A triangle mesh in object space; one bottom-level BVH on the GPU.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Name, for messages and tools.
    pub name: String,
    /// Vertex positions, in object space.
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
    /// Triangles in the mesh: a third of its indices.
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

    /// The object-space positions of triangle `t`'s vertices. Panics if `t` is out of range.
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
    /// Distinct edges.
    pub total: usize,
    /// Edges that bound only one triangle.
    pub open: usize,
}

/// A placed copy of a mesh: the unit of the top-level BVH, and what animation moves.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Name, by which animations and manifests address the instance.
    pub name: String,
    /// Index into [`Scene::meshes`].
    pub mesh: u32,
    /// Object-to-world transform.
    pub transform: Mat4,
}

/// How a material's alpha is used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlphaMode {
    /// Alpha is ignored: every surface is solid.
    Opaque,
    /// Texels whose alpha is below the cutoff are holes: rays pass through them.
    Mask {
        /// Alpha below which a texel is a hole, 0 … 1 (glTF `alphaCutoff`, 0.5 by default).
        cutoff: f32,
    },
}

/// glTF-style metallic-roughness material.
#[derive(Clone, Debug)]
pub struct Material {
    /// Name in the mesh file (MTL `newmtl`, glTF material name), as manifests address it.
    pub name: String,
    /// Linear base colour; alpha is coverage for [`AlphaMode::Mask`].
    pub base_color: Vec4,
    /// Index into [`Scene::textures`]; multiplies `base_color`.
    pub base_color_texture: Option<u32>,
    /// Emitted radiance (glTF emissive factor × KHR_materials_emissive_strength, or MTL `Ke`).
    pub emission: Vec3,
    /// 0 (dielectric) … 1 (metal: the base colour tints the reflection).
    pub metallic: f32,
    /// Perceptual roughness (GGX alpha = roughness²).
    pub roughness: f32,
    /// Scale of the dielectric specular lobe (F0 = 0.04 × specular). OBJ materials with
    /// `Ks 0 0 0` are pure Lambertian (0); glTF materials use 1.
    pub specular: f32,
    /// Whether alpha cuts holes (see [`AlphaMode`]).
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
    /// Name, for messages.
    pub name: String,
    /// Width, in texels.
    pub width: u32,
    /// Height, in texels.
    pub height: u32,
    /// `width` × `height` texels of 4 bytes, rows top to bottom.
    pub rgba8: Vec<u8>,
}

/// The shape of a light's emission.
#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    /// Light from `position` in every direction.
    Point,
    /// Cone angles in radians, measured from the axis.
    Spot {
        /// Angle within which the light is at full strength.
        inner_angle: f32,
        /// Angle past which there is no light; between the two it falls off smoothly.
        outer_angle: f32,
    },
    /// Parallel light along `direction`, as from the sun; `position` is unused.
    Directional,
}

/// A punctual light: point, spot or directional.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Name, by which animations address the light.
    pub name: String,
    /// Point, spot or directional, with a spot light's cone.
    pub kind: LightKind,
    /// Position in world space (point and spot lights).
    pub position: Vec3,
    /// The direction light travels (for spot and directional lights).
    pub direction: Vec3,
    /// Linear RGB colour, scaled by `intensity`.
    pub color: Vec3,
    /// Radiant intensity (point, spot) or irradiance (directional) of a white light.
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
    /// Eye position, in world space.
    pub position: Vec3,
    /// Point looked at, in world space.
    pub target: Vec3,
    /// Up direction, in world space (y up unless a file says otherwise).
    pub up: Vec3,
    /// Vertical field of view, in degrees.
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
    /// Name, for messages and tools.
    pub name: String,
    /// Lowest corner, in world space.
    pub min: Vec3,
    /// Highest corner, in world space.
    pub max: Vec3,
    /// Probes per axis (any count ≥ 2, not only powers of two).
    pub counts: [u32; 3],
    /// What the volume follows, in whole cells, keeping its size (a tracking window); None:
    /// it stays where `min` and `max` put it.
    pub follow: Option<Follow>,
}

/// What a probe volume follows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Follow {
    /// The camera: the volume stays centred on it.
    Camera,
    /// The instance of this name: the volume stays centred on its origin (a vehicle, a player).
    Instance(String),
}

impl Follow {
    /// The manifest's and the settings' word for it: `camera`, or an instance's name; None for
    /// an empty word (the volume stays).
    pub fn parse(word: &str) -> Option<Self> {
        match word {
            "" => None,
            "camera" => Some(Self::Camera),
            name => Some(Self::Instance(name.to_owned())),
        }
    }
}

impl ProbeVolumeDesc {
    /// A volume over `min`..`max` with `counts` probes per axis, staying where it is put.
    pub fn new(name: &str, min: Vec3, max: Vec3, counts: [u32; 3]) -> Self {
        Self {
            name: name.into(),
            min,
            max,
            counts,
            follow: None,
        }
    }
}

/// A named box of the scene, measured by the comparison lab (e.g. the dark room).
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// Name, as the comparison lab reports and selects it.
    pub name: String,
    /// Lowest corner, in world space.
    pub min: Vec3,
    /// Highest corner, in world space.
    pub max: Vec3,
}

impl Region {
    /// A region over `min`..`max`.
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
    /// The light of this name.
    Light(String),
    /// The instance of this name.
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

/// Keyframed tracks and what they drive.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// What the tracks drive.
    pub target: AnimationTarget,
    /// The keyframes.
    pub tracks: Tracks,
}

/// A complete scene, validated: every index is in range and every number finite.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Name: a built-in's, the manifest's `name`, or the mesh file's stem.
    pub name: String,
    /// The meshes, which instances place.
    pub meshes: Vec<Mesh>,
    /// Placed meshes: what is rendered.
    pub instances: Vec<Instance>,
    /// Materials, indexed by [`Mesh::triangle_materials`].
    pub materials: Vec<Material>,
    /// Textures, indexed by [`Material::base_color_texture`].
    pub textures: Vec<Texture>,
    /// Lights at rest; [`Scene::pose_at`] gives them at a time.
    pub lights: Vec<Light>,
    /// The view at rest; [`Scene::pose_at`] gives it at a time.
    pub camera: Camera,
    /// Radiance of rays that leave the scene.
    pub sky: Vec3,
    /// Probe volumes for the probe-based techniques; empty leaves the choice to the
    /// renderer.
    pub probe_volumes: Vec<ProbeVolumeDesc>,
    /// Named regions that the comparison lab measures.
    pub regions: Vec<Region>,
    /// Keyframed animations; none for a still scene.
    pub animations: Vec<Animation>,
    /// Renderer settings a manifest carries (its `[frame]` and `[technique]` tables), passed
    /// through unread: the renderer owns their meaning.
    pub settings: toml::Table,
}

impl Scene {
    /// Seconds until the last key of any animation: how long the scene plays (0 when still).
    pub fn animation_length(&self) -> f32 {
        (self.animations.iter())
            .flat_map(|a| {
                let t = &a.tracks;
                (t.translation.iter().map(|k| k.0))
                    .chain(t.intensity_scale.iter().map(|k| k.0))
                    .chain(t.rotation_y_degrees.iter().map(|k| k.0))
            })
            .fold(0.0, f32::max)
    }

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
            // The shape too: the same bytes as 2×1 and 1×2 texels are other textures.
            (t.width, t.height).hash(h);
            t.rgba8.hash(h);
        }
        format!("{:?}{:?}{:?}", self.instances, self.materials, self.sky).hash(h);
    }

    /// Triangles of every instance together: a mesh counts once per instance.
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

    /// The region called `name`, if any.
    pub fn region(&self, name: &str) -> Option<&Region> {
        self.regions.iter().find(|r| r.name == name)
    }

    /// Whether anything changes over time (drives accumulation resets and re-renders).
    pub fn is_animated(&self) -> bool {
        !self.animations.is_empty()
    }
}
