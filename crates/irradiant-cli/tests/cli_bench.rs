//! `irradiant bench` on the test adapter: the smoke run, the order check, and settings checked
//! before timing. The figures themselves are lavapipe's, so only the mechanism is tested.

mod common;

use common::*;

/// Needs the test adapter. The smoke bench times ray casting, the path tracer and the frames of
/// the techniques listed, a `--vary` grid applying to the techniques that have its settings.
#[test]
fn the_smoke_bench_times_every_pass_and_a_vary_grid() {
    let dir = scratch("bench-smoke");
    let path = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let json = path("bench.json");
    let rays = path("rays");
    let (ok, stdout, stderr) = irradiant(&[
        "bench",
        "--smoke",
        "--dump-rays",
        &rays,
        "--techniques",
        "ddgi{volume.rays_per_probe = 32},ssil",
        "--vary",
        "start = [\"quarter\", \"half\"]",
        "--vary",
        "visibility = [false, true]",
        "--json",
        &json,
    ]);
    if !has_adapter(ok, &stderr) {
        return;
    }
    assert!(ok, "{stderr}");
    assert!(
        stdout.contains("raycast/trace (diffuse)")
            && stdout.contains("pathtrace/trace")
            && stdout.contains("blend_irradiance")
            && stdout.contains("start=\"half\" visibility=true")
            && stdout.contains("voxel grid"),
        "{stdout}"
    );
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let frames = record["techniques"].as_array().unwrap();
    // DDGI has neither varied setting and is timed once; SSIL at each of the four.
    assert_eq!(frames.len(), 5, "{record}");
    let ssil = &frames[1..];
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
            "--techniques",
            "ssil",
            "--vary",
            "levels = [4, 9]",
        ],
        "technique.levels",
    );
    let record: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(record["passes"].as_array().unwrap().len() >= 4);
    // The wavefront's sample split by pass: each part within the whole, the tail among them.
    let median = |label: &str| {
        record["passes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["label"] == label)
            .unwrap_or_else(|| panic!("no {label} in {record}"))["median_ms"]
            .as_f64()
            .unwrap()
    };
    let whole = median("pathtrace/wavefront (1 spp)");
    for part in ["camera", "bounce", "tail"] {
        let part = median(&format!("pathtrace/{part} (wavefront, 1 spp)"));
        assert!(part > 0.0 && part <= whole, "{part} ms of {whole}");
    }
    let ddgi = &record["techniques"][0];
    assert!(ddgi["passes"].as_array().unwrap().len() >= 9, "{ddgi}");
    the_dumped_rays_land_on_the_dumped_triangles(&dir.join("rays"), &record);
}

/// `--dump-rays` (for tools/mitsuba/rays.py): every triangle of the world, 64×64 rays a set, and
/// each hit's distance, such that a primary ray's hit point lies on one of the triangles.
fn the_dumped_rays_land_on_the_dumped_triangles(dir: &std::path::Path, record: &serde_json::Value) {
    let floats = |name: &str| -> Vec<f32> {
        let bytes = std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        bytes
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect()
    };
    let triangles = floats("cornell.triangles.f32");
    let world_triangles = record["scenes"][0]["world_triangles"].as_u64().unwrap() as usize;
    assert_eq!(triangles.len(), world_triangles * 9);
    let corners: Vec<[f32; 3]> = triangles
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    for set in ["primary", "diffuse"] {
        let rays = floats(&format!("cornell.{set}.rays.f32"));
        let t = floats(&format!("cornell.{set}.t.f32"));
        assert_eq!((rays.len(), t.len()), (64 * 64 * 6, 64 * 64), "{set}");
        let hits = t.iter().filter(|&&t| t >= 0.0).count();
        assert!(hits > 64 * 64 / 2, "{set}: {hits} hits of 4096");
    }
    let rays = floats("cornell.primary.rays.f32");
    let t = floats("cornell.primary.t.f32");
    let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f32; 3], b: [f32; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // Whether p lies within 1 mm of the triangle's plane and inside its edges.
    let on = |p: [f32; 3], tri: &[[f32; 3]]| {
        let n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]));
        let area2 = dot(n, n).sqrt();
        let plane = dot(sub(p, tri[0]), n).abs() / area2;
        let inside = (0..3).all(|i| {
            let edge = cross(sub(tri[(i + 1) % 3], tri[i]), sub(p, tri[i]));
            dot(edge, n) >= -1e-3 * area2
        });
        plane < 1e-3 && inside
    };
    for (ray, &t) in rays
        .chunks_exact(6)
        .zip(&t)
        .step_by(97)
        .filter(|(_, t)| **t >= 0.0)
    {
        let p = [0, 1, 2].map(|i| ray[i] + ray[i + 3] * t);
        assert!(
            corners.chunks_exact(3).any(|tri| on(p, tri)),
            "the hit {p:?} lies on no triangle"
        );
    }
}

/// `bench --check-order` runs the scenes forward and reversed in one call and compares every
/// pass; the figures themselves are lavapipe's, so only the mechanism is tested here (the H100
/// figures are in BENCHMARKS.md).
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

/// Needs the test adapter. `bench --techniques` checks each technique's settings before any
/// timing: an unknown key is a warning (before 2026-11-24 it was ignored without a word), a bad
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
