//! `irradiant oracle`: DDGI's error split in two (docs/ddgi.md "Oracles"). For each DDGI variant
//! the probe oracle compares the converged atlases with the path tracer's value of every probe
//! texel (the update's error) and the query oracle compares the indirect light at the G-buffer's
//! points with the path tracer's (the query's error). Writes oracle.json and, per variant, the
//! histogram, the worst probes' tiles, the probe view with the worst probes circled and the
//! query's error map.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Args;
use irradiant::ddgi::oracle::{
    ProbeOracle, QueryOracle, compare_with_truth, converged_atlases, probe_oracle, query_oracle,
};
use irradiant::frame::write_png;
use irradiant::gpu_types::GpuCamera;
use irradiant::pathtrace::{LightSampling, PathTraceSettings};
use irradiant::{AdapterChoice, GpuContext, Session, SessionSettings};
use serde_json::json;

use crate::CliError;
use crate::options::{RunSettings, SettingsArgs, parse_size, technique_list};

#[derive(Args)]
pub struct OracleArgs {
    /// A built-in scene, a manifest or a mesh file.
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    /// DDGI variants, comma-separated, each measured by both oracles, e.g.
    /// `ddgi,ddgi{update.weights = "chebyshev"}`.
    #[arg(long, default_value = "ddgi")]
    pub techniques: Vec<String>,
    /// Output folder (created; files of an earlier run are replaced).
    #[arg(long)]
    pub out: PathBuf,
    /// Image size of the query oracle, WIDTHxHEIGHT.
    #[arg(long, default_value = "256x192", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Frames each variant runs before it is measured.
    #[arg(long, default_value = "300")]
    pub frames: u32,
    /// Frames whose atlases are averaged after that: the converged value, its frame-to-frame
    /// noise averaged out (1: one frame's atlases, noise and all).
    #[arg(long, default_value = "16")]
    pub average: u32,
    /// Path-traced samples a probe texel: the truth's noise falls as 1/√samples (the oracle
    /// prints its own precision).
    #[arg(long, default_value = "4096", value_parser = crate::options::parse_samples)]
    pub probe_samples: u32,
    /// Path-traced samples a G-buffer point (0: no query oracle).
    #[arg(long, default_value = "1024", value_parser = crate::options::parse_samples_or_none)]
    pub query_samples: u32,
    /// Probes drawn in worst-probes.png and circled in probe-view.png.
    #[arg(long, default_value = "8")]
    pub worst: usize,
    /// A diagnostic: the truth counts only light that reflected at most this many times on
    /// its way to the probe or the surface point (1: the emitters' light off one surface; at
    /// least 1, as DDGI's probes hold that light). Default: every bounce.
    #[arg(long)]
    pub truth_bounces: Option<u32>,
    /// A diagnostic: how the truth finds emitted light — both (multiple importance, the
    /// truth), emitters (the emitter sample alone, as DDGI's probe rays) or brdf
    /// (BRDF-sampled rays alone). The three must agree; where they do not, one is wrong.
    #[arg(long, default_value = "both", value_parser = parse_light_sampling)]
    pub truth_sampling: LightSampling,
    #[command(flatten)]
    pub settings: SettingsArgs,
}

