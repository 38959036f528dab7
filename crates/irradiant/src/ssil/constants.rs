//! Constants screen-space indirect illumination's Rust and WGSL share, defined once (the
//! shader library serves them as the module `ssil_constants`).

irradiant_gpu::wgsl_constants! {
    /// Threads that share one texel's gather, each taking every GATHER_LANES-th sample: a
    /// texel's samples run side by side instead of one after another, so the small coarse
    /// levels (a few hundred texels) fill the GPU too.
    GATHER_LANES: u32 = 16;
    /// Texels a gather workgroup covers in x and in y (GATHER_LANES × 4 threads).
    GATHER_TILE: u32 = 2;
    /// Depth slices of the voxel grid: one bit each in a texel's four u32.
    SLICES: u32 = 128;
}
