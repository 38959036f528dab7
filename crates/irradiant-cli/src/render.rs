//! `irradiant render`: a scene through a real-time technique (frames driven by the session) or
//! the reference path tracer, to PNG (tonemapped) or EXR (linear).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use irradiant::frame::{Image, write_png};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{
    AdapterChoice, GpuContext, GpuScene, GpuSceneSettings, Preset, Session, SessionSettings,
};

use crate::CliError;
use crate::options::{
    CameraArgs, RunSettings, SettingsArgs, TechniqueChoice, check_folder, check_output, parse_size,
};

/// The reference path tracer's name on the command line, beside the registered techniques.
pub const PATH: &str = "path";

#[derive(Args)]
pub struct RenderArgs {
    /// A built-in scene (cornell, two-rooms, box-cylinders, empty-box, thin-frames, table,
    /// slit-corridor, furnace, glowing-box, dense-cluster, many-lights, terrain, tunnel), a
    /// manifest (.toml) or a mesh (.obj, .gltf, .glb).
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    /// `path` (the reference path tracer) or a registered real-time technique, with settings
    /// of its own in braces over its preset: `ddgi{preset = "quality"}`,
    /// `ddgi{update.weights = "classic"}` (default: the one the --settings file or the scene's
    /// manifest names, else ddgi). `irradiant render --help` lists them below.
    #[arg(long, value_parser = parse_technique)]
    pub technique: Option<TechniqueChoice>,
    /// Samples per pixel (path tracer).
    #[arg(long, value_parser = crate::options::parse_samples)]
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
    /// Draw the probes as spheres showing their irradiance.
    #[arg(long)]
    pub show_probes: bool,
    /// Write the DDGI irradiance and distance atlases into this folder after the last frame.
    #[arg(long)]
    pub dump_atlas: Option<PathBuf>,
    /// Start DDGI's probes (ddgi, ssil+ddgi) from this file, which --save-probes wrote for the
    /// same scene and settings: the first frame is as converged as the saved one. A file saved
    /// for anything else is refused with the reason.
    #[arg(long)]
    pub load_probes: Option<PathBuf>,
    /// Write DDGI's probes to this file after the last frame, for --load-probes (and a game's
    /// start: docs/ddgi.md).
    #[arg(long)]
    pub save_probes: Option<PathBuf>,
    #[command(flatten)]
    pub view: CameraArgs,
    /// Also write the camera this render used to a camera file, for `--camera-from`.
    #[arg(long)]
    pub save_camera: Option<PathBuf>,
    #[command(flatten)]
    pub settings: SettingsArgs,
}

/// A `--technique` value: a registered technique or `path`, with settings in braces.
fn parse_technique(text: &str) -> Result<TechniqueChoice, String> {
    let choice = TechniqueChoice::parse(text).map_err(|e| e.to_string())?;
    if choice.name != PATH {
        irradiant::registry::find(&choice.name)
            .map_err(|e| format!("{e}, or path (the reference path tracer)"))?;
    }
    Ok(choice)
}

