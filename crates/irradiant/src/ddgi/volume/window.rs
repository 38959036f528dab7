//! A volume that follows the camera (003 §7.3, a tracking window): each frame it moves in whole
//! cells to stay centred on its target. The grid is a circular buffer (`ProbeGrid::step`), so
//! a step copies nothing: the probes that stay keep their slots and their light, and only the
//! planes that enter start over (ddgi/window_enter): vigilant, nothing blended, relocated and
//! classified on frames of their own.

use glam::Vec3;
use irradiant_gpu::{Profiler, wgpu};
use irradiant_scene::{Follow, Pose, Scene};

use super::DdgiVolume;
use crate::ddgi::settings::RELOCATION_FRAMES;
use crate::probes::grid::EnteringPlanes;

/// What a volume follows, and its last step.
#[derive(Debug, Default)]
pub(super) struct Window {
    /// What the volume follows; None: it stays where it was put.
    pub follow: Option<Follow>,
    /// Where the followed instance's origin stands at the scene's last pose.
    instance_at: Option<Vec3>,
    /// The planes this frame's step brought in, until ddgi/window_enter has run.
    entering: Option<EnteringPlanes>,
    /// Frames left in which the probes that last entered are relocated on their own.
    pub fresh_frames: u32,
    /// Where the target stood at the last `follow`: the blend weights centre on it.
    target: Option<Vec3>,
    /// Steps taken since the volume was made (after its first frame), for measurements.
    steps: u64,
}

impl Window {
    /// A window that follows `follow`, or (None) one that stays.
    pub fn new(follow: Option<Follow>) -> Self {
        Self {
            follow,
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

    /// `GpuDdgiVolume::blend_centre`: the target, w 1, for a window that has one.
    pub fn blend_centre(&self) -> [f32; 4] {
        match (&self.follow, self.target) {
            (Some(_), Some(t)) => t.extend(1.0).to_array(),
            _ => [0.0; 4],
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
    /// Whether the volume follows the camera or an instance.
    pub fn follows(&self) -> bool {
        self.window.follow.is_some()
    }

    /// Steps its window took since the volume was made (after its first frame): a frame in
    /// which this grows brought planes in.
    pub fn window_steps(&self) -> u64 {
        self.window.steps
    }

    /// Notes where a followed instance stands at the scene's new pose (one removed since
    /// leaves the volume where it is).
    pub fn follow_pose(&mut self, scene: &Scene, pose: &Pose) {
        if let Some(Follow::Instance(name)) = &self.window.follow {
            let index = scene.instances.iter().position(|i| &i.name == name);
            self.window.instance_at = index
                .and_then(|i| pose.instance_transforms.get(i))
                .map(|t| t.w_axis.truncate());
        }
    }

    /// Moves a following volume onto its target (the camera at `camera`, or the followed
    /// instance) in whole cells, before [`DdgiVolume::prepare`] uploads the step; nothing for
    /// a volume that stays or a target near the centre (`ProbeGrid::cells_to_centre`).
    pub fn follow(&mut self, camera: Vec3) {
        let target = match &self.window.follow {
            None => return,
            Some(Follow::Camera) => camera,
            Some(Follow::Instance(_)) => match self.window.instance_at {
                Some(at) => at,
                None => return,
            },
        };
        self.window.target = Some(target);
        let cells = self.grid.cells_to_centre(target);
        if cells == glam::IVec3::ZERO {
            return;
        }
        let planes = self.grid.step(cells);
        if self.frame == 0 {
            // Nothing blended yet: the whole volume starts over anyway.
            return;
        }
        // A second step before ddgi/window_enter ran (it runs every frame, so never in
        // practice) would leave the first's planes in old coordinates: start them all over.
        self.window.entering = Some(match self.window.entering {
            Some(_) => EnteringPlanes {
                start: glam::UVec3::ZERO,
                end: self.grid.counts,
            },
            None => planes,
        });
        self.window.fresh_frames = RELOCATION_FRAMES;
        self.window.steps += 1;
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
