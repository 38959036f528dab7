//! Path-traced references, cached on disk under a hash of everything that shapes them, so that
//! a comparison renders each reference once. Entries are written under a temporary name and
//! renamed into place: a half-written entry is never read.

use std::hash::{Hash, Hasher};
use std::path::Path;

use irradiant::frame::Image;
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{GpuContext, GpuScene};

use crate::CliError;

/// The path-traced reference, from the cache when an entry for exactly this scene, view and
/// settings exists; otherwise rendered and stored.
#[allow(clippy::too_many_arguments)]
pub fn reference(
    ctx: &GpuContext,
    gpu_scene: &GpuScene,
    scene: &irradiant_scene::Scene,
    pose: &irradiant_scene::Pose,
    spec: &str,
    size: (u32, u32),
    settings: &PathTraceSettings,
    cache: Option<&Path>,
) -> Result<(Image, bool), CliError> {
    let key = reference_key(scene, pose, size, settings);
    let dir = crate::cache::dir(cache);
    let file = dir.join(format!("reference-{key:016x}.exr"));
    if let Ok(image) = Image::read_exr(&file, Some(size)) {
        return Ok((image, true));
    }
    eprintln!(
        "rendering the reference of {spec} ({} spp); it is cached in {}",
        settings.samples_per_pixel,
        dir.display()
    );
    let mut tracer = PathTracer::new(ctx, gpu_scene, size.0, size.1)?;
    let image = tracer.render(ctx, gpu_scene, &pose.camera, settings, |_, _| {})?;
    if std::fs::create_dir_all(&dir).is_ok() {
        // Image::write_exr writes a temporary file and renames it.
        let _ = image.write_exr(&file);
    }
    Ok((image, false))
}

/// A hash of everything that shapes the reference: geometry, materials, textures, lights,
/// camera, sky, size, the path tracer's settings and this program's version.
pub fn reference_key(
    scene: &irradiant_scene::Scene,
    pose: &irradiant_scene::Pose,
    size: (u32, u32),
    settings: &PathTraceSettings,
) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    env!("IRRADIANT_COMMIT").hash(&mut h);
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
        let key = |s: &irradiant_scene::Scene, size, p: &PathTraceSettings| {
            reference_key(s, &s.pose_at(0.0), size, p)
        };
        let base = key(&scene, (64, 64), &settings);
        assert_eq!(base, key(&scene, (64, 64), &settings));
        assert_ne!(base, key(&scene, (64, 48), &settings));
        assert_ne!(
            base,
            key(
                &scene,
                (64, 64),
                &PathTraceSettings {
                    seed: 1,
                    ..settings.clone()
                }
            )
        );
        let mut moved = scene.clone();
        moved.camera.position.x += 0.01;
        assert_ne!(base, key(&moved, (64, 64), &settings));
        let mut repainted = scene.clone();
        repainted.materials[0].base_color.x *= 0.5;
        assert_ne!(base, key(&repainted, (64, 64), &settings));
        let mut bent = scene.clone();
        bent.meshes[0].positions[0].y += 1e-3;
        assert_ne!(base, key(&bent, (64, 64), &settings));
    }
}
