//! `irradiant render` and `info` on the test adapter: every technique and output, sizes up to
//! 8K, settings files and manifests, cameras, and a cache shared by two processes.

mod common;

use std::process::Command;

use common::*;

/// Needs the test adapter: each technique and output kind, a frame sequence, the probe view,
/// the atlas dump and the smoke benchmark.
#[test]
fn renders_every_technique_and_output() {
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
    if !has_adapter(ok, &stderr) {
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
            "--technique",
            "ddgi{update.weights = \"classic\", volume.probe_counts = [3, 2, 2], volume.rays_per_probe = 16}",
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
/// each block of the large image looks like the same block of a small render of the view. One
/// technique at a time: an 8K frame of `none` or `ddgi` takes 6.5 GB on lavapipe.
#[test]
fn four_k_and_eight_k_images_render_completely() {
    // DDGI's probes few: their work does not grow with the image.
    let few_probes = "ddgi{volume.probe_counts = [2, 2, 2], volume.rays_per_probe = 16}";
    for technique in ["path", "none", few_probes] {
        large_images_render_completely(technique);
    }
}

/// `technique` at 192×108, 3840×2160 and 7680×4320: every block of the large images as the
/// small one's.
fn large_images_render_completely(technique: &str) {
    let name = technique.split('{').next().unwrap();
    let dir = scratch(&format!("large-{name}"));
    // Cheap settings, as every pass still runs: one sample of one bounce, one frame, one
    // emitter candidate and, in the first frame, one neighbour (with none, frame/direct_reuse
    // draws the light alone and frame/direct does not run).
    let cheap = dir.join("cheap.toml");
    std::fs::write(
        &cheap,
        "[frame.resampling]\ncandidates = 1\nneighbours = 0\ncut_candidates = 1\ncut_neighbours = 1\n",
    )
    .unwrap();
    let mut images = Vec::new();
    for (w, h) in [(192u32, 108u32), (3840, 2160), (7680, 4320)] {
        let out = dir.join(format!("{name}-{w}.png"));
        let size = format!("{w}x{h}");
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
            "--settings",
            cheap.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        let (ok, _, stderr) = irradiant(&args);
        if !has_adapter(ok, &stderr) {
            return;
        }
        assert!(ok, "irradiant {args:?}: {stderr}");
        assert!(
            !stderr.contains("unknown setting"),
            "irradiant {args:?} ignored a setting: {stderr}"
        );
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
    if !has_adapter(ok, &stderr) {
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

/// Needs the test adapter. A camera written by `render --save-camera` and read back by
/// `--camera-from` gives the same image as the same view typed with `--camera`; a spec's own
/// preset reaches the technique (`quality`'s image differs from the default's).
#[test]
fn a_saved_camera_renders_the_same_view_and_a_spec_carries_its_preset() {
    let dir = scratch("camera");
    let path = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let render = |extra: &[&str], out: &str| {
        let mut args = vec![
            "render", "--scene", "cornell", "--size", "24x16", "--frames", "2", "--out",
        ];
        let out = path(out);
        args.push(&out);
        args.extend_from_slice(extra);
        let (ok, _, stderr) = irradiant(&args);
        (ok, stderr, std::fs::read(&out).unwrap_or_default())
    };
    let view = "0.3,1.2,2.8,0,0.8,0,50";
    let camera_file = path("view.toml");
    let (ok, stderr, typed) = render(
        &["--camera", view, "--save-camera", &camera_file],
        "typed.png",
    );
    if !has_adapter(ok, &stderr) {
        return;
    }
    assert!(ok, "{stderr}");
    let saved = std::fs::read_to_string(&camera_file).unwrap();
    assert!(
        saved.contains("[camera]") && saved.contains("fov_y_degrees = 50"),
        "{saved}"
    );
    let (ok, stderr, read_back) = render(&["--camera-from", &camera_file], "read.png");
    assert!(ok, "{stderr}");
    assert_eq!(typed, read_back, "the saved camera rendered another image");
    let (ok, stderr, default_view) = render(&[], "default.png");
    assert!(ok, "{stderr}");
    assert_ne!(typed, default_view, "--camera left the scene's view");
    let (ok, stderr, quality) = render(
        &["--technique", "ddgi{preset = \"quality\"}"],
        "quality.png",
    );
    assert!(ok, "{stderr}");
    assert_ne!(
        quality, default_view,
        "the spec's preset did not reach the technique"
    );
    fails_with(
        &["render", "--camera", view, "--camera-from", &camera_file],
        "cannot be used with",
    );
}
