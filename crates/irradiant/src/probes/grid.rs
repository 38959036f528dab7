//! A regular grid of probes filling a box: where each probe sits. A grid may also move in
//! whole cells (a tracking window, 003 §7.3): its probes stay in their storage slots, and a
//! per-axis phase maps grid coordinates to slots as a 3D circular buffer, so a step copies
//! nothing and only the planes that enter start over.

use glam::{IVec3, UVec3, Vec3};
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
    /// Where grid coordinate (0, 0, 0) is stored: the slot of coordinate c along an axis is
    /// (c + phase) mod count. Zero until the grid steps.
    pub phase: UVec3,
}

/// Cells a target may stray from a window's centre before it steps (past half a cell, so
/// that no target can make it step back and forth).
const CENTRE_DEAD_ZONE: f32 = 0.75;

/// The grid coordinates a step brought in: along each axis, the planes `start..end` (empty
/// where the step did not move along it). A probe whose coordinate lies in any of them is new.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnteringPlanes {
    /// First entering coordinate along each axis.
    pub start: UVec3,
    /// One past the last.
    pub end: UVec3,
}

impl EnteringPlanes {
    /// Whether grid coordinate `coord` entered.
    pub fn contains(&self, coord: UVec3) -> bool {
        (coord.cmpge(self.start) & coord.cmplt(self.end)).any()
    }

