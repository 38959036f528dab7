//! `irradiant agreement`: rays from the surfaces the camera sees, traced through a light field
//! alone and through the BVH, and the share on which they agree (the light-field paper's §4,
//! proved on a scene; docs/lightfield.md).

use std::path::PathBuf;
use std::sync::Arc;

use clap::Args;
use irradiant::{AdapterChoice, GpuContext, Session, SessionSettings};
use serde::Serialize;

use crate::CliError;
use crate::options::{RunSettings, SettingsArgs, parse_size};

#[derive(Args)]
pub struct AgreementArgs {
    /// A built-in scene, a manifest (.toml) or a mesh.
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    /// Light-field techniques, comma-separated, each measured in turn (settings of their own in
    /// braces, e.g. `lightfield-traced{probe_counts = [4, 2, 4]}`).
    #[arg(long, default_value = "lightfield-traced")]
    pub techniques: Vec<String>,
    /// Rays to trace both ways: more narrow the share's noise (a million puts it under 0.1 %).
    #[arg(long, default_value = "100000", value_parser = crate::options::parse_samples)]
    pub rays: u32,
    /// The image the rays start from, WIDTHxHEIGHT: its visible surfaces are the rays' origins.
    #[arg(long, default_value = "320x240", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Also write the figures as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    #[command(flatten)]
    pub settings: SettingsArgs,
}

#[derive(Serialize)]
struct Record {
    scene: String,
    technique: String,
    adapter: String,
    commit: &'static str,
    rays: u32,
    share: f64,
    hits: u32,
    misses: u32,
    wrong_distance: u32,
    false_hits: u32,
    false_misses: u32,
    tolerance: f32,
    mean_visits: f64,
}

pub fn run(args: &AgreementArgs, adapter: &AdapterChoice) -> Result<(), CliError> {
    if let Some(path) = &args.json {
        crate::options::check_output(path, &["json"])?;
    }
    let loaded = irradiant_scene::load(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let scene = loaded.scene;
    let run = RunSettings::new(&args.settings, &scene, 0)?;
    let techniques = crate::options::technique_list(&args.techniques)?;
    for choice in &techniques {
        if !choice.name.starts_with("lightfield") {
            return Err(CliError::Usage(format!(
                "agreement measures light fields: '{}' is not one; use lightfield, lightfield-traced or lightfield-naive",
                choice.label
            )));
        }
    }
    let specs = run.checked_specs(&techniques, &args.settings, &scene)?;
    let ctx = Arc::new(GpuContext::new(adapter)?);
    let mut records = Vec::new();
    for (choice, spec) in techniques.iter().zip(specs) {
        let mut session = Session::new(
            ctx.clone(),
            scene.clone(),
            SessionSettings {
                size: args.size,
                frame: run.frame.clone(),
                technique: spec,
                cache_dir: Some(irradiant::pathtrace::reference_cache::cache_dir(None)),
                progress: Some(crate::cache::bake_progress()),
                ..Default::default()
            },
        )?;
        // One frame lays down the G-buffer whose surfaces the rays leave.
        session.render()?;
        let a = irradiant::lightfield::agreement::measure(&session, args.rays, 1)?;
        println!(
            "{} {}: {:.2} % of {} rays agree (hits {}, misses {}; wrong distance {}, false hits {}, false misses {}; tolerance {:.4}, {:.2} probes a ray) on {}",
            scene.name,
            choice.label,
            100.0 * a.share(),
            a.rays,
            a.hits,
            a.misses,
            a.wrong_distance,
            a.false_hits,
            a.false_misses,
            a.tolerance,
            a.mean_visits,
            ctx.info.name
        );
        records.push(Record {
            scene: scene.name.clone(),
            technique: choice.label.clone(),
            adapter: ctx.info.name.clone(),
            commit: env!("IRRADIANT_COMMIT"),
            rays: a.rays,
            share: a.share(),
            hits: a.hits,
            misses: a.misses,
            wrong_distance: a.wrong_distance,
            false_hits: a.false_hits,
            false_misses: a.false_misses,
            tolerance: a.tolerance,
            mean_visits: a.mean_visits,
        });
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&records).expect("agreement records serialise");
        crate::write_file(path, text)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
