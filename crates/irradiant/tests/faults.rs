//! GPU faults (issue 13): a device lost in the middle of a run ends it with an error that says
//! what happened and what to try — never a panic, never a raw wgpu message — and nothing is
//! read back from the lost device as if it were an image.

mod common;

use irradiant::{Preset, Session, SessionSettings, TechniqueSpec};

#[test]
fn a_device_lost_mid_run_is_an_error_naming_what_happened() {
    let Some(ctx) = common::gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let settings = || SessionSettings {
        size: (32, 32),
        technique: TechniqueSpec::new("ddgi", Preset::Fast),
        ..Default::default()
    };
    let mut session = Session::new(ctx.clone(), scene.clone(), settings()).unwrap();
    session.render().unwrap();
    session.image().unwrap();
    ctx.device.destroy();
    // Recording may still succeed; reading the frame back may not pretend to.
    let _ = session.render();
    let Err(error) = session.image() else {
        panic!("no image comes back from a lost device")
    };
    let message = error.to_string();
    assert!(
        message.contains("GPU device was lost") && message.contains("try"),
        "{message}"
    );
    // A new session on the lost device: refused, not a panic inside wgpu.
    let message = Session::new(ctx.clone(), scene, settings())
        .err()
        .expect("a lost device builds no session")
        .to_string();
    assert!(message.contains("GPU device was lost"), "{message}");
}
