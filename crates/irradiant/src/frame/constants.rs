//! Constants the frame's Rust and WGSL share, defined once (the shader library serves them as
//! the module `frame_constants`).

irradiant_gpu::wgsl_constants! {
    /// `GpuFrameParams::tone_curve`: the filmic curve (ACES fit), which rolls highlights off.
    TONE_FILMIC: u32 = 0;
    /// `GpuFrameParams::tone_curve`: a plain clamp, for side-by-side checks with renderers
    /// that clamp.
    TONE_CLAMP: u32 = 1;
    /// The most neighbours `frame.resampling.neighbours` may name: frame/direct_reuse keeps
    /// each one it merges, to weigh every sample by how likely each would have drawn it.
    MAX_REUSE_NEIGHBOURS: u32 = 16;
}
