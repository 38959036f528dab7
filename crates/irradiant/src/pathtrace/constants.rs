//! Constants the path tracer's Rust and WGSL share, defined once (the shader library serves
//! them as the module `pathtrace_constants`).

irradiant_gpu::wgsl_constants! {
    /// `light_sampling` of the path tracer's params: the emitter sample and BRDF-sampled
    /// emitter hits, weighed by the power heuristic (`LightSampling::Both`).
    LIGHT_SAMPLING_BOTH: u32 = 0;
    /// The emitter sample alone (`LightSampling::Emitters`).
    LIGHT_SAMPLING_EMITTERS: u32 = 1;
    /// BRDF-sampled emitter hits alone (`LightSampling::Brdf`).
    LIGHT_SAMPLING_BRDF: u32 = 2;
    /// The most shadow rays a path vertex defers to the wavefront's `pathtrace/shadows` (one a
    /// punctual light and the emitter sample): a vertex with more traces them in place.
    DEFERRED_SHADOWS_MAX: u32 = 4;
}