    /// Whether the step brought in nothing.
    pub fn is_empty(&self) -> bool {
        self.start.cmpge(self.end).all()
    }
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
            phase: UVec3::ZERO,
        }
    }

    /// The smallest spacing of the three axes.
    pub fn min_spacing(&self) -> f32 {
        self.spacing.min_element()
    }

    /// Grid coordinates of the probe stored in slot `probe` (slots x fastest): the CPU twin
    /// of probes/grid.wgsl and, for a grid that steps, of ddgi/volume.wgsl's probe_grid_coord.
    pub fn coord(&self, probe: u32) -> UVec3 {
        let c = self.counts;
        let slot = UVec3::new(probe % c.x, (probe / c.x) % c.y, probe / (c.x * c.y));
        (slot + c - self.phase) % c
    }

    /// The slot of the probe at grid coordinates `coord`: the inverse of [`ProbeGrid::coord`].
    pub fn slot(&self, coord: UVec3) -> u32 {
        let c = self.counts;
        let s = (coord + self.phase) % c;
        s.x + c.x * (s.y + c.y * s.z)
    }

    /// Moves the grid by `cells` whole cells: the origin moves, the phase turns, and every
    /// probe still inside keeps its slot (and its light). Returns the planes that entered,
    /// whose slots held probes that left: all of them where a step reaches past the grid.
    pub fn step(&mut self, cells: IVec3) -> EnteringPlanes {
        let counts = self.counts.as_ivec3();
        let mut planes = EnteringPlanes::default();
        for axis in 0..3 {
            let (d, n) = (cells[axis], counts[axis]);
            let (start, end) = if d == 0 {
                (0, 0)
            } else if d.abs() >= n {
                (0, n)
            } else if d > 0 {
                (n - d, n)
            } else {
                (0, -d)
            };
            planes.start[axis] = start as u32;
            planes.end[axis] = end as u32;
            self.phase[axis] = (self.phase[axis] as i32 + d).rem_euclid(n) as u32;
        }
        self.origin += cells.as_vec3() * self.spacing;
        planes
    }

    /// The whole cells to step so that the grid stays centred on `target`: none while the
    /// target is within three quarters of a cell of the centre along an axis, so that a target
    /// resting on a cell's middle (where rounding would step back and forth each frame,
    /// starting the entering planes over every time) leaves the grid still.
    pub fn cells_to_centre(&self, target: Vec3) -> IVec3 {
        let extent = (self.counts.as_vec3() - 1.0) * self.spacing;
        let off_centre = (target - (self.origin + extent * 0.5)) / self.spacing;
        let cells = (off_centre.abs() + 1.0 - CENTRE_DEAD_ZONE)
            .floor()
            .max(Vec3::ZERO);
        (cells * off_centre.signum()).as_ivec3()
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
            follow: None,
        });
        assert_eq!(grid.probe_count, 15);
        assert_eq!(grid.probe_position(0), Vec3::new(-1.0, 0.0, 2.0));
        assert_eq!(grid.probe_position(14), Vec3::new(1.0, 4.0, 2.0));
        assert_eq!(grid.spacing.x, 1.0);
        assert_eq!(grid.coord(4), UVec3::new(1, 1, 0));
        assert_eq!(grid.bounds().1, Vec3::new(1.0, 4.0, 2.0));
    }

    fn grid(counts: [u32; 3]) -> ProbeGrid {
        ProbeGrid::new(&ProbeVolumeDesc::new(
            "window",
            Vec3::ZERO,
            Vec3::from(counts.map(|c| c as f32 - 1.0)) * 0.5,
            counts,
        ))
    }

    /// The circular buffer against the plain oracle through many steps in every direction:
    /// slots and coordinates stay inverse; a probe whose world position was in the grid before
    /// a step keeps its slot; the entering planes are exactly the positions that were not.
    #[test]
    fn a_window_keeps_every_probe_that_stays_in_its_slot_through_many_steps() {
        let mut g = grid([5, 3, 4]);
        // A fixed pseudo-random walk (a linear congruential sequence), steps of -6..6 cells
        // an axis: small ones, and ones past the grid.
        let mut seed = 12345u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 16) as i32 % 13 - 6
        };
        let key = |p: Vec3| (p * 2.0).round().as_ivec3();
        for _ in 0..400 {
            let before: std::collections::HashMap<IVec3, u32> = (0..g.probe_count)
                .map(|slot| (key(g.probe_position(slot)), slot))
                .collect();
            let cells = IVec3::new(next(), next() / 3, next());
            let planes = g.step(cells);
            for slot in 0..g.probe_count {
                let coord = g.coord(slot);
                assert_eq!(g.slot(coord), slot);
                let stayed = before.get(&key(g.probe_position(slot)));
                assert_eq!(stayed.is_none(), planes.contains(coord), "{cells} {coord}");
                if let Some(&old) = stayed {
                    assert_eq!(old, slot, "a probe that stayed moved slot");
                }
            }
            assert_eq!(planes.is_empty(), cells == IVec3::ZERO);
        }
    }

    #[test]
    fn a_window_centres_itself_on_the_target_in_whole_cells() {
        let mut g = grid([4, 4, 4]);
        let target = Vec3::new(10.2, -3.1, 0.7);
        let cells = g.cells_to_centre(target);
        g.step(cells);
        let (lo, hi) = g.bounds();
        let centre = (lo + hi) * 0.5;
        // Within the dead zone of three quarters of a cell (0.5 apart).
        assert!(
            (centre - target).abs().max_element() <= 0.75 * 0.5 + 1e-5,
            "{centre}"
        );
        assert_eq!(g.cells_to_centre(target), IVec3::ZERO);
        // A target on a cell's middle, and one creeping past it, step once and no more (a
        // rounding rule stepped back and forth there every frame).
        for creep in [0.0, 1e-4, 0.3, 0.37, 0.38, 0.6] {
            let mut g = grid([4, 4, 4]);
            let (lo, hi) = g.bounds();
            let mid = (lo + hi) * 0.5 + Vec3::new(0.25 + creep, 0.0, 0.0);
            let first = g.cells_to_centre(mid);
            g.step(first);
            assert_eq!(g.cells_to_centre(mid), IVec3::ZERO, "creep {creep}");
        }
        // The lattice stays: every probe sits on a multiple of the spacing.
        for slot in 0..g.probe_count {
            let p = g.probe_position(slot) / g.spacing;
            assert!((p - p.round()).abs().max_element() < 1e-4, "{p}");
        }
    }
}
