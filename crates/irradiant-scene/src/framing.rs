//! A camera for scenes that bring none.

use glam::Vec3;

use crate::model::{Camera, Scene};

/// Looks at the centre of the scene's bounds from +z, far enough that the whole box is in view.
pub fn camera_for_bounds(scene: &Scene) -> Camera {
    let (lo, hi) = scene.bounds();
    if !lo.is_finite() || !hi.is_finite() {
        return Camera::default();
    }
    let center = (lo + hi) * 0.5;
    let radius = ((hi - lo) * 0.5).length().max(1e-3);
    let fov_y_degrees: f32 = 45.0;
    let distance = radius / (fov_y_degrees.to_radians() * 0.5).sin();
    Camera {
        position: center + Vec3::Z * distance,
        target: center,
        up: Vec3::Y,
        fov_y_degrees,
    }
}
