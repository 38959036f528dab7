use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use irradiant::ddgi::{Ddgi, DdgiSettings, ProbeWeights};
use irradiant::frame::{
    FrameRenderer, FrameSettings, Technique as FrameTechnique, ToneSettings, Tonemapper,
    apply_pose, write_png,
};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{AdapterChoice, GpuContext, GpuScene, GpuSceneSettings};

use crate::CliError;
use crate::options::{check_output, parse_size};

#[derive(Clone, Copy, Debug, PartialEq, ValueEnum)]
pub enum Technique {
    /// The reference path tracer (ground truth).
    Path,
    /// Direct light only: no indirect light at all (the baseline every technique improves on).
    None,
    /// Dynamic diffuse global illumination: ray-traced probes with Chebyshev visibility.
    Ddgi,
}

/// The DDGI paper's Figure 7 ladder.
#[derive(Clone, Copy, Debug, PartialEq, ValueEnum)]
pub enum Weights {
    /// Classic irradiance probes: trilinear weights only.
    Classic,
    /// + smooth backface weight.
    Backface,
    /// + Chebyshev visibility.
    Chebyshev,
    /// + self-shadow bias and backface-hit rule (the full method).
    Full,
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
    #[arg(long, value_enum, default_value = "ddgi")]
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
    /// Animation time, in seconds, of the image written. The path tracer renders the scene as
    /// it is at this time; a real-time technique's frames lead up to it at --fps (frame i of N
    /// at time − (N − 1 − i) / fps, held at 0), so the default shows the scene at rest.
    #[arg(long, default_value = "0")]
    pub time: f32,
    /// Real-time techniques: frames to simulate; the last one is written.
    #[arg(long, default_value = "120")]
    pub frames: u32,
    /// Simulated frames per second.
    #[arg(long, default_value = "60")]
    pub fps: f32,
    /// Write every frame, numbered: OUT stem + "-0001.png", …
    #[arg(long)]
    pub sequence: bool,
    #[command(flatten)]
    pub ddgi: DdgiArgs,
}

#[derive(Args, Clone, Debug)]
pub struct DdgiArgs {
    /// DDGI weights (the paper's Figure 7 ladder).
    #[arg(long, value_enum, default_value = "full")]
    pub weights: Weights,
    /// Rays per probe per frame (default: the preset's).
    #[arg(long)]
    pub rays: Option<u32>,
    /// Irradiance hysteresis (default: the preset's).
    #[arg(long)]
    pub hysteresis: Option<f32>,
    /// Probes per axis, e.g. 8x4x8 (default: the scene's probe volume).
    #[arg(long, value_parser = parse_counts)]
    pub probes: Option<[u32; 3]>,
    /// Draw the probes as spheres showing their irradiance.
    #[arg(long)]
    pub show_probes: bool,
    /// Write the irradiance and distance atlases into this folder after the last frame.
    #[arg(long)]
    pub dump_atlas: Option<PathBuf>,
}

pub fn parse_counts(text: &str) -> Result<[u32; 3], String> {
    let parts: Vec<_> = text
        .split(['x', 'X'])
        .map(|p| p.trim().parse::<u32>())
        .collect();
    match parts.as_slice() {
        [Ok(x), Ok(y), Ok(z)]
            if (1..=irradiant_scene::MAX_PROBES_PER_AXIS).contains(x)
                && (1..=irradiant_scene::MAX_PROBES_PER_AXIS).contains(y)
                && (1..=irradiant_scene::MAX_PROBES_PER_AXIS).contains(z) =>
        {
            Ok([*x, *y, *z])
        }
        _ => Err(format!(
            "'{text}' is not a probe count: write XxYxZ with 1…{} each, e.g. 8x4x8",
            irradiant_scene::MAX_PROBES_PER_AXIS
        )),
    }
}

