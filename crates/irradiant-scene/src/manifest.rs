//! Scene manifests (TOML): a mesh file placed in the world, plus what OBJ files cannot carry:
//! lights, camera, sky, probe volumes, named regions and keyframed animation.
//!
//! ```toml
//! name = "sponza"
//! sky = [0.5, 0.6, 0.8]
//! [mesh]
//! path = "../../shared/scenes/sponza-dabrovic/sponza.obj"   # relative to this manifest
//! scale = 0.01
//! [camera]
//! position = [8.0, 2.0, 0.0]
//! target = [0.0, 3.0, 0.0]
//! fov_y_degrees = 60.0
//! [[light]]
//! name = "sun"
//! kind = "directional"
//! direction = [0.2, -1.0, 0.1]
//! color = [1.0, 0.95, 0.85]
//! intensity = 8.0
//! [[probe_volume]]
//! min = [-15.0, 0.5, -6.0]
//! max = [15.0, 14.0, 6.0]
//! counts = [16, 8, 8]
//! [[region]]
//! name = "gallery"
//! min = [-15.0, 0.0, -7.0]
//! max = [15.0, 5.0, -4.0]
//! [[animation]]
//! light = "sun"
//! intensity_scale = [[0.0, 1.0], [2.0, 0.0]]   # [time, scale]
//! translation = [[0.0, 0.0, 0.0, 0.0]]         # [time, x, y, z]
//! ```

use std::path::{Path, PathBuf};

use glam::{Mat3, Mat4, UVec3, Vec3};
use serde::{Deserialize, Serialize};

use crate::error::{Result, SceneError};
use crate::model::{
    Animation, AnimationTarget, Camera, Follow, Instance, Light, LightKind, Mesh, ProbeVolumeDesc,
    Region, Scene, Tracks,
};
use crate::place::PlaceDesc;

/// A scene manifest: a mesh file, and the lights, camera and the rest to add to it. Read
/// with [`parse`](Self::parse), then [`apply`](Self::apply) to the loaded mesh file.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Name of the scene; when absent, the mesh file's stem or the built-in's name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The geometry: an .obj, .gltf or .glb file, or a built-in scene name.
    pub mesh: MeshRef,
    /// The view; when absent, the mesh file's, or one framing the whole scene where
    /// `mesh.scale` or `mesh.translation` moved it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraDesc>,
    /// Radiance of rays that leave the scene; black when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky: Option<[f32; 3]>,
    /// Lights added to those the mesh file brings (glTF lights are kept).
    #[serde(default, rename = "light", skip_serializing_if = "Vec::is_empty")]
    pub lights: Vec<LightDesc>,
    /// Probe volumes (`[[probe_volume]]` tables) for the probe-based techniques.
    #[serde(
        default,
        rename = "probe_volume",
        skip_serializing_if = "Vec::is_empty"
    )]
    pub probe_volumes: Vec<ProbeVolumeManifest>,
    /// Named regions (`[[region]]` tables) that the comparison lab measures.
    #[serde(default, rename = "region", skip_serializing_if = "Vec::is_empty")]
    pub regions: Vec<RegionDesc>,
    /// Changes to the mesh file's materials, by name (glossy and mirror variants of a scene).
    #[serde(default, rename = "material", skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<MaterialDesc>,
    /// More meshes placed in the world (`[[place]]` tables): a world made of several files.
    #[serde(default, rename = "place", skip_serializing_if = "Vec::is_empty")]
    pub places: Vec<PlaceDesc>,
    /// Keyframed animations (`[[animation]]` tables).
    #[serde(default, rename = "animation", skip_serializing_if = "Vec::is_empty")]
    pub animations: Vec<AnimationDesc>,
    /// Renderer settings for this scene: the `[frame]` table (the frame's settings) and the
    /// `[technique]` table (a registered technique and its settings). Kept as written; the
    /// renderer reads them and warns about unknown keys (irradiant::settings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<toml::Table>,
    /// The `[technique]` table, kept as written (see `frame`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub technique: Option<toml::Table>,
}

/// The `[mesh]` table: the geometry, and where it is placed in the world (scale, then
/// rotation, then translation).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshRef {
    /// Path relative to the manifest (or a built-in scene name such as `cornell`).
    pub path: String,
    /// Uniform scale applied first (Sponza's OBJ is in centimetres in some exports).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f32>,
    /// Rotation about the y axis, in degrees, applied after the scale.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation_y_degrees: Option<f32>,
    /// Offset applied last, in scene units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translation: Option<[f32; 3]>,
    /// Copies of the whole mesh on a grid, `[x, y, z]` counts (default `[1, 1, 1]`), placed
    /// `repeat_spacing` apart: large scenes made from the shipped ones. Copies are instances
    /// that share the mesh's bottom-level trees (memory grows with the instance count only)
    /// unless `flatten` is set.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repeat: Option<[u32; 3]>,
    /// Offset between neighbouring copies of `repeat` on each axis, in scene units
    /// (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repeat_spacing: Option<[f32; 3]>,
    /// Merges every instance into one mesh in world space: one bottom-level tree over all the
    /// triangles (the slowest build and the most memory, the best-behaved traversal).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flatten: Option<bool>,
}

