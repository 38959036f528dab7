//! The workgroups of a volume's dispatches, from its grid, settings and the image size.

use irradiant_gpu::Workgroups;

use crate::ddgi::settings::DdgiSettings;
use crate::frame::IMAGE_TILE;
use crate::probes::ProbeGrid;

/// The workgroups of each of a volume's dispatches: one function, used to record them and by
/// the test that every dispatch fits the adapter at the largest sizes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DdgiDispatches {
    /// ddgi/ray_directions (one thread a ray of the set).
    pub ray_directions: Workgroups,
    /// ddgi/trace and ddgi/shade (one thread a probe ray) when every probe updates: they are
    /// dispatched indirectly over the probes that do (`DdgiResources::active_probes`), which
    /// starts as this.
    pub rays: Workgroups,
    /// ddgi/relocate and ddgi/probe_states (one thread a probe).
    pub probes: Workgroups,
    /// ddgi/blend_weights (one workgroup a tile texel, irradiance and distance).
    pub blend_weights: Workgroups,
    /// The blends: one workgroup a probe (as `rays`, the most of an indirect dispatch).
    pub blends: Workgroups,
    /// ddgi/trace when every probe updates: `rays`, or where its lanes fetch a workgroup a run
    /// of the probe rays (`crate::shaders::fetch_dispatch`; at most `rays`).
    pub trace: Workgroups,
    /// ddgi/resolve and ddgi/visualize over the image.
    pub image: Workgroups,
}

impl DdgiDispatches {
    /// The dispatches of a volume of this grid, with these settings, at this image size;
    /// `fetches`: ddgi/trace's lanes fetch their rays (`DdgiSettings::fetches_rays`).
    pub fn new(
        grid: &ProbeGrid,
        settings: &DdgiSettings,
        (width, height): (u32, u32),
        fetches: bool,
    ) -> Self {
        let v = &settings.volume;
        let per_group = settings.speed.probes_per_group;
        let ray_groups = grid.probe_count.div_ceil(per_group) as u64
            * v.rays_per_probe.div_ceil(64 / per_group) as u64;
        let probe_rays = grid.probe_count as u64 * v.rays_per_probe as u64;
        let trace = match fetches {
            true => crate::shaders::fetch_dispatch(probe_rays, settings.speed.fetch_workgroups),
            false => Workgroups::linear(ray_groups),
        };
        Self {
            trace,
            ray_directions: Workgroups::for_threads(v.rays_per_probe as u64, 64),
            rays: Workgroups::linear(ray_groups),
            probes: Workgroups::for_threads(grid.probe_count as u64, 64),
            blend_weights: Workgroups::linear(
                (v.irradiance_texels.pow(2) + v.distance_texels.pow(2)) as u64,
            ),
            blends: Workgroups::linear(grid.probe_count as u64),
            image: Workgroups::for_image(width, height, IMAGE_TILE),
        }
    }

    /// Every dispatch with its pass label.
    pub fn all(&self) -> Vec<(&'static str, Workgroups)> {
        vec![
            ("ddgi/ray_directions", self.ray_directions),
            ("ddgi/trace", self.trace),
            ("ddgi/shade", self.rays),
            ("ddgi/between_volumes", self.rays),
            ("ddgi/relocate", self.probes),
            ("ddgi/window_enter", self.probes),
            ("ddgi/probe_states", self.probes),
            ("ddgi/blend_weights", self.blend_weights),
            ("ddgi/blend_irradiance", self.blends),
            ("ddgi/blend_distance", self.blends),
            ("ddgi/resolve", self.image),
            ("ddgi/visualize", self.image),
            ("ddgi/visualize_states", self.image),
        ]
    }
}
