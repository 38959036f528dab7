//! Irradiant's scene model and loaders. No GPU code lives here.
//!
//! [`load`] takes what a user types after `--scene`: a built-in name (`cornell`), a manifest
//! (`scenes/sponza.toml`), or a mesh file (`.obj`, `.gltf`, `.glb`), and returns a validated
//! [`Scene`] plus the warnings a user should see.

#![warn(missing_docs)]

mod animation;
mod builtin;
mod camera_file;
mod error;
mod framing;
mod gltf_load;
mod manifest;
mod model;
mod obj;
mod place;
mod textures;
mod validate;

use std::path::Path;

pub use animation::Pose;
pub use builtin::{BUILTIN_SCENES, GLOWING_BOX_ALBEDO, GLOWING_BOX_EMISSION, builtin, xorshift};
pub use camera_file::{
    FOV_RANGE_DEGREES, camera_desc, camera_file_text, camera_from_desc, read_camera_file,
};
pub use error::{Result, SceneError};
pub use framing::camera_for_bounds;
pub use manifest::{
    AnimationDesc, CameraDesc, LightDesc, LightKindDesc, Manifest, MaterialDesc, MeshRef,
    ProbeVolumeManifest, RegionDesc,
};
pub use model::*;
pub use place::PlaceDesc;
pub use textures::{MAX_TEXTURE_SIDE, decode_texture};
pub use validate::{MAX_PROBES_PER_AXIS, validate};

/// A loaded scene and the warnings collected on the way (missing textures, unknown keys, …).
#[derive(Debug)]
pub struct Loaded {
    /// The scene, validated.
    pub scene: Scene,
    /// Problems that did not stop the load, one message each, for the user.
    pub warnings: Vec<String>,
}

/// Loads a built-in scene, a manifest or a mesh file, and validates it.
pub fn load(spec: &str) -> Result<Loaded> {
    let mut warnings = Vec::new();
    let path = Path::new(spec);
    let extension = path.extension().map(|e| e.to_string_lossy().to_lowercase());
    let mut scene = match extension.as_deref() {
        None => builtin(spec).ok_or_else(|| unknown(spec))?,
        Some("toml") => {
            let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
                path: path.to_owned(),
                source,
            })?;
            let manifest = Manifest::parse(&text, path, &mut warnings)?;
            let mut scene = match builtin(&manifest.mesh.path) {
                Some(scene) => scene,
                None => load_mesh_file(&manifest.mesh_path(path), &mut warnings)?,
            };
            let placed = (manifest.places.iter())
                .map(|place| match builtin(&place.path) {
                    Some(scene) => Ok(scene),
                    None => {
                        load_mesh_file(&manifest::relative_to(path, &place.path), &mut warnings)
                    }
                })
                .collect::<Result<Vec<_>>>()?;
            manifest.apply(&mut scene, path, placed)?;
            scene
        }
        Some(_) => load_mesh_file(path, &mut warnings)?,
    };
    validate::validate(&mut scene, path, &mut warnings)?;
    for w in &warnings {
        tracing::debug!("{w}");
    }
    Ok(Loaded { scene, warnings })
}

fn load_mesh_file(path: &Path, warnings: &mut Vec<String>) -> Result<Scene> {
    if !path.is_file() {
        return Err(SceneError::Io {
            path: path.to_owned(),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"),
        });
    }
    let extension = path.extension().map(|e| e.to_string_lossy().to_lowercase());
    let mut scene = match extension.as_deref() {
        Some("obj") => obj::load_obj(path, warnings)?,
        Some("gltf" | "glb") => gltf_load::load_gltf(path, warnings)?,
        _ => return Err(unknown(&path.display().to_string())),
    };
    if extension.as_deref() == Some("obj") {
        scene.camera = camera_for_bounds(&scene);
    }
    Ok(scene)
}

fn unknown(name: &str) -> SceneError {
    SceneError::Unknown {
        name: name.to_owned(),
        builtins: BUILTIN_SCENES
            .iter()
            .map(|(n, _)| *n)
            .collect::<Vec<_>>()
            .join(", "),
    }
}