/// Most copies `repeat` makes: past it the top-level tree, rebuilt every frame, costs more than
/// it is worth, and a flattened mesh would pass 4 billion vertex indices sooner or later.
pub const MAX_REPEAT_COPIES: u32 = 4096;

/// A camera as TOML writes it: the `[camera]` table of a manifest or a camera file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CameraDesc {
    /// Eye position, in world space.
    pub position: [f32; 3],
    /// Point looked at, in world space.
    pub target: [f32; 3],
    /// Up direction; y up when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<[f32; 3]>,
    /// Vertical field of view in degrees; the default camera's (40) when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov_y_degrees: Option<f32>,
}

/// The `kind` of a manifest's light.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LightKindDesc {
    /// `point`: light from `position` in every direction.
    Point,
    /// `spot`: a cone of light from `position` along `direction`.
    Spot,
    /// `directional`: parallel light along `direction`, as from the sun.
    Directional,
}

/// A light of a manifest: a `[[light]]` table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LightDesc {
    /// Name, by which animations refer to the light.
    pub name: String,
    /// What kind of light it is.
    pub kind: LightKindDesc,
    /// Position, in world space; required except for directional lights.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f32; 3]>,
    /// The direction the light travels (spot, directional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f32; 3]>,
    /// Linear RGB colour; white when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f32; 3]>,
    /// Radiant intensity (point, spot) or irradiance (directional), scaling `color`.
    pub intensity: f32,
    /// Spot lights: angle from the axis within which the light is at full strength, in
    /// degrees (default 20).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_angle_degrees: Option<f32>,
    /// Spot lights: angle from the axis past which there is no light, in degrees
    /// (default 30).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_angle_degrees: Option<f32>,
    /// Off lights can be switched on by animation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub enabled: Option<bool>,
}

/// A probe volume of a manifest (a `[[probe_volume]]` table): a box filled with a
/// regular grid of probes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProbeVolumeManifest {
    /// Name; `volume<i>`, its index among the volumes, when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Lowest corner, in world space.
    pub min: [f32; 3],
    /// Highest corner, in world space.
    pub max: [f32; 3],
    /// Probes per axis, 1 to [`MAX_PROBES_PER_AXIS`](crate::MAX_PROBES_PER_AXIS).
    pub counts: [u32; 3],
    /// `"camera"`: the volume follows the camera in whole cells, keeping its size (a tracking
    /// window, placed by `min` and `max` until the first frame); absent: it stays.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub follow: Option<String>,
}

/// An override of one of the mesh file's materials; the keys left out keep the file's values.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MaterialDesc {
    /// The material's name in the mesh file (MTL `newmtl`, glTF material name).
    pub name: String,
    /// Linear RGB base colour, 0 … 1; the file's alpha is kept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_color: Option<[f32; 3]>,
    /// 0 (dielectric) … 1 (metal: the base colour tints the reflection).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metallic: Option<f32>,
    /// Perceptual roughness, 0.05 (mirror-like) … 1 (GGX alpha = roughness²).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<f32>,
    /// Scale of the dielectric specular lobe (F0 = 0.04 × specular), 0 … 25.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub specular: Option<f32>,
    /// Emitted radiance, linear RGB, 0 … 10⁶.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emission: Option<[f32; 3]>,
}

/// A named region of a manifest (a `[[region]]` table): a box that the comparison lab
/// measures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionDesc {
    /// Name, as the comparison lab reports and selects it.
    pub name: String,
    /// Lowest corner, in world space.
    pub min: [f32; 3],
    /// Highest corner, in world space.
    pub max: [f32; 3],
}

/// A keyframed animation of a manifest (an `[[animation]]` table). It drives exactly
/// one of `light`, `instance` or `camera`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AnimationDesc {
    /// Name of the light it drives.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub light: Option<String>,
    /// Name of the instance it drives (of `repeat`'s copies, the first).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub instance: Option<String>,
    /// The camera: translation moves it with its target, rotation pans its view.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub camera: bool,
    /// Keys `[time, x, y, z]`: offset from the rest position.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub translation: Vec<[f32; 4]>,
    /// Keys `[time, scale]` of a light's intensity; 0 switches it off.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub intensity_scale: Vec<[f32; 2]>,
    /// Keys `[time, degrees]` about the y axis.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rotation_y_degrees: Vec<[f32; 2]>,
}

