//! DDGI's settings, in three groups by what changing them costs: `volume` (sizes and layouts:
//! a rebuild, and the probes start over), `update` (applied between frames) and `speed`
//! (switches that change only how fast the same image is made: for measuring; a rebuild).
//! Every setting states its trade-off; `fast`, `balanced` and `quality` are the presets.

use documented::DocumentedFields;
use serde::{Deserialize, Serialize};

pub use super::reflections::DdgiReflectionSettings;
use crate::scene::GpuScene;
use crate::settings::TechniqueSpec;
use crate::settings::{Presets, SettingsError, check_range, overlay};

/// Which of the query's weights are on: the paper's Figure 7 ladder, each step adding one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
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

/// DDGI's settings, in groups by what changing them costs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct DdgiSettings {
    /// Sizes and layouts: changing any rebuilds the volumes, which start over.
    pub volume: DdgiVolumeSettings,
    /// The probe update and the query: changes apply from the next frame.
    pub update: DdgiUpdateSettings,
    /// Switches that change only the speed of the same image: off exists to measure what each
    /// buys. Changing any rebuilds the volumes.
    pub speed: DdgiSpeedSettings,
    /// A traced final gather at the pixels, the probes lighting the rays' hits: changing any
    /// rebuilds the volumes.
    pub gather: DdgiGatherSettings,
    /// GI in glossy reflections (003 §4.4): a rebuild.
    #[serde(default = "DdgiReflectionSettings::off")]
    pub reflections: DdgiReflectionSettings,
}

/// Probe volume sizes and layouts (`[technique.volume]`): a change rebuilds the volumes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct DdgiVolumeSettings {
    /// Rays per probe per frame. More rays: less noise and lower usable hysteresis, at a
    /// linear cost in trace and shade time (the paper's m; 256 by default).
    pub rays_per_probe: u32,
    /// Interior texels per side of a probe's irradiance tile (a 1-texel border is added: 6 →
    /// 8×8). Irradiance is smooth; more texels cost blend time and memory for little gain.
    pub irradiance_texels: u32,
    /// Interior texels per side of a distance tile (14 → 16×16). Sharper visibility, at the
    /// cost of blend time; too few blur occluder edges into light leaks.
    pub distance_texels: u32,
    /// Encoding exponent of the irradiance the query samples, value^(1/γ) (003 §4.2 uses 5).
    /// Whatever γ, the query blends its eight probes in a gamma-2 space (Listing 2), so γ
    /// decides what the bilinear filter averages. 1, the default, stores linear light:
    /// filtering encoded values darkens (Jensen), and measured against the path tracer γ = 1
    /// is closer on every scene (two-rooms' dark room −3.5 % against −7.4 % at 5;
    /// docs/ddgi.md). The blend's running value is linear f32 whatever this is. A change starts
    /// the probes over.
    pub irradiance_gamma: f32,
    /// Probe rays shade every punctual light (one shadow ray each) instead of one light chosen
    /// at random (weighted by the light count). One light keeps the shading cost at one shadow
    /// ray per probe ray however many lights there are; the extra noise grows with the light
    /// count and the hysteresis averages it away.
    pub shade_all_lights: bool,
    /// Probes per axis in every volume, overriding the scene's; [0, 0, 0] keeps each volume's
    /// own. More probes: finer light and visibility, at a linear cost in the update.
    pub probe_counts: [u32; 3],
    /// `"camera"` (or an instance's name): every volume follows the camera (or that instance)
    /// in whole cells, keeping its size (a tracking window, 003 §7.3), so its cost stays fixed
    /// however large the world, and what lies outside it gets no probe light; `""` keeps each
    /// volume's own (the manifest's `follow`).
    /// The probes that enter as it steps start over: fast motion shows their convergence.
    #[serde(default)]
    pub follow: String,
    /// Cascades in place of the scene's volumes: this many nested volumes following the camera,
    /// each twice the spacing of the last, so that a world of any size gets fine light near
    /// the camera and coarse light far off at a fixed cost. 0 keeps the scene's volumes. The
    /// finest updates every frame and exactly one coarser one besides (cascade i every 2^i
    /// frames, the coarsest every 2^(n−2) of n), so the rays a frame are two cascades' worth
    /// however many there are; a coarse cascade's light lags by its interval.
    #[serde(default)]
    pub cascades: u32,
    /// Spacing of the finest cascade's probes, in scene units (metres): finer catches smaller
    /// rooms and contact light, and covers less around the camera before the next cascade
    /// takes over.
    #[serde(default = "default_cascade_spacing")]
    pub cascade_spacing: f32,
    /// Probes along each axis of every cascade. More: each cascade reaches further at the same
    /// spacing, at a linear cost in its update.
    #[serde(default = "default_cascade_probes")]
    pub cascade_probes: [u32; 3],
}

