//! `irradiant bench`: BVH build time, and each GPU pass timed with timestamp queries after a
//! warm-up (median of many runs), with rays per second where a pass traces rays.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use glam::Vec3;
use irradiant::ddgi::{Ddgi, DdgiSettings};
use irradiant::frame::{FrameRenderer, FrameSettings, Technique};
use irradiant::gpu_types::{GpuCamera, GpuRay};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::raycast::RayCaster;
use irradiant::{AdapterChoice, GpuContext, GpuScene, GpuSceneSettings};
use irradiant_gpu::{Profiler, wgpu};
use rand::{Rng, SeedableRng, rngs::StdRng};
use serde::Serialize;

use crate::CliError;
use crate::options::parse_size;

#[derive(Args)]
pub struct BenchArgs {
    /// Scenes to measure (built-in names, manifests or mesh files), comma-separated.
    #[arg(long, default_value = "cornell", value_delimiter = ',')]
    pub scene: Vec<String>,
    /// Image size for camera-driven passes: rays per dispatch = width × height.
    #[arg(long, default_value = "1920x1080", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Timed runs per pass (after the warm-up); the median is reported.
    #[arg(long, default_value = "20")]
    pub iterations: u32,
    /// Warm-up runs per pass, not timed.
    #[arg(long, default_value = "3")]
    pub warmup: u32,
    /// Also write every figure as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// A quick check that every pass runs (CI): 64×64, 2 iterations, no warm-up.
    #[arg(long)]
    pub smoke: bool,
    /// Also time the real-time frame with DDGI, for each probe grid listed (e.g.
    /// 16x8x16,32x8x32; "scene" takes the scene's own volume).
    #[arg(long, value_delimiter = ',')]
    pub ddgi_probes: Vec<String>,
    /// Rays per probe to time DDGI with, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "256")]
    pub ddgi_rays: Vec<u32>,
    /// DDGI probe rays shade every punctual light instead of one chosen at random.
    #[arg(long)]
    pub ddgi_shade_all_lights: bool,
    /// Probes per workgroup of ddgi/trace and ddgi/shade to time, comma-separated (powers of
    /// two up to 64; see DdgiSettings::probes_per_group).
    #[arg(long, value_delimiter = ',', default_value = "1")]
    pub ddgi_probes_per_group: Vec<u32>,
    /// Probe ray orders to time, comma-separated: coherent (sorted into compact patches, the
    /// default) and/or fibonacci (the plain spiral order).
    #[arg(long, value_delimiter = ',', default_value = "coherent")]
    pub ddgi_ray_order: Vec<String>,
    /// Probe states to time with, comma-separated: on (the default: probes in walls switch off
    /// and probes far from geometry sleep, 003 §6) and/or off (every probe traces every frame).
    #[arg(long, value_delimiter = ',', default_value = "on")]
    pub ddgi_probe_states: Vec<String>,
    /// Light choice of the probe rays' shadow rays to time, comma-separated: warp (one random
    /// light for 32 neighbouring rays, the default) and/or ray (one for each ray).
    #[arg(long, value_delimiter = ',', default_value = "warp")]
    pub ddgi_light_choice: Vec<String>,
    /// Time DDGI with trace and shade as one pass (on) and/or two (off, the default),
    /// comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "off")]
    pub ddgi_fuse_trace_shade: Vec<String>,
    /// Time DDGI with the probe rays' shadow rays queued for a dense pass (on, the default)
    /// and/or traced in ddgi/shade (off), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "on")]
    pub ddgi_shadow_queue: Vec<String>,
    /// DDGI weights to time with (the Figure 7 ladder; classic skips the visibility lookups).
    #[arg(long, value_enum, default_value = "full")]
    pub ddgi_weights: crate::render::Weights,
    /// BVH build effort: fast, balanced or quality (spatial pre-splits, the default).
    #[arg(long, value_enum, default_value = "quality")]
    pub bvh_quality: BvhQuality,
    /// Bottom-level BVH layout: wide (compressed 8-wide nodes, the default) or binary.
    #[arg(long, value_enum, default_value = "wide")]
    pub blas_layout: BlasLayoutArg,
    /// Keep traversal stacks in workgroup memory instead of private memory (binary layout).
    #[arg(long)]
    pub stack_in_workgroup: bool,
}

#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum BlasLayoutArg {
    Binary,
    Wide,
}

#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum BvhQuality {
    Fast,
    Balanced,
    Quality,
}

