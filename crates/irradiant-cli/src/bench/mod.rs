//! `irradiant bench`: BVH build time, and each GPU pass timed with timestamp queries after a
//! warm-up (median of many runs), with rays per second where a pass traces rays. Frames of
//! every technique are timed through the session, pass by pass, grouped by the labels each
//! technique reports.

mod frames;
mod rays;
mod ssil;
mod table;

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use irradiant::ddgi::DdgiSettings;
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::raycast::RayCaster;
use irradiant::{AdapterChoice, GpuContext, GpuScene, GpuSceneSettings};
use irradiant_gpu::{Profiler, wgpu};
use serde::Serialize;

use crate::CliError;
use crate::options::parse_size;
pub use frames::FrameRecord;

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
    pub ddgi_weights: crate::options::Weights,
    /// BVH build effort: fast, balanced or quality (spatial pre-splits, the default).
    #[arg(long, value_enum, default_value = "quality")]
    pub bvh_quality: BvhQuality,
    /// Bottom-level BVH layout: wide (compressed 8-wide nodes, the default) or binary.
    #[arg(long, value_enum, default_value = "wide")]
    pub blas_layout: BlasLayoutArg,
    /// Keep traversal stacks in workgroup memory instead of private memory (binary layout).
    #[arg(long)]
    pub stack_in_workgroup: bool,
    /// Also time the real-time frame of each of these registered techniques with their
    /// balanced settings and the scene's own probe volumes, comma-separated (`all`: every one);
    /// settings of their own in braces, e.g. `ssil{samples = 256}`.
    #[arg(long)]
    pub techniques: Vec<String>,
    /// Time frames without TAA (the frame/taa pass then only copies), as frames were before it.
    #[arg(long)]
    pub no_taa: bool,
    #[command(flatten)]
    pub ssil: ssil::SsilGridArgs,
    /// Light-field techniques: after timing, trace this many rays from the visible surfaces
    /// both through the light field and through the BVH, and report the share on which they
    /// agree (counters agreement_*). 0: not measured.
    #[arg(long, default_value_t = 0)]
    pub lightfield_agreement: u32,
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
struct SceneRecord {
    scene: String,
    triangles: usize,
    bvh_nodes: usize,
    bvh_build_ms: f64,
    max_blas_depth: u32,
    scene_load_ms: f64,
}

#[derive(Serialize)]
pub struct BenchRecord {
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
    /// DDGI frames for each probe grid and variant asked for (--ddgi-probes).
    ddgi: Vec<FrameRecord>,
    /// Frames of each technique asked for (--techniques).
    techniques: Vec<FrameRecord>,
    /// SSIL frames over the grid asked for (--ssil-start, the paper's Figure 9).
    ssil: Vec<FrameRecord>,
}

