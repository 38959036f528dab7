//! A camera in a file of its own, so that a view seen in one command (`render --save-camera`,
//! the viewer's bookmarks) can be rendered or compared by another (`--camera-from`).
//!
//! The file is TOML with a `[camera]` table, the same table a scene manifest holds, so a
//! manifest is a camera file too:
//!
//! ```toml
//! [camera]
//! position = [0.0, 1.0, 3.4]
//! target = [0.0, 1.0, 0.0]
//! up = [0.0, 1.0, 0.0]        # optional: y up
//! fov_y_degrees = 45.0        # optional: 40
//! ```

use std::path::Path;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::{Camera, CameraDesc, SceneError};

/// Narrowest and widest vertical field of view a camera may have, in degrees: past them the
/// projection degenerates.
pub const FOV_RANGE_DEGREES: (f32, f32) = (0.5, 179.0);

#[derive(Serialize, Deserialize)]
struct CameraFile {
    camera: Option<CameraDesc>,
}

/// A camera as a description: what a camera file and a manifest's `[camera]` hold.
pub fn camera_desc(camera: &Camera) -> CameraDesc {
    CameraDesc {
        position: camera.position.into(),
        target: camera.target.into(),
        up: Some(camera.up.into()),
        fov_y_degrees: Some(camera.fov_y_degrees),
    }
}

/// The camera a description places, checked: finite numbers, a target apart from the position,
/// an up direction not along the view, and a field of view in [`FOV_RANGE_DEGREES`]. `origin`
/// names where the description came from in the error.
pub fn camera_from_desc(desc: &CameraDesc, origin: &Path) -> Result<Camera, SceneError> {
    let camera = Camera {
        position: desc.position.into(),
        target: desc.target.into(),
        up: desc.up.map(Vec3::from).unwrap_or(Vec3::Y),
        fov_y_degrees: desc
            .fov_y_degrees
            .unwrap_or(Camera::default().fov_y_degrees),
    };
    let invalid = |problem: String, fix: &str| SceneError::Invalid {
        path: origin.to_owned(),
        problem,
        fix: fix.into(),
    };
    let finite = [camera.position, camera.target, camera.up]
        .iter()
        .all(|v| v.is_finite())
        && camera.fov_y_degrees.is_finite();
    if !finite {
        return Err(invalid(
            "the camera holds a number that is not finite".into(),
            "Write finite numbers for position, target, up and fov_y_degrees.",
        ));
    }
    let view = camera.target - camera.position;
    if view.length() < 1e-6 {
        return Err(invalid(
            "the camera's target is its position, so it looks nowhere".into(),
            "Move the target away from the position.",
        ));
    }
    if camera.up.cross(view).length() < 1e-6 * view.length() * camera.up.length().max(1e-30) {
        return Err(invalid(
            "the camera's up direction is zero or along its view".into(),
            "Give an up direction across the view, e.g. up = [0, 1, 0].",
        ));
    }
    let (narrowest, widest) = FOV_RANGE_DEGREES;
    if !(narrowest..=widest).contains(&camera.fov_y_degrees) {
        return Err(invalid(
            format!(
                "fov_y_degrees = {} is outside {narrowest}…{widest}",
                camera.fov_y_degrees
            ),
            "Give a vertical field of view in degrees within that range, e.g. 45.",
        ));
    }
    Ok(camera)
}

/// Reads the `[camera]` table of a TOML file (a camera file or a scene manifest; other tables
/// are ignored).
pub fn read_camera_file(path: &Path) -> Result<Camera, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
        path: path.to_owned(),
        source,
    })?;
    let file: CameraFile = toml::from_str(&text).map_err(|e| SceneError::Invalid {
        path: path.to_owned(),
        problem: format!("not a camera file: {}", e.message()),
        fix: "Write a [camera] table with position = [x, y, z] and target = [x, y, z] \
              (as `irradiant render --save-camera` writes)."
            .into(),
    })?;
    let desc = file.camera.ok_or_else(|| SceneError::Invalid {
        path: path.to_owned(),
        problem: "the file has no [camera] table".into(),
        fix: "Add a [camera] table with position and target, or name a file \
              `irradiant render --save-camera` wrote."
            .into(),
    })?;
    camera_from_desc(&desc, path)
}

/// The text of a camera file holding `camera`.
pub fn camera_file_text(camera: &Camera) -> String {
    toml::to_string(&CameraFile {
        camera: Some(camera_desc(camera)),
    })
    .expect("a camera serialises to TOML")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads `text` as a camera file, written to a file of its own for each call (the tests run
    /// in parallel).
    fn read(text: &str) -> Result<Camera, SceneError> {
        static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let path =
            std::env::temp_dir().join(format!("irradiant-camera-{}-{n}.toml", std::process::id()));
        std::fs::write(&path, text).unwrap();
        let camera = read_camera_file(&path);
        std::fs::remove_file(&path).unwrap();
        camera
    }

    #[test]
    fn a_written_camera_reads_back_the_same() {
        let camera = Camera {
            position: Vec3::new(1.5, 2.0, -3.25),
            target: Vec3::new(0.0, 1.0, 0.5),
            up: Vec3::Y,
            fov_y_degrees: 60.0,
        };
        assert_eq!(read(&camera_file_text(&camera)).unwrap(), camera);
        // A manifest's [camera] with other tables beside it, up and field of view left out.
        let from_manifest =
            read("[mesh]\npath = \"x.obj\"\n[camera]\nposition = [0, 1, 3]\ntarget = [0, 1, 0]\n")
                .unwrap();
        assert_eq!(from_manifest.up, Vec3::Y);
        assert_eq!(from_manifest.fov_y_degrees, Camera::default().fov_y_degrees);
    }

    #[test]
    fn bad_cameras_name_the_problem_and_the_fix() {
        for (text, expected) in [
            (
                "[camera]\nposition = [0, 0, 0]\ntarget = [0, 0, 0]\n",
                "target is its position",
            ),
            (
                "[camera]\nposition = [0, 0, 0]\ntarget = [0, 1, 0]\n",
                "along its view",
            ),
            (
                "[camera]\nposition = [0, 0, 0]\ntarget = [0, 0, 1]\nfov_y_degrees = 200\n",
                "outside",
            ),
            (
                "[camera]\nposition = [0, nan, 0]\ntarget = [0, 0, 1]\n",
                "not finite",
            ),
            ("[view]\nposition = [0, 0, 0]\n", "no [camera] table"),
            ("[camera]\nposition = \"here\"\n", "not a camera file"),
        ] {
            let e = read(text).unwrap_err().to_string();
            assert!(e.contains(expected), "{text}: {e}");
        }
        let missing = read_camera_file(Path::new("/nonexistent/view.toml"))
            .unwrap_err()
            .to_string();
        assert!(missing.contains("/nonexistent/view.toml"), "{missing}");
    }
}
