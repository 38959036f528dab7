//! `irradiant compare` on the test adapter: bad input, the report and its cached reference,
//! animations and camera pans, and the report opened in a browser.

mod common;

use std::process::Command;

use common::*;

#[test]
fn compare_refuses_bad_input_and_leaves_nothing_half_written() {
    let dir = scratch("compare");
    let out = dir.join("report");
    let out_text = out.to_string_lossy().into_owned();
    fails_with(
        &["compare", "--techniques", "ddgi,magic", "--out", &out_text],
        "unknown technique 'magic'",
    );
    fails_with(
        &[
            "compare",
            "--scene",
            "two-rooms",
            "--regions",
            "attic",
            "--out",
            &out_text,
        ],
        "no region 'attic'",
    );
    fails_with(
        &["compare", "--out", "/nonexistent-dir/report"],
        "does not exist",
    );
    fails_with(
        &[
            "compare",
            "--reference-spp",
            "4000000000",
            "--out",
            &out_text,
        ],
        "from 1 to 1048576",
    );
    // A file where the report would go is refused before the reference is rendered, and kept.
    let file = dir.join("notes.txt");
    std::fs::write(&file, "keep me").unwrap();
    fails_with(
        &["compare", "--out", file.to_str().unwrap()],
        "is a file, and a report is a folder",
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep me");
    assert!(
        !out.exists() && !out.with_extension("partial").exists(),
        "a refused comparison must leave no folder behind"
    );
}

/// Needs the test adapter: a tiny comparison, then the same again from the reference cache.
#[test]
fn compare_writes_a_report_and_reuses_the_cached_reference() {
    let dir = scratch("compare-run");
    let out = dir.join("report").to_string_lossy().into_owned();
    let cache = dir.join("cache").to_string_lossy().into_owned();
    let args = [
        "compare",
        "--scene",
        "two-rooms",
        "--size",
        "32x24",
        "--reference-spp",
        "16",
        "--frames",
        "4",
        "--out",
        &out,
        "--cache",
        &cache,
    ];
    let (ok, stdout, stderr) = irradiant(&args);
    if !has_adapter(ok, &stderr) {
        return;
    }
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains("ddgi") && stdout.contains("FLIP mean"),
        "{stdout}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report/comparison.json")).unwrap())
            .unwrap();
    assert_eq!(json["results"].as_array().unwrap().len(), 3);
    assert_eq!(json["reference_cached"], false);
    assert_eq!(json["results"][2]["regions"][0][0], "dark-room");
    let html = std::fs::read_to_string(dir.join("report/report.html")).unwrap();
    assert_eq!(
        html.matches("data:image/png;base64,").count(),
        1 + 2 * 3,
        "reference + image and error map per technique"
    );
    let (ok, _, stderr) = irradiant(&args);
    assert!(ok, "{stderr}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report/comparison.json")).unwrap())
            .unwrap();
    assert_eq!(
        json["reference_cached"], true,
        "the second run must reuse the cached reference"
    );
    // A different view must not reuse it.
    let other = [
        "compare",
        "--scene",
        "two-rooms",
        "--size",
        "32x24",
        "--reference-spp",
        "17",
        "--frames",
        "2",
        "--techniques",
        "none",
        "--out",
        &out,
        "--cache",
        &cache,
    ];
    let (ok, _, stderr) = irradiant(&other);
    assert!(ok, "{stderr}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report/comparison.json")).unwrap())
            .unwrap();
    assert_eq!(
        json["reference_cached"], false,
        "changed settings must not hit the cache"
    );
}

/// Needs the test adapter: a comparison that follows an animation (the lamp of two-rooms
/// switches off at frame 6 at 6 frames a second) and plots error and flicker over time.
#[test]
fn compare_follows_an_animation_and_plots_it() {
    let dir = scratch("compare-time");
    let out = dir.join("report").to_string_lossy().into_owned();
    let cache = dir.join("cache").to_string_lossy().into_owned();
    let manifest = TWO_ROOMS_SWITCH;
    let args = [
        "compare",
        "--scene",
        manifest,
        "--size",
        "24x18",
        "--reference-spp",
        "8",
        "--frames",
        "2",
        "--techniques",
        "none,ddgi",
        "--over-time",
        "10",
        "--fps",
        "6",
        "--every",
        "3",
        "--sequence-spp",
        "8",
        "--out",
        &out,
        "--cache",
        &cache,
    ];
    let (ok, _, stderr) = irradiant(&args);
    if !has_adapter(ok, &stderr) {
        return;
    }
    assert!(ok, "{stderr}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report/comparison.json")).unwrap())
            .unwrap();
    let series = json["over_time"].as_array().unwrap();
    assert_eq!(series.len(), 2);
    assert_eq!(
        series[1]["change_frame"], 6,
        "the lamp switches off at 1 s = frame 6"
    );
    assert_eq!(
        series[1]["error"].as_array().unwrap().len(),
        4,
        "frames 0, 3, 6 and 9 are compared"
    );
    assert_eq!(series[1]["flicker"].as_array().unwrap().len(), 9);
    let html = std::fs::read_to_string(dir.join("report/report.html")).unwrap();
    assert_eq!(
        html.matches("<svg").count(),
        2,
        "an error plot and a flicker plot"
    );
}

