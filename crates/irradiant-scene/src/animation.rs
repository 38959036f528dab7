//! Keyframe evaluation: the pose of the lights and instances at a time.

use glam::{Mat4, Vec3};

use crate::model::{AnimationTarget, Camera, Light, Scene};

/// What animation changes, at one instant. Everything else in the scene is static.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Every light of the scene at that instant, in [`Scene::lights`]' order.
    pub lights: Vec<Light>,
    /// Object-to-world transform of each instance, in [`Scene::instances`]' order.
    pub instance_transforms: Vec<Mat4>,
    /// The camera at that instant.
    pub camera: Camera,
}

impl Scene {
    /// The time of the last animation key (0 for a still scene): where every track has ended.
    pub fn animation_end(&self) -> f32 {
        self.animations
            .iter()
            .flat_map(|a| {
                let t = &a.tracks;
                t.translation
                    .iter()
                    .map(|k| k.0)
                    .chain(t.intensity_scale.iter().map(|k| k.0))
                    .chain(t.rotation_y_degrees.iter().map(|k| k.0))
            })
            .fold(0.0, f32::max)
    }

    /// The scene's lights and instance transforms at `time` seconds. Tracks are linearly
    /// interpolated and clamped at their first and last keys.
    pub fn pose_at(&self, time: f32) -> Pose {
        let mut pose = Pose {
            lights: self.lights.clone(),
            instance_transforms: self.instances.iter().map(|i| i.transform).collect(),
            camera: self.camera.clone(),
        };
        for animation in &self.animations {
            let tracks = &animation.tracks;
            let offset = sample(&tracks.translation, time, Vec3::ZERO, |a, b, t| {
                a.lerp(b, t)
            });
            let scale = sample(&tracks.intensity_scale, time, 1.0, |a, b, t| {
                a + (b - a) * t
            });
            let angle = sample(&tracks.rotation_y_degrees, time, 0.0, |a, b, t| {
                a + (b - a) * t
            });
            match &animation.target {
                AnimationTarget::Light(name) => {
                    for light in pose.lights.iter_mut().filter(|l| &l.name == name) {
                        light.position += offset;
                        light.direction = Mat4::from_rotation_y(angle.to_radians())
                            .transform_vector3(light.direction);
                        light.intensity *= scale;
                        if scale <= 0.0 {
                            light.enabled = false;
                        }
                    }
                }
                AnimationTarget::Instance(name) => {
                    for (i, instance) in self
                        .instances
                        .iter()
                        .enumerate()
                        .filter(|(_, i)| &i.name == name)
                    {
                        let rest = instance.transform;
                        pose.instance_transforms[i] = Mat4::from_translation(offset)
                            * rest
                            * Mat4::from_rotation_y(angle.to_radians());
                    }
                }
                AnimationTarget::Camera => {
                    let camera = &mut pose.camera;
                    let view = Mat4::from_rotation_y(angle.to_radians())
                        .transform_vector3(camera.target - camera.position);
                    camera.position += offset;
                    camera.target = camera.position + view;
                }
            }
        }
        pose
    }
}

fn sample<T: Copy>(keys: &[(f32, T)], time: f32, rest: T, lerp: impl Fn(T, T, f32) -> T) -> T {
    let Some(first) = keys.first() else {
        return rest;
    };
    if time <= first.0 {
        return first.1;
    }
    for pair in keys.windows(2) {
        let (t0, v0) = pair[0];
        let (t1, v1) = pair[1];
        if time <= t1 {
            let span = t1 - t0;
            return if span > 0.0 {
                lerp(v0, v1, (time - t0) / span)
            } else {
                v1
            };
        }
    }
    keys[keys.len() - 1].1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Animation, LightKind, Tracks};

    fn lamp_scene() -> Scene {
        let mut scene = Scene::default();
        scene.lights.push(Light {
            name: "lamp".into(),
            kind: LightKind::Point,
            position: Vec3::ZERO,
            direction: -Vec3::Y,
            color: Vec3::ONE,
            intensity: 10.0,
            enabled: true,
        });
        scene.animations.push(Animation {
            target: AnimationTarget::Light("lamp".into()),
            tracks: Tracks {
                translation: vec![(0.0, Vec3::ZERO), (2.0, Vec3::new(2.0, 0.0, 0.0))],
                intensity_scale: vec![(0.0, 1.0), (1.0, 1.0), (1.5, 0.0)],
                ..Default::default()
            },
        });
        scene
    }

    #[test]
    fn tracks_interpolate_and_clamp() {
        let scene = lamp_scene();
        assert_eq!(scene.pose_at(-1.0).lights[0].position, Vec3::ZERO);
        assert!((scene.pose_at(1.0).lights[0].position.x - 1.0).abs() < 1e-6);
        assert_eq!(scene.pose_at(5.0).lights[0].position.x, 2.0);
        assert!((scene.pose_at(1.25).lights[0].intensity - 5.0).abs() < 1e-5);
    }

    #[test]
    fn zero_intensity_switches_the_light_off() {
        let scene = lamp_scene();
        assert!(scene.pose_at(0.5).lights[0].enabled);
        let off = &scene.pose_at(1.5).lights[0];
        assert!(!off.enabled);
        assert_eq!(off.power(), Vec3::ZERO);
    }

    /// A camera track pans the view about the camera's position and dollies position and
    /// target together; a manifest's `camera = true` names it.
    #[test]
    fn a_camera_track_pans_and_dollies_the_view() {
        let manifest = r#"
            [mesh]
            path = "cornell"
            [[animation]]
            camera = true
            rotation_y_degrees = [[0, 0], [1, 90]]
            translation = [[1, 0, 0, 0], [2, 0, 1, 0]]
        "#;
        let path = std::path::Path::new("pan.toml");
        let mut scene = crate::builtin::builtin("cornell").unwrap();
        crate::manifest::Manifest::parse(manifest, path, &mut Vec::new())
            .unwrap()
            .apply(&mut scene, path, Vec::new())
            .unwrap();
        let rest = scene.camera.clone();
        assert_eq!(scene.pose_at(0.0).camera, rest);
        let panned = scene.pose_at(1.0).camera;
        assert_eq!(panned.position, rest.position);
        let (before, after) = (rest.target - rest.position, panned.target - panned.position);
        assert!((before.length() - after.length()).abs() < 1e-5);
        assert!(
            before.dot(after).abs() < 1e-4 * before.length_squared(),
            "a quarter turn: {before} → {after}"
        );
        let moved = scene.pose_at(2.0).camera;
        assert!((moved.position - rest.position - Vec3::Y).length() < 1e-6);
        assert!((moved.target - moved.position - after).length() < 1e-5);
        assert_eq!(scene.pose_at(2.0).lights, scene.pose_at(0.0).lights);
    }
}
