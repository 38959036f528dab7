//! `irradiant bench`: BVH build time, and each GPU pass timed with timestamp queries after a
//! warm-up (median of many runs), with rays per second where a pass traces rays. Frames of
//! every technique are timed through the session, pass by pass, grouped by the labels each
//! technique reports.

mod frames;
mod rays;
mod ssil;
mod table;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::Args;
use irradiant::ddgi::DdgiSettings;
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::raycast::RayCaster;
use irradiant::{AdapterChoice, GpuContext, GpuScene, GpuSceneSettings, TechniqueSpec};
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
    /// Warm-up runs per pass, not timed (at least; see --warmup-ms).
    #[arg(long, default_value = "3")]
    pub warmup: u32,
    /// Each pass and frame also runs untimed for at least this long before it is timed. GPU
    /// clocks fall while the GPU waits for the CPU (loading a scene, building its tree,
    /// making rays) and climb back only under steady work: a few runs after such a wait were
    /// timed at a sixth of the clock (BENCHMARKS.md, session 7). Longer costs bench time only.
    #[arg(long, default_value = "500")]
    pub warmup_ms: u64,
    /// Runs the scenes again in reverse order in the same call and compares every pass and
    /// frame between the two orders; fails if any differs by more than --order-tolerance.
    #[arg(long)]
    pub check_order: bool,
    /// Largest difference between the two orders --check-order accepts, percent.
    #[arg(long, default_value = "3", allow_negative_numbers = true)]
    pub order_tolerance: f64,
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
    /// Time frames while the camera sways (a hundredth of a degree about the vertical, back
    /// and forth every frame) instead of standing still: TAA then reprojects and clips its
    /// history, and every running mean restarts, as in a game.
    #[arg(long)]
    pub moving_camera: bool,
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

/// How long a timed configuration runs untimed first: at least `runs` runs and `time`.
#[derive(Clone, Copy, Debug)]
pub struct Warmup {
    pub runs: u32,
    pub time: Duration,
}

impl Warmup {
    /// Whether `runs_done` runs since `start` have warmed the GPU up.
    pub fn done(&self, runs_done: u32, start: Instant) -> bool {
        runs_done >= self.runs && start.elapsed() >= self.time
    }
}

/// A warm-up, then `iterations` timed runs.
#[derive(Clone, Copy, Debug)]
struct Timing {
    warmup: Warmup,
    iterations: u32,
}

#[derive(Serialize)]
struct PassRecord {
    scene: String,
    /// Which run over the scene list: "forward", or "reverse" under --check-order.
    order: &'static str,
    label: String,
    median_ms: f64,
    min_ms: f64,
    max_ms: f64,
    rays: Option<u64>,
    mrays_per_s: Option<f64>,
}

