//! A host changes its scene between frames (issue 40): instances added, moved and removed with
//! ids that outlive other removals, past the headroom too; lights replaced; the sky changed;
//! and whatever cannot be used refused by name.

mod common;

use common::*;
use glam::{Mat4, Quat, Vec3};
use irradiant::{GpuSceneSettings, Session, SessionSettings};

/// A small copy of the Cornell box (its mesh 0) in the middle of the room, or `aside` of it.
fn small_box(aside: f32) -> Mat4 {
    Mat4::from_scale_rotation_translation(
        Vec3::splat(0.2),
        Quat::IDENTITY,
        Vec3::new(aside, 0.8, 0.0),
    )
}

fn cornell_session(scene: irradiant_scene::Scene, instance_headroom: u32) -> Option<Session> {
    let ctx = gpu()?;
    Some(
        Session::new(
            ctx,
            scene,
            SessionSettings {
                size: (32, 32),
                frame: irradiant::frame::FrameSettings::default().without_taa(),
                technique: spec(Some(&irradiant::ddgi::DdgiSettings::fast())),
                scene: GpuSceneSettings {
                    instance_headroom,
                    ..Default::default()
                },
                ..Default::default()
            },
        )
        .unwrap(),
    )
}

fn centre_depth(s: &mut Session) -> f32 {
    s.render().unwrap();
    s.gbuffer().unwrap()[16 * 32 + 16].depth
}

/// A host moves its objects by hand: the frame sees the instance where it was put, the pose
/// says so, and an id or a transform that cannot be used is refused by name.
#[test]
fn an_instance_moved_by_hand_is_seen_where_it_was_put() {
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    scene.instances.push(irradiant_scene::Instance {
        name: "small".into(),
        mesh: 0,
        transform: small_box(0.0),
    });
    let Some(mut s) = cornell_session(scene, 0) else {
        return;
    };
    let before = centre_depth(&mut s);
    s.set_instance_transform(1, small_box(5.0)).unwrap();
    assert_eq!(s.pose().instance_transforms[1], small_box(5.0));
    let after = centre_depth(&mut s);
    assert!(
        after > before + 0.5,
        "the centre saw {before} before and {after} after"
    );
    let e = s.set_instance_transform(2, small_box(5.0)).unwrap_err();
    let e = e.to_string();
    assert!(
        e.contains("instance 2 does not exist") && e.contains("[0, 1]"),
        "{e}"
    );
    let flat = Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0));
    let e = s.set_instance_transform(1, flat).unwrap_err().to_string();
    assert!(e.contains("not invertible"), "{e}");
    let mut nan = small_box(5.0);
    nan.w_axis.x = f32::NAN;
    assert!(s.set_instance_transform(1, nan).is_err());
}

/// Instances come and go: one added within the headroom, one past it (the scene's buffers
/// built anew), one removed; the others keep their ids and places.
#[test]
fn instances_are_added_and_removed_between_frames_with_ids_that_stay() {
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let Some(mut s) = cornell_session(scene, 1) else {
        return;
    };
    let empty_room = centre_depth(&mut s);
    let centre = s.add_instance(0, small_box(0.0), "small").unwrap();
    assert_eq!(s.instance_ids(), &[0, centre]);
    let blocked = centre_depth(&mut s);
    assert!(blocked < empty_room - 0.5, "{blocked} against {empty_room}");
    // Past the headroom of one: built anew, and the first stays where it was.
    let aside = s.add_instance(0, small_box(-5.0), "").unwrap();
    assert_eq!(s.scene().instances[2].name, format!("instance-{aside}"));
    assert!((centre_depth(&mut s) - blocked).abs() < 1e-3);
    s.remove_instance(centre).unwrap();
    assert_eq!(s.instance_ids(), &[0, aside]);
    assert_eq!(s.pose().instance_transforms.len(), 2);
    assert!((centre_depth(&mut s) - empty_room).abs() < 1e-3);
    // The other's id still names it.
    s.set_instance_transform(aside, small_box(0.0)).unwrap();
    assert!((centre_depth(&mut s) - blocked).abs() < 1e-3);

    let e = s
        .add_instance(7, Mat4::IDENTITY, "")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("mesh 7 does not exist") && e.contains("1 meshes"),
        "{e}"
    );
    let name = format!("instance-{aside}");
    let e = s
        .add_instance(0, Mat4::IDENTITY, &name)
        .unwrap_err()
        .to_string();
    assert!(e.contains("exists already"), "{e}");
    let e = s
        .add_instance(0, Mat4::ZERO, "zero")
        .unwrap_err()
        .to_string();
    assert!(e.contains("not invertible"), "{e}");
    let e = s.remove_instance(centre).unwrap_err().to_string();
    assert!(
        e.contains(&format!("instance {centre} does not exist")),
        "{e}"
    );
    s.remove_instance(0).unwrap();
    let e = s.remove_instance(aside).unwrap_err().to_string();
    assert!(e.contains("last"), "{e}");
}

