//! Light-field probes' settings, in two groups by what changing them costs: `bake` (the probe
//! data: a new bake, or another cache entry) and `shade` (how the frame uses the probes:
//! applied between frames). Every setting states its trade-off; `fast`, `balanced` and
//! `quality` are the presets.

use documented::DocumentedFields;
use serde::{Deserialize, Serialize};

use crate::settings::TechniqueSpec;
use crate::settings::{Presets, SettingsError, check_range, overlay};

/// Light-field probes' settings, in two groups by what changing them costs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct LightfieldSettings {
    /// The probe data. Changing any of these bakes again (or finds another cache entry).
    pub bake: LightfieldBakeSettings,
    /// How the frame shades with the probes; changes apply from the next frame.
    pub shade: LightfieldShadeSettings,
}

/// The probe data (`[technique.bake]`): a change bakes again or finds another cache entry.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct LightfieldBakeSettings {
    /// Probes per axis; [0, 0, 0] takes the scene's first probe volume (or one over its bounds);
    /// other counts place that many probes at the centres of equal cells of that volume's box.
    /// More probes: shorter projected rays (faster traces) and fewer regions no probe sees, at
    /// a linear cost in memory and bake time.
    pub probe_counts: [u32; 3],
    /// Texels a side of each probe's radiance, normal and distance maps (the paper: 1024; a
    /// multiple of 16 for the min-mip). Higher: sharper glossy reflections and finer
    /// visibility; memory and bake time grow with its square (8 bytes a texel).
    pub resolution: u32,
    /// Interior texels a side of each probe's prefiltered irradiance tile (the paper: 128,
    /// "often 32 suffice"). Irradiance is smooth; more cost memory and bake time.
    pub irradiance_texels: u32,
    /// Interior texels a side of each probe's filtered distance tile (Chebyshev visibility).
    /// Sharper indirect shadows, at bake time and memory.
    pub distance_texels: u32,
    /// Texels a side of the reduced maps the prefilters convolve (the full maps averaged down):
    /// the cosine lobes are wide, so 64 loses nothing the tiles can show and keeps the bake
    /// fast. At most `resolution`; on llvmpipe at most 128 (each texel's sum runs in one
    /// invocation, whose loops llvmpipe ends past 65 535 iterations).
    pub prefilter_resolution: u32,
    /// Steps that move probes out of geometry before the bake (each re-traces the maps' geometry:
    /// a geometry pass's cost). 0: probes stay on the grid, and those inside solids are only
    /// switched off — leaving dark regions where a solid swallows a whole cage.
    pub relocation_steps: u32,
    /// Bounces of indirect light in the radiance maps: each re-shades every probe texel with the
    /// previous bounce's irradiance (the paper's iteration). 0: direct light only. Each costs
    /// one radiance pass of the bake; closed bright rooms need many (two-rooms: 3 bounces left
    /// the dark room at 59 % of the path tracer's light, 8 at 91 %).
    pub bounces: u32,
    /// Emitter samples per probe texel for area lights (punctual lights are exact). More: less
    /// noise in the maps of scenes lit by emissive surfaces, at a linear cost in bake time.
    pub emitter_samples: u32,
    /// Cosine power of the distance prefilter (DDGI's distance blend uses 50). Higher: sharper
    /// visibility, noisier at low prefilter resolution.
    pub distance_exponent: f32,
}

/// Which of the paper's three shading algorithms (§5) the technique runs; the registry's three
/// light-field entries set it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShadingAlgorithm {
    /// (a) Monte Carlo through the light field: `naive_rays` diffuse and glossy rays a pixel,
    /// no filters. Converges to the light field's answer; noisy at real-time ray counts.
    Naive,
    /// (b) One Lambertian and one glossy ray a pixel, each denoised by cross-bilateral and
    /// reprojected temporal filters.
    Filtered,
    /// (c) The fast path: prefiltered irradiance with Chebyshev visibility for the Lambertian
    /// term (DDGI's query), one filtered glossy ray.
    #[default]
    Prefiltered,
}

