//! What changed between two poses of the scene: how a change reaches the techniques that adapt
//! to it (DDGI lowers its hysteresis for a while, 003 §4.3).

use irradiant_scene::Pose;

/// How much the lighting changed between two poses (003 §4.3's scene-level heuristics).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum LightingChange {
    /// No light changed.
    #[default]
    None,
    /// A light moved, turned, or changed its power by less than half.
    Small,
    /// A light switched on or off, or its power changed by half or more.
    Large,
}

/// What changed between two poses of the scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneChange {
    /// How much the lights changed: the largest change of any one light.
    pub lighting: LightingChange,
    /// An instance moved.
    pub geometry: bool,
    /// World bounds of every animated instance at the new pose (GpuScene::dynamic_bounds).
    pub dynamic_bounds: Vec<(glam::Vec3, glam::Vec3)>,
}

impl SceneChange {
    /// Compares the lights and instance transforms of two poses; `dynamic_bounds` is left
    /// empty for the caller to fill.
    pub fn between(old: &Pose, new: &Pose) -> Self {
        let mut lighting = LightingChange::None;
        for (a, b) in old.lights.iter().zip(&new.lights) {
            let (pa, pb) = (a.power().max_element(), b.power().max_element());
            let change = if a == b {
                LightingChange::None
            } else if (pa > 0.0) != (pb > 0.0) || (pa - pb).abs() >= 0.5 * pa.max(pb) {
                LightingChange::Large
            } else if a != b {
                LightingChange::Small
            } else {
                LightingChange::None
            };
            lighting = lighting.max(change);
        }
        Self {
            lighting,
            geometry: old.instance_transforms != new.instance_transforms,
            dynamic_bounds: Vec::new(),
        }
    }

    /// True when neither the lighting nor the geometry changed.
    pub fn is_empty(&self) -> bool {
        self.lighting == LightingChange::None && !self.geometry
    }
}