#[derive(Serialize)]
struct PassRecord {
    scene: String,
    label: String,
    median_ms: f64,
    min_ms: f64,
    rays: Option<u64>,
    mrays_per_s: Option<f64>,
}

#[derive(Serialize)]
struct DdgiRecord {
    scene: String,
    probes: [u32; 3],
    rays_per_probe: u32,
    /// How the probe rays were laid out: ray order and probes per workgroup.
    variant: String,
    rays: u64,
    /// Probes that traced rays in the timed frames (all of them with probe states off).
    updating_probes: u32,
    /// Rays actually traced a frame: updating probes × rays per probe.
    traced_rays: u64,
    /// Shadow rays ddgi/shade queued for ddgi/shadow in the last frame (0 without the queue).
    queued_shadow_rays: u32,
    /// Median milliseconds of each pass of the frame.
    passes: Vec<(String, f64)>,
    /// ddgi/trace alone.
    trace_mrays_per_s: f64,
    /// Every ddgi/ pass but resolve: ray directions, trace, shade, blend weights, blends,
    /// probe states (and relocation in the frames it runs).
    update_ms: f64,
    /// Every probe's rays (probes × rays per probe) ÷ update time: the paper's Table 2 figure.
    update_mrays_per_s: f64,
    /// Rays actually traced ÷ update time (lower than the above when probes sleep).
    update_traced_mrays_per_s: f64,
    /// update + resolve: all of the frame's GI work.
    gi_ms: f64,
    frame_ms: f64,
}

#[derive(Serialize)]
struct SceneRecord {
    scene: String,
    triangles: usize,
    bvh_nodes: usize,
    bvh_build_ms: f64,
    max_blas_depth: u32,
    scene_load_ms: f64,
}

#[derive(Serialize)]
struct BenchRecord {
    adapter: String,
    backend: String,
    driver: String,
    timing: &'static str,
    commit: &'static str,
    date_unix: u64,
    command: String,
    size: [u32; 2],
    iterations: u32,
    scenes: Vec<SceneRecord>,
    passes: Vec<PassRecord>,
    ddgi: Vec<DdgiRecord>,
}

