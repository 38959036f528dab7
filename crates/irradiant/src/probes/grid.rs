//! A regular grid of probes filling a box: where each probe sits.

use glam::{UVec3, Vec3};
use irradiant_scene::ProbeVolumeDesc;

/// Probes on a regular grid from a volume's `min` to `max` (a volume of count 1 along an axis
/// has its probe in the middle).
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeGrid {
    /// Position of probe (0, 0, 0).
    pub origin: Vec3,
    /// World distance between neighbouring probes along each axis (for an axis of one probe,
    /// the volume's extent).
    pub spacing: Vec3,
    /// Probes along each axis, at least 1.
    pub counts: UVec3,
    /// Probes in all: the product of `counts`.
    pub probe_count: u32,
}

impl ProbeGrid {
    /// The grid a volume description asks for.
    pub fn new(desc: &ProbeVolumeDesc) -> Self {
        let counts = UVec3::from(desc.counts).max(UVec3::ONE);
        let steps = (counts.as_vec3() - 1.0).max(Vec3::ONE);
        let extent = desc.max - desc.min;
        let single = counts.cmpeq(UVec3::ONE);
        Self {
            origin: Vec3::select(single, (desc.min + desc.max) * 0.5, desc.min),
            spacing: Vec3::select(single, extent.max(Vec3::splat(1e-3)), extent / steps),
            counts,
            probe_count: counts.x * counts.y * counts.z,
        }
    }

    /// The smallest spacing of the three axes.
    pub fn min_spacing(&self) -> f32 {
        self.spacing.min_element()
    }

    /// Grid coordinates of probe `probe` (x fastest): the CPU twin of probes/grid.wgsl.
    pub fn coord(&self, probe: u32) -> UVec3 {
        let c = self.counts;
        UVec3::new(probe % c.x, (probe / c.x) % c.y, probe / (c.x * c.y))
    }

    /// World position of probe `probe` (x fastest).
    pub fn probe_position(&self, probe: u32) -> Vec3 {
        self.origin + self.coord(probe).as_vec3() * self.spacing
    }

    /// The box the probes span (from the first probe to the last).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        (
            self.origin,
            self.origin + (self.counts.as_vec3() - 1.0) * self.spacing,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn probes_span_the_box_and_single_probes_sit_in_the_middle() {
        let grid = ProbeGrid::new(&ProbeVolumeDesc {
            name: "v".into(),
            min: Vec3::new(-1.0, 0.0, 2.0),
            max: Vec3::new(1.0, 4.0, 2.0),
            counts: [3, 5, 1],
        });
        assert_eq!(grid.probe_count, 15);
        assert_eq!(grid.probe_position(0), Vec3::new(-1.0, 0.0, 2.0));
        assert_eq!(grid.probe_position(14), Vec3::new(1.0, 4.0, 2.0));
        assert_eq!(grid.spacing.x, 1.0);
        assert_eq!(grid.coord(4), UVec3::new(1, 1, 0));
        assert_eq!(grid.bounds().1, Vec3::new(1.0, 4.0, 2.0));
    }
}