/// How the frame shades with the probes (`[technique.shade]`): applied between frames.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct LightfieldShadeSettings {
    /// Set by the registry entry (`lightfield`, `lightfield-traced`, `lightfield-naive`), not
    /// by settings files: one name, one algorithm.
    #[serde(skip)]
    pub algorithm: ShadingAlgorithm,
    /// Rays a pixel of each lobe for the naive renderer. Noise falls as 1/√rays; the cost is
    /// linear.
    pub naive_rays: u32,
    /// Trace glossy rays at all. Off: the Lambertian term alone (the probe cost stays at the
    /// irradiance query for the fast path).
    pub glossy: bool,
    /// Surfaces rougher than this (perceptual roughness) trace no glossy ray: their wide lobe
    /// reflects about what the irradiance holds, so their specular light is F0 × the
    /// irradiance. 1: every specular surface traces (the paper); lower: faster where most
    /// surfaces are rough (Sponza's plaster), and rough reflections lose their shape.
    pub glossy_max_roughness: f32,
    /// Probes a ray may try before it takes the last point a probe saw as its hit (the paper
    /// tries the cage's 8, then moves to the next cage). More: fewer wrong hits behind complex
    /// occluders, at the cost of the worst rays.
    pub max_probe_visits: u32,
    /// Thickness of a probe texel's surface for a hit, as a share of the smallest probe
    /// spacing, at head-on and grazing views (the paper: 3 cm and 50 cm at room scale).
    /// Thinner: rays slip behind surfaces and fall back to other probes; thicker: rays hit
    /// surfaces they pass near.
    pub min_thickness: f32,
    /// The thickness at grazing views, as `min_thickness` is head-on.
    pub max_thickness: f32,
    /// Cross-bilateral filter of the Lambertian buffer: radius and stride in pixels (the paper:
    /// 12 and 2). Wider: less noise, blurrier indirect shadows.
    pub lambert_radius: u32,
    /// Pixels between the Lambertian filter's taps.
    pub lambert_stride: u32,
    /// Share of last frame's Lambertian light kept (the paper: 98 %). Higher: less noise, more
    /// lag after a change of view.
    pub lambert_hysteresis: f32,
    /// The same for the glossy buffer (the paper: 3 px, stride 1, 75 %): glossy light moves
    /// over surfaces with the view, so it is filtered less.
    pub glossy_radius: u32,
    /// Share of last frame's glossy light kept.
    pub glossy_hysteresis: f32,
    /// DDGI's self-shadow bias for the prefiltered irradiance query (003 eq. 2). The bake's
    /// bounces gather through the same query: a session started with another bias bakes anew,
    /// while a live change reaches the query and keeps the bake.
    pub self_shadow_bias: f32,
    /// Pixels a side of the blocks the fast path queries irradiance once for (1, 2 or 4), the
    /// result joint-bilaterally upsampled by depth and normal (1: the exact query at every
    /// pixel). Irradiance is smooth: 2 costs about a third of 1, 4 about a sixth, with softer
    /// indirect shadows at contact edges.
    pub irradiance_block: u32,
}

impl Default for LightfieldSettings {
    fn default() -> Self {
        Self::balanced()
    }
}

crate::settings::presets_from_inherent!(LightfieldSettings);
crate::settings::setting_docs!(LightfieldSettings {
    "bake" => LightfieldBakeSettings,
    "shade" => LightfieldShadeSettings,
});
crate::settings::setting_docs!(LightfieldBakeSettings);
crate::settings::setting_docs!(LightfieldShadeSettings);

impl LightfieldSettings {
    /// Balanced with 256² maps, 16² irradiance tiles, 4 bounces and fewer samples.
    pub fn fast() -> Self {
        let mut s = Self::balanced();
        s.bake.resolution = 256;
        s.bake.irradiance_texels = 16;
        s.bake.bounces = 4;
        s.bake.emitter_samples = 4;
        s.shade.naive_rays = 4;
        s
    }

    /// 512² maps, 32² irradiance tiles, 8 bounces, irradiance queried in 4×4 blocks.
    pub fn balanced() -> Self {
        Self {
            bake: LightfieldBakeSettings {
                probe_counts: [0, 0, 0],
                resolution: 512,
                irradiance_texels: 32,
                distance_texels: 32,
                prefilter_resolution: 64,
                relocation_steps: 2,
                bounces: 8,
                emitter_samples: 16,
                distance_exponent: 50.0,
            },
            shade: LightfieldShadeSettings {
                algorithm: ShadingAlgorithm::Prefiltered,
                naive_rays: 16,
                glossy: true,
                glossy_max_roughness: 0.6,
                max_probe_visits: 16,
                min_thickness: 0.01,
                max_thickness: 0.15,
                lambert_radius: 12,
                lambert_stride: 2,
                lambert_hysteresis: 0.98,
                glossy_radius: 3,
                glossy_hysteresis: 0.75,
                self_shadow_bias: 0.3,
                irradiance_block: 4,
            },
        }
    }