fn default_light_between_volumes() -> bool {
    true
}

fn default_cascade_spacing() -> f32 {
    1.0
}

fn default_cascade_probes() -> [u32; 3] {
    [16, 8, 16]
}

/// Most convergence rounds (`update.convergence_rounds`) a frame: past 8 the running mean of
/// a round's 1/9 share changes little, and each round is a dispatch of every updating probe.
pub const MAX_CONVERGENCE_ROUNDS: u32 = 8;

/// The probe update and the query (`[technique.update]`): most apply from the next frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct DdgiUpdateSettings {
    /// Share of last frame's irradiance kept each frame. Higher: stable, slow to react (about
    /// 1/(1−h) frames of lag); lower: fast but flickering.
    pub hysteresis: f32,
    /// The same for the distance moments; kept high, since visibility noise reads as flicker.
    pub distance_hysteresis: f32,
    /// Hysteresis of the copy of irradiance that probe rays read at their hits (the next
    /// bounce). Each bounce waits on the last, so with one hysteresis h for both, light that
    /// bounces with albedo a closes its gap at only (1 − h)(1 − a) a frame: in a white room
    /// (a ≈ 0.8) at h = 0.97, 170 frames a time constant — DDGI was still 9 % dark after 300
    /// frames (docs/ddgi.md). Lower: multi-bounce light converges in tens of frames, at a little
    /// more noise in the probes; equal to `hysteresis`: the paper's single atlas.
    pub bounce_hysteresis: f32,
    /// How far past the outermost probes, in grid cells (0 to 0.5), the query extrapolates the
    /// last two probe layers' trend instead of holding the outermost probes' value. Surfaces
    /// beyond the last layer (walls half a cell out) get more light than the outermost probes
    /// hold, and the bounce loop multiplies that deficit by about albedo / (1 − albedo): the
    /// empty box was 6.5 % dark with 0 (the paper's clamp). Higher follows the light to the
    /// walls; it overshoots a little where the light flattens out (kept within 2× and ½ of the
    /// clamped value, and only where visibility leaves the extrapolation well-conditioned).
    pub extrapolation: f32,
    /// Weight in the query (0.01 to 1) of a tied probe: one that relocation found inside geometry
    /// with no single way out (a column around its grid point), which leaves towards the
    /// volume's middle. Any exit lights some of the probe's eight cells and misleads the others;
    /// lower lets the probes with a clear view light every cell that has one, and the tied
    /// probe the cells that have none (between columns), at the price of a band a tenth of a
    /// cell wide where the two meet (at 0.01 the gaps read the probes beyond the columns). 1: a
    /// probe like any other (003). On box-cylinders, whose sixteen probes stand on the columns'
    /// axes, 0.1 takes the query from 12 % dark to 4.5 % and DDGI's FLIP from 0.175 to 0.140
    /// (docs/ddgi.md); no other scene of ours has a tied probe.
    pub tied_probe_weight: f32,
    /// Longest probe ray, in scene units; 0: 1.5 × the volume's diagonal. Shorter rays are
    /// cheaper but miss distant light.
    pub max_ray_distance: f32,
    /// TunableShadowBias of 003 (eq. 2), in probe cells along each axis: moves the visibility
    /// test off the surface. Too low: self-shadowing blotches; too high: light leaks at thin
    /// walls.
    pub self_shadow_bias: f32,
    /// Cosine power of the distance blend (RTXGI uses 50). Higher: sharper visibility, noisier.
    pub distance_exponent: f32,
    /// The Figure 7 ladder.
    pub weights: ProbeWeights,
    /// 003 §4.3's convergence heuristics: per-texel hysteresis drops where the light changed
    /// by more than 25 % / 80 %, and scene-level drops for some frames after a light or an
    /// object changes. Faster response to changes, slightly more flicker.
    pub convergence_heuristics: bool,
    /// The convergence pass (003 §6.3): in the frame a probe wakes (newly awake) or is
    /// classified near geometry (newly vigilant: a volume's start, a plane a tracking window
    /// brings in), it traces this many more rounds of its rays before the normal update, as a
    /// running mean, each round reading the light the last one gathered. Higher: such probes
    /// reach their light in their first frame instead of over the next ones, and a plane that
    /// enters gathers the bounces among its own probes; costs that many more traces of those
    /// probes in that frame, and nothing in frames without one. 0: the running mean alone.
    pub convergence_rounds: u32,
    /// Probe relocation (003 §5): during the volume's first frames, probes inside geometry
    /// move out through the nearest backface, and probes hugging a surface step away from it
    /// (never more than 45 % of the spacing, nor past the grid's outer layers). Without it,
    /// probes swallowed by geometry darken everything around them. A change restarts the
    /// probes.
    pub relocation: bool,
    /// Let probes still inside geometry after relocation (more than 25 % backfaces; 003 §6's
    /// off state) shade, as classic irradiance probes' do. Each then darkens every surface
    /// near its solid (000's dark halos): for comparisons with that baseline only; off in
    /// every preset. A change restarts the probes.
    pub shade_probes_in_geometry: bool,
    /// Light each probe ray's hit by one more ray traced on from it (its hit lit directly and by
    /// the probes there) instead of by the probes read at the hit. Surfaces by an opening
    /// narrower than the probe spacing then pass on what they see through it, which no probe
    /// sees: light that enters through slits reaches the probes behind them. Costs a traced
    /// ray and a shadow ray more a probe ray (the update about twice as long) and a little
    /// noise in the probes. Compiled into ddgi/shade: a change rebuilds the volumes.
    pub traced_bounce: bool,
    /// Where the probes are blind to a hit whose light they would give (under
    /// `blind_threshold` of its cage's weight passes their visibility test: the faces inside a
    /// slit, a surface in a wall's thickness), trace one more cosine-distributed ray on from it
    /// instead, at most this many times along a probe ray. Such a hit reads probes that stand
    /// in other light; the traced ray sees its own. Costs a traced ray and a shadow ray at
    /// each blind hit, and a little noise there. The final gather's rays do not take them.
    /// Compiled into DDGI's passes: a change rebuilds the volumes.
    pub blind_bounces: u32,
    /// The share of a hit's cage weight (trilinear) whose probes must see it (Chebyshev) for
    /// the hit to read them rather than trace on (`blind_bounces`): 1 in open space, the
    /// near side's share at a wall between two layers, near 0 in a slit's reveals. Higher
    /// traces on at more hits: closer to the truth where the probes stand in other light,
    /// and slower. Compiled in, as `blind_bounces`.
    pub blind_threshold: f32,
    /// With several volumes (cascades, or the scene's probe volumes), light passes between
    /// them (003 §7.4): a probe ray's hit reads the probes of every volume that covers it,
    /// each with the share a pixel there would get, finest first, so that a ray that leaves
    /// its volume reads the one it lands in and a lamp's bounce in one volume reaches the
    /// probes of the next. Off: each probe ray reads its own volume, whose probes hold none of
    /// the light past its edge (two-rooms with a finer volume over its dark room: that room's
    /// indirect light 13.5 % low, docs/ddgi.md). Costs one pass a volume over each updating
    /// volume's rays (ddgi/between_volumes); nothing with one volume. With several volumes the
    /// 36 bytes a probe ray it needs are allocated, on or off.
    #[serde(default = "default_light_between_volumes")]
    pub light_between_volumes: bool,
    /// Seed of the per-frame random rotation of the ray set.
    pub seed: u32,
}