#[derive(Serialize)]
struct SceneRecord {
    scene: String,
    /// Triangles the bottom-level trees hold (each mesh once).
    triangles: usize,
    instances: usize,
    /// Triangles in the world: each instance's mesh counted once an instance.
    world_triangles: usize,
    bvh_nodes: usize,
    bvh_build_ms: f64,
    max_blas_depth: u32,
    scene_load_ms: f64,
    /// What the scene's buffers and textures take on the GPU.
    gpu_scene_mib: f64,
    /// Everything wgpu's allocator holds after the scene's upload (where reported).
    gpu_allocated_mib: Option<f64>,
    /// The process's peak resident host memory after loading and building this scene.
    peak_host_mib: Option<f64>,
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
        (
            (64, 64),
            2,
            Warmup {
                runs: 0,
                time: Duration::ZERO,
            },
        )
    } else {
        let time = Duration::from_millis(args.warmup_ms);
        (
            args.size,
            args.iterations.max(1),
            Warmup {
                runs: args.warmup,
                time,
            },
        )
    };
    if args.order_tolerance.is_nan() || args.order_tolerance < 0.0 {
        return Err(CliError::Usage(format!(
            "--order-tolerance {} is not a percentage; give 0 or more (3 is the default)",
            args.order_tolerance
        )));
    }
    let techniques = crate::options::technique_list(&args.techniques)?;
    // Each technique's balanced settings with its own in braces over them, checked (and its
    // unknown keys warned of) before the GPU is touched.
    let technique_specs: Vec<TechniqueSpec> = techniques
        .iter()
        .map(|choice| {
            let mut spec = TechniqueSpec::new(&choice.name, irradiant::Preset::Balanced);
            spec.settings = choice.overrides.clone();
            spec
        })
        .collect();
    crate::options::check_techniques(&[], &technique_specs, None)?;
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
    let mut orders = vec![("forward", args.scene.clone())];
    if args.check_order {
        orders.push(("reverse", args.scene.iter().rev().cloned().collect()));
    }
    let mut order_boundaries = Vec::new();
    for (order, scenes) in &orders {
        order_boundaries.push(RecordLengths::of(&record));
        for name in scenes {
            let start = Instant::now();
            let scene = irradiant_scene::load(name)?.scene;
            let load_ms = start.elapsed().as_secs_f64() * 1e3;
            let gpu_scene = GpuScene::new(&ctx, &scene, &scene_settings)?;
            record.scenes.push(SceneRecord {
                scene: scene.name.clone(),
                triangles: gpu_scene.stats.triangles,
                instances: scene.instances.len(),
                world_triangles: scene
                    .instances
                    .iter()
                    .map(|i| scene.meshes[i.mesh as usize].triangle_count())
                    .sum(),
                bvh_nodes: gpu_scene.stats.bvh_nodes,
                bvh_build_ms: gpu_scene.stats.bvh_build.as_secs_f64() * 1e3,
                max_blas_depth: gpu_scene.stats.max_blas_depth,
                scene_load_ms: load_ms,
                gpu_scene_mib: gpu_scene.stats.gpu_bytes as f64 / (1024.0 * 1024.0),
                gpu_allocated_mib: crate::memory::gpu_mib(&ctx),
                peak_host_mib: crate::memory::peak_host_mib(),
            });
            time_rays(
                &ctx,
                &scene,
                &gpu_scene,
                size,
                Timing { warmup, iterations },
                order,
                &mut record,
            )?;
            drop(gpu_scene);
            let frames = frames::FrameBench {
                ctx: ctx.clone(),
                scene: &scene,
                scene_settings: &scene_settings,
                size,
                taa: !args.no_taa,
                moving_camera: args.moving_camera,
                iterations,
                agreement_rays: args.lightfield_agreement,
                order,
            };
            // A frame is run once at least before timing: its first one builds what it caches.
            let frame_warmup = Warmup {
                runs: warmup.runs.max(1),
                ..warmup
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
                        let spec = irradiant::TechniqueSpec::with_settings("ddgi", &settings);
                        let mut r = frames.time(&spec, frame_warmup)?;
                        r.variant = variant_name(&settings);
                        record.ddgi.push(r);
                    }
                }
            }
            for settings in &ssil_variants {
                let spec = irradiant::TechniqueSpec::with_settings("ssil", settings);
                let mut r = frames.time(&spec, frame_warmup)?;
                r.variant = ssil::variant_name(settings);
                record.ssil.push(r);
            }
            for (choice, spec) in techniques.iter().zip(&technique_specs) {
                let mut r = frames.time(spec, frame_warmup)?;
                r.technique = choice.label.clone();
                r.variant = choice.label.clone();
                record.techniques.push(r);
            }
        }
    }
    table::print_table(&record);
    let order_problems = if args.check_order {
        order_check(&record, &order_boundaries[1], args.order_tolerance)
    } else {
        Vec::new()
    };
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&record).expect("bench records serialise");
        crate::write_file(path, text)?;
        println!("wrote {}", path.display());
    }
    if !order_problems.is_empty() {
        return Err(CliError::Usage(format!(
            "timings depend on the order of the scenes (over {}%):\n{}",
            args.order_tolerance,
            order_problems.join("\n")
        )));
    }
    Ok(())
}