pub fn run(args: &BenchArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    let (size, iterations, warmup) = if args.smoke {
        ((64, 64), 2, 0)
    } else {
        (args.size, args.iterations.max(1), args.warmup)
    };
    let ctx = GpuContext::new(adapter)?;
    let mut record = BenchRecord {
        adapter: ctx.info.name.clone(),
        backend: ctx.info.backend.clone(),
        driver: format!("{} {}", ctx.info.driver, ctx.info.driver_info),
        timing: if ctx.info.timestamps {
            "GPU timestamp queries"
        } else {
            "wall clock (no timestamp queries)"
        },
        commit: env!("IRRADIANT_COMMIT"),
        date_unix: std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs())
            .unwrap_or(0),
        command: std::env::args().collect::<Vec<_>>().join(" "),
        size: [size.0, size.1],
        iterations,
        scenes: Vec::new(),
        passes: Vec::new(),
        ddgi: Vec::new(),
    };
    let ddgi_variants = ddgi_variants(args)?;
    for name in &args.scene {
        let start = Instant::now();
        let scene = irradiant_scene::load(name)?.scene;
        let load_ms = start.elapsed().as_secs_f64() * 1e3;
        let gpu_scene = GpuScene::new(
            &ctx,
            &scene,
            &GpuSceneSettings {
                stack_in_workgroup: args.stack_in_workgroup,
                blas_layout: match args.blas_layout {
                    BlasLayoutArg::Binary => irradiant::BlasLayout::Binary,
                    BlasLayoutArg::Wide => irradiant::BlasLayout::Wide,
                },
                bvh_quality: match args.bvh_quality {
                    BvhQuality::Fast => irradiant::BuildQuality::Fast,
                    BvhQuality::Balanced => irradiant::BuildQuality::Balanced,
                    BvhQuality::Quality => irradiant::BuildQuality::Quality,
                },
                ..GpuSceneSettings::default()
            },
        )?;
        record.scenes.push(SceneRecord {
            scene: scene.name.clone(),
            triangles: gpu_scene.stats.triangles,
            bvh_nodes: gpu_scene.stats.bvh_nodes,
            bvh_build_ms: gpu_scene.stats.bvh_build.as_secs_f64() * 1e3,
            max_blas_depth: gpu_scene.stats.max_blas_depth,
            scene_load_ms: load_ms,
        });
        let caster = RayCaster::new(&ctx, &gpu_scene)?;
        let primary = primary_rays(&scene, size);
        let primary_batch = caster.upload(&ctx, &primary, false);
        let times = time_pass(&ctx, warmup, iterations, |encoder, profiler| {
            caster.record(encoder, &gpu_scene, &primary_batch, profiler)
        })?;
        record.passes.push(pass_record(
            &scene.name,
            "raycast/trace (primary)",
            &times,
            Some(primary.len() as u64),
        ));

        let hits = caster.trace(&ctx, &gpu_scene, &primary, false)?;
        let diffuse = diffuse_rays(&scene, &gpu_scene, &primary, &hits);
        let diffuse_batch = caster.upload(&ctx, &diffuse, false);
        let times = time_pass(&ctx, warmup, iterations, |encoder, profiler| {
            caster.record(encoder, &gpu_scene, &diffuse_batch, profiler)
        })?;
        record.passes.push(pass_record(
            &scene.name,
            "raycast/trace (diffuse)",
            &times,
            Some(diffuse.len() as u64),
        ));

        let shadow_batch = caster.upload(&ctx, &diffuse, true);
        let times = time_pass(&ctx, warmup, iterations, |encoder, profiler| {
            caster.record(encoder, &gpu_scene, &shadow_batch, profiler)
        })?;
        record.passes.push(pass_record(
            &scene.name,
            "raycast/trace (diffuse, any hit)",
            &times,
            Some(diffuse.len() as u64),
        ));

        let mut tracer = PathTracer::new(&ctx, &gpu_scene, size.0, size.1)?;
        let settings = PathTraceSettings {
            samples_per_pixel: 1,
            samples_per_dispatch: 1,
            ..PathTraceSettings::balanced()
        };
        let times = time_pass(&ctx, warmup, iterations, |encoder, profiler| {
            tracer.record(
                &ctx,
                encoder,
                &gpu_scene,
                &scene.camera,
                &settings,
                1,
                profiler,
            )
        })?;
        record.passes.push(pass_record(
            &scene.name,
            "pathtrace/trace (1 spp)",
            &times,
            None,
        ));

        for probes in &args.ddgi_probes {
            let counts = if probes == "scene" {
                scene
                    .probe_volumes
                    .first()
                    .map(|v| v.counts)
                    .ok_or_else(|| {
                        CliError::Usage(format!(
                            "{}: the scene has no probe volume; pass counts such as 16x8x16",
                            scene.name
                        ))
                    })?
            } else {
                crate::render::parse_counts(probes).map_err(CliError::Usage)?
            };
            for &rays in &args.ddgi_rays {
                for variant in &ddgi_variants {
                    let settings = DdgiSettings {
                        rays_per_probe: rays,
                        ..variant.clone()
                    };
                    let first_of_scene = !record.ddgi.iter().any(|d| d.scene == scene.name);
                    record.ddgi.push(time_ddgi(
                        &ctx,
                        &scene,
                        &gpu_scene,
                        counts,
                        &settings,
                        size,
                        // A scene's first configuration also warms the GPU up from idle after
                        // the scene's load (seen on an H200: those frames ran up to 5× slow).
                        warmup.max(match (args.smoke, first_of_scene) {
                            (true, _) => 1,
                            (false, true) => 60,
                            (false, false) => 5,
                        }),
                        iterations,
                    )?);
                }
            }
        }
    }
    print_table(&record);
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&record).expect("bench records serialise");
        std::fs::write(path, text).map_err(|e| CliError::Io {
            path: path.clone(),
            message: e.to_string(),
        })?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The DDGI settings `bench` times (rays per probe aside): every combination of the listed