/// Switches that change only how fast the same image is made (`[technique.speed]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct DdgiSpeedSettings {
    /// With one light per probe ray: pick the light once for 32 neighbouring rays (a GPU warp)
    /// rather than for each ray. The warp's shadow rays then all go to one light instead of
    /// taking turns for each light, at the price of noise shared by those 32 rays in a frame
    /// (still unbiased; the hysteresis averages it).
    pub light_per_warp: bool,
    /// Trace each probe ray and shade its hit in one pass (ddgi/trace_shade) instead of two
    /// (ddgi/trace, ddgi/shade): no hit buffer written and read back and one dispatch fewer,
    /// against the tracing running at the shading's (lower) occupancy. Same results.
    pub fuse_trace_and_shade: bool,
    /// Shadow rays of the probe rays' hits go to a queue that a second pass (ddgi/shadow)
    /// traces densely, instead of being traced in ddgi/shade, where only the lanes whose hit
    /// faces the chosen light trace and the rest of each warp waits for them (the wavefront
    /// idea of Laine, Karras and Aila 2013). Costs a 32-byte queue entry per probe ray of
    /// memory and an extra pass; the same image. Applies with one light per ray
    /// (`shade_all_lights` off); emitter samples still trace in ddgi/shade.
    pub shadow_queue: bool,
    /// Probe states (003 §6): after the first frames, probes stuck in walls switch off and
    /// probes with no static geometry within a grid cell sleep; neither traces, blends nor
    /// shades. Sleeping probes near animated instances wake. Saves the work of every probe no
    /// surface reads, for the same image: off, the probes are classified alike and the query
    /// reads the same ones, but every probe traces and blends (for measuring what states save).
    pub probe_states: bool,
    /// Trace the ray set in an order where neighbouring rays point in neighbouring directions
    /// (probes::rays::probe_ray_set), so that a GPU warp's rays walk the same BVH nodes. The
    /// set and the result are the same either way.
    pub coherent_rays: bool,
    /// Probes that share one 64-thread workgroup of ddgi/trace and ddgi/shade (1, 2, 4, … 64):
    /// 1 gives each warp a cone of 32 rays from one probe; more give it near-parallel rays from
    /// neighbouring probes. Only speed differs: on an H200 (Sibenik, 32×8×32, 256 rays) 1 is
    /// 5 % faster with probe states on, 4 is 5 % faster with every probe tracing, and 4 is
    /// 30 % faster at 32 rays a probe (BENCHMARKS.md).
    pub probes_per_group: u32,
    /// ddgi/trace and ddgi/shadow hand a workgroup a run of rays whose lanes fetch the next
    /// ray as theirs ends, so that a warp keeps walking while its longest ray does, instead of
    /// a ray a thread. Applies where the scene is one wide tree for good (no room for a host's
    /// instances) and the largest volume's probe rays, every probe updating, would fill more
    /// than `fetch_workgroups` workgroups; decided when the passes compile, so frames that list
    /// fewer probes (the convergence rounds, most probes asleep) or queue few shadow rays walk
    /// runs of 64 in the same loop, which is slower than a ray a thread (8 % on Sponza's trace).
    /// Costs a workgroup atomic a ray. The same hits. Sibenik at 32×8×32 probes × 256 rays
    /// (H200): trace 1.6 % and shadow 6 % faster.
    pub fetch_rays: bool,
    /// With `fetch_rays`: the workgroups a dispatch of rays holds at most before each takes
    /// more than 64 rays. Fewer give longer runs, whose lanes idle less, but can leave part of
    /// a large GPU empty; 8 192 suits an H200 (132 multiprocessors), a GPU with fewer may gain
    /// from less.
    pub fetch_workgroups: u32,
}

