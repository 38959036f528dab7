//! Path-traced references for the command line, through the library's on-disk cache
//! (irradiant::pathtrace::reference_cache), so that a comparison renders each reference once.

use std::path::Path;

use irradiant::frame::Image;
use irradiant::pathtrace::reference_cache::{ReferenceEntry, cache_dir};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{GpuContext, GpuScene};

use crate::CliError;

/// The program's version and commit: a reference rendered by another build is rendered anew.
pub const BUILD: &str = concat!(env!("CARGO_PKG_VERSION"), "+", env!("IRRADIANT_COMMIT"));

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
    let dir = cache_dir(cache);
    let entry = ReferenceEntry::new(&dir, scene, pose, size, settings, BUILD);
    if let Some(image) = entry.load(size) {
        return Ok((image, true));
    }
    eprintln!(
        "rendering the reference of {spec} ({} spp); it is cached in {}",
        settings.samples_per_pixel,
        dir.display()
    );
    let mut tracer = PathTracer::new(ctx, gpu_scene, size.0, size.1)?;
    let image = tracer.render(ctx, gpu_scene, &pose.camera, settings, |_, _| {})?;
    entry.store(&image);
    Ok((image, false))
}
