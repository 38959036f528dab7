//! The plots of how cost grows (BENCHMARKS.md, "How cost grows"; issue 42) from the `irradiant bench`
//! JSON files that `tools/device/growth.sh` writes:
//!
//! ```text
//! cargo run -p irradiant-eval --example growth_plots -- DIR docs/images/growth
//! ```
//!
//! DIR holds growth-*.json; five SVG files are written into the second folder.

use std::path::{Path, PathBuf};

use irradiant_eval::plot::{Axes, Curve, CurveStyle, Scale, plot_svg};
use serde_json::Value;

fn main() {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let [input, output] = args.as_slice() else {
        eprintln!(
            "usage: growth_plots DIR OUT_DIR (DIR: growth-*.json from tools/device/growth.sh)"
        );
        std::process::exit(2);
    };
    if let Err(e) = run(input, output) {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run(input: &Path, output: &Path) -> Result<(), String> {
    let records = read_records(input)?;
    std::fs::create_dir_all(output).map_err(|e| format!("{}: {e}", output.display()))?;
    let plots = [
        (
            "rays-against-triangles.svg",
            rays_against_triangles(&records),
        ),
        (
            "build-against-triangles.svg",
            build_against_triangles(&records),
        ),
        ("ddgi-against-probes.svg", ddgi_against_probes(&records)),
        ("ddgi-against-rays.svg", ddgi_against_rays(&records)),
        (
            "frame-against-resolution.svg",
            frame_against_resolution(&records),
        ),
    ];
    for (name, svg) in plots {
        let path = output.join(name);
        std::fs::write(&path, svg).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Every growth-*.json of `dir`, by file stem (`growth-rays-sibenik-world-4`).
fn read_records(dir: &Path) -> Result<Vec<(String, Value)>, String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut records = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        if !(stem.starts_with("growth-") && path.extension().is_some_and(|e| e == "json")) {
            continue;
        }
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let value = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        records.push((stem.to_string(), value));
    }
    if records.is_empty() {
        return Err(format!(
            "{}: no growth-*.json; run tools/device/growth.sh on the lent GPU and unpack its growth.tgz here",
            dir.display()
        ));
    }
    records.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(records)
}

/// Both axes logarithmic: every sweep here spans orders of magnitude.
fn log_log<'a>(title: &'a str, x_label: &'a str, y_label: &'a str) -> Axes<'a> {
    Axes {
        title,
        x_label,
        y_label,
        x: Scale::Log,
        y: Scale::Log,
    }
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

/// The first scene of a record and the Mrays/s of its ray pass whose label ends in `rays`.
fn scene_and_rays<'a>(record: &'a Value, rays: &str) -> Option<(&'a Value, f64)> {
    let scene = record["scenes"].get(0)?;
    let pass = record["passes"]
        .as_array()?
        .iter()
        .find(|p| p["label"].as_str().is_some_and(|l| l.ends_with(rays)))?;
    Some((scene, number(&pass["mrays_per_s"])))
}

/// Points of the grown Sibenik worlds (flattened or instanced) by triangles in the world.
fn world_points(
    records: &[(String, Value)],
    flat: bool,
    y: impl Fn(&Value) -> Option<f64>,
) -> Vec<(f64, f64)> {
    let mut points: Vec<(f64, f64)> = records
        .iter()
        .filter(|(name, _)| {
            name.starts_with("growth-rays-sibenik-world-") && name.ends_with("-flat") == flat
        })
        .filter_map(|(_, r)| Some((number(&r["scenes"][0]["world_triangles"]), y(r)?)))
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    points
}

fn rays_against_triangles(records: &[(String, Value)]) -> String {
    let mut curves = Vec::new();
    for (rays, label) in [("(diffuse)", "diffuse"), ("(primary)", "primary")] {
        for (flat, layout) in [(false, "instances"), (true, "one mesh")] {
            let points = world_points(records, flat, |r| Some(scene_and_rays(r, rays)?.1));
            curves.push(Curve::line(format!("{label}, {layout}"), points));
        }
    }
    let shipped = records
        .iter()
        .filter(|(name, _)| name.starts_with("growth-rays-") && !name.contains("sibenik-world"))
        .filter_map(|(_, r)| {
            let (scene, mrays) = scene_and_rays(r, "(diffuse)")?;
            Some((number(&scene["world_triangles"]), mrays))
        })
        .collect();
    curves.push(Curve {
        name: "diffuse, shipped scenes".into(),
        points: shipped,
        style: CurveStyle::Points,
    });
    let axes = log_log(
        "Rays a second against triangles (Sibenik's world grown around its camera)",
        "triangles in the world",
        "Mrays/s",
    );
    plot_svg(&axes, &curves)
}

