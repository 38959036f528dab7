//! More meshes placed in one world (a manifest's `[[place]]` tables): each is a mesh file or a
//! built-in scene, scaled, turned about y and moved, and merged into the manifest's scene with
//! its materials, textures, instances and lights. A world hundreds of metres across is then
//! written from the shipped scenes — a terrain, buildings to enter, a tunnel — without a
//! file of its own.

use std::path::Path;

use glam::{Mat4, Vec3};
use serde::{Deserialize, Serialize};

use crate::error::{Result, SceneError};
use crate::model::Scene;

/// A `[[place]]` table: what to place, and where (scale, then rotation, then translation).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PlaceDesc {
    /// Prefixes the names of the placed instances and lights (`name/instance`), which
    /// animations and `follow` then use; unique within the manifest.
    pub name: String,
    /// A mesh file relative to the manifest, or a built-in scene name.
    pub path: String,
    /// Uniform scale, applied first.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f32>,
    /// Rotation about the y axis, in degrees, after the scale.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation_y_degrees: Option<f32>,
    /// Offset applied last, in scene units.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translation: Option<[f32; 3]>,
}

impl PlaceDesc {
    /// Scale, then rotation about y, then translation.
    pub fn transform(&self) -> Mat4 {
        placement(self.scale, self.rotation_y_degrees, self.translation)
    }

    /// Refuses a placement that cannot work, naming the manifest and the table.
    pub fn check(&self, manifest: &Path, others: &[PlaceDesc]) -> Result<()> {
        let problem = |message: String| SceneError::Manifest {
            path: manifest.to_owned(),
            message,
        };
        if self.name.is_empty() || self.name.contains('/') {
            return Err(problem(format!(
                "[[place]] of '{}': name '{}' must be non-empty and without '/'",
                self.path, self.name
            )));
        }
        if others.iter().filter(|o| o.name == self.name).count() > 1 {
            return Err(problem(format!(
                "[[place]] name '{}' is used twice: each placement needs its own",
                self.name
            )));
        }
        let scale = self.scale.unwrap_or(1.0);
        let finite = self
            .translation
            .unwrap_or([0.0; 3])
            .iter()
            .all(|v| v.is_finite())
            && self.rotation_y_degrees.unwrap_or(0.0).is_finite();
        if !(scale.is_finite() && scale > 0.0 && finite) {
            return Err(problem(format!(
                "[[place]] '{}': scale must be positive and the translation and rotation finite",
                self.name
            )));
        }
        Ok(())
    }
}

/// A placement's transform: uniform scale, then rotation about y (degrees), then translation;
/// what is left out is the identity. `[mesh]` and `[[place]]` tables both place this way.
pub fn placement(
    scale: Option<f32>,
    rotation_y_degrees: Option<f32>,
    translation: Option<[f32; 3]>,
) -> Mat4 {
    Mat4::from_translation(translation.map(Vec3::from).unwrap_or(Vec3::ZERO))
        * Mat4::from_rotation_y(rotation_y_degrees.unwrap_or(0.0).to_radians())
        * Mat4::from_scale(Vec3::splat(scale.unwrap_or(1.0)))
}

/// Merges `placed` into `scene` at `desc`'s placement: its meshes, materials and textures are
/// appended (indices moved past the scene's), its instances and lights moved into place and
/// named `desc.name/…`. Its camera, sky, volumes and regions are the manifest's business.
pub fn merge(scene: &mut Scene, placed: Scene, desc: &PlaceDesc) {
    let transform = desc.transform();
    let (meshes, materials, textures) = (
        scene.meshes.len() as u32,
        scene.materials.len() as u32,
        scene.textures.len() as u32,
    );
    scene.textures.extend(placed.textures);
    scene
        .materials
        .extend(placed.materials.into_iter().map(|mut m| {
            m.base_color_texture = m.base_color_texture.map(|t| t + textures);
            m
        }));
    scene.meshes.extend(placed.meshes.into_iter().map(|mut m| {
        for material in &mut m.triangle_materials {
            *material += materials;
        }
        m
    }));
    scene
        .instances
        .extend(placed.instances.into_iter().map(|mut i| {
            i.mesh += meshes;
            i.transform = transform * i.transform;
            i.name = format!("{}/{}", desc.name, i.name);
            i
        }));
    scene.lights.extend(placed.lights.into_iter().map(|mut l| {
        l.position = transform.transform_point3(l.position);
        l.direction = transform.transform_vector3(l.direction).normalize_or_zero();
        l.name = format!("{}/{}", desc.name, l.name);
        l
    }));
}
