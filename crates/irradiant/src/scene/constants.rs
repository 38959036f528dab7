//! Constants the scene's Rust and WGSL share, defined once (the shader library serves them as
//! the module `scene_constants`).

irradiant_gpu::wgsl_constants! {
    /// `GpuTriangle::flags` bit: the material is alpha-masked and textured, so hits test the
    /// texture.
    TRIANGLE_ALPHA_TESTED: u32 = 1;
    /// `GpuLight::kind` of a point light.
    LIGHT_POINT: u32 = 0;
    /// `GpuLight::kind` of a spot light.
    LIGHT_SPOT: u32 = 1;
    /// `GpuLight::kind` of a directional light.
    LIGHT_DIRECTIONAL: u32 = 2;
    /// Surfaces `trace_crossings` records along one ray (SSIL's voxelization; Sponza's deepest
    /// rays cross about 20). Past this it counts them but keeps no distance.
    MAX_CROSSINGS: u32 = 48;
    /// Box exit distances are widened by this factor so that rounding never culls a tiny box
    /// whose triangle the ray hits (defined with the CPU traversal, in irradiant-bvh).
    SLAB_FAR_SCALE: f32 = irradiant_bvh::SLAB_FAR_SCALE;
}