fn check_args(args: &RenderArgs) -> Result<(), CliError> {
    check_output(&args.out, &["png", "exr"])?;
    if !(args.exposure.is_finite() && args.exposure > 0.0) {
        return Err(CliError::Usage(format!(
            "--exposure {} must be a positive number",
            args.exposure
        )));
    }
    if !is_path(args) && (args.frames == 0 || args.frames > 100_000) {
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
    if let Some(dir) = &args.dump_atlas
        && !dir.is_dir()
    {
        return Err(CliError::Io {
            path: dir.clone(),
            message: "the atlas folder does not exist; create it first".into(),
        });
    }
    if let Some(path) = &args.save_camera {
        check_output(path, &["toml"])?;
    }
    Ok(())
}

fn is_path(args: &RenderArgs) -> bool {
    args.technique.as_ref().is_some_and(|c| c.name == PATH)
}

pub fn run(args: &RenderArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    check_args(args)?;
    let path_settings = path_settings(args)?;
    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let mut scene = loaded.scene;
    args.view.apply(&mut scene)?;
    let mut run_settings = RunSettings::new(&args.settings, &scene, args.seed)?;
    run_settings.frame.tone.exposure = args.exposure;
    run_settings.frame.tone.filmic = !args.no_filmic;
    let choice = match &args.technique {
        Some(choice) => choice.clone(),
        None => TechniqueChoice::parse(
            &run_settings
                .named_technique()
                .unwrap_or_else(|| "ddgi".into()),
        )?,
    };
    let technique = choice.name.clone();
    let spec = if technique == PATH {
        None
    } else {
        Some(run_settings.choice(&choice, &args.settings, args.seed)?)
    };
    run_settings.check_and_warn(spec.as_ref(), &scene)?;
    let ctx = Arc::new(GpuContext::new(adapter)?);
    let (width, height) = args.size;
    let (image, what) = if technique == PATH {
        ctx.check_allocations(&PathTracer::plan(width, height))?;
        let mut gpu_scene = GpuScene::new(&ctx, &scene, &GpuSceneSettings::default())?;
        gpu_scene.update(&ctx, &scene.pose_at(args.time));
        let mut tracer = PathTracer::new(&ctx, &gpu_scene, width, height)?;
        let bar = progress(
            path_settings.samples_per_pixel,
            "path tracing {pos}/{len} spp",
        );
        let image = tracer.render(
            &ctx,
            &gpu_scene,
            &scene.camera,
            &path_settings,
            |done, _| bar.set_position(done as u64),
        )?;
        bar.finish_and_clear();
        if is_png(&args.out) {
            let rgba = srgb_rgba(&image, &run_settings.frame.tone);
            write_png(&args.out, &rgba, width, height)?;
        }
        (image, format!("{} spp", path_settings.samples_per_pixel))
    } else {
        let image = render_frames(
            args,
            ctx.clone(),
            scene.clone(),
            run_settings.frame.clone(),
            spec.expect("a real-time technique has a spec"),
        )?;
        (
            image,
            format!("{} after {} frames", choice.label, args.frames),
        )
    };
    if !is_png(&args.out) && !args.sequence {
        image.write_exr(&args.out)?;
    }
    if let Some(path) = &args.save_camera {
        crate::write_file(path, irradiant_scene::camera_file_text(&scene.camera))?;
    }
    let m = image.mean();
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

/// A real-time technique's frames leading up to --time; writes the last (or every) frame.
fn render_frames(
    args: &RenderArgs,
    ctx: Arc<GpuContext>,
    scene: irradiant_scene::Scene,
    frame: irradiant::frame::FrameSettings,
    spec: irradiant::TechniqueSpec,
) -> Result<Image, CliError> {
    let frame_time = |i: u32| (args.time - (args.frames - 1 - i) as f32 / args.fps).max(0.0);
    let mut session = Session::new(
        ctx.clone(),
        scene,
        SessionSettings {
            size: args.size,
            frame,
            technique: spec,
            scene: GpuSceneSettings::default(),
            time: frame_time(0),
            cache_dir: Some(irradiant::pathtrace::reference_cache::cache_dir(None)),
            progress: Some(crate::cache::bake_progress()),
        },
    )?;
    session.set_show_probes(args.show_probes);
    if let Some(file) = &args.load_probes {
        session.load_probes(file)?;
    }
    let bar = progress(args.frames, "frame {pos}/{len}");
    for i in 0..args.frames {
        session.seek(frame_time(i));
        session.render()?;
        if args.sequence {
            write_frame(&session, &numbered(&args.out, i + 1))?;
        }
        bar.set_position(i as u64 + 1);
    }
    bar.finish_and_clear();
    if let Some(file) = &args.save_probes {
        session.save_probes(file)?;
    }
    if let Some(dir) = &args.dump_atlas {
        match session.technique_as::<irradiant::ddgi::Ddgi>() {
            Some(ddgi) => crate::atlas::dump(&ctx, ddgi.volume(), dir)?,
            None => eprintln!(
                "warning: --dump-atlas: technique '{}' has no probe atlases",
                session.technique().name()
            ),
        }
    }
    if is_png(&args.out) && !args.sequence {
        let (w, h) = args.size;
        write_png(&args.out, &session.tonemapped()?, w, h)?;
    }
    Ok(session.image()?)
}

fn progress(len: u32, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len as u64);
    bar.set_style(
        ProgressStyle::with_template(&format!(
            "{{spinner}} {what} [{{elapsed_precise}} < {{eta}}] {{wide_bar}}"
        ))
        .expect("a valid progress template"),
    );
    bar
}

/// sRGB RGBA8 of a linear image, through the frame's curve (Image::to_srgb8 is frame/tonemap's
/// CPU twin).
pub fn srgb_rgba(image: &Image, tone: &irradiant::frame::ToneSettings) -> Vec<u8> {
    image
        .to_srgb8(tone.exposure, tone.filmic)
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect()
}

fn path_settings(args: &RenderArgs) -> Result<PathTraceSettings, CliError> {
    let choice = args.technique.as_ref().filter(|c| c.name == PATH);
    if let Some(c) = choice
        && !c.overrides.is_empty()
    {
        return Err(CliError::Usage(format!(
            "--technique '{}': the path tracer takes only a preset in braces; set its samples and bounces with --spp and --max-bounces",
            c.label
        )));
    }
    let preset = choice
        .and_then(|c| c.preset)
        .unwrap_or(args.settings.preset);
    let mut settings = match preset {
        Preset::Fast => PathTraceSettings::fast(),
        Preset::Balanced => PathTraceSettings::balanced(),
        Preset::Quality => PathTraceSettings::quality(),
    };
    if let Some(spp) = args.spp {
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

fn write_frame(session: &Session, path: &Path) -> Result<(), CliError> {
    check_folder(path)?;
    let (w, h) = session.frame().size();
    if is_png(path) {
        write_png(path, &session.tonemapped()?, w, h)?;
    } else {
        session.image()?.write_exr(path)?;
    }
    Ok(())
}

fn is_png(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
}