pub fn run(args: &BenchArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    let (size, iterations, warmup) = if args.smoke {
        ((64, 64), 2, 0)
    } else {
        (args.size, args.iterations.max(1), args.warmup)
    };
    let techniques = crate::options::technique_list(&args.techniques)?;
    let ddgi_variants = ddgi_variants(args)?;
    let ssil_variants = ssil::variants(&args.ssil);
    for v in &ssil_variants {
        v.validate().map_err(|e| CliError::Usage(e.to_string()))?;
        v.check_size(size)
            .map_err(|e| CliError::Usage(e.to_string()))?;
    }
    let ctx = std::sync::Arc::new(GpuContext::new(adapter)?);
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
        techniques: Vec::new(),
        ssil: Vec::new(),
    };
    let scene_settings = GpuSceneSettings {
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
    };
    for name in &args.scene {
        let start = Instant::now();
        let scene = irradiant_scene::load(name)?.scene;
        let load_ms = start.elapsed().as_secs_f64() * 1e3;
        let gpu_scene = GpuScene::new(&ctx, &scene, &scene_settings)?;
        record.scenes.push(SceneRecord {
            scene: scene.name.clone(),
            triangles: gpu_scene.stats.triangles,
            bvh_nodes: gpu_scene.stats.bvh_nodes,
            bvh_build_ms: gpu_scene.stats.bvh_build.as_secs_f64() * 1e3,
            max_blas_depth: gpu_scene.stats.max_blas_depth,
            scene_load_ms: load_ms,
        });
        time_rays(
            &ctx,
            &scene,
            &gpu_scene,
            size,
            warmup,
            iterations,
            &mut record,
        )?;
        drop(gpu_scene);
        let frames = frames::FrameBench {
            ctx: ctx.clone(),
            scene: &scene,
            scene_settings: &scene_settings,
            size,
            taa: !args.no_taa,
            iterations,
            agreement_rays: args.lightfield_agreement,
        };
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
                crate::options::parse_counts(probes).map_err(CliError::Usage)?
            };
            for &rays in &args.ddgi_rays {
                for variant in &ddgi_variants {
                    let mut settings = variant.clone();
                    settings.volume.rays_per_probe = rays;
                    settings.volume.probe_counts = counts;
                    let first_of_scene = !record.ddgi.iter().any(|d| d.scene == scene.name);
                    // A scene's first configuration also warms the GPU up from idle after the
                    // scene's load (seen on an H200: those frames ran up to 5× slow).
                    let warm = warmup.max(match (args.smoke, first_of_scene) {
                        (true, _) => 1,
                        (false, true) => 60,
                        (false, false) => 5,
                    });
                    let spec = irradiant::TechniqueSpec::with_settings("ddgi", &settings);
                    let mut r = frames.time(&spec, warm)?;
                    r.variant = variant_name(&settings);
                    record.ddgi.push(r);
                }
            }
        }
        for (i, settings) in ssil_variants.iter().enumerate() {
            // The grid's first configuration also brings the GPU's clocks up after the rays'
            // timing (on an H100 its frames otherwise ran up to 15% slow).
            let warm = warmup.max(match (args.smoke, i) {
                (true, _) => 1,
                (false, 0) => 300,
                (false, _) => 30,
            });
            let spec = irradiant::TechniqueSpec::with_settings("ssil", settings);
            let mut r = frames.time(&spec, warm)?;
            r.variant = ssil::variant_name(settings);
            record.ssil.push(r);
        }
        for choice in &techniques {
            let warm = warmup.max(if args.smoke { 1 } else { 30 });
            let mut spec = irradiant::TechniqueSpec::new(&choice.name, irradiant::Preset::Balanced);
            spec.settings = choice.overrides.clone();
            let mut r = frames.time(&spec, warm)?;
            r.technique = choice.label.clone();
            r.variant = choice.label.clone();
            record.techniques.push(r);
        }
    }
    table::print_table(&record);
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&record).expect("bench records serialise");
        crate::write_file(path, text)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Ray casting (primary, diffuse, diffuse any-hit) and one path-traced sample per pixel.
fn time_rays(
    ctx: &GpuContext,
    scene: &irradiant_scene::Scene,
    gpu_scene: &GpuScene,
    size: (u32, u32),
    warmup: u32,
    iterations: u32,
    record: &mut BenchRecord,
) -> Result<(), CliError> {
    let caster = RayCaster::new(ctx, gpu_scene)?;
    let primary = rays::primary_rays(scene, size);
    let hits = caster.trace(ctx, gpu_scene, &primary, false)?;
    let diffuse = rays::diffuse_rays(scene, gpu_scene, &primary, &hits);
    for (label, rays, any_hit) in [
        ("raycast/trace (primary)", &primary, false),
        ("raycast/trace (diffuse)", &diffuse, false),
        ("raycast/trace (diffuse, any hit)", &diffuse, true),
    ] {
        let batch = caster.upload(ctx, gpu_scene, rays, any_hit)?;
        let times = time_pass(ctx, warmup, iterations, |encoder, profiler| {
            caster.record(encoder, &batch, profiler);
            Ok(())
        })?;
        record.passes.push(pass_record(
            &scene.name,
            label,
            &times,
            Some(rays.len() as u64),
        ));
    }
    let mut tracer = PathTracer::new(ctx, gpu_scene, size.0, size.1)?;
    let settings = PathTraceSettings {
        samples_per_pixel: 1,
        samples_per_dispatch: 1,
        ..PathTraceSettings::balanced()
    };
    let times = time_pass(ctx, warmup, iterations, |encoder, profiler| {
        tracer.record(
            ctx,
            encoder,
            gpu_scene,
            &scene.camera,
            &settings,
            1,
            profiler,
        )?;
        Ok(())
    })?;
    record.passes.push(pass_record(
        &scene.name,
        "pathtrace/trace (1 spp)",
        &times,
        None,
    ));
    Ok(())
}

