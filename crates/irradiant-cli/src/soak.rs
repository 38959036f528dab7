//! `irradiant soak`: many frames of each technique over a scene, checked every K frames — no
//! NaN or infinite value in the image, the indirect light or the technique's state (probe
//! atlases, histories), GPU and host memory flat after the first check, and with `--still` no
//! drift of the converged image. The scene's animation loops. Exits with an error naming what
//! went wrong, at which frame.

use std::path::PathBuf;
use std::sync::Arc;

use clap::Args;
use irradiant::{AdapterChoice, GpuContext, Session, SessionSettings};
use serde::Serialize;

use crate::options::{RunSettings, SettingsArgs, parse_size};
use crate::{CliError, memory};

#[derive(Args)]
pub struct SoakArgs {
    /// A built-in scene, a manifest (.toml) or a mesh; its animation loops.
    #[arg(long, default_value = "scenes/two-rooms/switch.toml")]
    pub scene: String,
    /// Registered techniques, comma-separated (`all`: every one), each soaked in turn;
    /// settings of their own in braces, e.g. `ddgi{update.hysteresis = 0.9}`.
    #[arg(long, default_value = "all")]
    pub techniques: Vec<String>,
    /// Frames a technique.
    #[arg(long, default_value = "10000")]
    pub frames: u32,
    /// Check every this many frames.
    #[arg(long, default_value = "500")]
    pub every: u32,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "320x240", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Simulated frames per second.
    #[arg(long, default_value = "60")]
    pub fps: f32,
    /// Hold the scene at time 0: after --settle frames, the image's mean must stay within
    /// --drift of the first check's (a converged technique must not creep).
    #[arg(long)]
    pub still: bool,
    /// Frames before the reference check that drift and memory are measured against
    /// (convergence: DDGI in a bright closed room still gains a per cent between frames 500
    /// and 2000 as further bounces arrive).
    #[arg(long, default_value = "2000")]
    pub settle: u32,
    /// Largest relative change of the image's mean allowed with --still.
    #[arg(long, default_value = "0.005")]
    pub drift: f64,
    /// Largest growth of GPU memory (wgpu's allocator) after the reference check, in MiB.
    #[arg(long, default_value = "16")]
    pub memory_mib: f64,
    /// Largest growth of the process's resident host memory, in MiB: it moves with the
    /// allocator and the driver's caches, so its bound is loose (on lavapipe it also holds the
    /// "GPU" memory the driver keeps outside wgpu's allocator).
    #[arg(long, default_value = "512")]
    pub host_memory_mib: f64,
    /// Write every check as JSON.
    #[arg(long)]
    pub json: Option<PathBuf>,
    #[command(flatten)]
    pub settings: SettingsArgs,
}

#[derive(Serialize)]
struct Check {
    technique: String,
    frame: u32,
    time: f32,
    mean: [f64; 3],
    /// GPU memory wgpu's allocator holds (where the backend reports it), MiB.
    gpu_mib: Option<f64>,
    /// Resident host memory of this process, MiB.
    host_mib: Option<f64>,
    problems: Vec<String>,
}