pub fn run(args: &OracleArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    // --average 0 would read one frame's atlases while the header said none were averaged.
    if args.frames == 0 || args.average == 0 {
        return Err(CliError::Usage(
            "--frames and --average must be positive".into(),
        ));
    }
    // With no bounce the truth is the emitters seen directly, which DDGI's probes never hold
    // alone: every figure would compare the probes' light with nearly nothing.
    if args.truth_bounces == Some(0) {
        return Err(CliError::Usage(
            "--truth-bounces 0 leaves the truth without the direct light DDGI's probes hold: use 1 or more, or leave it out for every bounce".into(),
        ));
    }
    crate::options::check_report_folder(&args.out)?;
    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let scene = loaded.scene;
    let mut run = RunSettings::new(&args.settings, &scene, 0)?;
    // The query oracle compares with the G-buffer point by point: pixel centres, no history.
    run.frame.taa.enabled = false;
    let techniques = technique_list(&args.techniques)?;
    if let Some(other) = techniques.iter().find(|t| t.name != "ddgi") {
        return Err(CliError::Usage(format!(
            "--techniques: '{}' is not DDGI; the oracles measure DDGI variants",
            other.label
        )));
    }
    let specs = run.checked_specs(&techniques, &args.settings, &scene)?;
    // Made only once the input is known good, so that a refused run leaves no folder.
    std::fs::create_dir_all(&args.out).map_err(|e| CliError::Io {
        path: args.out.clone(),
        message: e.to_string(),
    })?;
    let ctx = Arc::new(GpuContext::new(adapter)?);
    let truth = |samples: u32| PathTraceSettings {
        samples_per_pixel: samples,
        samples_per_dispatch: 64,
        max_bounces: args
            .truth_bounces
            .unwrap_or(PathTraceSettings::balanced().max_bounces),
        light_sampling: args.truth_sampling,
        ..PathTraceSettings::balanced()
    };
    println!(
        "oracle: {} on {}, {}×{}, {} frames (+{} averaged), {} samples a probe texel, {} a pixel",
        scene.name,
        ctx.info.name,
        args.size.0,
        args.size.1,
        args.frames,
        args.average,
        args.probe_samples,
        args.query_samples
    );
    if args.truth_bounces.is_some() || args.truth_sampling != LightSampling::Both {
        let diagnostic = truth(1);
        println!(
            "the truth is a diagnostic's: at most {} bounces, light sampling {:?}",
            diagnostic.max_bounces, diagnostic.light_sampling
        );
    }
    println!(
        "{:<44} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "variant", "probe med", "probe Σ", "distance", "truth ±", "query med", "query Σ"
    );
    let mut results = Vec::new();
    // The G-buffer is the same for every variant: its truth is gathered once.
    let mut query_truth: Option<(Vec<[f32; 3]>, QueryOracle)> = None;
    for (choice, spec) in techniques.iter().zip(specs) {
        let mut session = Session::new(
            ctx.clone(),
            scene.clone(),
            SessionSettings {
                size: args.size,
                frame: run.frame.clone(),
                technique: spec,
                ..Default::default()
            },
        )?;
        let atlases = converged_atlases(&mut session, args.frames, args.average)?;
        let volume = session
            .technique_as::<irradiant::ddgi::Ddgi>()
            .expect("the variant is DDGI")
            .volume();
        let probes = probe_oracle(
            &ctx,
            session.gpu_scene(),
            volume,
            &atlases,
            &truth(args.probe_samples),
            |_, _| {},
        )?;
        if probes.probes.is_empty() {
            eprintln!(
                "warning: {}: no probe updates (every one is asleep or off), so the probe oracle compares none",
                choice.label
            );
        }
        let query = if args.query_samples > 0 {
            let gbuffer = session.gbuffer()?;
            let indirect = session.indirect()?;
            let positions: Vec<[f32; 3]> = gbuffer.iter().map(|g| g.position).collect();
            let oracle = match &query_truth {
                Some((seen, first)) if *seen == positions => {
                    compare_with_truth(&indirect, &first.truth, &gbuffer, &scene.regions)
                }
                _ => query_oracle(
                    &ctx,
                    session.gpu_scene(),
                    &gbuffer,
                    &indirect,
                    &scene.regions,
                    &truth(args.query_samples),
                    |_, _| {},
                )?,
            };
            query_truth = Some((positions, oracle.clone()));
            Some(oracle)
        } else {
            None
        };
        println!(
            "{:<44} {:>8.2}% {:>+8.2}% {:>8.2}% {:>8.2}% {:>9} {:>9}",
            choice.label,
            100.0 * probes.median_texel_error,
            100.0 * probes.signed_error,
            100.0 * probes.median_distance_error,
            100.0 * probes.truth_precision,
            query
                .as_ref()
                .map_or("-".into(), |q| format!("{:.2}%", 100.0 * q.median_error)),
            query
                .as_ref()
                .map_or("-".into(), |q| format!("{:+.2}%", 100.0 * q.signed_error)),
        );
        let dir = args.out.join(choice.file_stem());
        std::fs::create_dir_all(&dir).map_err(|e| CliError::Io {
            path: dir.clone(),
            message: e.to_string(),
        })?;
        write_text(&dir.join("histogram.txt"), &histogram_text(&probes))?;
        write_worst_tiles(&dir.join("worst-probes.png"), &probes, args.worst)?;
        session.set_show_probes(true);
        session.render()?;
        write_probe_view(
            &dir.join("probe-view.png"),
            &session,
            &probes,
            args.worst,
            args.size,
        )?;
        if let Some(q) = &query {
            write_error_map(&dir.join("query-error.png"), q)?;
        }
        results.push(json!({
            "label": choice.label,
            "probe": probe_json(&probes, args.worst),
            "query": query.as_ref().map(query_json),
        }));
    }
    let report = json!({
        "scene": scene.name,
        "adapter": ctx.info.name,
        "size": [args.size.0, args.size.1],
        "frames": args.frames,
        "average": args.average,
        "probe_samples": args.probe_samples,
        "query_samples": args.query_samples,
        "results": results,
    });
    write_text(
        &args.out.join("oracle.json"),
        &serde_json::to_string_pretty(&report).expect("JSON values serialize"),
    )?;
    println!(
        "wrote {}/oracle.json and a folder a variant",
        args.out.display()
    );
    Ok(())
}

