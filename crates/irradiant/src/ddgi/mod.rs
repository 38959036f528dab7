//! DDGI: dynamic diffuse global illumination with ray-traced irradiance fields (Majercik et
//! al. 2019, as evaluated in seed 001), with the production rules of seed 003 (self-shadow
//! bias, perceptual encoding, convergence heuristics, backface hits, probe relocation and
//! probe states). See docs/ddgi.md.
//!
//! Each frame [`Ddgi::update`] records `ddgi/ray_directions → ddgi/trace → ddgi/shade →
//! (ddgi/shadow) → (ddgi/relocate) → ddgi/blend_weights → ddgi/blend_irradiance → ddgi/blend_distance →
//! ddgi/probe_states` (the blends fill their tiles' borders), and [`Ddgi::resolve`] turns a
//! G-buffer into indirect diffuse light (`ddgi/resolve`).

pub mod octahedral;
mod passes;
mod resources;

pub use passes::{Ddgi, ProbeStateCounts};

/// Which of the query's weights are on: the paper's Figure 7 ladder, each step adding one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum ProbeWeights {
    /// Trilinear only: classic irradiance probes, which leak light through walls.
    Classic,
    /// + smooth backface (wrap) weight: probes behind the surface count less.
    Backface,
    /// + Chebyshev visibility from the distance moments: occluded probes are culled.
    Chebyshev,
    /// + self-shadow bias and the backface-hit rule: the full method.
    Full,
}

/// DDGI settings. Every one trades something; `fast`, `balanced` and `quality` are the presets.
#[derive(Clone, Debug, PartialEq)]
pub struct DdgiSettings {
    /// Rays per probe per frame. More rays: less noise and lower usable hysteresis, at a
    /// linear cost in trace and shade time (the paper's m; 256 by default).
    pub rays_per_probe: u32,
    /// Interior texels per side of a probe's irradiance tile (a 1-texel border is added: 6 →
    /// 8×8). Irradiance is smooth; more texels cost blend time and memory for little gain.
    pub irradiance_texels: u32,
    /// Interior texels per side of a distance tile (14 → 16×16). Sharper visibility, at the
    /// cost of blend time; too few blur occluder edges into light leaks.
    pub distance_texels: u32,
    /// Share of last frame's irradiance kept each frame. Higher: stable, slow to react (about
    /// 1/(1−h) frames of lag); lower: fast but flickering.
    pub hysteresis: f32,
    /// The same for the distance moments; kept high, since visibility noise reads as flicker.
    pub distance_hysteresis: f32,
    /// Longest probe ray, in scene units. `None`: the volume's diagonal. Shorter rays are
    /// cheaper but miss distant light.
    pub max_ray_distance: Option<f32>,
    /// TunableShadowBias of 003 (eq. 2): moves the visibility test off the surface. Too low:
    /// self-shadowing blotches; too high: light leaks at thin walls.
    pub self_shadow_bias: f32,
    /// Cosine power of the distance blend (RTXGI uses 50). Higher: sharper visibility, noisier.
    pub distance_exponent: f32,
    /// Perceptual encoding exponent (003 §4.2; 5 converges fastest); 1 stores linear values.
    pub irradiance_gamma: f32,
    /// The Figure 7 ladder.
    pub weights: ProbeWeights,
    /// 003 §4.3's convergence heuristics: per-texel hysteresis drops where the light changed
    /// by more than 25 % / 80 %, and scene-level drops for some frames after a light or an
    /// object changes. Faster response to changes, slightly more flicker.
    pub convergence_heuristics: bool,
    /// Probe relocation (003 §5): during the volume's first frames, probes inside geometry
    /// move out through the nearest backface, and probes hugging a surface step away from it
    /// (never more than 45 % of the spacing). Without it, probes swallowed by geometry darken
    /// everything around them.
    pub relocation: bool,
    /// Probe rays shade every punctual light (one shadow ray each) instead of one light chosen
    /// at random (weighted by the light count). One light keeps the shading cost at one shadow
    /// ray per probe ray however many lights there are; the extra noise grows with the light
    /// count and the hysteresis averages it away.
    pub shade_all_lights: bool,
    /// With one light per probe ray: pick the light once for 32 neighbouring rays (a GPU warp)
    /// rather than for each ray. The warp's shadow rays then all go to one light instead of
    /// taking turns for each light, at the price of noise shared by those 32 rays in a frame
    /// (still unbiased; the hysteresis averages it). Off only to measure what it buys.
    pub light_per_warp: bool,
    /// Trace each probe ray and shade its hit in one pass (ddgi/trace_shade) instead of two
    /// (ddgi/trace, ddgi/shade): no hit buffer written and read back and one dispatch fewer,
    /// against the tracing running at the shading's (lower) occupancy. Same results.
    pub fuse_trace_and_shade: bool,
    /// Shadow rays of the probe rays' hits go to a queue that a second pass (ddgi/shadow)
    /// traces densely, instead of being traced in ddgi/shade, where only the lanes whose hit
    /// faces the chosen light trace and the rest of each warp waits for them (the wavefront
    /// idea of Laine, Karras and Aila 2013). Costs a 32-byte queue entry per probe ray of
    /// memory and an extra pass; the same image.
    /// Applies with one light per ray (`shade_all_lights` off); emitter samples still trace
    /// in ddgi/shade.
    pub shadow_queue: bool,
    /// Probe states (003 §6): after the first frames, probes stuck in walls switch off and
    /// probes with no static geometry within a grid cell sleep; neither traces, blends nor
    /// shades. Sleeping probes near animated instances wake. Saves the work of every probe no
    /// surface reads, for the same image; off only to measure that.
    pub probe_states: bool,
    /// Trace the ray set in an order where neighbouring rays point in neighbouring directions
    /// (octahedral::probe_ray_set), so that a GPU warp's rays walk the same BVH nodes. The set
    /// and the result are the same either way; off exists only to measure what it buys.
    pub coherent_rays: bool,
    /// Probes that share one 64-thread workgroup of ddgi/trace and ddgi/shade (1, 2, 4, … 64):
    /// 1 gives each warp a cone of 32 rays from one probe; more give it near-parallel rays from
    /// neighbouring probes. Only speed differs: on an H200 (Sibenik, 32×8×32, 256 rays) 1 is
    /// 5 % faster with probe states on, 4 is 5 % faster with every probe tracing, and 4 is
    /// 30 % faster at 32 rays a probe (BENCHMARKS.md).
    pub probes_per_group: u32,
    /// Seed of the per-frame random rotation of the ray set.
    pub seed: u32,
}