/// values of the DDGI switches and of probes per group, in the order they are listed.
fn ddgi_variants(args: &BenchArgs) -> Result<Vec<DdgiSettings>, CliError> {
    let switch = |values: &[String], flag: &str, yes: &str, no: &str| {
        values
            .iter()
            .map(|v| match v.as_str() {
                v if v == yes => Ok(true),
                v if v == no => Ok(false),
                other => Err(CliError::Usage(format!(
                    "unknown {flag} {other:?}: use {yes} or {no}"
                ))),
            })
            .collect::<Result<Vec<bool>, CliError>>()
    };
    type Set = fn(&mut DdgiSettings, bool);
    let switches: [(Vec<bool>, Set); 5] = [
        (
            switch(
                &args.ddgi_ray_order,
                "--ddgi-ray-order",
                "coherent",
                "fibonacci",
            )?,
            |s, on| s.coherent_rays = on,
        ),
        (
            switch(&args.ddgi_probe_states, "--ddgi-probe-states", "on", "off")?,
            |s, on| s.probe_states = on,
        ),
        (
            switch(
                &args.ddgi_light_choice,
                "--ddgi-light-choice",
                "warp",
                "ray",
            )?,
            |s, on| s.light_per_warp = on,
        ),
        (
            switch(
                &args.ddgi_fuse_trace_shade,
                "--ddgi-fuse-trace-shade",
                "on",
                "off",
            )?,
            |s, on| s.fuse_trace_and_shade = on,
        ),
        (
            switch(&args.ddgi_shadow_queue, "--ddgi-shadow-queue", "on", "off")?,
            |s, on| s.shadow_queue = on,
        ),
    ];
    let mut variants = vec![DdgiSettings {
        shade_all_lights: args.ddgi_shade_all_lights,
        weights: crate::render::probe_weights(args.ddgi_weights),
        ..DdgiSettings::balanced()
    }];
    // Each switch multiplies the variants so far by its values (the first listed outermost).
    for (values, set) in switches {
        variants = variants
            .iter()
            .flat_map(|v| {
                values.iter().map(move |&on| {
                    let mut v = v.clone();
                    set(&mut v, on);
                    v
                })
            })
            .collect();
    }
    Ok(variants
        .iter()
        .flat_map(|v| {
            args.ddgi_probes_per_group
                .iter()
                .map(move |&probes_per_group| DdgiSettings {
                    probes_per_group,
                    ..v.clone()
                })
        })
        .collect())
}

/// Runs `record_pass` warm-up + timed times, one submission each, and returns the timed
/// durations in milliseconds (GPU timestamps, or wall clock around a wait without them).
fn time_pass(
    ctx: &GpuContext,
    warmup: u32,
    iterations: u32,
    mut record_pass: impl FnMut(&mut wgpu::CommandEncoder, Option<&mut Profiler>),
) -> Result<Vec<f64>, CliError> {
    let mut profiler = Profiler::new(ctx, 1);
    let mut times = Vec::new();
    for i in 0..warmup + iterations {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("bench"),
            });
        record_pass(
            &mut encoder,
            if profiler.enabled() {
                Some(&mut profiler)
            } else {
                None
            },
        );
        profiler.resolve(&mut encoder);
        let start = Instant::now();
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        let wall = start.elapsed().as_secs_f64() * 1e3;
        let gpu = profiler.read(ctx)?;
        if i >= warmup {
            times.push(gpu.first().map_or(wall, |t| t.milliseconds));
        }
    }
    Ok(times)
}

