use irradiant::{AdapterChoice, GpuContext};

use crate::CliError;

pub fn run(choice: &AdapterChoice) -> Result<(), CliError> {
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