/// A light replaced by hand lights the frame as it now is; the sky a host sets reaches the
/// indirect light through the box's open side; what is not a light or a sky is refused.
#[test]
fn lights_and_the_sky_are_changed_between_frames() {
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    let lamp = irradiant_scene::Light::point("lamp", Vec3::new(0.0, 1.5, 0.0), Vec3::ONE, 1.0);
    scene.lights.push(lamp.clone());
    let Some(mut s) = cornell_session(scene, 0) else {
        return;
    };
    let direct_sum = |s: &mut Session| {
        for _ in 0..4 {
            s.render().unwrap();
        }
        let direct = s.direct().unwrap();
        direct
            .pixels
            .iter()
            .map(|p| (p[0] + p[1] + p[2]) as f64)
            .sum::<f64>()
    };
    let indirect_sum = |s: &Session| {
        let indirect = s.indirect().unwrap();
        indirect
            .pixels
            .iter()
            .map(|p| (p[0] + p[1] + p[2]) as f64)
            .sum::<f64>()
    };
    let dim = direct_sum(&mut s);
    s.set_light(
        0,
        irradiant_scene::Light {
            intensity: 20.0,
            ..lamp.clone()
        },
    )
    .unwrap();
    let bright = direct_sum(&mut s);
    assert!(
        bright > dim * 1.5,
        "the lamp at 20 lit {bright}, at 1 {dim}"
    );

    let dark_sky = indirect_sum(&s);
    s.set_sky(Vec3::splat(20.0)).unwrap();
    for _ in 0..8 {
        s.render().unwrap();
    }
    let blue_sky = indirect_sum(&s);
    assert!(
        blue_sky > dark_sky * 1.05,
        "sky 20: {blue_sky}, sky 0: {dark_sky}"
    );

    let e = s.set_light(1, lamp.clone()).unwrap_err().to_string();
    assert!(
        e.contains("light 1 does not exist") && e.contains("1 lights"),
        "{e}"
    );
    let e = s
        .set_light(
            0,
            irradiant_scene::Light {
                intensity: f32::NAN,
                ..lamp.clone()
            },
        )
        .unwrap_err()
        .to_string();
    assert!(e.contains("not finite"), "{e}");
    let spot = irradiant_scene::Light {
        kind: irradiant_scene::LightKind::Directional,
        direction: Vec3::ZERO,
        ..lamp
    };
    let e = s.set_light(0, spot).unwrap_err().to_string();
    assert!(e.contains("no direction"), "{e}");
    let e = s
        .set_sky(Vec3::new(-1.0, 0.0, 0.0))
        .unwrap_err()
        .to_string();
    assert!(e.contains("the sky"), "{e}");
}

/// A card 0.4 m square facing the camera at z = 0.5, with its triangles' materials from 0.
fn card(indices: Vec<u32>) -> irradiant_scene::Mesh {
    irradiant_scene::Mesh {
        name: "card".into(),
        positions: vec![
            Vec3::new(-0.2, 0.8, 0.5),
            Vec3::new(0.2, 0.8, 0.5),
            Vec3::new(0.2, 1.2, 0.5),
            Vec3::new(-0.2, 1.2, 0.5),
        ],
        triangle_materials: vec![0; indices.len() / 3],
        indices,
        ..Default::default()
    }
}

/// A mesh registered while running is placed like any other (the scene built anew); a mesh
/// with an index past its vertices, or a material whose texture the scene lacks, is refused
/// naming the mesh and nothing changes.
#[test]
fn a_mesh_is_registered_while_running() {
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let Some(mut s) = cornell_session(scene, 0) else {
        return;
    };
    let empty_room = centre_depth(&mut s);
    let grey = irradiant_scene::Material {
        name: "grey".into(),
        ..Default::default()
    };
    let mesh = s
        .add_mesh(card(vec![0, 1, 2, 0, 2, 3]), vec![grey.clone()])
        .unwrap();
    assert_eq!(mesh, 1);
    s.add_instance(mesh, Mat4::IDENTITY, "card").unwrap();
    let blocked = centre_depth(&mut s);
    // The camera stands at z = 3.5: the card is 3 m away.
    assert!(
        (blocked - 3.0).abs() < 0.01,
        "{blocked} against {empty_room}"
    );

    let e = s
        .add_mesh(card(vec![0, 1, 7]), vec![grey.clone()])
        .unwrap_err()
        .to_string();
    assert!(e.contains("mesh 'card' refers to vertex 7"), "{e}");
    let textured = irradiant_scene::Material {
        base_color_texture: Some(3),
        ..grey
    };
    let e = s
        .add_mesh(card(vec![0, 1, 2]), vec![textured])
        .unwrap_err()
        .to_string();
    assert!(e.contains("texture"), "{e}");
    assert_eq!(s.scene().meshes.len(), 2);
    assert!((centre_depth(&mut s) - blocked).abs() < 1e-3);
}