pub fn run(args: &SoakArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    if args.frames == 0 || args.every == 0 || args.fps <= 0.0 || !args.fps.is_finite() {
        return Err(CliError::Usage(
            "--frames, --every and --fps must be positive".into(),
        ));
    }
    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let scene = loaded.scene;
    let run = RunSettings::new(&args.settings, &scene, 0)?;
    let techniques = crate::options::technique_list(&args.techniques)?;
    let specs = run.checked_specs(&techniques, &args.settings, &scene)?;
    let ctx = Arc::new(GpuContext::new(adapter)?);
    // The animation loops a second after its last key, so that the end state is seen too.
    let period = scene.animation_end() + 1.0;
    println!(
        "soak: {} on {}, {} frames a technique, checked every {}{}",
        scene.name,
        ctx.info.name,
        args.frames,
        args.every,
        if args.still { ", held still" } else { "" }
    );
    let mut checks = Vec::new();
    let mut failures = Vec::new();
    for (choice, spec) in techniques.iter().zip(specs) {
        let mut session = Session::new(
            ctx.clone(),
            scene.clone(),
            SessionSettings {
                size: args.size,
                frame: run.frame.clone(),
                technique: spec,
                cache_dir: None,
                ..Default::default()
            },
        )?;
        let mut first: Option<Baseline> = None;
        for frame in 1..=args.frames {
            if !args.still {
                session.seek((frame as f32 / args.fps) % period);
            }
            session.render()?;
            if frame % args.every != 0 && frame != args.frames {
                continue;
            }
            let image = session.image()?;
            let mut problems: Vec<String> = [
                irradiant::technique::non_finite("image", image.pixels.iter().flatten().copied()),
                irradiant::technique::non_finite(
                    "indirect light",
                    session.indirect()?.pixels.iter().flatten().copied(),
                ),
            ]
            .into_iter()
            .flatten()
            .collect();
            problems.extend(session.technique().check_state(session.ctx())?);
            let mean = image.mean();
            let (gpu, host) = (memory::gpu_mib(&ctx), memory::resident_host_mib());
            match first {
                None if frame >= args.settle.min(args.frames) => {
                    first = Some(Baseline {
                        mean,
                        gpu,
                        host,
                        frame,
                    })
                }
                None => {}
                Some(Baseline {
                    mean: mean0,
                    gpu: gpu0,
                    host: host0,
                    frame: frame0,
                }) => {
                    for (what, now, then, bound) in [
                        ("GPU", gpu, gpu0, args.memory_mib),
                        ("host", host, host0, args.host_memory_mib),
                    ] {
                        if let (Some(now), Some(then)) = (now, then)
                            && now > then + bound
                        {
                            problems.push(format!(
                                "{what} memory grew from {then:.1} MiB at frame {frame0} to {now:.1} MiB"
                            ));
                        }
                    }
                    if args.still {
                        let luminance = |m: [f64; 3]| m[0] + m[1] + m[2];
                        let change = (luminance(mean) - luminance(mean0)).abs()
                            / luminance(mean0).max(1e-12);
                        if change > args.drift {
                            problems.push(format!(
                                "the image's mean drifted by {:.2} % since frame {}",
                                change * 100.0,
                                frame0
                            ));
                        }
                    }
                }
            }
            let check = Check {
                technique: choice.label.clone(),
                frame,
                time: session.time(),
                mean,
                gpu_mib: gpu,
                host_mib: host,
                problems,
            };
            println!(
                "{:<24} frame {:>6}  mean ({:.4}, {:.4}, {:.4})  GPU {}  host {}  {}",
                check.technique,
                frame,
                mean[0],
                mean[1],
                mean[2],
                gpu.map_or("-".into(), |m| format!("{m:.1} MiB")),
                host.map_or("-".into(), |m| format!("{m:.1} MiB")),
                if check.problems.is_empty() {
                    "ok".to_owned()
                } else {
                    check.problems.join("; ")
                }
            );
            for p in &check.problems {
                failures.push(format!("{} at frame {frame}: {p}", choice.label));
            }
            checks.push(check);
        }
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&checks).expect("soak checks serialise");
        crate::write_file(path, text)?;
    }
    if failures.is_empty() {
        println!("soak: every check passed");
        Ok(())
    } else {
        Err(CliError::Usage(format!(
            "the soak found {} problem(s):\n  {}",
            failures.len(),
            failures.join("\n  ")
        )))
    }
}

/// What a technique's soak is checked against: the image's mean and the memory in use at the
/// first frame after `--settle`.
#[derive(Clone, Copy)]
struct Baseline {
    mean: [f64; 3],
    gpu: Option<f64>,
    host: Option<f64>,
    frame: u32,
}
