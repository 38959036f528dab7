//! `irradiant view` driven by scripts on the test adapter: offscreen (no display) and in a real
//! window under Xvfb. Its frames switch with the technique, are not black, and match
//! `irradiant render`'s at the same camera and frame count.

mod common;

use std::path::Path;
use std::process::Command;

use common::*;

/// The frame the viewer and `render` both show: a small Cornell box after 8 frames.
const SIZE: &str = "64x48";
const FRAMES: u32 = 8;

/// A script: `FRAMES` frames of DDGI, a screenshot (and, offscreen, captures of its indirect
/// light and its normals); `FRAMES` of direct light alone (key 1), a screenshot; a camera, the
/// path tracer, a screenshot; quit.
fn script(dir: &Path, offscreen: bool) -> std::path::PathBuf {
    let path = dir.join("script.toml");
    let captures = if offscreen {
        "[[step]]\nshow = \"indirect\"\n[[step]]\ncapture = \"indirect.png\"\n\
         [[step]]\nshow = \"normal\"\n[[step]]\ncapture = \"normal.png\"\n\
         [[step]]\nshow = \"final\"\n"
    } else {
        // A light field baked in the window: its progress is drawn into the surface while
        // the bake blocks the loop.
        "[[step]]\ntechnique = 'lightfield{bake = { probe_counts = [2, 2, 2], resolution = 32, \
         prefilter_resolution = 16, bounces = 1, emitter_samples = 2 }}'\n\
         [[step]]\nframes = 2\n[[step]]\nscreenshot = \"lightfield.png\"\n"
    };
    let text = format!(
        "[[step]]\nframes = {FRAMES}\n[[step]]\nscreenshot = \"ddgi.png\"\n{captures}\
         [[step]]\nkey = \"1\"\n[[step]]\nframes = {FRAMES}\n[[step]]\nscreenshot = \"none.png\"\n\
         [[step]]\ncamera = {{ position = [0.0, 1.0, 3.4], target = [0.0, 1.0, 0.0] }}\n\
         [[step]]\nkey = \"Space\"\n[[step]]\nframes = 2\n[[step]]\nscreenshot = \"path.png\"\n\
         [[step]]\nquit = true\n"
    );
    std::fs::write(&path, text).unwrap();
    path
}

fn rgb(path: &Path) -> (Vec<u8>, u32, u32) {
    let image = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8();
    let (w, h) = image.dimensions();
    (image.into_raw(), w, h)
}

fn mean(pixels: &[u8]) -> f64 {
    pixels.iter().map(|&p| p as f64).sum::<f64>() / pixels.len() as f64
}

/// What every scripted run must show: frames that are not black and change with the technique.
fn check_screenshots(dir: &Path) {
    let (ddgi, w, h) = rgb(&dir.join("ddgi.png"));
    let (none, ..) = rgb(&dir.join("none.png"));
    let (path, ..) = rgb(&dir.join("path.png"));
    assert_eq!((w, h), (64, 48));
    for (name, image) in [("ddgi", &ddgi), ("none", &none), ("path", &path)] {
        assert!(mean(image) > 10.0, "{name}'s screenshot is black");
    }
    // Direct light alone is darker than with DDGI's indirect light.
    assert!(
        mean(&none) < mean(&ddgi) - 2.0,
        "none {} against ddgi {}",
        mean(&none),
        mean(&ddgi)
    );
}

