//! `irradiant compare`: one view rendered by each technique and by the path tracer, with FLIP,
//! PSNR, relative MSE, indirect light in named regions and GPU time per pass, as an HTML report
//! and JSON. The reference is cached on disk under a hash of everything that shapes it.

use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

use clap::Args;
use irradiant::ddgi::{Ddgi, DdgiSettings, ProbeWeights};
use irradiant::frame::{FrameRenderer, FrameSettings, Image, Technique};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{AdapterChoice, GpuContext, GpuScene, GpuSceneSettings};
use irradiant_eval::report::{Comparison, TechniqueResult, TimeSeries};
use irradiant_gpu::Profiler;

use crate::CliError;
use crate::options::parse_size;

/// Techniques `compare` knows, with what each means.
const TECHNIQUES: &[(&str, &str)] = &[
    ("none", "direct light only"),
    (
        "classic-probes",
        "DDGI's probes with trilinear weights only (no visibility)",
    ),
    ("ddgi", "DDGI, full method"),
];

#[derive(Args)]
pub struct CompareArgs {
    /// A built-in scene, a manifest or a mesh file.
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    /// The view, instead of the scene's camera: "px,py,pz,tx,ty,tz" (position, target) or
    /// with a vertical field of view in degrees as a seventh number.
    #[arg(long, value_parser = parse_camera)]
    pub camera: Option<irradiant_scene::Camera>,
    /// Techniques to compare, comma-separated: none, classic-probes, ddgi.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "none,classic-probes,ddgi"
    )]
    pub techniques: Vec<String>,
    /// Output folder (created; replaced if it holds an earlier comparison).
    #[arg(long)]
    pub out: PathBuf,
    #[arg(long, default_value = "320x240", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Samples per pixel of the path-traced reference.
    #[arg(long, default_value = "2048")]
    pub reference_spp: u32,
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
    /// Frames a second of the animation.
    #[arg(long, default_value = "60")]
    pub fps: f32,
    /// Compare with a reference every this many frames over time.
    #[arg(long, default_value = "4")]
    pub every: u32,
    /// Samples per pixel of the per-frame references over time.
    #[arg(long, default_value = "256")]
    pub sequence_spp: u32,
    /// After a light switches, the lag is the frames until FLIP against that frame's reference
    /// is back under this (0.05: differences hard to spot side by side).
    #[arg(long, default_value = "0.05")]
    pub lag_bound: f32,
}

pub fn run(args: &CompareArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    for t in &args.techniques {
        if !TECHNIQUES.iter().any(|(name, _)| name == t) {
            let known: Vec<String> = TECHNIQUES
                .iter()
                .map(|(n, d)| format!("{n} ({d})"))
                .collect();
            return Err(CliError::Usage(format!(
                "unknown technique '{t}': use {}",
                known.join(", ")
            )));
        }
    }
    if args.reference_spp == 0 || args.frames == 0 {
        return Err(CliError::Usage(
            "--reference-spp and --frames must be at least 1".into(),
        ));
    }
    let parent = args
        .out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return Err(CliError::Io {
            path: parent.to_owned(),
            message: "the folder that should hold the report does not exist; create it first"
                .into(),
        });
    }
    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let mut scene = loaded.scene;
    if let Some(camera) = &args.camera {
        scene.camera = camera.clone();
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
                    CliError::Usage(format!("scene '{}' has no region '{name}' (it has: {}); name a region from its manifest's [[region]] list", scene.name, if known.is_empty() { "none".into() } else { known.join(", ") }))
                })
            })
            .collect::<Result<_, _>>()?
    };
    // Everything goes into a sibling folder first, renamed into place only when complete.
    let partial = args.out.with_extension("partial");
    let _ = std::fs::remove_dir_all(&partial);
    std::fs::create_dir(&partial).map_err(|e| CliError::Io {
        path: partial.clone(),
        message: format!("cannot create the output folder: {e}"),
    })?;
    let result = compare_into(args, adapter, &scene, &regions, &partial);
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
    }
    Ok(())
}

