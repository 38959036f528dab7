//! A volume that follows the camera (003 §7.3, a tracking window): each frame it moves in whole
//! cells to stay centred on its target. The grid is a circular buffer (`ProbeGrid::step`), so
//! a step copies nothing: the probes that stay keep their slots and their light, and only the
//! planes that enter start over (ddgi/window_enter): vigilant, nothing blended, relocated and
//! classified on frames of their own.

use glam::Vec3;
use irradiant_gpu::{Profiler, wgpu};

use super::DdgiVolume;
use crate::ddgi::settings::RELOCATION_FRAMES;
use crate::probes::grid::EnteringPlanes;

/// What a volume follows, and its last step.
#[derive(Debug, Default)]
pub(super) struct Window {
    /// Whether the volume follows the camera; false: it stays where it was put.
    pub follows: bool,
    /// The planes this frame's step brought in, until ddgi/window_enter has run.
    entering: Option<EnteringPlanes>,
    /// Frames left in which the probes that last entered are relocated on their own.
    pub fresh_frames: u32,
}

impl Window {
    /// A window that follows the camera where `follows`, else one that stays.
    pub fn new(follows: bool) -> Self {
        Self {
            follows,
            ..Default::default()
        }
    }

    /// `GpuDdgiVolume::entering_start`: w 1 on the frame of a step.
    pub fn entering_start(&self) -> [u32; 4] {
        match &self.entering {
            Some(p) => p.start.extend(1).to_array(),
            None => [0; 4],
        }
    }

    /// `GpuDdgiVolume::entering_end`: w the frames an entered probe stays fresh.
    pub fn entering_end(&self) -> [u32; 4] {
        match &self.entering {
            Some(p) => p.end.extend(RELOCATION_FRAMES).to_array(),
            None => [0; 4],
        }
    }
}

impl DdgiVolume {
    /// Whether the volume follows the camera.
    pub fn follows(&self) -> bool {
        self.window.follows
    }

    /// Moves a following volume onto `target` in whole cells (before [`DdgiVolume::prepare`],
    /// which uploads the step); nothing for a volume that stays or a target within half a
    /// cell of the centre.
    pub fn follow(&mut self, target: Vec3) {
        if !self.window.follows {
            return;
        }
        let cells = self.grid.cells_to_centre(target);
        if cells == glam::IVec3::ZERO {
            return;
        }
        let planes = self.grid.step(cells);
        if self.frame == 0 {
            // Nothing blended yet: the whole volume starts over anyway.
            return;
        }
        // A step over one not yet recorded brings in the planes of both.
        self.window.entering = Some(match self.window.entering.take() {
            Some(earlier) => EnteringPlanes {
                start: earlier.start.min(planes.start),
                end: earlier.end.max(planes.end),
            },
            None => planes,
        });
        self.window.fresh_frames = RELOCATION_FRAMES;
    }

    /// Records ddgi/window_enter on the frame of a step, before the probes trace (and on a
    /// cascade's frames off its turn, so that the query skips the entered probes until they
    /// have blended).
    pub fn record_window_enter(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
    ) {
        if self.window.entering.take().is_some() {
            self.passes
                .window_enter
                .dispatch(encoder, profiler, self.dispatches.probes);
        }
    }
}