/// Times whole frames (G-buffer, direct, DDGI update and resolve, compose) pass by pass.
#[allow(clippy::too_many_arguments)]
fn time_ddgi(
    ctx: &GpuContext,
    scene: &irradiant_scene::Scene,
    gpu_scene: &GpuScene,
    counts: [u32; 3],
    settings: &DdgiSettings,
    size: (u32, u32),
    warmup: u32,
    iterations: u32,
) -> Result<DdgiRecord, CliError> {
    let mut volume = scene
        .probe_volumes
        .first()
        .cloned()
        .unwrap_or_else(|| crate::render::default_volume(scene));
    volume.counts = counts;
    let rays = settings.rays_per_probe;
    let mut frame = FrameRenderer::new(ctx, gpu_scene, size.0, size.1, FrameSettings::default())?;
    let mut ddgi = Ddgi::new(ctx, gpu_scene, &volume, settings)?;
    ddgi.bind_frame(ctx, &frame.buffers);
    let mut profiler = Profiler::new(ctx, 32);
    let mut per_pass: Vec<(String, Vec<f64>)> = Vec::new();
    for i in 0..warmup + iterations {
        frame.render(
            ctx,
            gpu_scene,
            &scene.camera,
            Some(&mut ddgi as &mut dyn Technique),
            false,
            Some(&mut profiler),
        )?;
        ctx.wait()?;
        let timings = profiler.read(ctx)?;
        if i < warmup {
            continue;
        }
        for t in timings {
            match per_pass.iter_mut().find(|(l, _)| *l == t.label) {
                Some((_, v)) => v.push(t.milliseconds),
                None => per_pass.push((t.label, vec![t.milliseconds])),
            }
        }
    }
    let passes: Vec<(String, f64)> = per_pass
        .into_iter()
        .map(|(label, mut v)| {
            v.sort_by(f64::total_cmp);
            (label, v.get(v.len() / 2).copied().unwrap_or(0.0))
        })
        .collect();
    let ms = |label: &str| passes.iter().find(|(l, _)| l == label).map_or(0.0, |p| p.1);
    let update: f64 = [
        "ddgi/ray_directions",
        "ddgi/trace",
        "ddgi/shade",
        "ddgi/trace_shade",
        "ddgi/shadow",
        "ddgi/blend_irradiance",
        "ddgi/blend_distance",
        "ddgi/blend_weights",
        "ddgi/relocate",
        "ddgi/probe_states",
    ]
    .iter()
    .map(|l| ms(l))
    .sum();
    let total_rays = (counts[0] * counts[1] * counts[2]) as u64 * rays as u64;
    let updating_probes = ddgi.read_state_counts(ctx)?.updating();
    let traced_rays = updating_probes as u64 * rays as u64;
    let gi = update + ms("ddgi/resolve");
    Ok(DdgiRecord {
        scene: scene.name.clone(),
        probes: counts,
        rays_per_probe: rays,
        variant: format!(
            "{}/{}{}{}{}{}",
            if settings.coherent_rays {
                "coherent"
            } else {
                "fibonacci"
            },
            settings.probes_per_group,
            if settings.probe_states { "/states" } else { "" },
            if settings.light_per_warp {
                ""
            } else {
                "/ray-light"
            },
            if settings.fuse_trace_and_shade {
                "/fused"
            } else {
                ""
            },
            if settings.queues_shadow_rays() {
                "/queue"
            } else {
                ""
            }
        ),
        rays: total_rays,
        updating_probes,
        traced_rays,
        queued_shadow_rays: ddgi.read_queued_shadow_rays(ctx)?,
        trace_mrays_per_s: total_rays as f64 / (ms("ddgi/trace") * 1e-3) / 1e6,
        update_ms: update,
        update_mrays_per_s: total_rays as f64 / (update * 1e-3) / 1e6,
        update_traced_mrays_per_s: traced_rays as f64 / (update * 1e-3) / 1e6,
        gi_ms: gi,
        frame_ms: passes.iter().map(|p| p.1).sum(),
        passes,
    })
}

fn pass_record(scene: &str, label: &str, times: &[f64], rays: Option<u64>) -> PassRecord {
    let mut sorted = times.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    PassRecord {
        scene: scene.to_owned(),
        label: label.to_owned(),
        median_ms: median,
        min_ms: sorted[0],
        rays,
        mrays_per_s: rays.map(|r| r as f64 / (median * 1e-3) / 1e6),
    }
}

fn print_table(r: &BenchRecord) {
    println!(
        "adapter: {} ({}, driver {}); timing: {}; commit {}",
        r.adapter, r.backend, r.driver, r.timing, r.commit
    );
    println!(
        "{:<22} {:>10} {:>10} {:>12} {:>10}",
        "scene", "triangles", "BVH nodes", "BVH build ms", "load ms"
    );
    for s in &r.scenes {
        println!(
            "{:<22} {:>10} {:>10} {:>12.1} {:>10.1}",
            s.scene, s.triangles, s.bvh_nodes, s.bvh_build_ms, s.scene_load_ms
        );
    }
    println!(
        "\n{:<22} {:<34} {:>10} {:>10} {:>12} {:>10}",
        "scene", "pass", "median ms", "min ms", "rays", "Mrays/s"
    );
    for p in &r.passes {
        let rays = p.rays.map_or("-".into(), |n| n.to_string());
        let rate = p.mrays_per_s.map_or("-".into(), |m| format!("{m:.1}"));
        println!(
            "{:<22} {:<34} {:>10.3} {:>10.3} {:>12} {:>10}",
            p.scene, p.label, p.median_ms, p.min_ms, rays, rate
        );
    }
    if r.ddgi.is_empty() {
        return;
    }
    // Every pass any record has, in the order first seen (fused variants lack some passes).
    let mut full_labels: Vec<&str> = Vec::new();
    for d in &r.ddgi {
        for (l, _) in &d.passes {
            if !full_labels.contains(&l.as_str()) {
                full_labels.push(l);
            }
        }
    }
    let labels: Vec<&str> = full_labels
        .iter()
        .map(|l| {
            l.strip_prefix("ddgi/")
                .or(l.strip_prefix("frame/"))
                .unwrap_or(l)
        })
        .collect();
    print!(
        "\n{:<10} {:<10} {:>5} {:<28} {:>9}",
        "scene", "probes", "rays", "variant", "Mrays"
    );
    for l in &labels {
        print!(" {:>12}", l);
    }
    println!(
        " {:>10} {:>12} {:>10} {:>12} {:>9} {:>9}",
        "update ms", "update Mr/s", "trace Mr/s", "GI ms", "frame ms", "updating"
    );
    for d in &r.ddgi {
        print!(
            "{:<10} {:<10} {:>5} {:<28} {:>9.2}",
            d.scene,
            format!("{}x{}x{}", d.probes[0], d.probes[1], d.probes[2]),
            d.rays_per_probe,
            d.variant,
            d.rays as f64 / 1e6
        );
        for label in &full_labels {
            let ms = d
                .passes
                .iter()
                .find(|(l, _)| l == label)
                .map_or(0.0, |p| p.1);
            print!(" {:>12.3}", ms);
        }
        println!(
            " {:>10.3} {:>12.0} {:>10.0} {:>12.3} {:>9.3} {:>9}",
            d.update_ms,
            d.update_mrays_per_s,
            d.trace_mrays_per_s,
            d.gi_ms,
            d.frame_ms,
            d.updating_probes
        );
    }
}

