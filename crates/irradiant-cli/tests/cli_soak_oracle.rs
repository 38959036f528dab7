//! `irradiant soak` and `irradiant oracle` on the test adapter.

mod common;

use common::*;

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
        "--worst",
        "3",
        "--techniques",
        "ddgi{volume.probe_counts=[2,2,2]},ddgi{volume.probe_counts=[2,2,2],update.max_ray_distance=0.05,speed.probe_states=false}",
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
    // Each variant's files go into a folder named after its label.
    let first = out.join("ddgi_volume.probe_counts__2_2_2__".replace('.', "_"));
    for file in [
        "histogram.txt",
        "worst-probes.png",
        "probe-view.png",
        "query-error.png",
    ] {
        assert!(first.join(file).is_file(), "{}/{file}", first.display());
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