pub fn run(args: &RenderArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    check_output(&args.out, &["png", "exr"])?;
    if !(args.exposure.is_finite() && args.exposure > 0.0) {
        return Err(CliError::Usage(format!(
            "--exposure {} must be a positive number",
            args.exposure
        )));
    }
    if args.technique != Technique::Path && (args.frames == 0 || args.frames > 100_000) {
        return Err(CliError::Usage(format!(
            "--frames {} is out of range: use 1…100000",
            args.frames
        )));
    }
    if !(args.fps.is_finite() && args.fps > 0.0) {
        return Err(CliError::Usage(format!(
            "--fps {} must be a positive number",
            args.fps
        )));
    }
    if !(args.time.is_finite() && args.time >= 0.0) {
        return Err(CliError::Usage(format!(
            "--time {} must be a number of seconds ≥ 0",
            args.time
        )));
    }
    if let Some(dir) = &args.ddgi.dump_atlas {
        if !dir.is_dir() {
            return Err(CliError::Io {
                path: dir.clone(),
                message: "the atlas folder does not exist; create it first".into(),
            });
        }
    }
    let settings = path_settings(args)?;
    let ddgi_settings = ddgi_settings(args)?;
    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let scene = loaded.scene;
    let ctx = GpuContext::new(adapter)?;
    let (width, height) = args.size;
    let mut gpu_scene = GpuScene::new(&ctx, &scene, &GpuSceneSettings::default())?;
    if args.technique == Technique::Path {
        gpu_scene.update(&ctx, &scene.pose_at(args.time));
    }
    let tone = ToneSettings {
        exposure: args.exposure,
        filmic: !args.no_filmic,
    };
    let image = match args.technique {
        Technique::Path => {
            let mut tracer = PathTracer::new(&ctx, &gpu_scene, width, height)?;
            let bar = ProgressBar::new(settings.samples_per_pixel as u64);
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} path tracing {pos}/{len} spp [{elapsed_precise} < {eta}] {wide_bar}",
                )
                .unwrap(),
            );
            let image = tracer.render(&ctx, &gpu_scene, &scene.camera, &settings, |done, _| {
                bar.set_position(done as u64)
            })?;
            bar.finish_and_clear();
            if is_png(&args.out) {
                let rgba =
                    Tonemapper::new(&ctx)?.run(&ctx, &tracer.accumulation, width, height, &tone)?;
                write_png(&args.out, &rgba, width, height)?;
            }
            image
        }
        Technique::None | Technique::Ddgi => {
            let mut frame =
                FrameRenderer::new(&ctx, &gpu_scene, width, height, FrameSettings::default())?;
            let mut ddgi = match args.technique {
                Technique::Ddgi => {
                    let mut volume = scene
                        .probe_volumes
                        .first()
                        .cloned()
                        .unwrap_or_else(|| default_volume(&scene));
                    if let Some(counts) = args.ddgi.probes {
                        volume.counts = counts;
                    }
                    let mut ddgi = Ddgi::new(&ctx, &gpu_scene, &volume, &ddgi_settings)?;
                    ddgi.bind_frame(&ctx, &frame.buffers);
                    Some(ddgi)
                }
                _ => None,
            };
            let bar = ProgressBar::new(args.frames as u64);
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} frame {pos}/{len} [{elapsed_precise} < {eta}] {wide_bar}",
                )
                .unwrap(),
            );
            let frame_time =
                |i: u32| (args.time - (args.frames - 1 - i) as f32 / args.fps).max(0.0);
            let mut pose = scene.pose_at(frame_time(0));
            gpu_scene.update(&ctx, &pose);
            for i in 0..args.frames {
                let next = scene.pose_at(frame_time(i));
                apply_pose(
                    &ctx,
                    &mut gpu_scene,
                    &mut frame,
                    ddgi.as_mut().map(|d| d as &mut dyn FrameTechnique),
                    &pose,
                    &next,
                );
                pose = next;
                frame.render(
                    &ctx,
                    &gpu_scene,
                    &scene.camera,
                    ddgi.as_mut().map(|d| d as &mut dyn FrameTechnique),
                    args.ddgi.show_probes,
                    None,
                )?;
                if args.sequence {
                    write_frame(&ctx, &frame, &numbered(&args.out, i + 1), &tone)?;
                }
                bar.set_position(i as u64 + 1);
            }
            bar.finish_and_clear();
            if let (Some(dir), Some(ddgi)) = (&args.ddgi.dump_atlas, &ddgi) {
                crate::atlas::dump(&ctx, ddgi, dir)?;
            }
            if is_png(&args.out) && !args.sequence {
                write_png(&args.out, &frame.tonemapped(&ctx, &tone)?, width, height)?;
            }
            frame.image(&ctx)?
        }
    };
    if !is_png(&args.out) && !args.sequence {
        image.write_exr(&args.out)?;
    }
    let m = image.mean();
    let what = match args.technique {
        Technique::Path => format!("{} spp", settings.samples_per_pixel),
        _ => format!("{:?} after {} frames", args.technique, args.frames).to_lowercase(),
    };
    println!(
        "{}: {} {}x{}, {what} on {} — mean radiance ({:.4}, {:.4}, {:.4})",
        args.out.display(),
        scene.name,
        width,
        height,
        ctx.info.name,
        m[0],
        m[1],
        m[2]
    );
    Ok(())
}