/// One ray through each pixel centre.
fn primary_rays(scene: &irradiant_scene::Scene, (w, h): (u32, u32)) -> Vec<GpuRay> {
    let cam = GpuCamera::new(&scene.camera, w, h);
    let (forward, right, up) = (
        Vec3::from(cam.forward),
        Vec3::from(cam.right),
        Vec3::from(cam.up),
    );
    let mut rays = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let ndc_x = (x as f32 + 0.5) / w as f32 * 2.0 - 1.0;
            let ndc_y = 1.0 - (y as f32 + 0.5) / h as f32 * 2.0;
            let dir = (forward
                + right * ndc_x * cam.tan_half_fov_y * cam.aspect
                + up * ndc_y * cam.tan_half_fov_y)
                .normalize();
            rays.push(GpuRay {
                origin: cam.position,
                t_max: 1e20,
                dir: dir.into(),
                _pad: 0,
            });
        }
    }
    rays
}

/// Incoherent secondary rays: from each primary hit, a cosine-distributed direction about the
/// surface normal (what a path tracer's or DDGI's bounce rays look like). Pixels whose primary
/// ray missed shoot a uniformly random ray from the camera instead, keeping the count.
fn diffuse_rays(
    scene: &irradiant_scene::Scene,
    gpu_scene: &GpuScene,
    primary: &[GpuRay],
    hits: &[irradiant::gpu_types::GpuRayHit],
) -> Vec<GpuRay> {
    let mut rng = StdRng::seed_from_u64(1);
    let mut unit = || loop {
        let v = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let l = v.length_squared();
        if l > 1e-4 && l <= 1.0 {
            break v / l.sqrt();
        }
    };
    primary
        .iter()
        .zip(hits)
        .map(|(ray, hit)| {
            let o = Vec3::from(ray.origin);
            let d = Vec3::from(ray.dir);
            if hit.t < 0.0 {
                return GpuRay {
                    origin: ray.origin,
                    t_max: 1e20,
                    dir: unit().into(),
                    _pad: 0,
                };
            }
            let instance =
                &scene.instances[gpu_scene.instance_order[hit.instance as usize] as usize];
            let (mesh, t) = gpu_scene.triangle_sources[hit.triangle as usize];
            let [a, b, c] = scene.meshes[mesh as usize]
                .triangle(t as usize)
                .map(|p| instance.transform.transform_point3(p));
            let mut n = (b - a).cross(c - a).normalize();
            if n.dot(d) > 0.0 {
                n = -n;
            }
            let p = o + d * hit.t;
            // Cosine distribution: normal plus a uniform point on the unit sphere.
            let dir = (n + unit()).normalize_or(n);
            let origin = p + n * 1e-4 * p.abs().max_element().max(1.0);
            GpuRay {
                origin: origin.into(),
                t_max: 1e20,
                dir: dir.into(),
                _pad: 0,
            }
        })
        .collect()
}