/// The DDGI settings `bench` times (rays per probe and probe counts aside): every combination
/// of the listed values of the DDGI switches and of probes per group, in the order listed.
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
            |s, on| s.speed.coherent_rays = on,
        ),
        (
            switch(&args.ddgi_probe_states, "--ddgi-probe-states", "on", "off")?,
            |s, on| s.speed.probe_states = on,
        ),
        (
            switch(
                &args.ddgi_light_choice,
                "--ddgi-light-choice",
                "warp",
                "ray",
            )?,
            |s, on| s.speed.light_per_warp = on,
        ),
        (
            switch(
                &args.ddgi_fuse_trace_shade,
                "--ddgi-fuse-trace-shade",
                "on",
                "off",
            )?,
            |s, on| s.speed.fuse_trace_and_shade = on,
        ),
        (
            switch(&args.ddgi_shadow_queue, "--ddgi-shadow-queue", "on", "off")?,
            |s, on| s.speed.shadow_queue = on,
        ),
    ];
    let mut base = DdgiSettings::balanced();
    base.volume.shade_all_lights = args.ddgi_shade_all_lights;
    base.update.weights = match args.ddgi_weights {
        crate::options::Weights::Classic => irradiant::ddgi::ProbeWeights::Classic,
        crate::options::Weights::Backface => irradiant::ddgi::ProbeWeights::Backface,
        crate::options::Weights::Chebyshev => irradiant::ddgi::ProbeWeights::Chebyshev,
        crate::options::Weights::Full => irradiant::ddgi::ProbeWeights::Full,
    };
    let mut variants = vec![base];
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
    let mut all = Vec::new();
    for v in &variants {
        for &probes_per_group in &args.ddgi_probes_per_group {
            let mut v = v.clone();
            v.speed.probes_per_group = probes_per_group;
            v.validate().map_err(|e| CliError::Usage(e.to_string()))?;
            all.push(v);
        }
    }
    Ok(all)
}

/// How a DDGI variant laid out its rays: ray order, probes a group and the switches on.
fn variant_name(s: &DdgiSettings) -> String {
    let p = &s.speed;
    format!(
        "{}/{}{}{}{}{}",
        if p.coherent_rays {
            "coherent"
        } else {
            "fibonacci"
        },
        p.probes_per_group,
        if p.probe_states { "/states" } else { "" },
        if p.light_per_warp { "" } else { "/ray-light" },
        if p.fuse_trace_and_shade { "/fused" } else { "" },
        if s.queues_shadow_rays() { "/queue" } else { "" }
    )
}

/// Runs `record_pass` warm-up + timed times, one submission each, and returns the timed
/// durations in milliseconds (GPU timestamps, or wall clock around a wait without them).
fn time_pass(
    ctx: &GpuContext,
    warmup: u32,
    iterations: u32,
    mut record_pass: impl FnMut(
        &mut wgpu::CommandEncoder,
        Option<&mut Profiler>,
    ) -> Result<(), CliError>,
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
        )?;
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
