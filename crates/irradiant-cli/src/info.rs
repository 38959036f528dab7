use clap::Args;
use irradiant::{AdapterChoice, GpuContext};

use crate::CliError;

#[derive(Args)]
pub struct InfoArgs {
    /// Describe this scene (a built-in name, a manifest or a mesh file) instead of the
    /// adapters: its size, lights, probe volumes and how watertight its meshes are.
    #[arg(long)]
    pub scene: Option<String>,
}

pub fn run(args: &InfoArgs, choice: &AdapterChoice) -> Result<(), CliError> {
    match &args.scene {
        Some(scene) => describe_scene(scene),
        None => describe_adapters(choice),
    }
}

/// What a scene holds, with its watertightness: screen-space visibility (SSIL's solid
/// voxelization) counts the space behind an open surface as solid.
fn describe_scene(spec: &str) -> Result<(), CliError> {
    let loaded = irradiant_scene::load(spec)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let scene = &loaded.scene;
    let triangles: usize = scene
        .instances
        .iter()
        .map(|i| scene.meshes[i.mesh as usize].triangle_count())
        .sum();
    let edges = scene.meshes.iter().map(|m| m.edges()).fold(
        irradiant_scene::EdgeCount::default(),
        |a, b| irradiant_scene::EdgeCount {
            total: a.total + b.total,
            open: a.open + b.open,
        },
    );
    let emissive = scene
        .materials
        .iter()
        .filter(|m| m.emission.max_element() > 0.0)
        .count();
    println!("Scene {}", scene.name);
    println!("  triangles (instanced)   {triangles}");
    println!(
        "  meshes / instances      {} / {}",
        scene.meshes.len(),
        scene.instances.len()
    );
    println!(
        "  materials (emissive)    {} ({emissive})",
        scene.materials.len()
    );
    println!("  textures                {}", scene.textures.len());
    println!("  punctual lights         {}", scene.lights.len());
    println!("  probe volumes           {}", scene.probe_volumes.len());
    println!("  animations              {}", scene.animations.len());
    println!(
        "  open edges              {} of {} ({:.1}%){}",
        edges.open,
        edges.total,
        100.0 * edges.open as f64 / edges.total.max(1) as f64,
        if edges.open == 0 {
            ": watertight"
        } else {
            ": not watertight; SSIL's visibility counts the space behind open surfaces as solid"
        }
    );
    Ok(())
}

fn describe_adapters(choice: &AdapterChoice) -> Result<(), CliError> {
    let (_, adapters) = GpuContext::adapters();
    println!("Adapters:");
    if adapters.is_empty() {
        println!("  (none)");
    }
    for (i, a) in adapters.iter().enumerate() {
        let info = a.get_info();
        println!(
            "  {i}: {} ({:?}, {:?}, driver {} {})",
            info.name, info.backend, info.device_type, info.driver, info.driver_info
        );
    }
    let ctx = GpuContext::new(choice)?;
    let i = &ctx.info;
    println!("\nIrradiant uses: {}", i.name);
    println!("  backend                 {}", i.backend);
    println!("  device type             {}", i.device_type);
    println!("  driver                  {} {}", i.driver, i.driver_info);
    println!(
        "  timestamp queries       {}",
        if i.timestamps {
            "yes (bench times each pass)"
        } else {
            "no (bench falls back to wall-clock time)"
        }
    );
    println!(
        "  storage buffer binding  {} MiB",
        i.max_storage_buffer_binding_size >> 20
    );
    println!("  buffer size             {} MiB", i.max_buffer_size >> 20);
    println!(
        "  storage buffers/stage   {}",
        i.max_storage_buffers_per_shader_stage
    );
    println!(
        "  workgroup size x        {}",
        i.max_compute_workgroup_size_x
    );
    println!(
        "  workgroups/dimension    {}",
        i.max_compute_workgroups_per_dimension
    );
    println!(
        "  device memory           {}",
        i.memory.map_or("not reported".into(), irradiant_gpu::bytes)
    );
    println!("  hardware ray tracing    not used (Irradiant traces rays in compute shaders)");
    Ok(())
}