/// The traced final gather at the pixels (`[technique.gather]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct DdgiGatherSettings {
    /// Cosine-distributed rays each pixel traces a frame, each shaded at its hit like a probe
    /// ray (direct light with a shadow ray, one emitter sample, the probes' irradiance), in
    /// place of the query at the pixel. 0: the paper's query. The probes then light only the
    /// second bounce on, so their interpolation between layers (the Cornell box's edges and the
    /// faces by its boxes) no longer shows: on the Cornell box at its 4×4×4 probes FLIP 0.063
    /// → 0.031 at one ray and 32 frames of history (H100, docs/ddgi.md). Each ray costs a
    /// traced ray, a shadow ray and a query a pixel a volume (+3.2 ms on Sibenik at 1080p); one
    /// ray is noisy and leans on `history_frames`.
    pub rays_per_pixel: u32,
    /// Frames a pixel waits between gathers (1 to 16): each frame one 8×8 tile in this many
    /// traces, in turn, and the rest keep their running mean. The gather's cost falls by this
    /// factor, and the mean holds as many times fewer rays over `history_frames`. A
    /// disoccluded pixel reads the probes' query until its tile's turn.
    pub pixel_interval: u32,
    /// Frames the gathered light is averaged over where the same surface stays in view (a
    /// running mean, reprojected along the motion vectors, of the gathers in up to this many
    /// frames): more, less noise, and as many frames of lag after the light changes (the
    /// probes' own convergence included: after 300 frames 128 reads a few per cent darker than
    /// 32 on most scenes); disoccluded pixels start over. After a scene change it shortens as
    /// the probes' hysteresis does (`convergence_heuristics`).
    pub history_frames: u32,
    /// The most a gather ray may bring back, as a multiple of the probes' light at the pixel
    /// (luminance; 0: no bound). A ray whose hit takes its emitter sample from a small bright
    /// emitter close by returns hundreds of times the mean, and one such ray in a mean of a few
    /// dozen is a firefly that stays for `history_frames` (many small emitters: `quality` read
    /// worse than `balanced`, docs/ddgi.md). Lower removes more of them, and with them the
    /// energy of rare bright paths: at 8 the relative MSE fell on six scenes and FLIP rose on
    /// four, at 16 FLIP rose on three of seven, at 64 (`quality`) on none but two-rooms'
    /// +0.0001 (docs/notes/light-quality.md); compiled in. Only the gather has it: `fast` and
    /// `balanced` do not gather.
    pub firefly_clamp: f32,
    /// Passes of an edge-aware filter across the image over the gathered light
    /// (ddgi/gather_filter: 3×3 taps, 1, 2, 4, … pixels apart; 0: none). A mean of a few
    /// dozen one-ray gathers is noisy in every pixel; each pass averages the neighbours on the
    /// pixel's plane whose light lies within a few of its standard errors, so that the noise
    /// goes and edges and contact shadows stay. More reach farther, against a pass over the
    /// image each and the blur of detail finer than the noise.
    pub filter_passes: u32,
    /// The gather, its mean and its filter on a half-size image: the rays from the top-left
    /// pixel of each 2×2 block, brought to every pixel by ddgi/gather_upsample (joint
    /// bilateral, times the query's detail within the block). A quarter of the rays, and a
    /// third of the filter's time (Sibenik at 1080p, H200), against light finer than two pixels
    /// and thin objects no block's pixel lies on, which keep the query.
    #[serde(default)]
    pub half_resolution: bool,
}

