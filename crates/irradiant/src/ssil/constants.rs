//! Constants screen-space indirect illumination's Rust and WGSL share, defined once (the
//! shader library serves them as the module `ssil_constants`).

irradiant_gpu::wgsl_constants! {
    /// Threads that share one texel's gather, each taking every GATHER_LANES-th sample: a
    /// texel's samples run side by side instead of one after another, so the small coarse
    /// levels (a few hundred texels) fill the GPU too.
    GATHER_LANES: u32 = 16;
    /// Texels a gather workgroup covers in x and in y (GATHER_LANES × 4 threads).
    GATHER_TILE: u32 = 2;
    /// Threads that share one voxelization ray, each collecting the crossings of its share of
    /// the depth range: XOR parity is the same whatever the order, so the shares' masks
    /// combine by XOR, and the grid's few thousand rays fill the GPU.
    VOXEL_SEGMENTS: u32 = 4;
    /// Texels a voxelization workgroup covers in x and in y (VOXEL_SEGMENTS × 16 threads).
    VOXEL_TILE: u32 = 4;
    /// Depth slices of the voxel grid: one bit each in a texel's four u32.
    SLICES: u32 = 128;
}
