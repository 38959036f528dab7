//! Out of memory in the middle of a run (issue 13), provoked on lavapipe, whose GPU memory is
//! the process's: an address-space limit (setrlimit) makes the driver's allocations fail. The
//! run ends with an error that names the shortage and what to try — not a raw wgpu message,
//! not a panic — and the session, and its device, stay usable once memory is back.
//!
//! A test binary of its own: the limit is the whole process's.

mod common;

use irradiant::ddgi::DdgiSettings;
use irradiant::{Preset, Session, SessionSettings, TechniqueSpec};

/// The process's virtual memory size now, bytes.
fn address_space_in_use() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = status.lines().find(|l| l.starts_with("VmSize:")).unwrap();
    line.split_whitespace()
        .nth(1)
        .unwrap()
        .parse::<u64>()
        .unwrap()
        * 1024
}

fn limit_address_space(bytes: u64) {
    let limit = libc::rlimit {
        rlim_cur: bytes,
        rlim_max: libc::RLIM_INFINITY,
    };
    // SAFETY: setrlimit reads the struct; no memory is handed over.
    assert_eq!(unsafe { libc::setrlimit(libc::RLIMIT_AS, &limit) }, 0);
}

#[test]
fn running_out_of_memory_mid_run_is_an_error_and_the_session_survives() {
    let Some(ctx) = common::gpu() else { return };
    if ctx.info.device_type != "Cpu" {
        eprintln!("SKIPPED: only a software adapter's memory is the process's");
        return;
    }
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut session = Session::new(
        ctx.clone(),
        scene,
        SessionSettings {
            size: (64, 64),
            technique: TechniqueSpec::new("ddgi", Preset::Fast),
            ..Default::default()
        },
    )
    .unwrap();
    session.render().unwrap();
    // DDGI with 28³ probes of 160 rays wants about 320 MB in buffers that each fit the
    // adapter's limits (so the plan accepts them); the process may grow by 128 MiB.
    let mut huge = DdgiSettings::balanced();
    huge.volume.probe_counts = [28, 28, 28];
    huge.volume.rays_per_probe = 160;
    limit_address_space(address_space_in_use() + (128 << 20));
    let result = session
        .set_technique(TechniqueSpec::with_settings("ddgi", &huge))
        .and_then(|()| session.render());
    limit_address_space(libc::RLIM_INFINITY);
    let message = result
        .expect_err("320 MB do not fit in 128 MiB")
        .to_string();
    assert!(
        message.contains("ran out of memory") && message.contains("lower"),
        "{message}"
    );
    assert!(!message.contains("Validation Error"), "{message}");
    // Memory is back: the same session renders again, on the same device.
    session
        .set_technique(TechniqueSpec::new("ddgi", Preset::Fast))
        .unwrap();
    session.render().unwrap();
    let image = session.image().unwrap();
    assert!(image.pixels.iter().flatten().all(|c| c.is_finite()));
}