/// Frames of probe relocation at the start (003 §5 uses five: enough for almost every probe,
/// and no more, so that probes never oscillate through tangent backfaces).
pub const RELOCATION_FRAMES: u32 = 5;

/// Most cascades `technique.volume.cascades` takes: the eighth has 128 times the finest
/// spacing, and updates every 64 frames.
pub const MAX_CASCADES: u32 = 8;

impl Default for DdgiSettings {
    fn default() -> Self {
        Self::balanced()
    }
}

crate::settings::presets_from_inherent!(DdgiSettings);
crate::settings::setting_docs!(DdgiSettings {
    "volume" => DdgiVolumeSettings,
    "update" => DdgiUpdateSettings,
    "speed" => DdgiSpeedSettings,
    "gather" => DdgiGatherSettings,
    "reflections" => DdgiReflectionSettings,
});
crate::settings::setting_docs!(DdgiVolumeSettings);
crate::settings::setting_docs!(DdgiUpdateSettings);
crate::settings::setting_docs!(DdgiSpeedSettings);
crate::settings::setting_docs!(DdgiGatherSettings);
crate::settings::setting_docs!(DdgiReflectionSettings);

impl DdgiSettings {
    /// Balanced with 64 rays a probe, hysteresis 0.95 and no reflections.
    pub fn fast() -> Self {
        let mut s = Self::balanced();
        s.volume.rays_per_probe = 64;
        s.update.hysteresis = 0.95;
        s.update.convergence_rounds = 1;
        s.reflections = DdgiReflectionSettings::off();
        s
    }