impl Manifest {
    /// Parses TOML; unknown keys are returned as warnings (a typo must not pass silently, and
    /// a newer manifest must still load in an older build).
    pub fn parse(text: &str, path: &Path, warnings: &mut Vec<String>) -> Result<Manifest> {
        let deserializer = toml::Deserializer::parse(text).map_err(|e| SceneError::Manifest {
            path: path.to_owned(),
            message: e.to_string(),
        })?;
        let mut unknown = Vec::new();
        let manifest: Manifest =
            serde_ignored::deserialize(deserializer, |key| unknown.push(key.to_string())).map_err(
                |e| SceneError::Manifest {
                    path: path.to_owned(),
                    message: e.to_string(),
                },
            )?;
        for key in unknown {
            warnings.push(format!("{}: unknown key '{key}' ignored (see scenes/README.md for the keys a manifest takes)", path.display()));
        }
        Ok(manifest)
    }

    /// The manifest as TOML; keys that are absent or empty are left out.
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).expect("a manifest always serialises")
    }

    /// Where the mesh file lies: relative paths are relative to the manifest's folder.
    pub fn mesh_path(&self, manifest_path: &Path) -> PathBuf {
        relative_to(manifest_path, &self.mesh.path)
    }

    /// Copies the scene's instances on `repeat`'s grid.
    fn repeat(&self, scene: &mut Scene, path: &Path) -> Result<()> {
        let counts = self.mesh.repeat.unwrap_or([1, 1, 1]);
        let spacing = Vec3::from(self.mesh.repeat_spacing.unwrap_or([0.0; 3]));
        let copies = counts.iter().try_fold(1u32, |n, &c| n.checked_mul(c));
        if counts.contains(&0) || copies.is_none_or(|n| n > MAX_REPEAT_COPIES) {
            return Err(invalid(
                path,
                format!("mesh.repeat = {counts:?} makes no copy or too many"),
                format!(
                    "Give three counts of at least 1 whose product is at most {MAX_REPEAT_COPIES}."
                ),
            ));
        }
        if !spacing.is_finite() {
            return Err(invalid(
                path,
                "mesh.repeat_spacing is not finite".into(),
                "Give three finite distances.",
            ));
        }
        let originals = std::mem::take(&mut scene.instances);
        for z in 0..counts[2] {
            for y in 0..counts[1] {
                for x in 0..counts[0] {
                    let cell = UVec3::new(x, y, z);
                    let offset = Mat4::from_translation(spacing * cell.as_vec3());
                    for instance in &originals {
                        let mut copy = instance.clone();
                        copy.transform = offset * instance.transform;
                        if cell != UVec3::ZERO {
                            // Animations address instances by name: they move the first copy.
                            copy.name = format!("{}@{x},{y},{z}", instance.name);
                        }
                        scene.instances.push(copy);
                    }
                }
            }
        }
        Ok(())
    }

    /// Applies everything but the mesh to a loaded scene; `placed` are the `[[place]]`
    /// tables' scenes, loaded, in order.
    pub fn apply(&self, scene: &mut Scene, path: &Path, placed: Vec<Scene>) -> Result<()> {
        if let Some(name) = &self.name {
            scene.name = name.clone();
        }
        let placement = crate::place::placement(
            self.mesh.scale,
            self.mesh.rotation_y_degrees,
            self.mesh.translation,
        );
        for instance in &mut scene.instances {
            instance.transform = placement * instance.transform;
        }
        self.repeat(scene, path)?;
        if self.mesh.flatten == Some(true) {
            flatten(scene, path)?;
        }
        for (desc, placed) in self.places.iter().zip(placed) {
            desc.check(path, &self.places)?;
            crate::place::merge(scene, placed, desc);
        }
        if let Some(c) = &self.camera {
            scene.camera = Camera {
                position: c.position.into(),
                target: c.target.into(),
                up: c.up.map(Vec3::from).unwrap_or(Vec3::Y),
                fov_y_degrees: c.fov_y_degrees.unwrap_or(Camera::default().fov_y_degrees),
            };
        } else if self.mesh.scale.is_some()
            || self.mesh.translation.is_some()
            || !self.places.is_empty()
        {
            scene.camera = crate::framing::camera_for_bounds(scene);
        }
        if let Some(sky) = self.sky {
            scene.sky = sky.into();
        }
        for (name, table) in [("frame", &self.frame), ("technique", &self.technique)] {
            if let Some(table) = table {
                scene
                    .settings
                    .insert(name.into(), toml::Value::Table(table.clone()));
            }
        }
        for l in &self.lights {
            let kind = match l.kind {
                LightKindDesc::Point => LightKind::Point,
                LightKindDesc::Directional => LightKind::Directional,
                LightKindDesc::Spot => LightKind::Spot {
                    inner_angle: l.inner_angle_degrees.unwrap_or(20.0).to_radians(),
                    outer_angle: l.outer_angle_degrees.unwrap_or(30.0).to_radians(),
                },
            };
            let needs_position = kind != LightKind::Directional;
            if needs_position && l.position.is_none() {
                return Err(invalid(
                    path,
                    format!("light '{}' has no position", l.name),
                    "Add `position = [x, y, z]` to it.",
                ));
            }
            if !needs_position && l.direction.is_none() {
                return Err(invalid(
                    path,
                    format!("light '{}' has no direction", l.name),
                    "Add `direction = [x, y, z]` (the way the light travels).",
                ));
            }
            scene.lights.push(Light {
                name: l.name.clone(),
                kind,
                position: l.position.map(Vec3::from).unwrap_or(Vec3::ZERO),
                direction: l
                    .direction
                    .map(Vec3::from)
                    .unwrap_or(-Vec3::Y)
                    .normalize_or(-Vec3::Y),
                color: l.color.map(Vec3::from).unwrap_or(Vec3::ONE),
                intensity: l.intensity,
                enabled: l.enabled.unwrap_or(true),
            });
        }
        for (i, v) in self.probe_volumes.iter().enumerate() {
            let name = v.name.clone().unwrap_or_else(|| format!("volume{i}"));
            let follow = Follow::parse(v.follow.as_deref().unwrap_or(""));
            scene.probe_volumes.push(ProbeVolumeDesc {
                name,
                min: v.min.into(),
                max: v.max.into(),
                counts: v.counts,
                follow,
            });
        }
        for m in &self.materials {
            apply_material(scene, m, path)?;
        }
        for r in &self.regions {
            scene
                .regions
                .push(Region::new(&r.name, r.min.into(), r.max.into()));
        }
        for a in &self.animations {
            let target = match (&a.light, &a.instance) {
                (None, None) if a.camera => AnimationTarget::Camera,
                (Some(light), None) if !a.camera => {
                    if !scene.lights.iter().any(|l| &l.name == light) {
                        return Err(invalid(
                            path,
                            format!(
                                "animation names light '{light}', which the scene does not have"
                            ),
                            "Use the `name` of one of the scene's lights.",
                        ));
                    }
                    AnimationTarget::Light(light.clone())
                }
                (None, Some(instance)) if !a.camera => {
                    if !scene.instances.iter().any(|i| &i.name == instance) {
                        let names: Vec<_> = scene
                            .instances
                            .iter()
                            .map(|i| i.name.as_str())
                            .take(8)
                            .collect();
                        return Err(invalid(
                            path,
                            format!(
                                "animation names instance '{instance}', which the scene does not have"
                            ),
                            format!("Use one of: {}.", names.join(", ")),
                        ));
                    }
                    AnimationTarget::Instance(instance.clone())
                }
                _ => {
                    return Err(invalid(
                        path,
                        "an [[animation]] must name exactly one of `light`, `instance` or `camera`"
                            .into(),
                        "Add `light = \"name\"`, `instance = \"name\"` or `camera = true`.",
                    ));
                }
            };
            let keys_sorted = |times: Vec<f32>| times.windows(2).all(|w| w[0] <= w[1]);
            if !keys_sorted(a.translation.iter().map(|k| k[0]).collect())
                || !keys_sorted(a.intensity_scale.iter().map(|k| k[0]).collect())
                || !keys_sorted(a.rotation_y_degrees.iter().map(|k| k[0]).collect())
            {
                return Err(invalid(
                    path,
                    "animation keys are not in time order".into(),
                    "Sort each track's keys by their first number, the time.",
                ));
            }
            scene.animations.push(Animation {
                target,
                tracks: Tracks {
                    translation: a
                        .translation
                        .iter()
                        .map(|k| (k[0], Vec3::new(k[1], k[2], k[3])))
                        .collect(),
                    intensity_scale: a.intensity_scale.iter().map(|k| (k[0], k[1])).collect(),
                    rotation_y_degrees: a.rotation_y_degrees.iter().map(|k| (k[0], k[1])).collect(),
                },
            });
        }
        Ok(())
    }
}

