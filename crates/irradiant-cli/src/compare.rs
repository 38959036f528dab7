//! `irradiant compare`: one view rendered by each technique and by the path tracer, with FLIP,
//! PSNR, relative MSE, indirect light in named regions and GPU time per pass, as an HTML report
//! and JSON (and, with --over-time, error and flicker while the scene's animation plays).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Args;
use irradiant::frame::Image;
use irradiant::pathtrace::PathTraceSettings;
use irradiant::{
    AdapterChoice, GpuContext, GpuScene, GpuSceneSettings, Session, SessionSettings, TechniqueSpec,
};
use irradiant_eval::report::{Comparison, TechniqueResult};

use crate::CliError;
use crate::options::{CameraArgs, RunSettings, SettingsArgs, parse_size};
use crate::reference::reference;

#[derive(Args)]
pub struct CompareArgs {
    /// A built-in scene, a manifest or a mesh file.
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    #[command(flatten)]
    pub view: CameraArgs,
    /// Techniques to compare, comma-separated, from the registry (`irradiant compare --help`
    /// lists them; `all` takes every one).
    /// Settings of a technique's own go in braces as a TOML inline table, so that variants of
    /// one technique compare side by side: `ssil,ssil{visibility = false}`.
    #[arg(long, default_value = "none,classic-probes,ddgi")]
    pub techniques: Vec<String>,
    /// Output folder (created; replaced if it holds an earlier comparison).
    #[arg(long)]
    pub out: PathBuf,
    #[arg(long, default_value = "320x240", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Samples per pixel of the path-traced reference.
    #[arg(long, default_value = "2048", value_parser = crate::options::parse_samples)]
    pub reference_spp: u32,
    /// Also show every other technique's image minus this one's (a label from --techniques):
    /// what a technique or a setting adds and removes, e.g. visibility with
    /// `--techniques "ssil{visibility = false},ssil" --difference-from "ssil{visibility = false}"`.
    #[arg(long)]
    pub difference_from: Option<String>,
    /// Indirect bounces the references follow (default: every bounce, full global
    /// illumination). 1 measures a one-bounce technique (SSIL with one bounce) against the
    /// light it models; 0 leaves direct light only.
    #[arg(long)]
    pub reference_bounces: Option<u32>,
    /// Frames each real-time technique runs before its image is taken.
    #[arg(long, default_value = "120")]
    pub frames: u32,
    /// Named regions to measure (default: all the scene's).
    #[arg(long, value_delimiter = ',')]
    pub regions: Vec<String>,
    /// Where references are cached (default: $XDG_CACHE_HOME/irradiant, ~/.cache/irradiant).
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Also follow the scene's animation for this many frames (0: off): per frame the flicker,
    /// every --every frames the FLIP against a reference of that frame, and the lag after a
    /// light switches.
    #[arg(long, default_value = "0")]
    pub over_time: u32,
    /// Over time, also pan the camera by this many degrees about the vertical through it,
    /// evenly over the --over-time frames: the flicker of a camera move (0: the view stays,
    /// unless the scene animates its camera).
    #[arg(long, default_value = "0")]
    pub pan: f32,
    /// Frames a second of the animation.
    #[arg(long, default_value = "60")]
    pub fps: f32,
    /// Compare with a reference every this many frames over time.
    #[arg(long, default_value = "4")]
    pub every: u32,
    /// Samples per pixel of the per-frame references over time.
    #[arg(long, default_value = "256", value_parser = crate::options::parse_samples)]
    pub sequence_spp: u32,
    /// After a light switches, the lag is the frames until FLIP against that frame's reference
    /// is back under this (0.05: differences hard to spot side by side).
    #[arg(long, default_value = "0.05")]
    pub lag_bound: f32,
    #[command(flatten)]
    pub settings: SettingsArgs,
}

/// What every technique of a comparison shares: the scene, its settings and the adapter.
pub struct Setup<'a> {
    pub args: &'a CompareArgs,
    pub ctx: Arc<GpuContext>,
    pub scene: &'a irradiant_scene::Scene,
    pub run: &'a RunSettings,
    /// Each technique's label (as the command line names it) and spec.
    pub specs: &'a [(String, TechniqueSpec)],
}

