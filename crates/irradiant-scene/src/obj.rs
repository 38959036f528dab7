//! Wavefront OBJ + MTL through tobj.

use std::path::Path;

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::error::{Result, SceneError, contain_parser_panic};
use crate::model::{AlphaMode, Instance, Material, Mesh, Scene};
use crate::textures::TextureCache;

/// Loads an OBJ as one mesh (one bottom-level BVH) with one material per triangle.
pub fn load_obj(path: &Path, warnings: &mut Vec<String>) -> Result<Scene> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let obj_error = |message| SceneError::Obj {
        path: path.to_owned(),
        message,
    };
    let (models, materials) = contain_parser_panic(|| tobj::load_obj(path, &options))
        .map_err(obj_error)?
        .map_err(|e| obj_error(e.to_string()))?;
    let base_dir = path.parent().unwrap_or(Path::new("."));
    let obj_materials = match materials {
        Ok(m) => m,
        Err(e) => {
            warnings.push(format!(
                "{}: material library not loaded ({e}); every surface gets the default grey material",
                path.display()
            ));
            Vec::new()
        }
    };

    let mut scene = Scene {
        name: file_stem(path),
        ..Default::default()
    };
    let mut textures = TextureCache::default();
    for m in &obj_materials {
        scene
            .materials
            .push(convert_material(m, base_dir, &mut textures, warnings));
    }
    let default_material = scene.materials.len() as u32;
    scene.materials.push(Material::default());

    let mut mesh = Mesh {
        name: scene.name.clone(),
        ..Default::default()
    };
    let any_normals = models.iter().any(|m| !m.mesh.normals.is_empty());
    let any_uvs = models.iter().any(|m| !m.mesh.texcoords.is_empty());
    for model in &models {
        let m = &model.mesh;
        let base = mesh.positions.len() as u32;
        let vertex_count = m.positions.len() / 3;
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if any_normals {
            if m.normals.len() == m.positions.len() {
                mesh.normals.extend(
                    m.normals
                        .chunks_exact(3)
                        .map(|n| Vec3::new(n[0], n[1], n[2])),
                );
            } else {
                // Groups without normals fall back to "no normal": the GPU uses the face normal.
                mesh.normals
                    .extend(std::iter::repeat_n(Vec3::ZERO, vertex_count));
            }
        }
        if any_uvs {
            if m.texcoords.len() / 2 == vertex_count {
                // OBJ's v axis points up; images are stored top row first.
                mesh.uvs.extend(
                    m.texcoords
                        .chunks_exact(2)
                        .map(|t| Vec2::new(t[0], 1.0 - t[1])),
                );
            } else {
                mesh.uvs
                    .extend(std::iter::repeat_n(Vec2::ZERO, vertex_count));
            }
        }
        let material = m
            .material_id
            .map(|i| i as u32)
            .filter(|&i| i < default_material)
            .unwrap_or(default_material);
        mesh.indices.extend(m.indices.iter().map(|&i| base + i));
        mesh.triangle_materials
            .extend(std::iter::repeat_n(material, m.indices.len() / 3));
    }
    scene.textures = textures.into_textures();
    scene.meshes.push(mesh);
    scene.instances.push(Instance {
        name: scene.name.clone(),
        mesh: 0,
        transform: Mat4::IDENTITY,
    });
    Ok(scene)
}

fn convert_material(
    m: &tobj::Material,
    base_dir: &Path,
    textures: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> Material {
    let kd = m.diffuse.unwrap_or([0.8; 3]);
    let ks = m.specular.unwrap_or([0.0; 3]);
    let ke = m.emissive.unwrap_or([0.0; 3]);
    let shininess = m.shininess.unwrap_or(10.0).max(0.0);
    let has_specular = ks.iter().any(|&k| k > 0.0);
    let mut material = Material {
        name: m.name.clone(),
        base_color: Vec4::new(kd[0], kd[1], kd[2], 1.0),
        emission: Vec3::from(ke),
        // Phong exponent to GGX roughness: alpha² = 2 / (Ns + 2) (Walter et al. 2007).
        roughness: (2.0 / (shininess + 2.0)).sqrt().sqrt().clamp(0.05, 1.0),
        specular: if has_specular { 1.0 } else { 0.0 },
        ..Default::default()
    };
    if let Some(name) = &m.diffuse_texture {
        material.base_color_texture =
            textures.load(base_dir, name, m.dissolve_texture.as_deref(), warnings);
        if material.base_color_texture.is_some() {
            // The texture carries the colour; Kd would darken it twice.
            material.base_color = Vec4::ONE;
        }
    }
    if m.dissolve_texture.is_some() && material.base_color_texture.is_some() {
        material.alpha_mode = AlphaMode::Mask { cutoff: 0.5 };
    }
    material
}

pub(crate) fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into())
}
