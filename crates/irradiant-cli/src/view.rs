//! `irradiant view`: the interactive viewer (crates/irradiant-view) from the command line.

use std::path::PathBuf;

use clap::Args;
use irradiant::AdapterChoice;

use crate::CliError;
use crate::options::parse_size;

#[derive(Args)]
pub struct ViewArgs {
    /// A built-in scene, a manifest (.toml) or a mesh (.obj, .gltf, .glb).
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    /// The technique shown first: a spec as `render --technique` takes (`ddgi{preset =
    /// "quality"}`), or `path`. The panel and the number keys switch it.
    #[arg(long, default_value = "ddgi")]
    pub technique: String,
    /// The window's size, WIDTHxHEIGHT (the frame renders at the window's size).
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Run the steps of this TOML script instead of a person (docs/view.md): technique
    /// switches, camera moves, key presses, frames, screenshots, quit.
    #[arg(long)]
    pub script: Option<PathBuf>,
    /// Draw into a texture instead of a window: no display needed (tests, measurements). Prints
    /// the median frame time at the end.
    #[arg(long)]
    pub offscreen: bool,
    /// Leave the panel out (to measure what it costs).
    #[arg(long)]
    pub no_panel: bool,
    /// Where screenshots (F12), bookmarks (B) and saved settings go.
    #[arg(long, default_value = ".")]
    pub out_dir: PathBuf,
    /// Samples a pixel of the truth (T): the path-traced reference of the view, cached as
    /// `compare --reference-spp` caches it (the same default, so they share entries). Fewer:
    /// sooner, and noise in the FLIP map.
    #[arg(long, default_value = "2048", value_parser = crate::options::parse_samples)]
    pub truth_spp: u32,
    /// Where the truth's references and the light field's bakes are cached (default: the
    /// user's cache folder, as `compare --cache`).
    #[arg(long)]
    pub cache: Option<PathBuf>,
}

pub fn run(args: &ViewArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    if !args.out_dir.is_dir() {
        return Err(CliError::Io {
            path: args.out_dir.clone(),
            message: "the output folder does not exist; create it first".into(),
        });
    }
    let options = irradiant_view::ViewOptions {
        scene: args.scene.clone(),
        size: args.size,
        technique: args.technique.clone(),
        adapter: adapter.clone(),
        script: args.script.clone(),
        offscreen: args.offscreen,
        panel: !args.no_panel,
        out_dir: args.out_dir.clone(),
        cache_dir: Some(irradiant::pathtrace::reference_cache::cache_dir(
            args.cache.as_deref(),
        )),
        truth_spp: args.truth_spp,
        build: crate::reference::BUILD.into(),
        progress: Some(crate::cache::bake_progress()),
    };
    let report = irradiant_view::run(&options).map_err(|e| CliError::Usage(e.to_string()))?;
    if args.offscreen {
        println!(
            "view: {} frames, median {:.3} ms a frame (the GPU waited for), {:.3} ms (mean) of it building the panel{}",
            report.frames,
            report.frame_ms,
            report.ui_cpu_ms,
            if args.no_panel { " (no panel)" } else { "" }
        );
        if let Some(ms) = report.present_gpu_ms {
            println!(
                "view: the viewer's own pass (blit{}) {ms:.3} ms of GPU time a frame (median)",
                if args.no_panel { "" } else { " and panel" }
            );
        }
        if report.restarts > 0 {
            println!("view: {} restarts after a lost device", report.restarts);
        }
    }
    Ok(())
}
