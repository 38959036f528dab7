//! The fly camera: a position, a heading (yaw) and a pitch, moved by the keys and turned by the
//! mouse, converted to and from the scene's look-at [`Camera`] so that a view seen here can be
//! saved as a camera file and rendered from the command line.

use glam::Vec3;
use irradiant_scene::Camera;

/// Steepest pitch, in radians: just short of straight up or down, where the heading would be
/// lost.
const MAX_PITCH: f32 = 1.55;
/// Radians the view turns a pixel of mouse movement.
pub const LOOK_RADIANS_PER_PIXEL: f32 = 0.003;
/// How much each wheel notch multiplies the speed by.
pub const SPEED_STEP: f32 = 1.25;
/// How much faster Shift moves.
pub const FAST_FACTOR: f32 = 4.0;

/// The movement keys held this frame: each axis −1, 0 or 1 (forward, right, up).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Movement {
    /// W minus S.
    pub forward: f32,
    /// D minus A.
    pub right: f32,
    /// E minus Q.
    pub up: f32,
    /// Shift: move [`FAST_FACTOR`] times faster.
    pub fast: bool,
}

/// A camera that flies: y up, yaw about y, pitch about the camera's right axis.
#[derive(Clone, Debug, PartialEq)]
pub struct FlyCamera {
    /// Where the eye is, in scene units.
    pub position: Vec3,
    /// Heading in radians: 0 looks down −z, positive turns left (counter-clockwise from above).
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
    /// Vertical field of view, degrees.
    pub fov_y_degrees: f32,
    /// Scene units a second.
    pub speed: f32,
}

impl FlyCamera {
    /// The fly camera looking as `camera` does, moving at `speed` units a second (a tenth of
    /// the scene's size a second is a good start).
    pub fn from_camera(camera: &Camera, speed: f32) -> Self {
        let d = (camera.target - camera.position).normalize_or(Vec3::NEG_Z);
        Self {
            position: camera.position,
            yaw: (-d.x).atan2(-d.z),
            pitch: d.y.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH),
            fov_y_degrees: camera.fov_y_degrees,
            speed,
        }
    }

    /// The unit vector the camera looks along.
    pub fn forward(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(-sy * cp, sp, -cy * cp)
    }

    /// The camera as the scene describes cameras: looking at a point a unit ahead, y up.
    pub fn camera(&self) -> Camera {
        Camera {
            position: self.position,
            target: self.position + self.forward(),
            up: Vec3::Y,
            fov_y_degrees: self.fov_y_degrees,
        }
    }

    /// Turns the view by a mouse movement of (dx, dy) pixels (right and down positive).
    pub fn look(&mut self, dx: f32, dy: f32) {
        self.yaw -= dx * LOOK_RADIANS_PER_PIXEL;
        self.pitch = (self.pitch - dy * LOOK_RADIANS_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves for `seconds` with the keys held: forward along the view, right level with the
    /// ground, up along y. Returns whether it moved.
    pub fn step(&mut self, movement: Movement, seconds: f32) -> bool {
        let forward = self.forward();
        let right = forward.cross(Vec3::Y).normalize_or(Vec3::X);
        let direction = forward * movement.forward + right * movement.right + Vec3::Y * movement.up;
        if direction == Vec3::ZERO || seconds <= 0.0 {
            return false;
        }
        let speed = self.speed * if movement.fast { FAST_FACTOR } else { 1.0 };
        self.position += direction.normalize() * speed * seconds;
        true
    }

    /// Faster or slower by `notches` wheel notches (up faster).
    pub fn change_speed(&mut self, notches: f32) {
        self.speed = (self.speed * SPEED_STEP.powf(notches)).clamp(1e-3, 1e5);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn a_camera_round_trips_through_the_fly_camera() {
        for target in [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(3.0, 0.5, 1.0),
            Vec3::new(-2.0, 4.0, 5.0),
        ] {
            let camera = Camera::looking_at(Vec3::new(0.5, 1.0, 3.0), target, 50.0);
            let fly = FlyCamera::from_camera(&camera, 1.0);
            let back = fly.camera();
            let expected = (target - camera.position).normalize();
            assert!(close(back.target - back.position, expected), "{target}");
            assert_eq!(back.position, camera.position);
            assert_eq!(back.fov_y_degrees, 50.0);
        }
    }

    #[test]
    fn keys_move_along_the_view_and_the_mouse_turns_it() {
        let camera = Camera::looking_at(Vec3::ZERO, Vec3::NEG_Z, 45.0);
        let mut fly = FlyCamera::from_camera(&camera, 2.0);
        let w = Movement {
            forward: 1.0,
            ..Default::default()
        };
        assert!(fly.step(w, 0.5));
        assert!(close(fly.position, Vec3::new(0.0, 0.0, -1.0)));
        let d = Movement {
            right: 1.0,
            fast: true,
            ..Default::default()
        };
        fly.step(d, 0.25);
        assert!(
            close(fly.position, Vec3::new(2.0, 0.0, -1.0)),
            "{}",
            fly.position
        );
        assert!(!fly.step(Movement::default(), 1.0));
        // A quarter turn to the right: the view now looks down +x.
        fly.look(std::f32::consts::FRAC_PI_2 / LOOK_RADIANS_PER_PIXEL, 0.0);
        assert!(close(fly.forward(), Vec3::X), "{}", fly.forward());
        // Looking far past straight up stops short of it.
        fly.look(0.0, -1e6);
        assert!(fly.pitch <= MAX_PITCH && fly.forward().y > 0.99);
        fly.change_speed(2.0);
        assert!((fly.speed - 2.0 * SPEED_STEP * SPEED_STEP).abs() < 1e-5);
    }
}