fn write_text(path: &Path, text: &str) -> Result<(), CliError> {
    std::fs::write(path, text).map_err(|e| CliError::Io {
        path: path.to_owned(),
        message: e.to_string(),
    })
}

fn probe_json(p: &ProbeOracle, worst: usize) -> serde_json::Value {
    json!({
        "probes": p.probes.len(),
        "skipped_probes": p.skipped_probes,
        "tied_probes": p.tied_probes,
        "median_texel_error": p.median_texel_error,
        "signed_error": p.signed_error,
        "median_distance_error": p.median_distance_error,
        "truth_precision": p.truth_precision,
        "histogram": (0..p.histogram.len()).map(|b| {
            let (lo, hi) = ProbeOracle::histogram_range(b);
            json!({"from": finite_or_null(lo), "to": finite_or_null(hi), "probes": p.histogram[b]})
        }).collect::<Vec<_>>(),
        "worst": p.worst(worst).into_iter().map(probe_error_json).collect::<Vec<_>>(),
        "every_probe": p.probes.iter().map(probe_error_json).collect::<Vec<_>>(),
    })
}

fn probe_error_json(p: &irradiant::ddgi::oracle::ProbeError) -> serde_json::Value {
    json!({
        "probe": p.probe,
        "centre": p.centre.to_array(),
        "signed": p.signed,
        "texel_median": p.texel_median,
        "distance_median": p.distance_median,
    })
}

fn finite_or_null(v: f32) -> Option<f32> {
    v.is_finite().then_some(v)
}

fn query_json(q: &QueryOracle) -> serde_json::Value {
    json!({
        "median_error": q.median_error,
        "signed_error": q.signed_error,
        "bright_specks": q.specks.0,
        "dark_specks": q.specks.1,
        "regions": q.regions.iter().map(|(name, ddgi, truth)| json!({
            "name": name, "ddgi": ddgi, "truth": truth,
            "signed": ddgi / truth.max(1e-12) - 1.0,
        })).collect::<Vec<_>>(),
    })
}

/// The per-probe error histogram as text bars.
fn histogram_text(p: &ProbeOracle) -> String {
    let mut text = format!(
        "per-probe error (Σ DDGI ÷ Σ truth − 1), {} probes, {} skipped, {} tied\n",
        p.probes.len(),
        p.skipped_probes,
        p.tied_probes
    );
    let most = p.histogram.iter().copied().max().unwrap_or(1).max(1);
    for (b, &count) in p.histogram.iter().enumerate() {
        let (lo, hi) = ProbeOracle::histogram_range(b);
        let bar = "#".repeat((count as usize * 50).div_ceil(most as usize));
        let _ = writeln!(
            text,
            "{:>7} … {:<7} {count:>6} {bar}",
            percent(lo),
            percent(hi)
        );
    }
    text
}

fn percent(v: f32) -> String {
    if v.is_finite() {
        format!("{:+.0}%", 100.0 * v)
    } else if v > 0.0 {
        "+∞".into()
    } else {
        "−∞".into()
    }
}