/// How many records of each kind there were when an order's run began.
struct RecordLengths {
    passes: usize,
    frames: [usize; 3],
}

impl RecordLengths {
    fn of(record: &BenchRecord) -> Self {
        Self {
            passes: record.passes.len(),
            frames: [
                record.ddgi.len(),
                record.techniques.len(),
                record.ssil.len(),
            ],
        }
    }
}

/// Prints every pass's and frame's median in both orders and returns those that differ by
/// more than `tolerance` percent.
fn order_check(record: &BenchRecord, reverse_start: &RecordLengths, tolerance: f64) -> Vec<String> {
    let mut pairs: Vec<(String, f64, f64)> = Vec::new();
    let (forward, reverse) = record.passes.split_at(reverse_start.passes);
    for f in forward {
        if let Some(r) = reverse
            .iter()
            .find(|r| r.scene == f.scene && r.label == f.label)
        {
            pairs.push((format!("{} {}", f.scene, f.label), f.median_ms, r.median_ms));
        }
    }
    let frame_lists = [&record.ddgi, &record.techniques, &record.ssil];
    for (list, start) in frame_lists.into_iter().zip(reverse_start.frames) {
        let (forward, reverse) = list.split_at(start);
        for f in forward {
            let same = |r: &&FrameRecord| {
                r.scene == f.scene && r.technique == f.technique && r.variant == f.variant
            };
            if let Some(r) = reverse.iter().find(same) {
                let name = format!("{} {} {} frame", f.scene, f.technique, f.variant);
                pairs.push((name, f.frame_ms, r.frame_ms));
            }
        }
    }
    println!(
        "\n{:<64} {:>10} {:>10} {:>8}",
        "order check", "forward", "reverse", "diff %"
    );
    let mut problems = Vec::new();
    for (name, f, r) in pairs {
        let diff = 100.0 * (r - f) / f.max(1e-9);
        println!("{name:<64} {f:>10.3} {r:>10.3} {diff:>+8.2}");
        if diff.abs() > tolerance {
            problems.push(format!(
                "  {name}: {f:.3} ms forward, {r:.3} ms reverse ({diff:+.1}%)"
            ));
        }
    }
    problems
}

/// Ray casting (primary, diffuse, diffuse any-hit) and one path-traced sample per pixel.
fn time_rays(
    ctx: &GpuContext,
    scene: &irradiant_scene::Scene,
    gpu_scene: &GpuScene,
    size: (u32, u32),
    timing: Timing,
    order: &'static str,
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
        let times = time_pass(ctx, timing, |encoder, profiler| {
            caster.record(encoder, &batch, profiler);
            Ok(())
        })?;
        record.passes.push(pass_record(
            &scene.name,
            order,
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
    let times = time_pass(ctx, timing, |encoder, profiler| {
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
        order,
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
    timing: Timing,
    mut record_pass: impl FnMut(
        &mut wgpu::CommandEncoder,
        Option<&mut Profiler>,
    ) -> Result<(), CliError>,
) -> Result<Vec<f64>, CliError> {
    let mut profiler = Profiler::new(ctx, 1);
    let mut times = Vec::new();
    let warm_start = Instant::now();
    let mut warm_runs = 0;
    while times.len() < timing.iterations as usize {
        let warming = !timing.warmup.done(warm_runs, warm_start);
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
        if warming {
            warm_runs += 1;
        } else {
            times.push(gpu.first().map_or(wall, |t| t.milliseconds));
        }
    }
    Ok(times)
}

fn pass_record(
    scene: &str,
    order: &'static str,
    label: &str,
    times: &[f64],
    rays: Option<u64>,
) -> PassRecord {
    let mut sorted = times.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    PassRecord {
        scene: scene.to_owned(),
        order,
        label: label.to_owned(),
        median_ms: median,
        min_ms: sorted[0],
        max_ms: sorted[sorted.len() - 1],
        rays,
        mrays_per_s: rays.map(|r| r as f64 / (median * 1e-3) / 1e6),
    }
}