fn invalid(path: &Path, problem: String, fix: impl Into<String>) -> SceneError {
    SceneError::Invalid {
        path: path.to_owned(),
        problem,
        fix: fix.into(),
    }
}

/// Most triangles `flatten` makes into one mesh: the 10.8 million of `scenes/scale` took 4.2 GiB
/// of host memory to build; past this a manifest could ask for more memory than a machine has
/// (`repeat` of a large mesh), where instances cost nothing.
pub const MAX_FLATTENED_TRIANGLES: u64 = 32_000_000;

/// Replaces every instance by one mesh holding all their triangles in world space.
fn flatten(scene: &mut Scene, path: &Path) -> Result<()> {
    let triangles: u64 = scene
        .instances
        .iter()
        .map(|i| scene.meshes[i.mesh as usize].triangle_count() as u64)
        .sum();
    if triangles > MAX_FLATTENED_TRIANGLES {
        return Err(invalid(
            path,
            format!(
                "mesh.flatten would make one mesh of {triangles} triangles, past {MAX_FLATTENED_TRIANGLES}"
            ),
            "Leave the copies as instances (flatten = false), which share one tree, or make fewer.",
        ));
    }
    let mut merged = Mesh {
        name: format!("{} (flattened)", scene.name),
        ..Mesh::default()
    };
    // Every vertex keeps a normal and a texture coordinate once any mesh has them.
    let keep_normals = scene.meshes.iter().any(|m| !m.normals.is_empty());
    let keep_uvs = scene.meshes.iter().any(|m| !m.uvs.is_empty());
    for instance in &scene.instances {
        let mesh = &scene.meshes[instance.mesh as usize];
        let base = merged.positions.len() as u32;
        merged.positions.extend(
            mesh.positions
                .iter()
                .map(|&p| instance.transform.transform_point3(p)),
        );
        if keep_normals {
            let normal_matrix = Mat3::from_mat4(instance.transform).inverse().transpose();
            merged.normals.extend((0..mesh.positions.len()).map(|v| {
                mesh.normals
                    .get(v)
                    .map_or(Vec3::ZERO, |&n| (normal_matrix * n).normalize_or_zero())
            }));
        }
        if keep_uvs {
            merged.uvs.extend(
                (0..mesh.positions.len()).map(|v| mesh.uvs.get(v).copied().unwrap_or_default()),
            );
        }
        merged
            .indices
            .extend(mesh.indices.iter().map(|&i| base + i));
        merged
            .triangle_materials
            .extend_from_slice(&mesh.triangle_materials);
    }
    scene.meshes = vec![merged];
    scene.instances = vec![Instance {
        name: scene.name.clone(),
        mesh: 0,
        transform: Mat4::IDENTITY,
    }];
    Ok(())
}