/// Needs the test adapter. The offscreen viewer runs the script; its DDGI frame matches
/// `irradiant render`'s with the same scene, size and frame count.
#[test]
fn the_offscreen_viewer_switches_techniques_and_matches_render() {
    let dir = scratch("view-offscreen");
    let script = script(&dir, true);
    let out = dir.to_str().unwrap();
    let (ok, stdout, stderr) = irradiant(&[
        "view",
        "--offscreen",
        "--size",
        SIZE,
        "--script",
        script.to_str().unwrap(),
        "--out-dir",
        out,
    ]);
    if !has_adapter(ok, &stderr) {
        return;
    }
    assert!(ok, "{stdout}\n{stderr}");
    assert!(stdout.contains("frames"), "{stdout}");
    check_screenshots(&dir);
    // The debug views show the frame's textures: the indirect light and the normals differ
    // from each other where the frame is (the panel, over the left, is the same in both).
    let (indirect, ..) = rgb(&dir.join("indirect.png"));
    let (normal, ..) = rgb(&dir.join("normal.png"));
    assert!(mean(&indirect) > 5.0 && mean(&normal) > 5.0);
    let differing = indirect
        .chunks(3)
        .zip(normal.chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        differing > indirect.len() / 3 / 4,
        "the indirect light and the normals look alike ({differing} pixels differ)"
    );
    let rendered = dir.join("render.png");
    let frames = FRAMES.to_string();
    let (ok, _, stderr) = irradiant(&[
        "render",
        "--size",
        SIZE,
        "--frames",
        &frames,
        "--out",
        rendered.to_str().unwrap(),
    ]);
    assert!(ok, "{stderr}");
    let (viewer, w, h) = rgb(&dir.join("ddgi.png"));
    let (render, ..) = rgb(&rendered);
    let flip = irradiant_eval::flip(&render, &viewer, w, h).unwrap();
    // One session, one technique, one frame count: the viewer renders the frames `render`
    // does. 0.02 leaves room for a different order of the same work on another driver; the
    // difference between DDGI and direct light alone here is about 0.3.
    assert!(
        flip.mean < 0.02,
        "the viewer's DDGI frame is {} FLIP from render's",
        flip.mean
    );
}

/// Needs the test adapter, Xvfb and lavapipe (`./run test` installs them as root; under
/// `CI=true` their absence fails the test). The same script in a real window.
#[test]
fn the_viewer_runs_a_script_in_a_window_under_xvfb() {
    let xvfb = Command::new("xvfb-run").arg("--help").output().is_ok();
    let icd = irradiant_gpu::lavapipe_icd();
    let (Some(icd), true) = (icd, xvfb) else {
        assert_ne!(
            std::env::var("CI").as_deref(),
            Ok("true"),
            "the viewer's window test needs xvfb and mesa-vulkan-drivers: apt-get install xvfb libxkbcommon-x11-0 mesa-vulkan-drivers"
        );
        eprintln!(
            "SKIPPED: no xvfb-run or lavapipe (apt-get install xvfb libxkbcommon-x11-0 mesa-vulkan-drivers)"
        );
        return;
    };
    let dir = scratch("view-window");
    let script = script(&dir, false);
    // Xvfb has no DRI3, which hardware Vulkan drivers need to present: lavapipe is pinned.
    let out = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 640x480x24"])
        .arg(env!("CARGO_BIN_EXE_irradiant"))
        .args(["view", "--size", SIZE, "--script"])
        .arg(&script)
        .arg("--out-dir")
        .arg(&dir)
        .arg("--cache")
        .arg(&dir)
        .env("VK_ICD_FILENAMES", &icd)
        .env("XDG_RUNTIME_DIR", "/tmp")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && !stderr.contains("panicked"),
        "{stderr}"
    );
    check_screenshots(&dir);
    let (lightfield, ..) = rgb(&dir.join("lightfield.png"));
    assert!(
        mean(&lightfield) > 10.0,
        "the light field's screenshot is black"
    );
}

/// Bad input gets a message, not a panic: a script that does not parse, a missing scene.
#[test]
fn the_viewer_refuses_bad_input_by_name() {
    let dir = scratch("view-bad");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[[step]]\nframes = 0\n").unwrap();
    fails_with(
        &["view", "--offscreen", "--script", bad.to_str().unwrap()],
        "frames = 0",
    );
    fails_with(
        &["view", "--offscreen", "--scene", "/nonexistent/x.obj"],
        "/nonexistent/x.obj",
    );
    fails_with(
        &[
            "view",
            "--offscreen",
            "--technique",
            "ddgi{update.hysteresis = 2}",
        ],
        "technique.update.hysteresis = 2",
    );
}
