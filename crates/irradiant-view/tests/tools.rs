//! The viewer's tools on the test adapter: the truth beside the frame (rendered, cached,
//! compared, shown three ways, dropped when the view moves), the inspector's probe picked by
//! its pixel, the lights switched from the panel, screenshots in both formats, and a session
//! restarted on a new device after the last one was lost.

mod common;

use egui_kittest::kittest::Queryable;
use irradiant_view::Viewer;
use irradiant_view::present::Decode;
use irradiant_view::truth::TruthShow;

/// Renders frames until the truth has its verdict (the comparison runs on a thread).
fn until_verdict(viewer: &mut Viewer) {
    for _ in 0..400 {
        if viewer.truth.as_ref().is_some_and(|t| t.verdict().is_some()) {
            return;
        }
        viewer.render(1.0 / 60.0).unwrap();
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    panic!("no verdict after 400 frames");
}

#[test]
fn the_truth_is_rendered_cached_compared_and_shown_three_ways() {
    let options = common::options("cornell", (48, 32));
    let Some(mut viewer) = common::viewer(&options) else {
        return;
    };
    for _ in 0..8 {
        viewer.render(1.0 / 60.0).unwrap();
    }
    viewer.press("T").unwrap();
    let truth = viewer.truth.as_ref().unwrap();
    assert!(
        !truth.cached && truth.rendering(),
        "a new cache has no entry"
    );
    until_verdict(&mut viewer);
    let truth = viewer.truth.as_ref().unwrap();
    assert_eq!(truth.progress(), (8, 8));
    let verdict = truth.verdict().unwrap().clone();
    // DDGI after 8 frames against an 8-sample reference: neither is the other, nor far off.
    assert!(
        verdict.flip_mean > 0.0 && verdict.flip_mean < 0.5,
        "{verdict:?}"
    );
    assert!(verdict.technique.starts_with("ddgi"), "{verdict:?}");
    // The wipe shows the reference from the split's column; the maps replace the frame.
    let shown = viewer.image_view();
    assert_eq!(shown.beside.map(|b| b.1), Some(24));
    viewer.truth.as_mut().unwrap().show = TruthShow::Flip;
    let shown = viewer.image_view();
    assert!(shown.beside.is_none() && shown.decode == Decode::Shown);
    // The panel says FLIP's mean.
    let mut harness = common::harness(viewer);
    harness.run();
    let label = format!("FLIP {:.4} mean", verdict.flip_mean);
    assert!(
        harness.query_all_by_label_contains(&label).next().is_some(),
        "no '{label}' in the panel"
    );
    let (mut viewer, _) = harness.into_state();
    // T again turns it off; a third time finds the reference in the cache.
    viewer.press("T").unwrap();
    assert!(viewer.truth.is_none());
    viewer.press("T").unwrap();
    assert!(viewer.truth.as_ref().unwrap().cached);
    until_verdict(&mut viewer);
    // Another view is another truth: moving drops this one.
    viewer
        .fly(
            irradiant_view::camera::Movement {
                forward: 1.0,
                ..Default::default()
            },
            0.1,
        )
        .unwrap();
    assert!(viewer.truth.is_none());
}

#[test]
fn a_click_on_a_probe_picks_it_in_the_inspector() {
    let options = common::options("cornell", (64, 48));
    let Some(mut viewer) = common::viewer(&options) else {
        return;
    };
    viewer.render(1.0 / 60.0).unwrap();
    viewer.press("I").unwrap();
    let inspection = viewer
        .inspection
        .as_ref()
        .expect("DDGI has state to inspect");
    assert_eq!(inspection.images.len(), 2);
    // The probe nearest the camera that projects inside the image: its pixel picks it.
    let camera = viewer.fly.camera();
    let gpu_camera = irradiant::scene::types::GpuCamera::new(&camera, 64, 48);
    let (probe, pixel) = inspection
        .probes
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let (pixel, depth) = gpu_camera.project(p.position, 64, 48)?;
            (pixel.x > 0.0 && pixel.y > 0.0 && pixel.x < 64.0 && pixel.y < 48.0)
                .then_some((i, pixel, depth))
        })
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .map(|(i, pixel, _)| (i, pixel))
        .expect("a probe in view");
    assert_eq!(viewer.pick_probe((pixel.x, pixel.y)), Some(probe));
    assert_eq!(
        viewer.pick_probe((0.0, 0.0)),
        None,
        "a corner sees no probe"
    );
    assert_eq!(viewer.picked, Some(probe), "a miss keeps the last pick");
    let mut harness = common::harness(viewer);
    harness.run();
    let label = format!("probe {probe} at");
    assert!(
        harness.query_all_by_label_contains(&label).next().is_some(),
        "the inspector does not show '{label}'"
    );
}

#[test]
fn the_panel_switches_a_light_and_f12_writes_png_and_exr() {
    let mut options = common::options("two-rooms", (32, 24));
    options.out_dir =
        std::env::temp_dir().join(format!("irradiant-view-f12-{}", std::process::id()));
    std::fs::create_dir_all(&options.out_dir).unwrap();
    let Some(mut viewer) = common::viewer(&options) else {
        return;
    };
    viewer.render(1.0 / 60.0).unwrap();
    let mut harness = common::harness(viewer);
    harness.run();
    harness.get_by_label("lights (1)").click();
    harness.run();
    harness.get_by_label("lamp").click();
    harness.run();
    let (mut viewer, _) = harness.into_state();
    assert!(!viewer.session.light_enabled(0));
    assert!(!viewer.session.pose().lights[0].enabled);
    viewer.press("F12").unwrap();
    for name in ["irradiant-view-001.png", "irradiant-view-001.exr"] {
        let path = options.out_dir.join(name);
        assert!(
            path.is_file(),
            "{} missing: {}",
            path.display(),
            viewer.status
        );
    }
    let exr = irradiant::frame::Image::read_exr(
        &options.out_dir.join("irradiant-view-001.exr"),
        Some((32, 24)),
    )
    .unwrap();
    assert!(exr.pixels.iter().all(|p| p.iter().all(|c| c.is_finite())));
}

#[test]
fn a_lost_device_is_said_and_r_restarts_on_a_new_one() {
    let mut options = common::options("cornell", (32, 24));
    let dir = std::env::temp_dir().join(format!("irradiant-view-lost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let script = dir.join("lost.toml");
    std::fs::write(
        &script,
        "[[step]]\nframes = 2\n[[step]]\nlose_device = true\n[[step]]\nframes = 2\n\
         [[step]]\nkey = \"R\"\n[[step]]\nframes = 3\n[[step]]\nscreenshot = \"after.png\"\n",
    )
    .unwrap();
    options.script = Some(script);
    if common::viewer(&options).is_none() {
        return;
    }
    let report = irradiant_view::run_offscreen(&options).unwrap();
    assert_eq!(report.restarts, 1, "{report:?}");
    let image = image::open(dir.join("after.png")).unwrap().to_rgb8();
    assert!(
        image.pixels().any(|p| p.0 != [0, 0, 0]),
        "the restarted frame is black"
    );
}