fn compare_into(
    args: &CompareArgs,
    adapter: &AdapterChoice,
    scene: &irradiant_scene::Scene,
    regions: &[irradiant_scene::Region],
    dir: &Path,
) -> Result<Comparison, CliError> {
    let (width, height) = args.size;
    let ctx = GpuContext::new(adapter)?;
    let gpu_scene = GpuScene::new(&ctx, scene, &GpuSceneSettings::default())?;
    let pt = PathTraceSettings {
        samples_per_pixel: args.reference_spp,
        ..PathTraceSettings::balanced()
    };
    let (reference, cached) = reference(
        &ctx,
        &gpu_scene,
        scene,
        &scene.pose_at(0.0),
        &args.scene,
        args.size,
        &pt,
        args.cache.as_deref(),
    )?;
    write_png(&dir.join("reference.png"), &reference)?;
    let reference_srgb = reference.to_srgb8(1.0, true);
    let mut results = Vec::new();
    for name in &args.techniques {
        let mut frame =
            FrameRenderer::new(&ctx, &gpu_scene, width, height, FrameSettings::default())?;
        let mut ddgi = make_technique(&ctx, &gpu_scene, scene, name, &frame)?;
        let mut profiler = Profiler::new(&ctx, 32);
        let mut passes = Vec::new();
        for i in 0..args.frames {
            let last = i + 1 == args.frames;
            frame.render(
                &ctx,
                &gpu_scene,
                &scene.camera,
                ddgi.as_mut().map(|d| d as &mut dyn Technique),
                false,
                if last { Some(&mut profiler) } else { None },
            )?;
            if last {
                ctx.wait()?;
                passes = profiler
                    .read(&ctx)?
                    .into_iter()
                    .map(|t| (t.label, t.milliseconds))
                    .collect();
            }
        }
        let image = frame.image(&ctx)?;
        let flip = irradiant_eval::flip(&reference_srgb, &image.to_srgb8(1.0, true), width, height)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        let psnr = irradiant_eval::psnr(&reference.pixels, &image.pixels)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        let relative_mse = irradiant_eval::relative_mse(&reference.pixels, &image.pixels)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        let direct = frame.read(&ctx, &frame.buffers.direct)?;
        let indirect = frame.read(&ctx, &frame.buffers.indirect)?;
        let gbuffer = frame.read_gbuffer(&ctx)?;
        let region_means = regions
            .iter()
            .map(|r| {
                let (mut t, mut reference_sum, mut n) = (0.0, 0.0, 0usize);
                for (i, g) in gbuffer.iter().enumerate() {
                    let p = glam::Vec3::from(g.position);
                    if g.depth >= 0.0 && p.cmpge(r.min).all() && p.cmple(r.max).all() {
                        let lum =
                            |c: [f32; 3]| (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) as f64;
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
            .collect();
        let image_file = format!("{name}.png");
        let error_file = format!("{name}-flip.png");
        write_png(&dir.join(&image_file), &image)?;
        write_rgb8(&dir.join(&error_file), &flip.error_map_rgb8, width, height)?;
        results.push(TechniqueResult {
            technique: name.clone(),
            flip_mean: flip.mean,
            flip_p95: flip.p95,
            psnr_db: psnr,
            relative_mse,
            regions: region_means,
            passes,
            image: image_file,
            error_map: error_file,
        });
    }
    let over_time = if args.over_time > 0 {
        follow_animation(args, &ctx, scene)?
    } else {
        Vec::new()
    };
    let comparison = Comparison {
        scene: scene.name.clone(),
        width,
        height,
        adapter: ctx.info.name.clone(),
        reference_spp: args.reference_spp,
        reference_image: "reference.png".into(),
        reference_cached: cached,
        frames: args.frames,
        results,
        over_time,
    };
    let json = serde_json::to_string_pretty(&comparison).expect("comparisons serialise");
    std::fs::write(dir.join("comparison.json"), json).map_err(|e| CliError::Io {
        path: dir.join("comparison.json"),
        message: e.to_string(),
    })?;
    let page = irradiant_eval::report::html(&comparison, &|file| {
        std::fs::read(dir.join(file)).unwrap_or_default()
    });
    std::fs::write(dir.join("report.html"), page).map_err(|e| CliError::Io {
        path: dir.join("report.html"),
        message: e.to_string(),
    })?;
    Ok(comparison)
}

/// The path-traced reference, from the cache when an entry for exactly this scene, view and
/// settings exists; otherwise rendered and stored.
#[allow(clippy::too_many_arguments)]
fn reference(
    ctx: &GpuContext,
    gpu_scene: &GpuScene,
    scene: &irradiant_scene::Scene,
    pose: &irradiant_scene::Pose,
    spec: &str,
    size: (u32, u32),
    settings: &PathTraceSettings,
    cache: Option<&Path>,
) -> Result<(Image, bool), CliError> {
    let key = reference_key(scene, pose, size, settings);
    let dir = cache
        .map(Path::to_owned)
        .or_else(default_cache)
        .unwrap_or_else(|| std::env::temp_dir().join("irradiant-cache"));
    let file = dir.join(format!("reference-{key:016x}.exr"));
    if let Ok(image) = Image::read_exr(&file) {
        if (image.width, image.height) == size {
            return Ok((image, true));
        }
    }
    eprintln!(
        "rendering the reference of {spec} ({} spp); it is cached in {}",
        settings.samples_per_pixel,
        dir.display()
    );
    let mut tracer = PathTracer::new(ctx, gpu_scene, size.0, size.1)?;
    let image = tracer.render(ctx, gpu_scene, &scene.camera, settings, |_, _| {})?;
    if std::fs::create_dir_all(&dir).is_ok() {
        // Written under a temporary name and renamed, so a half-written file is never found.
        let temporary = dir.join(format!(
            "reference-{key:016x}.{}.partial.exr",
            std::process::id()
        ));
        if image.write_exr(&temporary).is_ok() {
            let _ = std::fs::rename(&temporary, &file);
        }
    }
    Ok((image, false))
}

fn parse_camera(text: &str) -> Result<irradiant_scene::Camera, String> {
    let numbers: Vec<f32> = text
        .split(',')
        .map(|n| n.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{text}' is not a camera: write px,py,pz,tx,ty,tz[,fov_degrees]"))?;
    if !(numbers.len() == 6 || numbers.len() == 7) || numbers.iter().any(|n| !n.is_finite()) {
        return Err(format!(
            "'{text}' is not a camera: write six or seven finite numbers, px,py,pz,tx,ty,tz[,fov_degrees]"
        ));
    }
    let camera = irradiant_scene::Camera {
        position: glam::Vec3::new(numbers[0], numbers[1], numbers[2]),
        target: glam::Vec3::new(numbers[3], numbers[4], numbers[5]),
        up: glam::Vec3::Y,
        fov_y_degrees: numbers.get(6).copied().unwrap_or(45.0),
    };
    if camera.position == camera.target
        || !(camera.fov_y_degrees > 0.5 && camera.fov_y_degrees < 179.0)
    {
        return Err(format!(
            "'{text}': the position must differ from the target and the field of view lie in 0.5…179°"
        ));
    }
    Ok(camera)
}

/// Runs each technique through the animation, measuring error and flicker per frame.
fn follow_animation(
    args: &CompareArgs,
    ctx: &GpuContext,
    scene: &irradiant_scene::Scene,
) -> Result<Vec<TimeSeries>, CliError> {
    use irradiant::frame::{LightingChange, SceneChange, apply_pose};
    let (width, height) = args.size;
    let poses: Vec<irradiant_scene::Pose> = (0..args.over_time)
        .map(|i| scene.pose_at(i as f32 / args.fps))
        .collect();
    let change_frame = (1..poses.len())
        .find(|&i| SceneChange::between(&poses[i - 1], &poses[i]).lighting == LightingChange::Large)
        .map(|i| i as u32);
    // The references of the sampled frames, each cached under its own pose.
    let mut reference_scene = GpuScene::new(ctx, scene, &GpuSceneSettings::default())?;
    let settings = PathTraceSettings {
        samples_per_pixel: args.sequence_spp,
        ..PathTraceSettings::balanced()
    };
    let mut references = Vec::new();
    for i in (0..args.over_time).step_by(args.every as usize) {
        reference_scene.update(ctx, &poses[i as usize]);
        let (image, _) = reference(
            ctx,
            &reference_scene,
            scene,
            &poses[i as usize],
            &args.scene,
            args.size,
            &settings,
            args.cache.as_deref(),
        )?;
        references.push((i, image.to_srgb8(1.0, true)));
    }
    let mut series = Vec::new();
    for name in &args.techniques {
        let mut gpu_scene = GpuScene::new(ctx, scene, &GpuSceneSettings::default())?;
        let mut frame =
            FrameRenderer::new(ctx, &gpu_scene, width, height, FrameSettings::default())?;
        let mut ddgi = make_technique(ctx, &gpu_scene, scene, name, &frame)?;
        let (mut error, mut flicker) = (Vec::new(), Vec::new());
        let mut previous: Option<Image> = None;
        for i in 0..args.over_time {
            if i > 0 {
                apply_pose(
                    ctx,
                    &mut gpu_scene,
                    &mut frame,
                    ddgi.as_mut().map(|d| d as &mut dyn Technique),
                    &poses[i as usize - 1],
                    &poses[i as usize],
                );
            }
            frame.render(
                ctx,
                &gpu_scene,
                &scene.camera,
                ddgi.as_mut().map(|d| d as &mut dyn Technique),
                false,
                None,
            )?;
            let image = frame.image(ctx)?;
            if let Some(p) = &previous {
                let lum = |c: &[f32; 3]| (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) as f64;
                let change = image
                    .pixels
                    .iter()
                    .zip(&p.pixels)
                    .map(|(a, b)| (lum(a) - lum(b)).abs())
                    .sum::<f64>()
                    / image.pixels.len() as f64;
                flicker.push((i, change));
            }
            if let Some((_, reference)) = references.iter().find(|(f, _)| *f == i) {
                let flip =
                    irradiant_eval::flip(reference, &image.to_srgb8(1.0, true), width, height)
                        .map_err(|e| CliError::Usage(e.to_string()))?;
                error.push((i, flip.mean));
            }
            previous = Some(image);
        }
        let lag_bound = args.lag_bound;
        let lag_frames = change_frame.and_then(|c| {
            error
                .iter()
                .find(|(f, e)| *f >= c && *e <= lag_bound)
                .map(|(f, _)| f - c)
        });
        series.push(TimeSeries {
            technique: name.clone(),
            error,
            flicker,
            change_frame,
            lag_frames,
            lag_bound,
        });
    }
    Ok(series)
}

/// The DDGI volume a technique name stands for (None: direct light only).
fn make_technique(
    ctx: &GpuContext,
    gpu_scene: &GpuScene,
    scene: &irradiant_scene::Scene,
    name: &str,
    frame: &FrameRenderer,
) -> Result<Option<Ddgi>, CliError> {
    if name == "none" {
        return Ok(None);
    }
    let weights = if name == "classic-probes" {
        ProbeWeights::Classic
    } else {
        ProbeWeights::Full
    };
    let volume = scene
        .probe_volumes
        .first()
        .cloned()
        .unwrap_or_else(|| crate::render::default_volume(scene));
    let mut d = Ddgi::new(
        ctx,
        gpu_scene,
        &volume,
        &DdgiSettings {
            weights,
            ..DdgiSettings::balanced()
        },
    )?;
    d.bind_frame(ctx, &frame.buffers);
    Ok(Some(d))
}

fn default_cache() -> Option<PathBuf> {
    std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .map(|d| d.join("irradiant"))
}

/// A hash of everything that shapes the reference: geometry, materials, textures, lights,
/// camera, sky, size, the path tracer's settings and this program's version.
pub fn reference_key(
    scene: &irradiant_scene::Scene,
    pose: &irradiant_scene::Pose,
    size: (u32, u32),
    settings: &PathTraceSettings,
) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    env!("IRRADIANT_COMMIT").hash(&mut h);
    size.hash(&mut h);
    format!("{settings:?}").hash(&mut h);
    for mesh in &scene.meshes {
        for p in &mesh.positions {
            p.to_array().map(f32::to_bits).hash(&mut h);
        }
        for n in &mesh.normals {
            n.to_array().map(f32::to_bits).hash(&mut h);
        }
        for t in &mesh.uvs {
            t.to_array().map(f32::to_bits).hash(&mut h);
        }
        mesh.indices.hash(&mut h);
        mesh.triangle_materials.hash(&mut h);
    }
    for t in &scene.textures {
        t.rgba8.hash(&mut h);
    }
    format!(
        "{:?}{:?}{:?}{:?}{:?}",
        scene.instances, scene.materials, pose, scene.camera, scene.sky
    )
    .hash(&mut h);
    h.finish()
}

fn write_png(path: &Path, image: &Image) -> Result<(), CliError> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_key_changes_with_everything_that_shapes_the_reference() {
        let scene = irradiant_scene::builtin("cornell").unwrap();
        let settings = PathTraceSettings::fast();
        let key = |s: &irradiant_scene::Scene, size, p: &PathTraceSettings| {
            reference_key(s, &s.pose_at(0.0), size, p)
        };
        let base = key(&scene, (64, 64), &settings);
        assert_eq!(base, key(&scene, (64, 64), &settings));
        assert_ne!(base, key(&scene, (64, 48), &settings));
        assert_ne!(
            base,
            key(
                &scene,
                (64, 64),
                &PathTraceSettings {
                    seed: 1,
                    ..settings.clone()
                }
            )
        );
        let mut moved = scene.clone();
        moved.camera.position.x += 0.01;
        assert_ne!(base, key(&moved, (64, 64), &settings));
        let mut repainted = scene.clone();
        repainted.materials[0].base_color.x *= 0.5;
        assert_ne!(base, key(&repainted, (64, 64), &settings));
        let mut bent = scene.clone();
        bent.meshes[0].positions[0].y += 1e-3;
        assert_ne!(base, key(&bent, (64, 64), &settings));
    }
}