/// The worst probes' irradiance tiles, a row each: truth, DDGI, and their difference (red:
/// DDGI brighter, blue: darker, full at ±50 %), each texel drawn 8×8.
fn write_worst_tiles(path: &Path, p: &ProbeOracle, worst: usize) -> Result<(), CliError> {
    const SCALE: u32 = 8;
    let texels = p.irradiance_texels;
    let side = texels * SCALE;
    let rows: Vec<usize> = p
        .worst(worst)
        .iter()
        .map(|w| p.probes.iter().position(|q| q.probe == w.probe).unwrap())
        .collect();
    if rows.is_empty() {
        return Ok(());
    }
    let (width, height) = (3 * side + 2 * SCALE, rows.len() as u32 * (side + SCALE));
    let mut rgba = vec![0u8; (width * height * 4) as usize];
    let peak = p
        .irradiance
        .iter()
        .flatten()
        .map(|(_, t)| t[0].max(t[1]).max(t[2]))
        .fold(1e-6f32, f32::max);
    let tone = |v: f32| ((v / peak).clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0) as u8;
    for (row, &slot) in rows.iter().enumerate() {
        for (t, (ddgi, truth)) in p.irradiance[slot].iter().enumerate() {
            let relative = (irradiant::pathtrace::gather::luminance(*ddgi)
                / irradiant::pathtrace::gather::luminance(*truth).max(1e-6)
                - 1.0)
                .clamp(-0.5, 0.5)
                * 2.0;
            let difference = if relative >= 0.0 {
                [
                    255,
                    (255.0 * (1.0 - relative)) as u8,
                    (255.0 * (1.0 - relative)) as u8,
                ]
            } else {
                [
                    (255.0 * (1.0 + relative)) as u8,
                    (255.0 * (1.0 + relative)) as u8,
                    255,
                ]
            };
            let colours = [truth.map(tone), ddgi.map(tone), difference];
            let (tx, ty) = (t as u32 % texels, t as u32 / texels);
            for (panel, colour) in colours.iter().enumerate() {
                for dy in 0..SCALE {
                    for dx in 0..SCALE {
                        let x = panel as u32 * (side + SCALE) + tx * SCALE + dx;
                        let y = row as u32 * (side + SCALE) + ty * SCALE + dy;
                        let i = ((y * width + x) * 4) as usize;
                        rgba[i..i + 4].copy_from_slice(&[colour[0], colour[1], colour[2], 255]);
                    }
                }
            }
        }
    }
    Ok(write_png(path, &rgba, width, height)?)
}

/// The probe view (every probe a sphere showing its irradiance) with the worst probes
/// circled: red where DDGI is too bright, blue where too dark.
fn write_probe_view(
    path: &Path,
    session: &Session,
    p: &ProbeOracle,
    worst: usize,
    (width, height): (u32, u32),
) -> Result<(), CliError> {
    let mut rgba = session.tonemapped()?;
    let camera = GpuCamera::new(session.camera(), width, height);
    for w in p.worst(worst) {
        let Some((pixel, _)) = camera.project(w.centre, width, height) else {
            continue;
        };
        let colour = if w.signed >= 0.0 {
            [255, 40, 40]
        } else {
            [40, 120, 255]
        };
        let radius = (width.min(height) as f32 / 40.0).max(4.0);
        for step in 0..256 {
            let angle = step as f32 / 256.0 * std::f32::consts::TAU;
            for ring in [radius, radius + 1.0] {
                let x = (pixel.x + ring * angle.cos()) as i64;
                let y = (pixel.y + ring * angle.sin()) as i64;
                if x >= 0 && y >= 0 && (x as u32) < width && (y as u32) < height {
                    let i = ((y as u32 * width + x as u32) * 4) as usize;
                    rgba[i..i + 3].copy_from_slice(&colour);
                }
            }
        }
    }
    Ok(write_png(path, &rgba, width, height)?)
}

/// The query's signed error per pixel: white where exact, red where DDGI is brighter, blue
/// where darker (full at ±50 %), black where nothing is measured.
fn write_error_map(path: &Path, q: &QueryOracle) -> Result<(), CliError> {
    let rgba: Vec<u8> = q
        .error
        .iter()
        .flat_map(|&e| {
            if !e.is_finite() {
                return [0, 0, 0, 255];
            }
            let v = (e.clamp(-0.5, 0.5) * 2.0).abs();
            let fade = (255.0 * (1.0 - v)) as u8;
            if e >= 0.0 {
                [255, fade, fade, 255]
            } else {
                [fade, fade, 255, 255]
            }
        })
        .collect();
    Ok(write_png(path, &rgba, q.width, q.height)?)
}

fn parse_light_sampling(text: &str) -> Result<LightSampling, String> {
    match text {
        "both" => Ok(LightSampling::Both),
        "emitters" => Ok(LightSampling::Emitters),
        "brdf" => Ok(LightSampling::Brdf),
        _ => Err(format!(
            "'{text}' is not a way to sample light: write both, emitters or brdf"
        )),
    }
}
