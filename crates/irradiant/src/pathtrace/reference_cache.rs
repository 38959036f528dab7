//! Path-traced references cached on disk under a hash of everything that shapes them, so that
//! `irradiant compare` and the viewer's truth key render each reference once. Entries are
//! written under a temporary name and renamed into place: a half-written entry is never read.

use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

use crate::frame::Image;
use crate::pathtrace::PathTraceSettings;

/// `explicit` (--cache), else $XDG_CACHE_HOME/irradiant, ~/.cache/irradiant, or the temporary
/// directory.
pub fn cache_dir(explicit: Option<&Path>) -> PathBuf {
    explicit
        .map(Path::to_owned)
        .or_else(|| {
            std::env::var_os("XDG_CACHE_HOME")
                .map(PathBuf::from)
                .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
                .map(|d| d.join("irradiant"))
        })
        .unwrap_or_else(|| std::env::temp_dir().join("irradiant-cache"))
}

/// One reference's place in the cache: the file its key names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReferenceEntry {
    /// The hash of everything that shapes the reference.
    pub key: u64,
    /// `reference-KEY.exr` in the cache directory.
    pub file: PathBuf,
}

impl ReferenceEntry {
    /// The entry of a reference of `scene` at `pose`, `size` pixels, `settings`, rendered by
    /// `build` (the program's version and commit: a new build renders anew, as its path
    /// tracer may differ).
    pub fn new(
        dir: &Path,
        scene: &irradiant_scene::Scene,
        pose: &irradiant_scene::Pose,
        size: (u32, u32),
        settings: &PathTraceSettings,
        build: &str,
    ) -> Self {
        let key = reference_key(scene, pose, size, settings, build);
        Self {
            key,
            file: dir.join(format!("reference-{key:016x}.exr")),
        }
    }

    /// The cached image, if an entry of this size exists.
    pub fn load(&self, size: (u32, u32)) -> Option<Image> {
        Image::read_exr(&self.file, Some(size)).ok()
    }

    /// Stores `image`; a cache that cannot be written is skipped (the reference is rendered
    /// again next time), never an error.
    pub fn store(&self, image: &Image) {
        if let Some(dir) = self.file.parent()
            && std::fs::create_dir_all(dir).is_ok()
        {
            // Image::write_exr writes a temporary file and renames it.
            let _ = image.write_exr(&self.file);
        }
    }
}

/// A hash of everything that shapes the reference: geometry, materials, textures, lights,
/// camera, sky, size, the path tracer's settings and the build.
pub fn reference_key(
    scene: &irradiant_scene::Scene,
    pose: &irradiant_scene::Pose,
    size: (u32, u32),
    settings: &PathTraceSettings,
    build: &str,
) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    build.hash(&mut h);
    size.hash(&mut h);
    format!("{settings:?}").hash(&mut h);
    scene.hash_content(&mut h);
    format!("{pose:?}").hash(&mut h);
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_key_changes_with_everything_that_shapes_the_reference() {
        let scene = irradiant_scene::builtin("cornell").unwrap();
        let settings = PathTraceSettings::fast();
        let key = |s: &irradiant_scene::Scene, size, p: &PathTraceSettings, build| {
            reference_key(s, &s.pose_at(0.0), size, p, build)
        };
        let base = key(&scene, (64, 64), &settings, "a");
        assert_eq!(base, key(&scene, (64, 64), &settings, "a"));
        assert_ne!(base, key(&scene, (64, 64), &settings, "b"));
        assert_ne!(base, key(&scene, (64, 48), &settings, "a"));
        let reseeded = PathTraceSettings {
            seed: 1,
            ..settings.clone()
        };
        assert_ne!(base, key(&scene, (64, 64), &reseeded, "a"));
        let mut moved = scene.clone();
        moved.camera.position.x += 0.01;
        assert_ne!(base, key(&moved, (64, 64), &settings, "a"));
        let mut repainted = scene.clone();
        repainted.materials[0].base_color.x *= 0.5;
        assert_ne!(base, key(&repainted, (64, 64), &settings, "a"));
        let mut bent = scene.clone();
        bent.meshes[0].positions[0].y += 1e-3;
        assert_ne!(base, key(&bent, (64, 64), &settings, "a"));
        // The same texels in another shape.
        let textured = |width, height| {
            let mut s = scene.clone();
            s.textures.push(irradiant_scene::Texture {
                name: "shape".into(),
                width,
                height,
                rgba8: vec![7; 8],
            });
            key(&s, (64, 64), &settings, "a")
        };
        assert_ne!(textured(2, 1), textured(1, 2));
        // A light switched off (the viewer's lights) is another reference.
        let lamp = irradiant_scene::builtin("two-rooms").unwrap();
        let lit = lamp.pose_at(0.0);
        let mut dark = lit.clone();
        dark.lights[0].enabled = false;
        assert_ne!(
            reference_key(&lamp, &lit, (64, 64), &settings, "a"),
            reference_key(&lamp, &dark, (64, 64), &settings, "a")
        );
    }
}