/// Frames of probe relocation at the start (003 §5 uses five: enough for almost every probe,
/// and no more, so that probes never oscillate through tangent backfaces).
pub const RELOCATION_FRAMES: u32 = 5;

impl Default for DdgiSettings {
    fn default() -> Self {
        Self::balanced()
    }
}

impl DdgiSettings {
    pub fn fast() -> Self {
        Self {
            rays_per_probe: 64,
            hysteresis: 0.95,
            ..Self::balanced()
        }
    }
    pub fn balanced() -> Self {
        Self {
            rays_per_probe: 256,
            irradiance_texels: 6,
            distance_texels: 14,
            hysteresis: 0.97,
            distance_hysteresis: 0.97,
            max_ray_distance: None,
            self_shadow_bias: 0.3,
            distance_exponent: 50.0,
            irradiance_gamma: 5.0,
            weights: ProbeWeights::Full,
            convergence_heuristics: true,
            relocation: true,
            shade_all_lights: false,
            light_per_warp: true,
            fuse_trace_and_shade: false,
            shadow_queue: true,
            probe_states: true,
            coherent_rays: true,
            probes_per_group: 1,
            seed: 0,
        }
    }
    pub fn quality() -> Self {
        Self {
            rays_per_probe: 512,
            hysteresis: 0.98,
            distance_hysteresis: 0.98,
            shade_all_lights: true,
            ..Self::balanced()
        }
    }

    /// Whether ddgi/shade queues shadow rays for ddgi/shadow: `shadow_queue`, with one light
    /// per probe ray.
    pub fn queues_shadow_rays(&self) -> bool {
        self.shadow_queue && !self.shade_all_lights
    }

    /// Refuses settings that cannot work, saying which and why.
    pub fn validate(&self) -> Result<(), String> {
        if !(1..=4096).contains(&self.rays_per_probe) {
            return Err(format!(
                "rays per probe {} is out of range: use 1…4096",
                self.rays_per_probe
            ));
        }
        if !(2..=16).contains(&self.irradiance_texels) || !(2..=30).contains(&self.distance_texels)
        {
            return Err(
                "probe texels out of range: irradiance 2…16, distance 2…30 per side".into(),
            );
        }
        for (name, h) in [
            ("hysteresis", self.hysteresis),
            ("distance hysteresis", self.distance_hysteresis),
        ] {
            if !(0.0..1.0).contains(&h) {
                return Err(format!(
                    "{name} {h} must be in [0, 1): 1 would never update"
                ));
            }
        }
        if self
            .max_ray_distance
            .is_some_and(|d| !(d.is_finite() && d > 0.0))
        {
            return Err("max ray distance must be a positive number".into());
        }
        if !(self.probes_per_group.is_power_of_two() && self.probes_per_group <= 64) {
            return Err(format!(
                "probes per group {} must be a power of two from 1 to 64",
                self.probes_per_group
            ));
        }
        if !(self.self_shadow_bias.is_finite() && self.self_shadow_bias >= 0.0) {
            return Err("self-shadow bias must be ≥ 0".into());
        }
        if !(self.distance_exponent.is_finite() && self.distance_exponent >= 1.0) {
            return Err("distance exponent must be ≥ 1".into());
        }
        if !(self.irradiance_gamma.is_finite() && self.irradiance_gamma >= 1.0) {
            return Err("irradiance gamma must be ≥ 1".into());
        }
        Ok(())
    }
}
