//! The viewer's panel driven as a person would, through egui_kittest on the test adapter: it
//! builds from every registered technique's settings, a changed setting reaches the session's
//! live settings without a rebuild, and a setting that shapes the passes rebuilds the technique.

use egui_kittest::kittest::Queryable;
use irradiant_view::Viewer;

mod common;

/// A small viewer on the Cornell box, or None (skipped) without an adapter outside CI.
fn viewer() -> Option<Viewer> {
    common::viewer(&common::options("cornell", (32, 24)))
}

/// The address of the technique the session runs: a rebuilt one is a new object.
fn technique_address(viewer: &Viewer) -> usize {
    viewer.session.technique() as *const dyn irradiant::Technique as *const () as usize
}

#[test]
fn the_panel_shows_every_techniques_settings() {
    let Some(viewer) = viewer() else { return };
    let names: Vec<String> = viewer
        .techniques
        .iter()
        .filter(|t| *t != "path" && !t.starts_with("lightfield"))
        .cloned()
        .collect();
    let mut harness = common::harness(viewer);
    for name in names {
        harness.state_mut().0.switch_to(&name).unwrap();
        harness.run();
        let spec = harness.state().0.session.spec().clone();
        let table = spec.kind().unwrap().resolved_settings(&spec).unwrap();
        // Every top-level setting or group of the technique has its row.
        for key in table.keys() {
            assert!(
                harness.query_all_by_label_contains(key).next().is_some(),
                "{name}: no row for {key}"
            );
        }
        assert!(
            harness
                .query_all_by_label_contains("technique")
                .next()
                .is_some()
        );
    }
}

#[test]
fn a_live_setting_changes_in_place_and_a_structural_one_rebuilds() {
    let Some(viewer) = viewer() else { return };
    let mut harness = common::harness(viewer);
    harness.run();
    let before = technique_address(&harness.state().0);
    // Opens the `update` group, then flips a setting the blend reads each frame.
    harness.get_by_label("update").click();
    harness.run();
    harness.get_by_label("convergence_heuristics").click();
    harness.run();
    let spec = harness.state().0.session.spec().clone();
    assert_eq!(
        spec.settings["update"]["convergence_heuristics"].as_bool(),
        Some(false),
        "the panel's change did not reach the session: {spec:?}"
    );
    assert_eq!(
        technique_address(&harness.state().0),
        before,
        "a live setting rebuilt the technique"
    );
    // The traced bounce is a shader constant of ddgi/shade: the technique is built anew.
    harness.get_by_label("traced_bounce").click();
    harness.run();
    let spec = harness.state().0.session.spec().clone();
    assert_eq!(
        spec.settings["update"]["traced_bounce"].as_bool(),
        Some(true)
    );
    assert_ne!(
        technique_address(&harness.state().0),
        before,
        "a setting that shapes the passes did not rebuild the technique"
    );
    // A preset button applies the preset.
    harness.get_by_label("quality").click();
    harness.run();
    assert_eq!(
        harness.state().0.session.spec().preset,
        irradiant::Preset::Quality
    );
}

/// A manifest's `[technique]` table holds for every technique the viewer shows that it names
/// a part of: the first one's spec, a hybrid switched to and a spec typed (the large world's `ssil+ddgi`
/// ran one volume over 480 m where its `ddgi` ran the manifest's cascades).
#[test]
fn a_manifests_technique_table_reaches_a_hybrid_switched_to() {
    let dir = std::env::temp_dir().join(format!("irradiant-view-table-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let original = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/cornell-box/original.toml");
    let text = std::fs::read_to_string(&original).unwrap().replace(
        "../../../shared/",
        &format!("{}/../../../shared/", env!("CARGO_MANIFEST_DIR")),
    );
    let manifest = dir.join("with-table.toml");
    std::fs::write(
        &manifest,
        format!("{text}\n[technique]\nname = \"ddgi\"\n[technique.volume]\nrays_per_probe = 32\n"),
    )
    .unwrap();
    let options = common::options(manifest.to_str().unwrap(), (32, 24));
    let Some(mut viewer) = common::viewer(&options) else {
        return;
    };
    let rays = |spec: &irradiant::TechniqueSpec, part: Option<&str>| {
        let settings = match part {
            Some(part) => spec.settings[part].as_table().unwrap(),
            None => &spec.settings,
        };
        settings["volume"]["rays_per_probe"].as_integer()
    };
    assert_eq!(rays(viewer.session.spec(), None), Some(32));
    viewer.switch_to("ssil+ddgi").unwrap();
    assert_eq!(viewer.session.spec().name, "ssil+ddgi");
    assert_eq!(rays(viewer.session.spec(), Some("ddgi")), Some(32));
    viewer.render(1.0 / 60.0).unwrap();
    // A spec typed in the panel or a script's step lays the table too.
    viewer.apply_text("ssil+ddgi{near_field = 0.25}").unwrap();
    assert_eq!(rays(viewer.session.spec(), Some("ddgi")), Some(32));
}