    /// Balanced with 1024² maps, 64² irradiance tiles, 16 bounces, irradiance at every pixel
    /// and glossy rays on every specular surface.
    pub fn quality() -> Self {
        let mut s = Self::balanced();
        s.bake.resolution = 1024;
        s.bake.irradiance_texels = 64;
        s.bake.bounces = 16;
        s.bake.emitter_samples = 64;
        s.shade.naive_rays = 64;
        s.shade.irradiance_block = 1;
        s.shade.glossy_max_roughness = 1.0;
        s
    }

    /// The settings a spec asks for: its preset, the algorithm of its registry entry, then the
    /// spec's keys over them, validated.
    pub fn from_spec(
        spec: &TechniqueSpec,
        algorithm: ShadingAlgorithm,
        warnings: &mut Vec<String>,
    ) -> Result<Self, SettingsError> {
        let preset = <Self as Presets>::preset(spec.preset);
        let mut s: Self = overlay(&preset, &spec.settings, "technique", warnings)?;
        s.shade.algorithm = algorithm;
        s.validate()?;
        Ok(s)
    }

    /// Refuses settings that cannot work, naming the field, the value and what is allowed.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let (b, s) = (&self.bake, &self.shade);
        for (axis, &count) in ["x", "y", "z"].iter().zip(&b.probe_counts) {
            check_range(&format!("technique.bake.probe_counts.{axis}"), count, 0, 64)?;
        }
        if b.probe_counts.contains(&0) && b.probe_counts != [0, 0, 0] {
            return Err(SettingsError::invalid(
                "technique.bake.probe_counts",
                format!("{:?}", b.probe_counts),
                "three counts of 1 or more, or [0, 0, 0] for the scene's own volume",
            ));
        }
        check_range("technique.bake.resolution", b.resolution, 16, 4096)?;
        if b.resolution % super::constants::MIN_MIP_FACTOR != 0 {
            return Err(SettingsError::invalid(
                "technique.bake.resolution",
                b.resolution,
                format!(
                    "a multiple of {} (the min-mip's block)",
                    super::constants::MIN_MIP_FACTOR
                ),
            ));
        }
        check_range(
            "technique.bake.irradiance_texels",
            b.irradiance_texels,
            4,
            128,
        )?;
        check_range("technique.bake.distance_texels", b.distance_texels, 4, 128)?;
        check_range(
            "technique.bake.prefilter_resolution",
            b.prefilter_resolution,
            8,
            256,
        )?;
        if b.resolution % b.prefilter_resolution.min(b.resolution) != 0 {
            return Err(SettingsError::invalid(
                "technique.bake.prefilter_resolution",
                b.prefilter_resolution,
                "a divisor of technique.bake.resolution",
            ));
        }
        check_range("technique.bake.bounces", b.bounces, 0, 16)?;
        check_range("technique.bake.relocation_steps", b.relocation_steps, 0, 8)?;
        check_range("technique.bake.emitter_samples", b.emitter_samples, 1, 1024)?;
        check_range(
            "technique.bake.distance_exponent",
            b.distance_exponent,
            1.0,
            1000.0,
        )?;
        check_range("technique.shade.naive_rays", s.naive_rays, 1, 1024)?;
        check_range(
            "technique.shade.max_probe_visits",
            s.max_probe_visits,
            1,
            64,
        )?;
        if ![1, 2, 4].contains(&s.irradiance_block) {
            return Err(SettingsError::invalid(
                "technique.shade.irradiance_block",
                s.irradiance_block,
                "1, 2 or 4",
            ));
        }
        check_range("technique.shade.min_thickness", s.min_thickness, 0.0, 1.0)?;
        check_range(
            "technique.shade.max_thickness",
            s.max_thickness,
            s.min_thickness,
            2.0,
        )?;
        check_range("technique.shade.lambert_radius", s.lambert_radius, 0, 32)?;
        check_range("technique.shade.lambert_stride", s.lambert_stride, 1, 8)?;
        check_range(
            "technique.shade.lambert_hysteresis",
            s.lambert_hysteresis,
            0.0,
            0.999,
        )?;
        check_range("technique.shade.glossy_radius", s.glossy_radius, 0, 32)?;
        check_range(
            "technique.shade.glossy_hysteresis",
            s.glossy_hysteresis,
            0.0,
            0.999,
        )?;
        check_range(
            "technique.shade.self_shadow_bias",
            s.self_shadow_bias,
            0.0,
            2.0,
        )?;
        Ok(())
    }

    /// The reduced maps' side: the prefilter resolution, at most the maps'.
    pub fn prefilter_side(&self) -> u32 {
        self.bake.prefilter_resolution.min(self.bake.resolution)
    }
}
