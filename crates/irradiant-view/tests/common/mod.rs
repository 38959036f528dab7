//! What the viewer's tests share: small options, and a viewer on the test adapter.

#![allow(dead_code)]

use egui_kittest::Harness;
use irradiant_view::ui::{PanelState, draw};
use irradiant_view::{ViewOptions, Viewer};

/// Offscreen options for a small viewer of `scene`: the references and bakes are cached in a
/// folder of their own, so that no test reads another's entries.
pub fn options(scene: &str, size: (u32, u32)) -> ViewOptions {
    let cache = std::env::temp_dir().join(format!(
        "irradiant-view-test-{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos()
    ));
    ViewOptions {
        scene: scene.into(),
        size,
        technique: "ddgi".into(),
        adapter: irradiant::AdapterChoice::from_env(),
        script: None,
        offscreen: true,
        panel: true,
        out_dir: std::env::temp_dir(),
        cache_dir: Some(cache),
        truth_spp: 8,
        build: "test".into(),
        progress: None,
    }
}

/// The viewer `options` start, or None (skipped) without an adapter outside CI.
pub fn viewer(options: &ViewOptions) -> Option<Viewer> {
    match irradiant_view::start(options) {
        Ok(viewer) => Some(viewer),
        Err(e)
            if e.to_string().contains("no GPU adapter")
                && std::env::var("CI").as_deref() != Ok("true") =>
        {
            eprintln!("SKIPPED: {e}");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

/// The panel over `viewer`, driven as a person would (egui_kittest), tall enough to show
/// every row.
pub fn harness(viewer: Viewer) -> Harness<'static, (Viewer, PanelState)> {
    Harness::builder()
        .with_size(egui::vec2(900.0, 2400.0))
        .build_ui_state(
            |ui, (viewer, panel): &mut (Viewer, PanelState)| draw(ui, viewer, panel, 16.0),
            (viewer, PanelState::default()),
        )
}