    /// 256 rays a probe, hysteresis 0.97, relocation and probe states on, no final gather,
    /// reflections traced at half resolution.
    pub fn balanced() -> Self {
        Self {
            volume: DdgiVolumeSettings {
                rays_per_probe: 256,
                irradiance_texels: 6,
                distance_texels: 14,
                irradiance_gamma: 1.0,
                shade_all_lights: false,
                probe_counts: [0; 3],
                follow: String::new(),
                cascades: 0,
                cascade_spacing: default_cascade_spacing(),
                cascade_probes: default_cascade_probes(),
            },
            update: DdgiUpdateSettings {
                hysteresis: 0.97,
                distance_hysteresis: 0.97,
                bounce_hysteresis: 0.8,
                extrapolation: 0.5,
                tied_probe_weight: 0.1,
                max_ray_distance: 0.0,
                self_shadow_bias: 0.3,
                distance_exponent: 50.0,
                weights: ProbeWeights::Full,
                convergence_heuristics: true,
                convergence_rounds: 3,
                relocation: true,
                shade_probes_in_geometry: false,
                traced_bounce: false,
                blind_bounces: 0,
                blind_threshold: 0.5,
                light_between_volumes: true,
                seed: 0,
            },
            speed: DdgiSpeedSettings {
                light_per_warp: true,
                fuse_trace_and_shade: false,
                shadow_queue: true,
                probe_states: true,
                coherent_rays: true,
                probes_per_group: 1,
                fetch_rays: true,
                fetch_workgroups: crate::shaders::FETCH_WORKGROUPS,
            },
            gather: DdgiGatherSettings {
                rays_per_pixel: 0,
                pixel_interval: 1,
                history_frames: 32,
                firefly_clamp: 0.0,
                filter_passes: 0,
                half_resolution: false,
            },
            reflections: DdgiReflectionSettings::half(),
        }
    }

    /// Balanced with the traced and blind bounces, every light shaded, hysteresis 0.98, a
    /// one-ray final gather and reflections traced at every glossy pixel.
    pub fn quality() -> Self {
        let mut s = Self::balanced();
        // The traced bounce, rather than 512 rays a probe: about the same time, every probe
        // median but the empty box's lower and the FLIP on six of eight scenes (docs/ddgi.md,
        // "A traced bounce at the probe rays' hits").
        s.update.traced_bounce = true;
        // Tracing on past hits the probes are blind to: the faces inside a slit then light
        // the corridor behind it (`slit-corridor`'s probe median 5.58 → 3.60 %), for 10 % more
        // GI on Sibenik (H100; docs/ddgi.md, "Tracing on where the probes are blind").
        s.update.blind_bounces = 1;
        s.volume.shade_all_lights = true;
        s.update.hysteresis = 0.98;
        s.update.distance_hysteresis = 0.98;
        s.gather.rays_per_pixel = 1;
        s.gather.pixel_interval = 2;
        s.gather.history_frames = 64;
        s.gather.filter_passes = 3;
        // Only the rays that bring back over 64× the probes' light: the stained-glass Sibenik's
        // relative MSE 0.00473 → 0.00295 (under `balanced`'s 0.00442), FLIP unchanged there and
        // on five other scenes, two-rooms +0.0001 (H100; docs/notes/light-quality.md).
        s.gather.firefly_clamp = 64.0;
        s.reflections = DdgiReflectionSettings::full();
        s
    }

    /// The settings a spec describes: its preset with its keys over it, validated. Unknown
    /// keys go to `warnings`.
    pub fn from_spec(
        spec: &TechniqueSpec,
        warnings: &mut Vec<String>,
    ) -> Result<Self, SettingsError> {
        let settings = overlay(
            &Self::preset(spec.preset),
            &spec.settings,
            "technique",
            warnings,
        )?;
        settings.validate()?;
        Ok(settings)
    }