impl Setup<'_> {
    /// The path tracer's settings for a reference of `spp` samples a pixel.
    pub fn reference_settings(&self, spp: u32) -> PathTraceSettings {
        let settings = PathTraceSettings {
            samples_per_pixel: spp,
            ..PathTraceSettings::balanced()
        };
        match self.args.reference_bounces {
            Some(bounces) => settings.with_indirect_bounces(bounces),
            None => settings,
        }
    }

    /// A session of one technique at the comparison's size, at animation time `time`.
    pub fn session(&self, spec: &TechniqueSpec, time: f32) -> Result<Session, CliError> {
        Ok(Session::new(
            self.ctx.clone(),
            self.scene.clone(),
            SessionSettings {
                size: self.args.size,
                frame: self.run.frame.clone(),
                technique: spec.clone(),
                scene: GpuSceneSettings::default(),
                time,
                cache_dir: Some(irradiant::pathtrace::reference_cache::cache_dir(
                    self.args.cache.as_deref(),
                )),
                progress: Some(crate::cache::bake_progress()),
            },
        )?)
    }
}

pub fn run(args: &CompareArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    let techniques = crate::options::technique_list(&args.techniques)?;
    if let Some(bounces) = args.reference_bounces.filter(|&b| b > 1023) {
        return Err(CliError::Usage(format!(
            "--reference-bounces {bounces} is out of range: use 0…1023, or leave it out for every bounce"
        )));
    }
    if args.frames == 0 {
        return Err(CliError::Usage("--frames must be at least 1".into()));
    }
    crate::options::check_report_folder(&args.out)?;
    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let mut scene = loaded.scene;
    args.view.apply(&mut scene)?;
    if args.pan != 0.0 {
        if !args.pan.is_finite() || args.pan.abs() > 360.0 || args.over_time < 2 {
            return Err(CliError::Usage(format!(
                "--pan {} needs --over-time of 2 frames or more and an angle within ±360 degrees",
                args.pan
            )));
        }
        let seconds = (args.over_time - 1) as f32 / args.fps;
        scene.animations.push(irradiant_scene::Animation {
            target: irradiant_scene::AnimationTarget::Camera,
            tracks: irradiant_scene::Tracks {
                rotation_y_degrees: vec![(0.0, 0.0), (seconds, args.pan)],
                ..Default::default()
            },
        });
    }
    let scene = scene;
    let regions: Vec<irradiant_scene::Region> = if args.regions.is_empty() {
        scene.regions.clone()
    } else {
        args.regions
            .iter()
            .map(|name| {
                scene.region(name).cloned().ok_or_else(|| {
                    let known: Vec<&str> = scene.regions.iter().map(|r| r.name.as_str()).collect();
                    CliError::Usage(format!(
                        "scene '{}' has no region '{name}' (it has: {}); name a region from its manifest's [[region]] list",
                        scene.name,
                        if known.is_empty() { "none".into() } else { known.join(", ") }
                    ))
                })
            })
            .collect::<Result<_, _>>()?
    };
    let run = RunSettings::new(&args.settings, &scene, 0)?;
    let specs: Vec<(String, TechniqueSpec)> = techniques
        .iter()
        .map(|t| t.label.clone())
        .zip(run.checked_specs(&techniques, &args.settings, &scene)?)
        .collect();
    if let Some(base) = &args.difference_from {
        let base = crate::options::TechniqueChoice::parse(base)?.label;
        if !specs.iter().any(|(label, _)| *label == base) {
            return Err(CliError::Usage(format!(
                "--difference-from '{base}' is not one of the techniques compared ({}); name one of them",
                specs
                    .iter()
                    .map(|(l, _)| l.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
    }
    // Everything goes into a sibling folder first, renamed into place only when complete.
    let partial = args.out.with_extension("partial");
    let _ = std::fs::remove_dir_all(&partial);
    std::fs::create_dir(&partial).map_err(|e| CliError::Io {
        path: partial.clone(),
        message: format!("cannot create the output folder: {e}"),
    })?;
    let ctx = Arc::new(GpuContext::new(adapter)?);
    let setup = Setup {
        args,
        ctx,
        scene: &scene,
        run: &run,
        specs: &specs,
    };
    let result = compare_into(&setup, &regions, &partial);
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&partial);
    }
    let comparison = result?;
    if args.out.exists() {
        std::fs::remove_dir_all(&args.out).map_err(|e| CliError::Io {
            path: args.out.clone(),
            message: format!("cannot replace the earlier report: {e}"),
        })?;
    }
    std::fs::rename(&partial, &args.out).map_err(|e| CliError::Io {
        path: args.out.clone(),
        message: e.to_string(),
    })?;
    println!(
        "{}: report.html and comparison.json for {} ({} techniques)",
        args.out.display(),
        comparison.scene,
        comparison.results.len()
    );
    for r in &comparison.results {
        println!(
            "  {:<16} FLIP mean {:.4}  p95 {:.4}  PSNR {:.2} dB  relMSE {:.5}",
            r.technique, r.flip_mean, r.flip_p95, r.psnr_db, r.relative_mse
        );
        if let Some(d) = &r.difference {
            println!(
                "  {:<16} minus {}: mean luminance {:+.5}, mean |Δ| {:.5}",
                "", d.from, d.mean, d.mean_abs
            );
        }
    }
    for t in comparison
        .over_time
        .iter()
        .filter(|t| !t.window_steps.is_empty())
    {
        let groups: Vec<String> = t
            .flicker_since_step(STEP_FLICKER_FRAMES)
            .iter()
            .map(|(k, mean, n)| format!("{k}: {mean:.5} ({n})"))
            .collect();
        println!(
            "  {:<16} flicker by frames since a probe window stepped ({} steps; the last group \
             {STEP_FLICKER_FRAMES} or more): {}",
            t.technique,
            t.window_steps.len(),
            groups.join(", ")
        );
    }
    Ok(())
}

/// Frames after a window step that `compare --over-time` tells apart in the flicker: past the
/// entered planes' relocation (5 frames) and the convergence rounds that follow it.
const STEP_FLICKER_FRAMES: u32 = 8;

fn compare_into(
    setup: &Setup,
    regions: &[irradiant_scene::Region],
    dir: &Path,
) -> Result<Comparison, CliError> {
    let args = setup.args;
    let (width, height) = args.size;
    let ctx = &setup.ctx;
    let scene = setup.scene;
    let gpu_scene = GpuScene::new(ctx, scene, &GpuSceneSettings::default())?;
    let pt = setup.reference_settings(args.reference_spp);
    let (reference, cached) = reference(
        ctx,
        &gpu_scene,
        scene,
        &scene.pose_at(0.0),
        &args.scene,
        args.size,
        &pt,
        args.cache.as_deref(),
    )?;
    drop(gpu_scene);
    write_png(&dir.join("reference.png"), &reference)?;
    let reference_srgb = reference.to_srgb8(1.0, true);
    let mut results = Vec::new();
    let mut images = Vec::new();
    for (label, spec) in setup.specs {
        let mut session = setup.session(spec, 0.0)?;
        let mut passes = Vec::new();
        for i in 0..args.frames {
            if i + 1 == args.frames {
                passes = session
                    .render_profiled()?
                    .into_iter()
                    .map(|t| (t.label, t.milliseconds))
                    .collect();
            } else {
                session.render()?;
            }
        }
        let image = session.image()?;
        let flip = irradiant_eval::flip(&reference_srgb, &image.to_srgb8(1.0, true), width, height)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        let psnr = irradiant_eval::psnr(&reference.pixels, &image.pixels)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        let relative_mse = irradiant_eval::relative_mse(&reference.pixels, &image.pixels)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        let region_means = region_means(&session, &reference, regions)?;
        let stem = crate::options::TechniqueChoice::parse(label)?.file_stem();
        let image_file = format!("{stem}.png");
        let error_file = format!("{stem}-flip.png");
        write_png(&dir.join(&image_file), &image)?;
        write_rgb8(&dir.join(&error_file), &flip.error_map_rgb8, width, height)?;
        results.push(TechniqueResult {
            technique: label.clone(),
            flip_mean: flip.mean,
            flip_p95: flip.p95,
            psnr_db: psnr,
            relative_mse,
            regions: region_means,
            passes,
            image: image_file,
            error_map: error_file,
            difference: None,
        });
        images.push((stem, image));
    }
    if let Some(base) = &args.difference_from {
        let base = crate::options::TechniqueChoice::parse(base)?;
        let (base_stem, base_image) = images
            .iter()
            .find(|(stem, _)| *stem == base.file_stem())
            .expect("checked to be compared");
        for (result, (stem, image)) in results.iter_mut().zip(&images) {
            if stem == base_stem {
                continue;
            }
            let d = irradiant_eval::difference(&base_image.pixels, &image.pixels)
                .map_err(|e| CliError::Usage(e.to_string()))?;
            let file = format!("{stem}-minus-{base_stem}.png");
            write_rgb8(&dir.join(&file), &d.map_rgb8, width, height)?;
            result.difference = Some(irradiant_eval::report::DifferenceResult {
                from: base.label.clone(),
                mean: d.mean,
                mean_abs: d.mean_abs,
                scale: d.scale,
                image: file,
            });
        }
    }
    let over_time = if args.over_time > 0 {
        crate::over_time::follow_animation(setup)?
    } else {
        Vec::new()
    };
    let comparison = Comparison {
        scene: scene.name.clone(),
        width,
        height,
        adapter: ctx.info.name.clone(),
        reference_spp: args.reference_spp,
        reference_indirect_bounces: args.reference_bounces,
        reference_image: "reference.png".into(),
        reference_cached: cached,
        frames: args.frames,
        results,
        over_time,
    };
    let json = serde_json::to_string_pretty(&comparison).expect("comparisons serialise");
    crate::write_file(&dir.join("comparison.json"), json)?;
    let page = irradiant_eval::report::html(&comparison, &|file| {
        std::fs::read(dir.join(file)).unwrap_or_default()
    });
    crate::write_file(&dir.join("report.html"), page)?;
    Ok(comparison)
}

/// Mean indirect luminance over each region's pixels: the technique's, and the reference's
/// (its total minus the frame's direct light and emission).
fn region_means(
    session: &Session,
    reference: &Image,
    regions: &[irradiant_scene::Region],
) -> Result<Vec<(String, f64, f64)>, CliError> {
    let direct = session.direct()?;
    let indirect = session.indirect()?;
    let gbuffer = session.gbuffer()?;
    let lum = |c: [f32; 3]| (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) as f64;
    Ok(regions
        .iter()
        .map(|r| {
            let (mut t, mut reference_sum, mut n) = (0.0, 0.0, 0usize);
            for (i, g) in gbuffer.iter().enumerate() {
                let p = glam::Vec3::from(g.position);
                if g.depth >= 0.0 && p.cmpge(r.min).all() && p.cmple(r.max).all() {
                    t += lum(indirect.pixels[i]);
                    let ref_indirect = [0, 1, 2]
                        .map(|c| reference.pixels[i][c] - direct.pixels[i][c] - g.emission[c]);
                    reference_sum += lum(ref_indirect);
                    n += 1;
                }
            }
            let n = n.max(1) as f64;
            (r.name.clone(), t / n, reference_sum / n)
        })
        .collect())
}

pub fn write_png(path: &Path, image: &Image) -> Result<(), CliError> {
    write_rgb8(path, &image.to_srgb8(1.0, true), image.width, image.height)
}

fn write_rgb8(path: &Path, rgb: &[u8], width: u32, height: u32) -> Result<(), CliError> {
    let rgba: Vec<u8> = rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    irradiant::frame::write_png(path, &rgba, width, height)?;
    Ok(())
}
