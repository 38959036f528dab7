//! `irradiant bench`: BVH build time, and each GPU pass timed with timestamp queries after a
//! warm-up (median of many runs), with rays per second where a pass traces rays. Frames of
//! every technique are timed through the session, pass by pass, grouped by the labels each
//! technique reports.

mod frames;
mod pathtrace;
mod rays;
mod ssil;
mod table;
mod vary;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::Args;
use irradiant::raycast::{RayCaster, RayOrder, RayWork};
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
    /// timed at a sixth of the clock (BENCHMARKS.md, commit 3169a4f). Longer costs bench time only.
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
    /// BVH build effort: fast, balanced or quality (spatial pre-splits, the default).
    #[arg(long, value_enum, default_value = "quality")]
    pub bvh_quality: BvhQuality,
    /// Bottom-level BVH layout: wide (compressed 8-wide nodes, the default) or binary.
    #[arg(long, value_enum, default_value = "wide")]
    pub blas_layout: BlasLayoutArg,
    /// Keep traversal stacks in workgroup memory instead of private memory (binary layout).
    #[arg(long)]
    pub stack_in_workgroup: bool,
    /// Also time the real-time frame of each of these techniques, comma-separated (`all`:
    /// every registered one), each at its balanced preset and the scene's own probe volumes,
    /// under the manifest's `[technique]` table where it names the technique, unless its braces
    /// say otherwise: `ddgi{preset = "quality"}`,
    /// `ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256}`.
    #[arg(long)]
    pub techniques: Vec<String>,
    /// Times every listed technique at each value of one of its settings, in the grammar of
    /// the braces: `--vary 'volume.rays_per_probe = [64, 256]'`. Several multiply, the first
    /// outermost (SSIL's Figure 9 grid is four).
    #[arg(long)]
    pub vary: Vec<String>,
    /// Time frames without TAA (the frame/taa pass then only copies), as frames were before it.
    #[arg(long)]
    pub no_taa: bool,
    /// A settings file whose `[frame]` table the timed frames use over the balanced preset
    /// (its `[technique]` table is not read: techniques take their settings in braces), e.g.
    /// to time `[frame.resampling]` variants.
    #[arg(long)]
    pub settings: Option<std::path::PathBuf>,
    /// Time frames while the camera sways (a hundredth of a degree about the vertical, back
    /// and forth every frame) instead of standing still: TAA then reprojects and clips its
    /// history, and every running mean restarts, as in a game.
    #[arg(long)]
    pub moving_camera: bool,
    /// Time frames as the scene's animation plays (a manifest's camera path, moving lights and
    /// instances), the timed frames spread evenly over its length: the medians are along the
    /// path, and the worst frame's GI is reported too. Takes precedence over --moving-camera.
    #[arg(long)]
    pub camera_path: bool,
    /// Also write each scene's triangles and the primary and diffuse rays timed, with their hit
    /// distances, into this folder as raw f32 files, so that a peer traces the very same rays
    /// (`tools/device/peer.sh`, Mitsuba 3 through OptiX).
    #[arg(long)]
    pub dump_rays: Option<PathBuf>,
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
    /// The counting variant's mean work a ray (ray-cast passes only).
    work: Option<RayWorkRecord>,
}