    /// Whether ddgi/trace's and ddgi/shadow's lanes fetch their workgroup's next ray
    /// (`speed.fetch_rays`) in `scene`, whose largest volume casts `probe_rays` a frame when every
    /// probe updates: the scene is one wide tree for good, and those rays would fill more than
    /// `speed.fetch_workgroups` workgroups (`crate::shaders::fetch_pays`).
    pub fn fetches_rays(&self, scene: &GpuScene, probe_rays: u64) -> bool {
        self.speed.fetch_rays
            && scene.fetches_rays()
            && crate::shaders::fetch_pays(probe_rays, self.speed.fetch_workgroups)
    }

    /// Whether ddgi/shade queues shadow rays for ddgi/shadow: `shadow_queue`, with one light
    /// per probe ray.
    pub fn queues_shadow_rays(&self) -> bool {
        self.speed.shadow_queue && !self.volume.shade_all_lights
    }

    /// Whether every setting that sizes or compiles the volumes is the same (so that the rest
    /// can change live).
    pub fn same_build(&self, other: &Self) -> bool {
        self.volume == other.volume
            && self.speed == other.speed
            && self.gather == other.gather
            && self.reflections == other.reflections
            && self.update.traced_bounce == other.update.traced_bounce
            && self.update.blind_bounces == other.update.blind_bounces
            && self.update.blind_threshold == other.update.blind_threshold
    }