/// Needs the test adapter: over time with the camera panning, against one-bounce references.
/// A pan changes every pixel from frame to frame, so the flicker the lab measures must rise
/// well above that of the same frames with the camera at rest (TAA's jitter alone).
#[test]
fn compare_pans_the_camera_against_one_bounce_references() {
    let dir = scratch("compare-pan");
    let cache = dir.join("cache").to_string_lossy().into_owned();
    fails_with(
        &[
            "compare",
            "--pan",
            "30",
            "--out",
            &dir.join("refused").to_string_lossy(),
        ],
        "--pan 30 needs --over-time",
    );
    fails_with(
        &[
            "compare",
            "--techniques",
            "none,ssil",
            "--difference-from",
            "ddgi",
            "--out",
            &dir.join("refused").to_string_lossy(),
        ],
        "--difference-from 'ddgi' is not one of the techniques compared (none, ssil)",
    );
    fails_with(
        &[
            "compare",
            "--reference-bounces",
            "5000",
            "--out",
            &dir.join("refused").to_string_lossy(),
        ],
        "--reference-bounces 5000 is out of range",
    );
    let mean_flicker = |pan: &str| {
        let out = dir
            .join(format!("report-{pan}"))
            .to_string_lossy()
            .into_owned();
        let args = [
            "compare",
            "--scene",
            "cornell",
            "--size",
            "24x18",
            "--reference-spp",
            "8",
            "--frames",
            "2",
            "--techniques",
            "none,ssil",
            "--reference-bounces",
            "1",
            "--over-time",
            "6",
            "--fps",
            "6",
            "--every",
            "5",
            "--sequence-spp",
            "4",
            "--difference-from",
            "none",
            "--pan",
            pan,
            "--out",
            &out,
            "--cache",
            &cache,
        ];
        let (ok, _, stderr) = irradiant(&args);
        if !has_adapter(ok, &stderr) {
            return None;
        }
        assert!(ok, "{stderr}");
        let json: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(format!("{out}/comparison.json")).unwrap(),
        )
        .unwrap();
        assert_eq!(json["reference_indirect_bounces"], 1);
        // SSIL only adds light to the frame's direct light.
        let added = json["results"][1]["difference"]["mean"].as_f64().unwrap();
        assert!(
            added > 0.0 && json["results"][0]["difference"].is_null(),
            "SSIL minus none: {added}"
        );
        let html = std::fs::read_to_string(format!("{out}/report.html")).unwrap();
        assert!(html.contains("one indirect bounce"));
        let series = json["over_time"].as_array().unwrap();
        assert_eq!(series.len(), 2);
        let flicker = series[0]["flicker"].as_array().unwrap();
        assert_eq!(flicker.len(), 5);
        Some(flicker.iter().map(|f| f[1].as_f64().unwrap()).sum::<f64>() / flicker.len() as f64)
    };
    let Some(panning) = mean_flicker("40") else {
        eprintln!("SKIPPED: no GPU adapter");
        return;
    };
    let resting = mean_flicker("0").unwrap();
    eprintln!("mean flicker of `none`: panning {panning:.5}, at rest {resting:.5}");
    assert!(
        panning > 3.0 * resting,
        "panning {panning}, at rest {resting}"
    );
}

/// Chromium's command, if installed: Debian names it `chromium`, others `chromium-browser`.
fn chromium() -> Option<&'static str> {
    ["chromium", "chromium-browser"].into_iter().find(|name| {
        Command::new(name)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// Needs the test adapter and Chromium (`.ci/run` installs it; under `CI=true` its absence
/// fails the test). A report with images and plots, opened as a person would open it: in a
/// browser, from disk. The page marks on load how many of its images decoded and how many plots
/// it has (`report.rs`); every image must decode and every plot be there.
#[test]
fn the_report_opens_in_headless_chromium_with_every_image_decoded() {
    let Some(browser) = chromium() else {
        assert_ne!(
            std::env::var("CI").as_deref(),
            Ok("true"),
            "Chromium is needed for the report's test under CI: apt-get install chromium"
        );
        eprintln!("SKIPPED: no Chromium (apt-get install chromium)");
        return;
    };
    let dir = scratch("report-browser");
    let out = dir.join("report");
    let (ok, stdout, stderr) = irradiant(&[
        "compare",
        "--scene",
        TWO_ROOMS_SWITCH,
        "--size",
        "24x18",
        "--reference-spp",
        "4",
        "--frames",
        "2",
        "--techniques",
        "none,ddgi",
        "--over-time",
        "4",
        "--every",
        "2",
        "--sequence-spp",
        "2",
        "--cache",
        dir.join("cache").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{stdout}\n{stderr}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let images = html.matches("<img").count();
    let plots = html.matches("<svg").count();
    assert!(images >= 5 && plots >= 2, "{images} images, {plots} plots");
    // --virtual-time-budget lets the page's load event run before the DOM is printed.
    let page = Command::new("timeout")
        .arg("120")
        .arg(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--virtual-time-budget=10000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", dir.join("profile").display()))
        .arg(format!("file://{}", out.join("report.html").display()))
        .output()
        .unwrap();
    let dom = String::from_utf8_lossy(&page.stdout);
    assert!(
        page.status.success(),
        "Chromium failed: {}",
        String::from_utf8_lossy(&page.stderr)
    );
    // The body's opening tag, where the page's marks are.
    let body = dom
        .find("<body")
        .map(|at| &dom[at..at + dom[at..].find('>').map_or(0, |end| end + 1)])
        .unwrap_or("no <body>");
    assert!(
        body.contains(&format!("data-images-loaded=\"{images}\"")),
        "not every one of the {images} images decoded: {body}"
    );
    assert!(
        body.contains(&format!("data-plots=\"{plots}\"")),
        "not every one of the {plots} plots is there: {body}"
    );
}