/// Work a ray, so that "nodes a ray" (the tree) and "time a node" (the kernel) are apart.
#[derive(Serialize, Clone, Copy)]
struct RayWorkRecord {
    /// Node visits a ray (8-wide nodes where the bottom level is wide).
    node_visits_per_ray: f64,
    /// Triangle tests a ray.
    triangle_tests_per_ray: f64,
    /// Node visits a second at the timed pass's median: the kernel's speed per node.
    g_node_visits_per_s: f64,
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
    /// The bottom-level trees' SAH cost (node visits and triangle tests at 1 each, averaged
    /// over the triangles): the tree's quality apart from the kernel.
    bvh_sah_cost: f32,
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
    /// Frames of each technique asked for (--techniques, at each --vary).
    techniques: Vec<FrameRecord>,
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
    let varies = args
        .vary
        .iter()
        .map(|v| vary::Vary::parse(v))
        .collect::<Result<Vec<_>, _>>()?;
    if !varies.is_empty() && args.techniques.is_empty() {
        return Err(CliError::Usage(
            "--vary varies the settings of --techniques: name the techniques to time, e.g. --techniques ddgi".into(),
        ));
    }
    let techniques = vary::expand(&crate::options::technique_list(&args.techniques)?, &varies)?;
    let frame_settings = match &args.settings {
        Some(path) => {
            let mut warnings = Vec::new();
            let file = irradiant::settings::SettingsFile::read(path, &mut warnings)?;
            let frame = file.frame_settings(irradiant::Preset::Balanced, &mut warnings)?;
            for w in warnings {
                eprintln!("warning: {w}");
            }
            frame
        }
        None => irradiant::frame::FrameSettings::balanced(),
    };
    // Each technique's preset (balanced unless its braces name one) with its own settings over
    // it, checked (and its unknown keys warned of) before the GPU is touched.
    let technique_specs: Vec<TechniqueSpec> = techniques
        .iter()
        .map(|choice| {
            let preset = choice.preset.unwrap_or(irradiant::Preset::Balanced);
            let mut spec = TechniqueSpec::new(&choice.name, preset);
            spec.settings = choice.overrides.clone();
            spec
        })
        .collect();
    crate::options::check_techniques(&[], &technique_specs, None)?;
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
        techniques: Vec::new(),
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
                bvh_sah_cost: gpu_scene.stats.sah_cost,
                scene_load_ms: load_ms,
                gpu_scene_mib: gpu_scene.stats.gpu_bytes as f64 / (1024.0 * 1024.0),
                gpu_allocated_mib: crate::memory::gpu_mib(&ctx),
                peak_host_mib: crate::memory::peak_host_mib(),
            });
            let rays = RayRun {
                size,
                timing: Timing { warmup, iterations },
                order,
                dump: args.dump_rays.as_deref(),
            };
            time_rays(&ctx, &scene, &gpu_scene, &rays, &mut record)?;
            drop(gpu_scene);
            let frames = frames::FrameBench {
                ctx: ctx.clone(),
                scene: &scene,
                scene_settings: &scene_settings,
                size,
                frame: frame_settings.clone(),
                taa: !args.no_taa,
                moving_camera: args.moving_camera,
                path_length: args.camera_path.then(|| scene.animation_length()),
                iterations,
                order,
            };
            // A frame is run once at least before timing: its first one builds what it caches.
            let frame_warmup = Warmup {
                runs: warmup.runs.max(1),
                ..warmup
            };
            for (choice, spec) in techniques.iter().zip(&technique_specs) {
                let spec = spec.on_scene(&scene)?;
                let mut r = frames.time(&spec, frame_warmup)?;
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
    frames: usize,
}

