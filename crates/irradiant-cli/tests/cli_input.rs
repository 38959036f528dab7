//! The binary's bad-input paths: a clear message and a non-zero exit, never a panic. These
//! fail before a GPU is needed.

mod common;

use common::*;

#[test]
fn absurd_sizes_are_refused() {
    fails_with(&["render", "--size", "0x0"], "no pixels");
    fails_with(&["render", "--size", "100000x100000"], "too large");
    fails_with(&["render", "--size", "wide"], "WIDTHxHEIGHT");
}

#[test]
fn unknown_scenes_and_techniques_are_refused() {
    fails_with(&["render", "--scene", "cornel"], "not a built-in scene");
    fails_with(
        &["render", "--scene", "/nonexistent/x.obj"],
        "/nonexistent/x.obj",
    );
    fails_with(&["render", "--technique", "magic"], "invalid value 'magic'");
    fails_with(&["render", "--frames", "0"], "--frames 0");
    fails_with(&["render", "--time=-1"], "--time");
    fails_with(
        &[
            "render",
            "--technique",
            "ddgi{volume.probe_counts = [0, 4, 4]}",
        ],
        "technique.volume.probe_counts = [0, 4, 4]",
    );
    fails_with(
        &["render", "--technique", "ddgi{update.hysteresis = 1.5}"],
        "technique.update.hysteresis = 1.5",
    );
    fails_with(
        &["render", "--technique", "ddgi{preset = \"best\"}"],
        "use fast, balanced or quality",
    );
    fails_with(
        &["render", "--technique", "path{max_bounces = 2}"],
        "only a preset in braces",
    );
    // The flags that specs replaced are gone, not aliases.
    for gone in ["--weights", "--rays", "--hysteresis", "--probes"] {
        fails_with(&["render", gone, "1"], "unexpected argument");
    }
    for gone in ["--ddgi-probes", "--ssil-start", "--lightfield-agreement"] {
        fails_with(&["bench", gone, "1"], "unexpected argument");
    }
    fails_with(
        &["render", "--camera", "0,0,0,0,0,0"],
        "position must differ from the target",
    );
    fails_with(
        &["render", "--camera-from", "/nonexistent/view.toml"],
        "/nonexistent/view.toml",
    );
    fails_with(
        &["render", "--save-camera", "view.txt"],
        "end the name in .toml",
    );
    fails_with(
        &["bench", "--techniques", "ssil", "--vary", "magic = [1, 2]"],
        "none of the techniques listed has that setting",
    );
}

#[test]
fn render_help_names_every_built_in_scene() {
    let (ok, help, _) = irradiant(&["render", "--help"]);
    assert!(ok);
    for (name, _) in irradiant_scene::BUILTIN_SCENES {
        assert!(
            help.contains(name),
            "`render --help` leaves out '{name}':\n{help}"
        );
    }
}

#[test]
fn bad_outputs_are_refused_before_rendering() {
    fails_with(
        &["render", "--out", "/nonexistent-dir/x.png"],
        "does not exist",
    );
    fails_with(&["render", "--out", "x.bmp"], "unsupported output type");
}

#[test]
fn absurd_settings_are_refused() {
    fails_with(&["render", "--spp", "0"], "'0' for '--spp");
    fails_with(&["render", "--exposure=-1"], "--exposure");
    fails_with(&["render", "--max-bounces", "99999"], "--max-bounces");
}

#[test]
fn a_malformed_manifest_names_the_file() {
    let dir = scratch("test");
    let manifest = dir.join("broken.toml");
    std::fs::write(&manifest, "[mesh\n").unwrap();
    fails_with(
        &["render", "--scene", manifest.to_str().unwrap()],
        "broken.toml",
    );
}

#[test]
fn an_unknown_adapter_lists_the_present_ones() {
    let (ok, _, stderr) = irradiant(&["--adapter", "no-such-gpu-xyz", "info"]);
    assert!(!ok);
    assert!(
        stderr.contains("no-such-gpu-xyz")
            && (stderr.contains("Adapters present") || stderr.contains("no GPU adapter")),
        "{stderr}"
    );
}
