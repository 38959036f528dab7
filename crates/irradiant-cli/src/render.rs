use std::path::PathBuf;

use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use irradiant::frame::{ToneSettings, Tonemapper, write_png};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{AdapterChoice, GpuContext, GpuScene, GpuSceneSettings};

use crate::CliError;
use crate::options::{check_output, parse_size};

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Technique {
    /// The reference path tracer (ground truth).
    Path,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Preset {
    Fast,
    Balanced,
    Quality,
}

#[derive(Args)]
pub struct RenderArgs {
    /// A built-in scene (cornell, two-rooms, box-cylinders, furnace), a manifest (.toml) or a
    /// mesh (.obj, .gltf, .glb).
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    #[arg(long, value_enum, default_value = "path")]
    pub technique: Technique,
    /// Settings preset; --spp and --max-bounces override it.
    #[arg(long, value_enum, default_value = "balanced")]
    pub preset: Preset,
    /// Samples per pixel (path tracer).
    #[arg(long)]
    pub spp: Option<u32>,
    #[arg(long)]
    pub max_bounces: Option<u32>,
    #[arg(long, default_value = "0")]
    pub seed: u32,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "640x480", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Output: .png (tonemapped sRGB) or .exr (linear radiance).
    #[arg(long, default_value = "irradiant.png")]
    pub out: PathBuf,
    /// Exposure multiplier before tonemapping.
    #[arg(long, default_value = "1.0")]
    pub exposure: f32,
    /// Clamp instead of the filmic curve.
    #[arg(long)]
    pub no_filmic: bool,
}

pub fn run(args: &RenderArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    check_output(&args.out, &["png", "exr"])?;
    if !(args.exposure.is_finite() && args.exposure > 0.0) {
        return Err(CliError::Usage(format!("--exposure {} must be a positive number", args.exposure)));
    }
    let mut settings = match args.preset {
        Preset::Fast => PathTraceSettings::fast(),
        Preset::Balanced => PathTraceSettings::balanced(),
        Preset::Quality => PathTraceSettings::quality(),
    };
    if let Some(spp) = args.spp {
        if spp == 0 || spp > 1 << 20 {
            return Err(CliError::Usage(format!("--spp {spp} is out of range: use 1…1048576")));
        }
        settings.samples_per_pixel = spp;
    }
    if let Some(b) = args.max_bounces {
        if b > 1024 {
            return Err(CliError::Usage(format!("--max-bounces {b} is out of range: use 0…1024")));
        }
        settings.max_bounces = b;
    }
    settings.seed = args.seed;

    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let scene = loaded.scene;
    let ctx = GpuContext::new(adapter)?;
    let (width, height) = args.size;
    let gpu_scene = GpuScene::new(&ctx, &scene, &GpuSceneSettings::default())?;
    let image = match args.technique {
        Technique::Path => {
            let mut tracer = PathTracer::new(&ctx, &gpu_scene, width, height)?;
            let bar = ProgressBar::new(settings.samples_per_pixel as u64);
            bar.set_style(ProgressStyle::with_template("{spinner} path tracing {pos}/{len} spp [{elapsed_precise} < {eta}] {wide_bar}").unwrap());
            let image = tracer.render(&ctx, &gpu_scene, &scene.camera, &settings, |done, _| bar.set_position(done as u64))?;
            bar.finish_and_clear();
            if is_png(&args.out) {
                let tone = ToneSettings { exposure: args.exposure, filmic: !args.no_filmic };
                let rgba = Tonemapper::new(&ctx)?.run(&ctx, &tracer.accumulation, width, height, &tone)?;
                write_png(&args.out, &rgba, width, height)?;
            }
            image
        }
    };
    if !is_png(&args.out) {
        image.write_exr(&args.out)?;
    }
    let m = image.mean();
    println!(
        "{}: {} {}x{}, {} spp on {} — mean radiance ({:.4}, {:.4}, {:.4})",
        args.out.display(),
        scene.name,
        width,
        height,
        settings.samples_per_pixel,
        ctx.info.name,
        m[0],
        m[1],
        m[2]
    );
    Ok(())
}

fn is_png(path: &std::path::Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"))
}
