//! Checks a loaded scene before anything reaches the GPU: a NaN vertex would poison the BVH,
//! an index out of range would read past a buffer.

use std::path::Path;

use crate::error::{Result, SceneError};
use crate::model::Scene;

/// Probes per axis above this are refused: 256³ probes would need gigabytes of atlas.
pub const MAX_PROBES_PER_AXIS: u32 = 256;

/// Checks `scene` (named `path` in the messages: its file, or what a host calls it) and
/// repairs what can be repaired, saying so in `warnings` (invalid normals or UVs dropped,
/// degenerate triangles removed, material values clamped); refuses, naming the mesh, material,
/// light or volume and the fix, what cannot: a vertex that is not finite, an index or material
/// out of range, a camera or sky that is not one.
pub fn validate(scene: &mut Scene, path: &Path, warnings: &mut Vec<String>) -> Result<()> {
    let invalid = |problem: String, fix: &str| SceneError::Invalid {
        path: path.to_owned(),
        problem,
        fix: fix.to_owned(),
    };
    for mesh in &mut scene.meshes {
        if let Some(v) = mesh.positions.iter().position(|p| !p.is_finite()) {
            return Err(invalid(
                format!(
                    "mesh '{}' has a vertex that is not a finite number (vertex {v}: {:?})",
                    mesh.name, mesh.positions[v]
                ),
                "Fix or remove the vertex in the modelling tool; NaN and infinite coordinates cannot be traced.",
            ));
        }
        let vertex_count = mesh.positions.len() as u32;
        if let Some(&i) = mesh.indices.iter().find(|&&i| i >= vertex_count) {
            return Err(invalid(
                format!(
                    "mesh '{}' refers to vertex {i} but has only {vertex_count}",
                    mesh.name
                ),
                "Re-export the mesh.",
            ));
        }
        if mesh.triangle_materials.len() != mesh.triangle_count() || mesh.indices.len() % 3 != 0 {
            return Err(invalid(
                format!("mesh '{}' has an incomplete triangle list", mesh.name),
                "Re-export the mesh.",
            ));
        }
        if let Some(&m) = mesh
            .triangle_materials
            .iter()
            .find(|&&m| m as usize >= scene.materials.len())
        {
            return Err(invalid(
                format!(
                    "mesh '{}' uses material {m}, which does not exist",
                    mesh.name
                ),
                "Re-export the mesh with its materials.",
            ));
        }
        if mesh.normals.iter().any(|n| !n.is_finite())
            || (!mesh.normals.is_empty() && mesh.normals.len() != mesh.positions.len())
        {
            warnings.push(format!(
                "{}: mesh '{}' has invalid vertex normals; it is shaded flat",
                path.display(),
                mesh.name
            ));
            mesh.normals.clear();
        }
        if mesh.uvs.iter().any(|t| !t.is_finite())
            || (!mesh.uvs.is_empty() && mesh.uvs.len() != mesh.positions.len())
        {
            warnings.push(format!(
                "{}: mesh '{}' has invalid texture coordinates; textures are not applied",
                path.display(),
                mesh.name
            ));
            mesh.uvs.clear();
        }
        let degenerate = drop_degenerate_triangles(mesh);
        if degenerate > 0 {
            warnings.push(format!(
                "{}: mesh '{}': {degenerate} degenerate (zero-area) triangles dropped",
                path.display(),
                mesh.name
            ));
        }
    }
    if let Some(i) = scene.instances.iter().find(|i| !i.transform.is_finite()) {
        return Err(invalid(
            format!("instance '{}' has a transform that is not finite", i.name),
            "Fix the node's transform.",
        ));
    }
    if scene.triangle_count() == 0 {
        return Err(invalid(
            "the scene has no triangles".into(),
            "Point the scene at a mesh with at least one non-degenerate triangle.",
        ));
    }
    for m in &mut scene.materials {
        let values = [
            m.base_color.to_array().as_slice(),
            m.emission.to_array().as_slice(),
            &[m.metallic, m.roughness, m.specular],
        ]
        .concat();
        if values.iter().any(|v| !v.is_finite() || *v < 0.0) {
            return Err(invalid(
                format!("material '{}' has a negative or non-finite value", m.name),
                "Colours, emission, metallic and roughness must be finite and ≥ 0.",
            ));
        }
        m.metallic = m.metallic.min(1.0);
        m.roughness = m.roughness.clamp(0.02, 1.0);
    }
    for l in &scene.lights {
        let values = [
            l.position.to_array(),
            l.direction.to_array(),
            l.color.to_array(),
        ]
        .concat();
        if values.iter().any(|v| !v.is_finite()) || !l.intensity.is_finite() || l.intensity < 0.0 {
            return Err(invalid(
                format!("light '{}' has a non-finite or negative value", l.name),
                "Give it finite position, direction, colour and intensity ≥ 0.",
            ));
        }
    }
    let c = &scene.camera;
    if !(c.position.is_finite() && c.target.is_finite() && c.up.is_finite())
        || c.position == c.target
    {
        return Err(invalid(
            "the camera's position and target must be finite and different".into(),
            "Fix [camera] in the manifest.",
        ));
    }
    if !(c.fov_y_degrees > 0.5 && c.fov_y_degrees < 179.0) {
        return Err(invalid(
            format!(
                "camera field of view {}° is outside 0.5°…179°",
                c.fov_y_degrees
            ),
            "Use a vertical field of view such as 45.",
        ));
    }
    if !scene.sky.is_finite() || scene.sky.min_element() < 0.0 {
        return Err(invalid(
            "the sky colour must be finite and ≥ 0".into(),
            "Fix `sky` in the manifest.",
        ));
    }
    for v in &scene.probe_volumes {
        if let Some(crate::model::Follow::Instance(name)) = &v.follow
            && !scene.instances.iter().any(|i| &i.name == name)
        {
            let names: Vec<&str> = scene.instances.iter().map(|i| i.name.as_str()).collect();
            return Err(invalid(
                format!(
                    "probe volume '{}' has follow = \"{name}\", which is neither the camera nor an instance of the scene (its instances: {})",
                    v.name,
                    names.join(", ")
                ),
                "Write follow = \"camera\" or an instance's name, or leave it out for a volume that stays.",
            ));
        }
        if !(v.min.is_finite() && v.max.is_finite()) || v.min.cmpge(v.max).any() {
            return Err(invalid(
                format!(
                    "probe volume '{}' has min ≥ max or non-finite bounds",
                    v.name
                ),
                "Give `min` below `max` on every axis.",
            ));
        }
        if v.counts.iter().any(|&n| n == 0 || n > MAX_PROBES_PER_AXIS) {
            return Err(invalid(
                format!("probe volume '{}' asks for {:?} probes", v.name, v.counts),
                &format!("Use 1…{MAX_PROBES_PER_AXIS} probes per axis."),
            ));
        }
    }
    for r in &scene.regions {
        if !(r.min.is_finite() && r.max.is_finite()) || r.min.cmpge(r.max).any() {
            return Err(invalid(
                format!("region '{}' has min ≥ max or non-finite bounds", r.name),
                "Give `min` below `max` on every axis.",
            ));
        }
    }
    Ok(())
}

fn drop_degenerate_triangles(mesh: &mut crate::model::Mesh) -> usize {
    let before = mesh.triangle_count();
    let mut indices = Vec::with_capacity(mesh.indices.len());
    let mut materials = Vec::with_capacity(mesh.triangle_materials.len());
    for t in 0..before {
        let [a, b, c] = mesh.triangle(t);
        let doubled_area = (b - a).cross(c - a).length();
        if doubled_area > 0.0 && doubled_area.is_finite() {
            indices.extend_from_slice(&mesh.indices[3 * t..3 * t + 3]);
            materials.push(mesh.triangle_materials[t]);
        }
    }
    mesh.indices = indices;
    mesh.triangle_materials = materials;
    before - mesh.triangle_count()
}
