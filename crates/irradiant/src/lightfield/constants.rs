//! Constants light-field probes' Rust and WGSL share, defined once (the shader library serves
//! them as the module `lightfield_constants`).

irradiant_gpu::wgsl_constants! {
    /// High-resolution texels a side of one texel of the min-mip (the paper's second level at
    /// 1/16² resolution): the coarse march skips 256 texels at a time where the ray stays
    /// clear of every surface they hold.
    MIN_MIP_FACTOR: u32 = 16;
    /// A single-probe trace's result: the probe guarantees no surface on the ray.
    LF_MISS: u32 = 0;
    /// A surface, at the returned distance.
    LF_HIT: u32 = 1;
    /// The ray passed behind a surface this probe sees: it cannot tell; another probe must.
    LF_UNKNOWN: u32 = 2;
    /// A stored distance where a probe's ray met nothing (f16's largest).
    LF_NO_SURFACE: f32 = 65504.0;
    /// Runtime buffers' channels (`GpuLightfieldParams::algorithm`): the naive Monte Carlo
    /// renderer.
    ALGORITHM_NAIVE: u32 = 0;
    /// `GpuLightfieldParams::algorithm`: one Lambertian and one glossy ray a pixel, filtered.
    ALGORITHM_FILTERED: u32 = 1;
    /// `GpuLightfieldParams::algorithm`: prefiltered irradiance and one filtered glossy ray.
    ALGORITHM_PREFILTERED: u32 = 2;
}