fn path_settings(args: &RenderArgs) -> Result<PathTraceSettings, CliError> {
    let mut settings = match args.preset {
        Preset::Fast => PathTraceSettings::fast(),
        Preset::Balanced => PathTraceSettings::balanced(),
        Preset::Quality => PathTraceSettings::quality(),
    };
    if let Some(spp) = args.spp {
        if spp == 0 || spp > 1 << 20 {
            return Err(CliError::Usage(format!(
                "--spp {spp} is out of range: use 1…1048576"
            )));
        }
        settings.samples_per_pixel = spp;
    }
    if let Some(b) = args.max_bounces {
        if b > 1024 {
            return Err(CliError::Usage(format!(
                "--max-bounces {b} is out of range: use 0…1024"
            )));
        }
        settings.max_bounces = b;
    }
    settings.seed = args.seed;
    Ok(settings)
}

pub fn probe_weights(weights: Weights) -> ProbeWeights {
    match weights {
        Weights::Classic => ProbeWeights::Classic,
        Weights::Backface => ProbeWeights::Backface,
        Weights::Chebyshev => ProbeWeights::Chebyshev,
        Weights::Full => ProbeWeights::Full,
    }
}

fn ddgi_settings(args: &RenderArgs) -> Result<DdgiSettings, CliError> {
    let mut s = match args.preset {
        Preset::Fast => DdgiSettings::fast(),
        Preset::Balanced => DdgiSettings::balanced(),
        Preset::Quality => DdgiSettings::quality(),
    };
    s.weights = probe_weights(args.ddgi.weights);
    if let Some(r) = args.ddgi.rays {
        s.rays_per_probe = r;
    }
    if let Some(h) = args.ddgi.hysteresis {
        s.hysteresis = h;
    }
    s.seed = args.seed;
    s.validate()
        .map_err(|e| CliError::Usage(format!("DDGI settings: {e}")))?;
    Ok(s)
}

/// A probe volume over the scene's bounds when its manifest names none: about 8 probes along
/// the longest side.
pub fn default_volume(scene: &irradiant_scene::Scene) -> irradiant_scene::ProbeVolumeDesc {
    let (lo, hi) = scene.bounds();
    let extent = (hi - lo).max(glam::Vec3::splat(1e-3));
    let step = extent.max_element() / 8.0;
    let counts = (extent / step)
        .ceil()
        .as_uvec3()
        .max(glam::UVec3::splat(2))
        .min(glam::UVec3::splat(32));
    let inset = extent / counts.as_vec3() * 0.5;
    irradiant_scene::ProbeVolumeDesc {
        name: "auto".into(),
        min: lo + inset,
        max: hi - inset,
        counts: counts.into(),
    }
}

fn numbered(out: &Path, index: u32) -> PathBuf {
    let stem = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "frame".into());
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_else(|| "png".into());
    out.with_file_name(format!("{stem}-{index:04}.{ext}"))
}

fn write_frame(
    ctx: &GpuContext,
    frame: &FrameRenderer,
    path: &Path,
    tone: &ToneSettings,
) -> Result<(), CliError> {
    if is_png(path) {
        write_png(
            path,
            &frame.tonemapped(ctx, tone)?,
            frame.buffers.width,
            frame.buffers.height,
        )?;
    } else {
        frame.image(ctx)?.write_exr(path)?;
    }
    Ok(())
}

fn is_png(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
}
