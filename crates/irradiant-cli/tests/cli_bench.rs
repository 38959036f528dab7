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
    let (ok, stdout, stderr) = irradiant(&[
        "bench",
        "--smoke",
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
    let ddgi = &record["techniques"][0];
    assert!(ddgi["passes"].as_array().unwrap().len() >= 9, "{ddgi}");
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