impl RecordLengths {
    fn of(record: &BenchRecord) -> Self {
        Self {
            passes: record.passes.len(),
            frames: record.techniques.len(),
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
    let (forward, reverse) = record.techniques.split_at(reverse_start.frames);
    for f in forward {
        let same = |r: &&FrameRecord| r.scene == f.scene && r.variant == f.variant;
        if let Some(r) = reverse.iter().find(same) {
            let name = format!("{} {} frame", f.scene, f.variant);
            pairs.push((name, f.frame_ms, r.frame_ms));
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
/// How a scene's rays are timed: the image size (rays a dispatch), the timing, which order of
/// the scene list this is, and where to dump the rays for a peer (`--dump-rays`).
struct RayRun<'a> {
    size: (u32, u32),
    timing: Timing,
    order: &'static str,
    dump: Option<&'a std::path::Path>,
}

fn time_rays(
    ctx: &GpuContext,
    scene: &irradiant_scene::Scene,
    gpu_scene: &GpuScene,
    run: &RayRun,
    record: &mut BenchRecord,
) -> Result<(), CliError> {
    let &RayRun {
        size,
        timing,
        order,
        dump,
    } = run;
    let caster = RayCaster::new(ctx, gpu_scene)?;
    let counting = RayCaster::counting(ctx, gpu_scene)?;
    let primary = rays::primary_rays(scene, size);
    let hits = caster.trace(ctx, gpu_scene, &primary, false, RayOrder::Coherent)?;
    let diffuse = rays::diffuse_rays(scene, gpu_scene, &primary, &hits);
    if let Some(dir) = dump {
        let diffuse_hits = caster.trace(ctx, gpu_scene, &diffuse, false, RayOrder::Incoherent)?;
        let sets = [
            ("primary", primary.as_slice(), hits.as_slice()),
            ("diffuse", diffuse.as_slice(), diffuse_hits.as_slice()),
        ];
        rays::dump(dir, scene, &sets)?;
    }
    // Primary rays in pixel order trace a ray a thread; the bounces' lanes fetch (RayOrder).
    for (label, rays, any_hit, ray_order) in [
        (
            "raycast/trace (primary)",
            &primary,
            false,
            RayOrder::Coherent,
        ),
        (
            "raycast/trace (diffuse)",
            &diffuse,
            false,
            RayOrder::Incoherent,
        ),
        (
            "raycast/trace (diffuse, any hit)",
            &diffuse,
            true,
            RayOrder::Incoherent,
        ),
    ] {
        let batch = caster.upload(ctx, gpu_scene, rays, any_hit, ray_order)?;
        let times = time_pass(ctx, timing, |encoder, profiler| {
            caster.record(encoder, &batch, profiler);
            Ok(())
        })?;
        let mut pass = pass_record(&scene.name, order, label, &times, Some(rays.len() as u64));
        let work = RayWork::of(&counting.trace(ctx, gpu_scene, rays, any_hit, ray_order)?);
        pass.work = Some(RayWorkRecord {
            node_visits_per_ray: work.node_visits,
            triangle_tests_per_ray: work.triangle_tests,
            g_node_visits_per_s: work.node_visits * rays.len() as f64
                / (pass.median_ms * 1e-3)
                / 1e9,
        });
        record.passes.push(pass);
    }
    let path_tracer = pathtrace::time_path_tracer(ctx, (scene, gpu_scene), run)?;
    record.passes.extend(path_tracer);
    Ok(())
}

/// Runs `record_pass` warm-up + timed times, one submission each, and returns the timed
/// durations in milliseconds (GPU timestamps, or wall clock around a wait without them).
fn time_pass(
    ctx: &GpuContext,
    timing: Timing,
    record_pass: impl FnMut(&mut wgpu::CommandEncoder, Option<&mut Profiler>) -> Result<(), CliError>,
) -> Result<Vec<f64>, CliError> {
    Ok(time_passes(ctx, timing, record_pass)?.spans)
}

/// A recording's timed runs: each run's span, and for each label its passes' summed time in
/// each run (in the order the labels first came; none without timestamps).
struct Timed {
    spans: Vec<f64>,
    by_label: Vec<(String, Vec<f64>)>,
}

/// [`time_pass`], with each run's time summed over the passes of each label.
fn time_passes(
    ctx: &GpuContext,
    timing: Timing,
    mut record_pass: impl FnMut(
        &mut wgpu::CommandEncoder,
        Option<&mut Profiler>,
    ) -> Result<(), CliError>,
) -> Result<Timed, CliError> {
    // Room for every pass of a recording: the wavefront's sixteen samples take 16 × 17 where
    // its bounce and shadow rays are traced apart.
    let mut profiler = Profiler::new(ctx, 2048);
    let mut timed = Timed {
        spans: Vec::new(),
        by_label: Vec::new(),
    };
    let warm_start = Instant::now();
    let mut warm_runs = 0;
    while timed.spans.len() < timing.iterations as usize {
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
            continue;
        }
        // From the first pass's beginning to the last one's end: the gaps count.
        let span = gpu
            .iter()
            .map(|t| t.start_milliseconds + t.milliseconds)
            .reduce(f64::max);
        let run = timed.spans.len();
        timed.spans.push(span.unwrap_or(wall));
        for pass in &gpu {
            let at = match timed.by_label.iter().position(|(l, _)| *l == pass.label) {
                Some(at) => at,
                None => {
                    timed.by_label.push((pass.label.clone(), Vec::new()));
                    timed.by_label.len() - 1
                }
            };
            let times = &mut timed.by_label[at].1;
            times.resize(run + 1, 0.0);
            times[run] += pass.milliseconds;
        }
    }
    Ok(timed)
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
        work: None,
    }
}
