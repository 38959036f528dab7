//! The binary's bad-input paths: a clear message and a non-zero exit, never a panic. Most of
//! these fail before a GPU is needed; the last ones render tiny images on the test adapter.

use std::process::Command;

fn irradiant(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_irradiant"))
        .args(args)
        .env("XDG_RUNTIME_DIR", "/tmp")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        !stderr.contains("panicked"),
        "irradiant {args:?} panicked:\n{stderr}"
    );
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr,
    )
}

/// Two-rooms with its lamp switching off: a scene that animates.
const TWO_ROOMS_SWITCH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenes/two-rooms/switch.toml"
);

/// An empty folder of its own for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("irradiant-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn fails_with(args: &[&str], expected: &str) {
    let (ok, _, stderr) = irradiant(args);
    assert!(!ok, "irradiant {args:?} should fail");
    assert!(
        stderr.contains(expected),
        "irradiant {args:?}: expected '{expected}' in:\n{stderr}"
    );
}

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
    fails_with(&["render", "--probes", "0x4x4"], "probe count");
    fails_with(&["render", "--hysteresis", "1.5"], "hysteresis");
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

/// Needs the test adapter: each technique and output kind, a frame sequence, the probe view,
/// the atlas dump and the smoke benchmark.
#[test]
fn renders_every_technique_and_output_and_runs_the_smoke_bench() {
    let dir = scratch("render");
    let path = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let (ok, _, stderr) = irradiant(&[
        "render",
        "--technique",
        "path",
        "--size",
        "32x24",
        "--spp",
        "4",
        "--out",
        &path("c.png"),
    ]);
    if !ok && stderr.contains("no GPU adapter") && std::env::var("CI").as_deref() != Ok("true") {
        eprintln!("SKIPPED: no GPU adapter");
        return;
    }
    assert!(ok, "{stderr}");
    let renders: [&[&str]; 4] = [
        &[
            "render",
            "--technique",
            "path",
            "--size",
            "32x24",
            "--spp",
            "4",
            "--out",
            &path("c.exr"),
        ],
        &[
            "render",
            "--size",
            "32x24",
            "--frames",
            "3",
            "--show-probes",
            "--dump-atlas",
            &path(""),
            "--out",
            &path("ddgi.exr"),
        ],
        &[
            "render",
            "--scene",
            "two-rooms",
            "--technique",
            "none",
            "--size",
            "32x24",
            "--frames",
            "2",
            "--sequence",
            "--out",
            &path("seq.png"),
        ],
        &[
            "render",
            "--scene",
            "two-rooms",
            "--weights",
            "classic",
            "--probes",
            "3x2x2",
            "--rays",
            "16",
            "--size",
            "32x24",
            "--frames",
            "2",
            "--out",
            &path("classic.png"),
        ],
    ];
    for args in renders {
        let (ok, _, stderr) = irradiant(args);
        assert!(ok, "irradiant {args:?}: {stderr}");
    }
    for file in [
        "c.png",
        "c.exr",
        "ddgi.exr",
        "irradiance.png",
        "irradiance.exr",
        "distance.png",
        "distance.exr",
        "seq-0001.png",
        "seq-0002.png",
        "classic.png",
    ] {
        assert!(
            std::fs::metadata(dir.join(file))
                .map(|m| m.len() > 50)
                .unwrap_or(false),
            "{file} was not written"
        );
    }
    let json = path("bench.json");
    let (ok, stdout, stderr) = irradiant(&[
        "bench",
        "--smoke",
        "--ddgi-probes",
        "scene",
        "--ddgi-rays",
        "32",
        "--ssil-start",
        "quarter,half",
        "--ssil-visibility",
        "off,on",
        "--json",
        &json,
    ]);
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains("raycast/trace (diffuse)")
            && stdout.contains("pathtrace/trace")
            && stdout.contains("blend_irradiance")
            && stdout.contains("half/4/64/vis")
            && stdout.contains("voxel grid"),
        "{stdout}"
    );
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let ssil = record["ssil"].as_array().unwrap();
    assert_eq!(ssil.len(), 4, "quarter and half, visibility off and on");
    let labels = |i: usize| -> Vec<String> {
        ssil[i]["passes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p[0].as_str().unwrap().to_owned())
            .collect()
    };
    assert!(
        labels(1).contains(&"ssil/voxelize".into()) && !labels(0).contains(&"ssil/voxelize".into())
    );
    assert!(
        (1..=4).all(|l| labels(3).contains(&format!("ssil/gather_{l}"))),
        "{:?}",
        labels(3)
    );
    fails_with(
        &[
            "bench",
            "--smoke",
            "--ssil-start",
            "quarter",
            "--ssil-levels",
            "9",
        ],
        "technique.levels",
    );
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(record["passes"].as_array().unwrap().len() >= 4);
    let ddgi = &record["ddgi"][0];
    assert!(ddgi["passes"].as_array().unwrap().len() >= 9, "{ddgi}");
}

