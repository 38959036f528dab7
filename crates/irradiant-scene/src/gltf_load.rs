//! glTF 2.0 (.gltf and .glb) through the gltf crate: node hierarchy, metallic-roughness
//! materials, KHR_materials_emissive_strength, KHR_lights_punctual and perspective cameras.

use std::collections::HashMap;
use std::path::Path;

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::error::{Result, SceneError, contain_parser_panic};
use crate::model::{AlphaMode, Camera, Instance, Light, LightKind, Material, Mesh, Scene, Texture};
use crate::obj::file_stem;

pub fn load_gltf(path: &Path, warnings: &mut Vec<String>) -> Result<Scene> {
    let gltf_error = |message| SceneError::Gltf {
        path: path.to_owned(),
        message,
    };
    let (document, buffers, images) = contain_parser_panic(|| gltf::import(path))
        .map_err(gltf_error)?
        .map_err(|e| gltf_error(e.to_string()))?;
    let mut scene = Scene {
        name: file_stem(path),
        ..Default::default()
    };

    for (i, image) in images.iter().enumerate() {
        scene.textures.push(convert_image(image, i, path, warnings));
    }
    for material in document.materials() {
        scene.materials.push(convert_material(&material, &document));
    }
    let default_material = scene.materials.len() as u32;
    scene.materials.push(Material {
        specular: 1.0,
        ..Default::default()
    });

    let Some(root) = document
        .default_scene()
        .or_else(|| document.scenes().next())
    else {
        return Err(SceneError::Invalid {
            path: path.to_owned(),
            problem: "the file has no scene".into(),
            fix: "Export it with at least one scene and one mesh.".into(),
        });
    };
    let mut mesh_of_gltf_mesh = HashMap::new();
    let mut camera = None;
    let mut stack: Vec<(gltf::Node, Mat4)> = root.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
    while let Some((node, parent)) = stack.pop() {
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            let index = *mesh_of_gltf_mesh.entry(mesh.index()).or_insert_with(|| {
                scene.meshes.push(convert_mesh(
                    &mesh,
                    &buffers,
                    default_material,
                    path,
                    warnings,
                ));
                scene.meshes.len() as u32 - 1
            });
            let name = node
                .name()
                .map(str::to_owned)
                .unwrap_or_else(|| format!("node{}", node.index()));
            scene.instances.push(Instance {
                name,
                mesh: index,
                transform: world,
            });
        }
        if let Some(light) = node.light() {
            scene.lights.push(convert_light(&light, &node, world));
        }
        if let (None, Some(cam)) = (&camera, node.camera())
            && let gltf::camera::Projection::Perspective(p) = cam.projection()
        {
            let position = world.transform_point3(Vec3::ZERO);
            let forward = world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Z);
            camera = Some(Camera {
                position,
                target: position + forward,
                up: world.transform_vector3(Vec3::Y).normalize_or(Vec3::Y),
                fov_y_degrees: p.yfov().to_degrees(),
            });
        }
        stack.extend(node.children().map(|c| (c, world)));
    }
    // Meshes that no node uses are dropped by validation's "unused" check only implicitly:
    // they cost memory but no rays.
    if let Some(camera) = camera {
        scene.camera = camera;
    } else {
        scene.camera = crate::framing::camera_for_bounds(&scene);
    }
    Ok(scene)
}

fn convert_material(m: &gltf::Material, _document: &gltf::Document) -> Material {
    let pbr = m.pbr_metallic_roughness();
    let strength = m.emissive_strength().unwrap_or(1.0);
    Material {
        name: m.name().unwrap_or("material").to_owned(),
        base_color: Vec4::from(pbr.base_color_factor()),
        base_color_texture: pbr
            .base_color_texture()
            .map(|t| t.texture().source().index() as u32),
        emission: Vec3::from(m.emissive_factor()) * strength,
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        specular: 1.0,
        alpha_mode: match m.alpha_mode() {
            gltf::material::AlphaMode::Mask => AlphaMode::Mask {
                cutoff: m.alpha_cutoff().unwrap_or(0.5),
            },
            // Blending is approximated as opaque: a path tracer has no draw order.
            _ => AlphaMode::Opaque,
        },
    }
}

