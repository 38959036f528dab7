//! Probe code shared by the probe techniques (DDGI now, light-field probes next): grids of
//! probes, octahedral maps with their border texels, probe ray sets, atlas layouts and the
//! copies of atlas buffers into textures — each with its WGSL twin (`probe_grid`,
//! `octahedral`, `probe_atlas` in the shader library), and the constants both sides share
//! (`probe_constants`).

pub mod atlas;
pub mod constants;
pub mod grid;
pub mod octahedral;
pub mod rays;

pub use atlas::AtlasLayout;
pub use grid::ProbeGrid;

use irradiant_scene::{ProbeVolumeDesc, Scene};

/// The probe volumes a probe technique fills for a scene: the scene's own (its manifest's
/// `[[probe_volume]]` tables), or, when it names none, one volume over the scene's bounds.
/// The one place a default volume is chosen.
pub fn volumes_of(scene: &Scene) -> Vec<ProbeVolumeDesc> {
    if scene.probe_volumes.is_empty() {
        vec![default_volume(scene)]
    } else {
        scene.probe_volumes.clone()
    }
}

/// About 8 probes along the scene's longest side, inset half a cell from its bounds.
pub fn default_volume(scene: &Scene) -> ProbeVolumeDesc {
    let (lo, hi) = scene.bounds();
    let extent = (hi - lo).max(glam::Vec3::splat(1e-3));
    let step = extent.max_element() / 8.0;
    let counts = (extent / step)
        .ceil()
        .as_uvec3()
        .max(glam::UVec3::splat(2))
        .min(glam::UVec3::splat(32));
    let inset = extent / counts.as_vec3() * 0.5;
    ProbeVolumeDesc {
        name: "auto".into(),
        min: lo + inset,
        max: hi - inset,
        counts: counts.into(),
        follow: None,
    }
}