fn build_against_triangles(records: &[(String, Value)]) -> String {
    let scene = |key: &'static str| move |r: &Value| Some(number(&r["scenes"][0][key]));
    let curves = vec![
        Curve::line(
            "build ms, one mesh",
            world_points(records, true, scene("bvh_build_ms")),
        ),
        Curve::line(
            "GPU scene MiB, one mesh",
            world_points(records, true, scene("gpu_scene_mib")),
        ),
        Curve::line(
            "peak host MiB, one mesh",
            world_points(records, true, scene("peak_host_mib")),
        ),
        Curve::line(
            "build ms, instances",
            world_points(records, false, scene("bvh_build_ms")),
        ),
    ];
    let axes = log_log(
        "BVH build time and memory against triangles",
        "triangles in the world",
        "ms or MiB",
    );
    plot_svg(&axes, &curves)
}

/// (probes in the volume, update ms) of every DDGI frame whose variant contains `variant`.
fn update_points(
    records: &[(String, Value)],
    prefix: &str,
    variant: &str,
    x: &str,
) -> Vec<(f64, f64)> {
    let mut points: Vec<(f64, f64)> = records
        .iter()
        .filter(|(name, _)| name.starts_with(prefix))
        .flat_map(|(_, r)| r["techniques"].as_array().cloned().unwrap_or_default())
        .filter(|t| t["variant"].as_str().is_some_and(|v| v.contains(variant)))
        .map(|t| {
            let x = match x {
                "probes" => t["probes"]
                    .as_array()
                    .map_or(f64::NAN, |p| p.iter().map(number).product()),
                key => number(&t[key]),
            };
            (x, number(&t["update_ms"]))
        })
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    points
}

fn ddgi_against_probes(records: &[(String, Value)]) -> String {
    let curves = vec![
        Curve::line(
            "update ms, probe states on",
            update_points(records, "growth-probes-", "probe_states=true", "probes"),
        ),
        Curve::line(
            "update ms, every probe traces",
            update_points(records, "growth-probes-", "probe_states=false", "probes"),
        ),
    ];
    let axes = log_log(
        "DDGI's update against probes (Sibenik, 256 rays a probe)",
        "probes in the volume",
        "ms",
    );
    plot_svg(&axes, &curves)
}

fn ddgi_against_rays(records: &[(String, Value)]) -> String {
    let points = update_points(
        records,
        "growth-rays-per-probe",
        "rays_per_probe",
        "rays_per_probe",
    );
    let axes = log_log(
        "DDGI's update against rays a probe (Sibenik, 32×8×32 probes)",
        "rays a probe",
        "ms",
    );
    plot_svg(&axes, &[Curve::line("update ms, probe states on", points)])
}

fn frame_against_resolution(records: &[(String, Value)]) -> String {
    let frames: Vec<(f64, &Value)> = records
        .iter()
        .filter(|(name, _)| name.starts_with("growth-resolution-"))
        .filter_map(|(_, r)| {
            let size = r["size"].as_array()?;
            let megapixels = number(&size[0]) * number(&size[1]) / 1e6;
            Some((megapixels, r["techniques"].get(0)?))
        })
        .collect();
    let pass = |label: &str| -> Vec<(f64, f64)> {
        let mut points: Vec<(f64, f64)> = frames
            .iter()
            .filter_map(|(mp, t)| {
                let ms = t["passes"].as_array()?.iter().find(|p| p[0] == label)?;
                Some((*mp, number(&ms[1])))
            })
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        points
    };
    let total = |key: &str| -> Vec<(f64, f64)> {
        let mut points: Vec<(f64, f64)> = frames
            .iter()
            .map(|(mp, t)| (*mp, number(&t[key])))
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        points
    };
    let curves = vec![
        Curve::line("whole frame", total("frame_ms")),
        Curve::line("DDGI (update + resolve)", total("gi_ms")),
        Curve::line("frame/direct", pass("frame/direct")),
        Curve::line("frame/gbuffer", pass("frame/gbuffer")),
        Curve::line("ddgi/resolve", pass("ddgi/resolve")),
    ];
    let axes = log_log(
        "The frame against resolution (Sibenik, DDGI balanced; 720p to 8K)",
        "megapixels",
        "ms",
    );
    plot_svg(&axes, &curves)
}
