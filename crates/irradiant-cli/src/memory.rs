//! What this process holds in memory, for `soak`'s checks and `bench`'s scene figures (Linux's
//! /proc; `None` elsewhere).

use irradiant_gpu::GpuContext;

const MIB: f64 = 1024.0 * 1024.0;

/// Resident host memory now, MiB.
pub fn resident_host_mib() -> Option<f64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: f64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096.0 / MIB)
}

/// The most resident host memory the process has held so far, MiB.
pub fn peak_host_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// GPU memory wgpu's allocator holds (where the backend reports it), MiB.
pub fn gpu_mib(ctx: &GpuContext) -> Option<f64> {
    ctx.device
        .generate_allocator_report()
        .map(|r| r.total_allocated_bytes as f64 / MIB)
}