fn convert_mesh(
    mesh: &gltf::Mesh,
    buffers: &[gltf::buffer::Data],
    default_material: u32,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Mesh {
    let name = mesh
        .name()
        .map(str::to_owned)
        .unwrap_or_else(|| format!("mesh{}", mesh.index()));
    let mut out = Mesh {
        name: name.clone(),
        ..Default::default()
    };
    let mut has_normals = true;
    let mut has_uvs = false;
    let mut primitives = Vec::new();
    for primitive in mesh.primitives() {
        if primitive.mode() != gltf::mesh::Mode::Triangles {
            warnings.push(format!("{}: mesh '{name}' has a primitive drawn as {:?}; only triangles are traced, it is skipped", path.display(), primitive.mode()));
            continue;
        }
        // The reader assumes each accessor has the type the spec requires (and asserts it in
        // debug builds; found by the gltf fuzz target): check before reading.
        if let Err(problem) = accessor_types_ok(&primitive) {
            warnings.push(format!(
                "{}: mesh '{name}' has a primitive whose {problem}: it is skipped",
                path.display()
            ));
            continue;
        }
        let reader = primitive.reader(|b| Some(&buffers[b.index()]));
        let Some(positions) = reader.read_positions() else {
            continue;
        };
        let positions: Vec<Vec3> = positions.map(Vec3::from).collect();
        let normals: Option<Vec<Vec3>> = reader.read_normals().map(|n| n.map(Vec3::from).collect());
        let uvs: Option<Vec<Vec2>> = reader
            .read_tex_coords(0)
            .map(|t| t.into_f32().map(Vec2::from).collect());
        let indices: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        has_normals &= normals.is_some();
        has_uvs |= uvs.is_some();
        let material = primitive
            .material()
            .index()
            .map(|i| i as u32)
            .unwrap_or(default_material);
        primitives.push((positions, normals, uvs, indices, material));
    }
    for (positions, normals, uvs, indices, material) in primitives {
        let base = out.positions.len() as u32;
        let n = positions.len();
        out.positions.extend(positions);
        if has_normals {
            out.normals.extend(normals.unwrap_or_default());
        }
        if has_uvs {
            out.uvs.extend(uvs.unwrap_or_else(|| vec![Vec2::ZERO; n]));
        }
        out.triangle_materials
            .extend(std::iter::repeat_n(material, indices.len() / 3));
        out.indices
            .extend(indices.iter().take(indices.len() / 3 * 3).map(|i| base + i));
    }
    out
}

fn convert_light(
    light: &gltf::khr_lights_punctual::Light,
    node: &gltf::Node,
    world: Mat4,
) -> Light {
    use gltf::khr_lights_punctual::Kind;
    let kind = match light.kind() {
        Kind::Point => LightKind::Point,
        Kind::Directional => LightKind::Directional,
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => LightKind::Spot {
            inner_angle: inner_cone_angle,
            outer_angle: outer_cone_angle,
        },
    };
    Light {
        name: light
            .name()
            .or(node.name())
            .map(str::to_owned)
            .unwrap_or_else(|| format!("light{}", light.index())),
        kind,
        position: world.transform_point3(Vec3::ZERO),
        direction: world.transform_vector3(-Vec3::Z).normalize_or(-Vec3::Y),
        color: Vec3::from(light.color()),
        intensity: light.intensity(),
        enabled: true,
    }
}

fn convert_image(
    image: &gltf::image::Data,
    index: usize,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Texture {
    use gltf::image::Format;
    let texels = (image.width * image.height) as usize;
    let mut rgba8 = Vec::with_capacity(texels * 4);
    let channels = match image.format {
        Format::R8 => 1,
        Format::R8G8 => 2,
        Format::R8G8B8 => 3,
        Format::R8G8B8A8 => 4,
        other => {
            warnings.push(format!(
                "{}: image {index} has format {other:?}, which is not supported; it is drawn white",
                path.display()
            ));
            return Texture {
                name: format!("image{index}"),
                width: 1,
                height: 1,
                rgba8: vec![255; 4],
            };
        }
    };
    for texel in image.pixels.chunks_exact(channels).take(texels) {
        let rgba = match channels {
            1 => [texel[0], texel[0], texel[0], 255],
            2 => [texel[0], texel[0], texel[0], texel[1]],
            3 => [texel[0], texel[1], texel[2], 255],
            _ => [texel[0], texel[1], texel[2], texel[3]],
        };
        rgba8.extend_from_slice(&rgba);
    }
    Texture {
        name: format!("image{index}"),
        width: image.width,
        height: image.height,
        rgba8,
    }
}

/// Whether a primitive's accessors have the types glTF 2.0 requires of them: POSITION and
/// NORMAL float VEC3, TEXCOORD_0 VEC2 of floats or normalized bytes or shorts, indices scalar
/// unsigned integers. A description of the first that does not.
fn accessor_types_ok(primitive: &gltf::Primitive) -> std::result::Result<(), String> {
    use gltf::accessor::{DataType, Dimensions};
    let check = |what: &str,
                 accessor: Option<gltf::Accessor>,
                 dimensions: Dimensions,
                 types: &[DataType]|
     -> std::result::Result<(), String> {
        match accessor {
            Some(a) if a.dimensions() != dimensions || !types.contains(&a.data_type()) => {
                Err(format!(
                    "{what} accessor is {:?} of {:?}, where glTF requires {dimensions:?} of {types:?}",
                    a.dimensions(),
                    a.data_type()
                ))
            }
            _ => Ok(()),
        }
    };
    check(
        "POSITION",
        primitive.get(&gltf::Semantic::Positions),
        Dimensions::Vec3,
        &[DataType::F32],
    )?;
    check(
        "NORMAL",
        primitive.get(&gltf::Semantic::Normals),
        Dimensions::Vec3,
        &[DataType::F32],
    )?;
    check(
        "TEXCOORD_0",
        primitive.get(&gltf::Semantic::TexCoords(0)),
        Dimensions::Vec2,
        &[DataType::F32, DataType::U8, DataType::U16],
    )?;
    check(
        "indices",
        primitive.indices(),
        Dimensions::Scalar,
        &[DataType::U8, DataType::U16, DataType::U32],
    )
}
