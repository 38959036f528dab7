//! `irradiant`: render, benchmark and inspect Irradiant from the command line.

mod agreement;
mod atlas;
mod bench;
mod cache;
mod compare;
mod info;
mod memory;
mod options;
mod oracle;
mod over_time;
mod reference;
mod render;
mod soak;
mod view;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "irradiant", version, about = "Real-time global illumination on any GPU", long_about = None)]
struct Cli {
    /// GPU adapter: an index or part of a name from `irradiant info` (default: the first
    /// hardware GPU, else the software one). Also IRRADIANT_ADAPTER.
    #[arg(long, global = true)]
    adapter: Option<String>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List adapters and show the one Irradiant would use, with its driver and limits; with
    /// --scene, what a scene holds instead.
    Info(info::InfoArgs),
    /// Render a scene to a PNG (tonemapped) or EXR (linear) image.
    Render(render::RenderArgs),
    /// Time every GPU pass with timestamp queries and report rays per second.
    Bench(bench::BenchArgs),
    /// Render one view with each technique and the path tracer; report the differences.
    Compare(compare::CompareArgs),
    /// Run many frames of each technique and check them for NaN, memory growth and drift.
    Soak(soak::SoakArgs),
    /// Measure DDGI's probes and its query against the path tracer, apart (docs/ddgi.md).
    Oracle(oracle::OracleArgs),
    /// Trace rays through a light field and through the BVH; report the share that agree.
    Agreement(agreement::AgreementArgs),
    /// Fly through a scene with every technique live (docs/view.md).
    View(view::ViewArgs),
}

fn main() -> ExitCode {
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_env("IRRADIANT_LOG")
                // winit's warnings about the X server's settings (Xvfb's especially) say
                // nothing a user can act on.
                .unwrap_or_else(|_| "warn,winit=error".into()),
        )
        .with_writer(std::io::stderr)
        .without_time()
        .init();
    let cli = Cli::parse();
    let adapter = cli
        .adapter
        .as_deref()
        .map(irradiant::AdapterChoice::parse)
        .unwrap_or_else(irradiant::AdapterChoice::from_env);
    let result = match cli.command {
        Command::Info(args) => info::run(&args, &adapter),
        Command::Render(args) => render::run(&args, &adapter),
        Command::Bench(args) => bench::run(&args, &adapter),
        Command::Compare(args) => compare::run(&args, &adapter),
        Command::Soak(args) => soak::run(&args, &adapter),
        Command::Oracle(args) => oracle::run(&args, &adapter),
        Command::Agreement(args) => agreement::run(&args, &adapter),
        Command::View(args) => view::run(&args, &adapter),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Everything a command can fail with; each message names the problem and the fix.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error(transparent)]
    Scene(#[from] irradiant_scene::SceneError),
    #[error(transparent)]
    Render(#[from] irradiant::RenderError),
    #[error(transparent)]
    Gpu(#[from] irradiant::GpuError),
    #[error(transparent)]
    Settings(#[from] irradiant::SettingsError),
    #[error("{0}")]
    Usage(String),
    #[error("{path}: {message}")]
    Io {
        path: std::path::PathBuf,
        message: String,
    },
}

/// Writes a whole file under a temporary name and renames it into place: a report, a JSON
/// record or a soak log is never seen half-written.
pub fn write_file(path: &std::path::Path, contents: impl AsRef<[u8]>) -> Result<(), CliError> {
    irradiant::frame::write_atomically(path, |temporary| {
        std::fs::write(temporary, contents.as_ref()).map_err(|e| e.to_string())
    })
    .map_err(|e| CliError::Io {
        path: path.to_owned(),
        message: e.to_string(),
    })
}