/// Applies a `[[material]]` override, checking its values.
fn apply_material(scene: &mut Scene, m: &MaterialDesc, path: &Path) -> Result<()> {
    let Some(material) = scene.materials.iter_mut().find(|x| x.name == m.name) else {
        let names: Vec<_> = scene.materials.iter().map(|x| x.name.as_str()).collect();
        return Err(invalid(
            path,
            format!(
                "[[material]] names '{}', which the mesh file does not have",
                m.name
            ),
            format!("Use one of: {}.", names.join(", ")),
        ));
    };
    let check = |key: &str, value: f32, lo: f32, hi: f32| -> Result<f32> {
        if value.is_finite() && (lo..=hi).contains(&value) {
            Ok(value)
        } else {
            Err(invalid(
                path,
                format!("material '{}': {key} = {value} is out of range", m.name),
                format!("Use a value from {lo} to {hi}."),
            ))
        }
    };
    let check3 = |key: &str, v: [f32; 3], hi: f32| -> Result<Vec3> {
        for c in v {
            check(key, c, 0.0, hi)?;
        }
        Ok(Vec3::from(v))
    };
    if let Some(c) = m.base_color {
        material.base_color = check3("base_color", c, 1.0)?.extend(material.base_color.w);
    }
    if let Some(v) = m.metallic {
        material.metallic = check("metallic", v, 0.0, 1.0)?;
    }
    if let Some(v) = m.roughness {
        material.roughness = check("roughness", v, 0.05, 1.0)?;
    }
    if let Some(v) = m.specular {
        material.specular = check("specular", v, 0.0, 25.0)?;
    }
    if let Some(e) = m.emission {
        material.emission = check3("emission", e, 1e6)?;
    }
    Ok(())
}

/// A path a manifest names, relative to the manifest's folder.
pub fn relative_to(manifest_path: &Path, path: &str) -> PathBuf {
    manifest_path.parent().unwrap_or(Path::new(".")).join(path)
}