/// `bench --check-order` runs the scenes forward and reversed in one call and compares every
/// pass; the figures themselves are lavapipe's, so only the mechanism is tested here (the H100
/// figures are in BENCHMARKS.md, session 7).
#[test]
fn bench_runs_the_scenes_in_both_orders_and_compares_them() {
    let dir = scratch("bench-order");
    let json = dir.join("order.json").to_string_lossy().into_owned();
    let args = |tolerance: &'static str| {
        [
            "bench",
            "--smoke",
            "--scene",
            "cornell,two-rooms",
            "--techniques",
            "none",
            "--check-order",
            "--order-tolerance",
            tolerance,
            "--json",
            &json,
        ]
        .map(String::from)
    };
    let owned = args("1e9");
    let (ok, stdout, stderr) = irradiant(&owned.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(ok, "{stderr}");
    assert!(stdout.contains("order check"), "{stdout}");
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let orders: Vec<(String, String)> = record["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p["scene"].to_string(), p["order"].to_string()))
        .collect();
    for scene in ["\"cornell\"", "\"two-rooms\""] {
        for order in ["\"forward\"", "\"reverse\""] {
            assert!(
                orders.iter().any(|(s, o)| s == scene && o == order),
                "{scene} {order}: {orders:?}"
            );
        }
    }
    // Reversed: the last scene forward is the first one reversed.
    assert_eq!(record["scenes"][1]["scene"], record["scenes"][2]["scene"]);
    let owned = args("-1");
    fails_with(
        &owned.iter().map(String::as_str).collect::<Vec<_>>(),
        "--order-tolerance",
    );
}

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
    if !ok && stderr.contains("no GPU adapter") && std::env::var("CI").as_deref() != Ok("true") {
        eprintln!("SKIPPED: no GPU adapter");
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
    if !ok && stderr.contains("no GPU adapter") && std::env::var("CI").as_deref() != Ok("true") {
        eprintln!("SKIPPED: no GPU adapter");
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

/// Mean of each of `bands`×`bands` blocks of an RGB image (rows of blocks top to bottom).
fn block_means(image: &image::RgbImage, bands: u32) -> Vec<f64> {
    let (w, h) = image.dimensions();
    let mut means = Vec::new();
    for by in 0..bands {
        for bx in 0..bands {
            let (x0, x1) = (bx * w / bands, (bx + 1) * w / bands);
            let (y0, y1) = (by * h / bands, (by + 1) * h / bands);
            let mut sum = 0u64;
            for y in y0..y1 {
                for x in x0..x1 {
                    sum += image
                        .get_pixel(x, y)
                        .0
                        .iter()
                        .map(|&c| c as u64)
                        .sum::<u64>();
                }
            }
            means.push(sum as f64 / ((x1 - x0) * (y1 - y0) * 3) as f64);
        }
    }
    means
}

/// Issue 14: images past 4.2 megapixels (65 535 workgroups × 64 pixels, where one-dimensional
/// dispatches used to stop) render completely with the path tracer and real-time techniques:
/// each block of the large image looks like the same block of a small render of the view.
#[test]
fn four_k_and_eight_k_images_render_completely() {
    let dir = scratch("large");
    for technique in ["path", "none", "ddgi"] {
        let mut images = Vec::new();
        for (w, h) in [(192u32, 108u32), (3840, 2160), (7680, 4320)] {
            let out = dir.join(format!("{technique}-{w}.png"));
            let size = format!("{w}x{h}");
            // Cheap settings: one sample of one bounce, one frame (lavapipe takes about 40 s a
            // frame at 8K on two cores).
            let args = [
                "render",
                "--technique",
                technique,
                "--size",
                &size,
                "--spp",
                "1",
                "--max-bounces",
                "1",
                "--frames",
                "1",
                "--preset",
                "fast",
                "--out",
                out.to_str().unwrap(),
            ];
            let (ok, _, stderr) = irradiant(&args);
            if !ok
                && stderr.contains("no GPU adapter")
                && std::env::var("CI").as_deref() != Ok("true")
            {
                eprintln!("SKIPPED: no GPU adapter");
                return;
            }
            assert!(ok, "irradiant {args:?}: {stderr}");
            let image = image::open(&out).unwrap().to_rgb8();
            assert_eq!(image.dimensions(), (w, h), "{technique} at {size}");
            std::fs::remove_file(&out).unwrap();
            images.push((size, block_means(&image, 8)));
        }
        let (_, small) = &images[0];
        for (size, large) in &images[1..] {
            for (i, (a, b)) in small.iter().zip(large).enumerate() {
                // Bound: the small render's one noisy sample a pixel against the large one's
                // average; an unwritten block (black) or a shifted one is off by far more.
                assert!(
                    (a - b).abs() <= 0.25 * a.max(*b) + 4.0,
                    "{technique} at {size}: block {i} (row {}, column {}) has mean {b:.1}, the small render {a:.1}",
                    i / 8,
                    i % 8
                );
            }
        }
    }
}

/// Settings files and manifest tables: a manifest names a technique and its settings, a
/// --settings file overrides them, unknown keys are warnings and bad values errors that name
/// the field, the value and what is allowed.
#[test]
fn settings_files_and_manifests_set_the_frame_and_the_technique() {
    let dir = scratch("settings");
    let manifest = dir.join("scene.toml");
    std::fs::write(
        &manifest,
        "[mesh]\npath = \"cornell\"\n[technique]\nname = \"none\"\nflavour = 1\n[frame]\narea_light_samples = 2\n",
    )
    .unwrap();
    let out = dir.join("a.png");
    let render = |extra: &[&str]| {
        let mut args = vec![
            "render",
            "--scene",
            manifest.to_str().unwrap(),
            "--size",
            "16x16",
            "--frames",
            "1",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        irradiant(&args)
    };
    let (ok, stdout, stderr) = render(&[]);
    if !ok && stderr.contains("no GPU adapter") && std::env::var("CI").as_deref() != Ok("true") {
        eprintln!("SKIPPED: no GPU adapter");
        return;
    }
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains("none after 1 frames"),
        "the manifest's technique is used: {stdout}"
    );
    assert!(
        stderr.contains("technique.flavour"),
        "an unknown key is a warning: {stderr}"
    );
    let settings = dir.join("settings.toml");
    std::fs::write(
        &settings,
        "[technique]\nname = \"ddgi\"\n[technique.volume]\nrays_per_probe = 16\n",
    )
    .unwrap();
    let (ok, stdout, stderr) = render(&["--settings", settings.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains("ddgi after 1 frames"),
        "the file overrides the manifest: {stdout}"
    );
    std::fs::write(
        &settings,
        "[technique]\nname = \"ddgi\"\n[technique.update]\nhysteresis = 1.5\n",
    )
    .unwrap();
    let (ok, _, stderr) = render(&["--settings", settings.to_str().unwrap()]);
    assert!(
        !ok && stderr.contains("technique.update.hysteresis = 1.5")
            && stderr.contains("0 to 0.999"),
        "{stderr}"
    );
    std::fs::write(&settings, "[frame.taa]\nblend = 0\n").unwrap();
    let (ok, _, stderr) = render(&["--settings", settings.to_str().unwrap()]);
    assert!(!ok && stderr.contains("frame.taa.blend = 0"), "{stderr}");
    std::fs::write(&settings, "[frame\n").unwrap();
    fails_with(
        &["render", "--settings", settings.to_str().unwrap()],
        "settings.toml",
    );
    fails_with(
        &["render", "--settings", "/nonexistent/s.toml"],
        "/nonexistent/s.toml",
    );
}

/// `info --scene` describes a scene's size and watertightness (two-rooms is closed, the
/// Cornell box's walls are open quads).
#[test]
fn info_describes_a_scene_and_its_watertightness() {
    let (ok, stdout, stderr) = irradiant(&["info", "--scene", "two-rooms"]);
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains("triangles (instanced)   108") && stdout.contains("watertight"),
        "{stdout}"
    );
    assert!(stdout.contains("open edges              0 of"), "{stdout}");
    let (ok, stdout, stderr) = irradiant(&["info", "--scene", "cornell"]);
    assert!(ok, "{stderr}");
    assert!(stdout.contains("not watertight"), "{stdout}");
    fails_with(&["info", "--scene", "cornel"], "unknown scene 'cornel'");
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
        if !ok && stderr.contains("no GPU adapter") && std::env::var("CI").as_deref() != Ok("true")
        {
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

/// Needs the test adapter: the soak's short version. Every technique kind's frames over the
/// animated two-rooms come out finite with flat GPU memory; held still with no drift allowed,
/// DDGI (still converging after a few frames) is caught drifting — the check can fail.
#[test]
fn soak_checks_frames_for_non_finite_values_memory_and_drift() {
    let techniques =
        "ddgi,ssil,lightfield{bake.probe_counts=[2,2,2],bake.resolution=32,bake.bounces=1}";
    let scene = TWO_ROOMS_SWITCH;
    let (ok, stdout, stderr) = irradiant(&[
        "soak",
        "--scene",
        scene,
        "--size",
        "32x24",
        "--frames",
        "12",
        "--every",
        "4",
        "--settle",
        "4",
        "--techniques",
        techniques,
    ]);
    assert!(ok, "{stdout}\n{stderr}");
    assert!(stdout.contains("every check passed"), "{stdout}");
    assert_eq!(
        stdout.matches(" ok").count(),
        9,
        "three checks a technique: {stdout}"
    );
    let (ok, stdout, stderr) = irradiant(&[
        "soak",
        "--scene",
        scene,
        "--still",
        "--drift",
        "0",
        "--size",
        "32x24",
        "--frames",
        "12",
        "--every",
        "4",
        "--settle",
        "4",
        "--techniques",
        "ddgi",
    ]);
    assert!(!ok, "{stdout}");
    assert!(
        stderr.contains("drifted by") && stderr.contains("since frame 4"),
        "{stderr}"
    );
    fails_with(&["soak", "--frames", "0"], "must be positive");
}

/// Needs the test adapter: two processes comparing at once, sharing one cache folder, each
/// render the path-traced reference and bake the light field and store both. Neither reads a
/// half-written entry (both succeed with the same figures), the folder ends with one complete
/// entry of each and no temporaries, and a third run reads both.
#[test]
fn two_processes_sharing_a_cache_never_corrupt_it() {
    let dir = scratch("shared-cache");
    let cache = dir.join("cache").to_string_lossy().into_owned();
    let run = |out: &str| {
        let out = dir.join(out).to_string_lossy().into_owned();
        let args = [
            "compare",
            "--scene",
            "cornell",
            "--size",
            "24x24",
            "--reference-spp",
            "8",
            "--frames",
            "2",
            "--techniques",
            "lightfield{bake.probe_counts=[2,2,2],bake.resolution=32,bake.bounces=1}",
            "--cache",
            &cache,
            "--out",
            &out,
        ]
        .map(str::to_owned);
        Command::new(env!("CARGO_BIN_EXE_irradiant"))
            .args(args)
            .env("XDG_RUNTIME_DIR", "/tmp")
            .output()
            .unwrap()
    };
    let json = |out: &str| -> serde_json::Value {
        serde_json::from_str(
            &std::fs::read_to_string(dir.join(out).join("comparison.json")).unwrap(),
        )
        .unwrap()
    };
    let (a, b) = std::thread::scope(|s| {
        let a = s.spawn(|| run("a"));
        let b = s.spawn(|| run("b"));
        (a.join().unwrap(), b.join().unwrap())
    });
    for out in [&a, &b] {
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    assert_eq!(
        json("a")["results"][0]["flip_mean"],
        json("b")["results"][0]["flip_mean"]
    );
    let entries: Vec<String> = std::fs::read_dir(&cache)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    let count = |prefix: &str| entries.iter().filter(|n| n.starts_with(prefix)).count();
    assert_eq!(
        (count("reference-"), count("lightfield-"), count(".")),
        (1, 1, 0),
        "one entry of each, no temporaries: {entries:?}"
    );
    let third = run("c");
    assert!(third.status.success());
    assert_eq!(json("c")["reference_cached"], true);
    assert_eq!(
        json("c")["results"][0]["flip_mean"],
        json("a")["results"][0]["flip_mean"]
    );
}

/// `irradiant oracle` measures each DDGI variant's probes and query against the path tracer and
/// writes what it found: the JSON, the histogram, the worst probes and the error map; it
/// refuses a technique that is not DDGI, naming it.
#[test]
fn oracle_measures_ddgi_probes_and_query_and_draws_the_worst() {
    let out = scratch("oracle");
    let out_text = out.to_str().unwrap();
    let (ok, stdout, stderr) = irradiant(&[
        "oracle",
        "--scene",
        "cornell",
        "--size",
        "32x24",
        "--frames",
        "30",
        "--average",
        "2",
        "--probe-samples",
        "32",
        "--query-samples",
        "16",
        "--probes",
        "2x2x2",
        "--worst",
        "3",
        "--techniques",
        "ddgi,ddgi{update.max_ray_distance=0.05,speed.probe_states=false}",
        "--out",
        out_text,
    ]);
    assert!(ok, "{stdout}\n{stderr}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("oracle.json")).unwrap()).unwrap();
    let results = report["results"].as_array().unwrap();
    assert_eq!(results.len(), 2, "{report}");
    let signed = |i: usize| results[i]["probe"]["signed_error"].as_f64().unwrap();
    // Rays cut at 5 cm bring back no light: the probe oracle sees it.
    assert!(signed(1) < -0.5 && signed(1) < signed(0) - 0.3, "{report}");
    let histogram: u64 = results[0]["probe"]["histogram"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["probes"].as_u64().unwrap())
        .sum();
    assert_eq!(histogram, results[0]["probe"]["probes"].as_u64().unwrap());
    assert_eq!(results[0]["probe"]["worst"].as_array().unwrap().len(), 3);
    assert!(
        results[0]["query"]["median_error"]
            .as_f64()
            .unwrap()
            .is_finite()
    );
    for file in [
        "histogram.txt",
        "worst-probes.png",
        "probe-view.png",
        "query-error.png",
    ] {
        assert!(out.join("ddgi").join(file).is_file(), "{file}");
    }
    let (ok, _, stderr) = irradiant(&["oracle", "--techniques", "ssil", "--out", out_text]);
    assert!(!ok && stderr.contains("'ssil' is not DDGI"), "{stderr}");
}

/// Needs the test adapter. `oracle` and `soak` read the same settings as `render` and
/// `compare`: a misspelt key is a warning, not a silent default, and a bad value in any variant
/// is refused before the first one runs; so are absurd sample counts, a truth without
/// bounces and a file where the report's folder would go.
#[test]
fn oracle_and_soak_warn_of_unknown_settings_and_refuse_bad_input_first() {
    let out = scratch("oracle-settings");
    let out_text = out.to_str().unwrap();
    let tiny_oracle = |techniques: &str| {
        irradiant(&[
            "oracle",
            "--size",
            "8x8",
            "--frames",
            "1",
            "--average",
            "1",
            "--probe-samples",
            "1",
            "--query-samples",
            "1",
            "--probes",
            "2x2x2",
            "--techniques",
            techniques,
            "--out",
            out_text,
        ])
    };
    let unknown = "unknown setting technique.update.bogus is ignored";
    let (ok, stdout, stderr) = tiny_oracle("ddgi{update.bogus=3}");
    assert!(ok, "{stdout}\n{stderr}");
    assert!(stderr.contains(unknown), "{stderr}");
    let (ok, stdout, stderr) = tiny_oracle("ddgi,ddgi{volume.rays_per_probe=0}");
    assert!(!ok, "{stdout}");
    assert!(
        stderr.contains("technique.volume.rays_per_probe = 0"),
        "{stderr}"
    );
    assert!(
        !stdout.contains("oracle:"),
        "the first variant ran before the second's settings were checked:\n{stdout}"
    );
    let fresh = out.join("refused");
    let (ok, _, _) = irradiant(&[
        "oracle",
        "--techniques",
        "ddgi{volume.rays_per_probe=0}",
        "--out",
        fresh.to_str().unwrap(),
    ]);
    assert!(
        !ok && !fresh.exists(),
        "a refused oracle left its folder behind"
    );
    fails_with(
        &["oracle", "--average", "0", "--out", out_text],
        "--average must be positive",
    );
    fails_with(
        &["oracle", "--probe-samples", "4000000000", "--out", out_text],
        "from 1 to 1048576",
    );
    fails_with(
        &["oracle", "--truth-bounces", "0", "--out", out_text],
        "--truth-bounces 0",
    );
    let file = out.join("oracle.json");
    fails_with(
        &["oracle", "--out", file.to_str().unwrap()],
        "is a file, and a report is a folder",
    );
    let (ok, stdout, stderr) = irradiant(&[
        "soak",
        "--scene",
        "cornell",
        "--size",
        "8x8",
        "--frames",
        "1",
        "--every",
        "1",
        "--techniques",
        "ddgi{update.bogus=3}",
    ]);
    assert!(ok, "{stdout}\n{stderr}");
    assert!(stderr.contains(unknown), "{stderr}");
}

/// Needs the test adapter. `bench --techniques` checks each technique's settings before any
/// timing: an unknown key is a warning (it was ignored without a word until session 20), a bad
/// value an error before the adapter is opened.
#[test]
fn bench_checks_technique_settings_before_timing() {
    let smoke_bench = |techniques: &str| {
        irradiant(&[
            "bench",
            "--smoke",
            "--scene",
            "cornell",
            "--techniques",
            techniques,
        ])
    };
    let (ok, stdout, stderr) = smoke_bench("none{bogus=1}");
    assert!(ok, "{stdout}\n{stderr}");
    assert!(
        stderr.contains("unknown setting technique.bogus is ignored"),
        "{stderr}"
    );
    let (ok, stdout, stderr) = smoke_bench("none,ssil{samples=0}");
    assert!(!ok, "{stdout}");
    assert!(stderr.contains("technique.samples = 0"), "{stderr}");
    assert!(
        !stdout.contains("adapter:"),
        "the bench started before the settings were checked:\n{stdout}"
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
