//! Constants DDGI's Rust and WGSL share, defined once (the shader library serves them as the
//! module `ddgi_constants`).

irradiant_gpu::wgsl_constants! {
    /// `GpuDdgiVolume::weights` bit: the smooth backface (wrap) weight.
    WEIGHT_BACKFACE: u32 = 1;
    /// `GpuDdgiVolume::weights` bit: Chebyshev visibility from the distance moments.
    WEIGHT_CHEBYSHEV: u32 = 2;
    /// `GpuDdgiVolume::weights` bit: the production rule (003 §4.1): rays that hit backfaces
    /// record no light and a shortened depth.
    WEIGHT_BACKFACE_HITS: u32 = 4;
    /// How much of a backface hit's distance is kept (003 §4.1: 80 % shorter).
    BACKFACE_DEPTH_SCALE: f32 = 0.2;
    /// The perceptual exponent (003 §4.2) under which the convergence heuristics judge how
    /// much a texel's light changed (25 % and 80 % of value^(1/5)), whatever encoding the
    /// atlas stores (`irradiance_gamma`).
    CHANGE_GAMMA: f32 = 5.0;

    /// Probe state (the low bits of a probe's state word, 003 §6, Figure 7): near static
    /// geometry; traces and updates every frame. Every probe starts so.
    PROBE_VIGILANT: u32 = 0;
    /// Stuck inside static geometry even after relocation: never traces, never shades.
    PROBE_OFF: u32 = 1;
    /// No static geometry within one grid cell, so no surface reads it: never traces.
    PROBE_SLEEPING: u32 = 2;
    /// Sleeping, but an animated instance's box reaches it: traces and updates until it leaves.
    PROBE_AWAKE: u32 = 3;
    /// Classified vigilant this frame (a volume's or an entered plane's classification): its
    /// frame converges it (`update.convergence_rounds`), then it is vigilant.
    PROBE_NEWLY_VIGILANT: u32 = 4;
    /// Woken from sleep this frame: starts from scratch, converges in its frame, then awake.
    PROBE_NEWLY_AWAKE: u32 = 5;
    /// The state's bits in the state word.
    PROBE_STATE_MASK: u32 = 7;
    /// State word bit: a classification frame saw static geometry near the probe.
    PROBE_NEAR_GEOMETRY: u32 = 8;
    /// State word bits 4 to 8: the frames left in which a probe that entered a tracking
    /// window is relocated and classified on its own (as a volume's probes are in its first
    /// frames); 0 for every other probe.
    PROBE_FRESH_SHIFT: u32 = 4;
    /// The fresh count's bits, shifted down.
    PROBE_FRESH_MASK: u32 = 31;
    /// The state word's bits from here up count the frames blended since the probe last
    /// started updating (a convergence round counts as one; a newly probe starts over).
    PROBE_AGE_SHIFT: u32 = 9;

    /// `GpuDdgiVolume::relocating`: only the probes that entered a tracking window (a fresh
    /// count above 0) are relocated; 1 relocates every probe, 0 none.
    RELOCATING_FRESH: u32 = 2;

    /// `GpuDdgiVolume::state_phase`: no classification; the states stay as written (the light
    /// field's prefiltered volume, whose own pass writes them). DDGI's volumes always classify,
    /// with `speed.probe_states` off too (`every_probe_updates`).
    STATES_OFF: u32 = 0;
    /// Probes are being classified (the relocation frames).
    STATES_CLASSIFYING: u32 = 1;
    /// The last classification frame: states are set.
    STATES_CLASSIFY_LAST: u32 = 2;
    /// Classified: sleeping probes wake and sleep with the wake boxes.
    STATES_CLASSIFIED: u32 = 3;
}