    /// Refuses settings that cannot work, naming the field, the value and what is allowed.
    pub fn validate(&self) -> Result<(), SettingsError> {
        self.reflections.validate()?;
        let (v, u, s) = (&self.volume, &self.update, &self.speed);
        check_range("technique.volume.rays_per_probe", v.rays_per_probe, 1, 4096)?;
        check_range(
            "technique.volume.irradiance_texels",
            v.irradiance_texels,
            2,
            16,
        )?;
        check_range("technique.volume.distance_texels", v.distance_texels, 2, 30)?;
        check_range(
            "technique.volume.irradiance_gamma",
            v.irradiance_gamma,
            1.0,
            16.0,
        )?;
        let counts = v.probe_counts;
        let limit = irradiant_scene::MAX_PROBES_PER_AXIS;
        if counts != [0; 3] && counts.iter().any(|&c| !(1..=limit).contains(&c)) {
            return Err(SettingsError::invalid(
                "technique.volume.probe_counts",
                format!("{counts:?}"),
                format!("1 to {limit} probes on each axis, or [0, 0, 0] for each volume's own"),
            ));
        }
        check_range("technique.volume.cascades", v.cascades, 0, MAX_CASCADES)?;
        check_range(
            "technique.update.convergence_rounds",
            u.convergence_rounds,
            0,
            MAX_CONVERGENCE_ROUNDS,
        )?;
        if v.cascades > 0 {
            check_range(
                "technique.volume.cascade_spacing",
                v.cascade_spacing,
                1e-3,
                1e4,
            )?;
            let probes = v.cascade_probes;
            if probes.iter().any(|&c| !(2..=limit).contains(&c)) {
                return Err(SettingsError::invalid(
                    "technique.volume.cascade_probes",
                    format!("{probes:?}"),
                    format!("2 to {limit} probes on each axis"),
                ));
            }
        }
        check_range("technique.update.hysteresis", u.hysteresis, 0.0, 0.999)?;
        check_range(
            "technique.update.distance_hysteresis",
            u.distance_hysteresis,
            0.0,
            0.999,
        )?;
        check_range(
            "technique.update.bounce_hysteresis",
            u.bounce_hysteresis,
            0.0,
            0.999,
        )?;
        check_range("technique.update.extrapolation", u.extrapolation, 0.0, 0.5)?;
        // At 0 the cells between columns, with only tied probes, would have no light at all.
        check_range(
            "technique.update.tied_probe_weight",
            u.tied_probe_weight,
            0.01,
            1.0,
        )?;
        check_range(
            "technique.update.max_ray_distance",
            u.max_ray_distance,
            0.0,
            1e9,
        )?;
        check_range(
            "technique.update.self_shadow_bias",
            u.self_shadow_bias,
            0.0,
            10.0,
        )?;
        check_range(
            "technique.update.distance_exponent",
            u.distance_exponent,
            1.0,
            1000.0,
        )?;
        // Each blind bounce a ray may take is a traced ray more; two read no better than one
        // on `slit-corridor` (docs/ddgi.md), and four bound the shaders' loop.
        check_range("technique.update.blind_bounces", u.blind_bounces, 0, 4)?;
        check_range(
            "technique.update.blind_threshold",
            u.blind_threshold,
            0.0,
            1.0,
        )?;
        // One workgroup a dispatch at least; past a million no GPU is filled any better.
        check_range(
            "technique.speed.fetch_workgroups",
            self.speed.fetch_workgroups,
            1,
            1 << 20,
        )?;
        let g = &self.gather;
        check_range("technique.gather.rays_per_pixel", g.rays_per_pixel, 0, 64)?;
        check_range("technique.gather.pixel_interval", g.pixel_interval, 1, 16)?;
        check_range("technique.gather.history_frames", g.history_frames, 1, 1024)?;
        check_range("technique.gather.firefly_clamp", g.firefly_clamp, 0.0, 1e6)?;
        check_range("technique.gather.filter_passes", g.filter_passes, 0, 5)?;
        if !(s.probes_per_group.is_power_of_two() && s.probes_per_group <= 64) {
            return Err(SettingsError::invalid(
                "technique.speed.probes_per_group",
                s.probes_per_group,
                "a power of two from 1 to 64",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::Preset;

    #[test]
    fn every_preset_round_trips_through_a_spec() {
        for preset in Preset::ALL {
            let settings = DdgiSettings::preset(preset);
            let spec = TechniqueSpec::with_settings("ddgi", &settings);
            let text = toml::to_string(&spec).unwrap();
            let back: TechniqueSpec = toml::from_str(&text).unwrap();
            let mut warnings = Vec::new();
            assert_eq!(
                DdgiSettings::from_spec(&back, &mut warnings).unwrap(),
                settings
            );
            assert!(warnings.is_empty(), "{warnings:?}");
        }
    }

    #[test]
    fn settings_errors_name_the_field_the_value_and_the_range() {
        let error = |text: &str, warnings: &mut Vec<String>| {
            let spec: TechniqueSpec = toml::from_str(text).unwrap();
            DdgiSettings::from_spec(&spec, warnings)
                .unwrap_err()
                .to_string()
        };
        // Each refused setting's error names the key, the value and the range allowed.
        let refused: [(&str, &[&str]); 8] = [
            (
                "[volume]\nrays_per_probe = 0",
                &["technique.volume.rays_per_probe = 0", "1 to 4096"],
            ),
            ("[update]\nweights = \"magic\"", &["magic", "technique"]),
            (
                "[update]\nextrapolation = 2.0",
                &["technique.update.extrapolation = 2", "0.5"],
            ),
            (
                "[update]\nblind_bounces = 9",
                &["technique.update.blind_bounces = 9", "0 to 4"],
            ),
            (
                "[update]\nblind_threshold = nan",
                &["technique.update.blind_threshold"],
            ),
            (
                "[gather]\nrays_per_pixel = 100",
                &["technique.gather.rays_per_pixel = 100", "0 to 64"],
            ),
            (
                "[gather]\nfilter_passes = 9",
                &["technique.gather.filter_passes = 9", "0 to 5"],
            ),
            // 0 would leave the cells of tied probes alone with no light at all.
            (
                "[update]\ntied_probe_weight = 0.0",
                &["technique.update.tied_probe_weight = 0", "0.01 to 1"],
            ),
        ];
        for (table, fragments) in refused {
            let e = error(&format!("name = \"ddgi\"\n{table}\n"), &mut Vec::new());
            assert!(fragments.iter().all(|f| e.contains(f)), "{table}: {e}");
        }
        let mut warnings = Vec::new();
        let e = error(
            "name = \"ddgi\"\n[update]\nhysteresis = 1.5\nwobble = 2\n",
            &mut warnings,
        );
        assert!(e.contains("hysteresis = 1.5"), "{e}");
        assert!(
            warnings[0].contains("technique.update.wobble"),
            "{warnings:?}"
        );
    }
}
