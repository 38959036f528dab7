//! How the frame renders what is not the technique's job. Every setting here can change between
//! frames (the frame's history restarts where the image would otherwise mix two settings).

use serde::{Deserialize, Serialize};

use crate::settings::{SettingsError, check_range};

/// The frame's settings (the `[frame]` table): direct light, TAA, tonemapping, the pyramid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameSettings {
    /// Emitter samples per pixel per frame for direct light from emissive surfaces. More:
    /// less noise on the first frames after a change; the running mean removes it over time.
    pub area_light_samples: u32,
    /// Random seed of the frame's sampling (area lights); change it for independent noise.
    pub seed: u32,
    /// How the emitter samples are chosen and reused across frames and pixels (ReSTIR DI).
    pub resampling: ResamplingSettings,
    /// Temporal anti-aliasing.
    pub taa: TaaSettings,
    /// Exposure and tone curve.
    pub tone: ToneSettings,
    /// The G-buffer pyramid's filter (used only where a technique asks for a pyramid).
    pub pyramid: PyramidSettings,
}

/// The G-buffer pyramid's voting filter (Soler et al. 2009, eq. 5), for techniques that ask for
/// a pyramid: each coarser texel takes the normal and depth of the finer texel whose
/// neighbourhood agrees most with it. Wider Gaussians let more neighbours vote (smoother,
/// small objects vanish sooner); narrower ones keep small objects longer (more flicker as they
/// come and go).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PyramidSettings {
    /// Width of the pixel-distance Gaussian, in texels of the finer level.
    pub pixel_sigma: f32,
    /// Width of the Gaussian of 1 − n·n' (0.2: normals within about 35° agree).
    pub normal_sigma: f32,
    /// Width of the Gaussian of the relative depth difference (0.05: within 5 %).
    pub depth_sigma: f32,
}

impl Default for PyramidSettings {
    fn default() -> Self {
        Self {
            pixel_sigma: 1.0,
            normal_sigma: 0.2,
            depth_sigma: 0.05,
        }
    }
}

/// Direct light from emissive surfaces by reservoir resampling (ReSTIR DI, Bitterli et al. 2020):
/// each pixel keeps one emitter sample chosen from many candidates, takes last frame's where
/// its surface was (while the view moves), then its neighbours', and traces one shadow ray for
/// the winner. Converges with hundreds of small emitters where independent samples leave
/// speckle. The neighbours' reuse is unbiased with `unbiased` (a shadow ray from each
/// neighbour); the temporal step counts last frame's candidates as this surface's
/// (docs/frame.md).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ResamplingSettings {
    /// Candidate emitter points a pixel draws each frame (no ray each). 0: resampling off, and
    /// `area_light_samples` independent samples a pixel instead. More: better first frames, at
    /// a few loads a candidate.
    pub candidates: u32,
    /// The most frames' worth of candidates last frame's reservoir may count for, as a multiple
    /// of `candidates` (0: no temporal reuse), while the view moves (a still view's running mean
    /// averages frames already). Higher: smoother in motion, slower to follow a moving light;
    /// 20 is the paper's.
    pub history: u32,
    /// Neighbours a pixel takes reservoirs from after the temporal step (0: none). More: fewer
    /// dark pixels right after a cut, at a few loads each (and a shadow ray, `unbiased`).
    pub neighbours: u32,
    /// How far those neighbours lie, in pixels.
    pub radius: f32,
    /// Candidates a pixel draws where temporal reuse (`history` > 0) finds no history for it:
    /// the first frame after a camera cut or a reset, and surfaces a moving view uncovers. Such
    /// a pixel's reservoir would stand for `candidates` alone against up to `history` times
    /// more around it, and its speckle would show until the view stops. More: a cleaner first
    /// frame (64 with `cut_neighbours` 8: many-lights' FLIP 0.111 → 0.087, four-halls' 0.121 →
    /// 0.092; H100, 320×240), at a few loads a candidate in those pixels only (a frame cut at
    /// every pixel: `frame/direct` 1.58 ms against 0.44 at 1920×1080; a swaying view 3 to 14 %
    /// more), and in a pan from a cut the frames after it read 2 to 3 % worse on average
    /// (docs/frame.md). A still view's later frames draw `candidates`.
    pub cut_candidates: u32,
    /// Neighbours such a pixel takes reservoirs from (at most 16): more, a cleaner first frame,
    /// at three target evaluations each (and a shadow ray, `unbiased`).
    pub cut_neighbours: u32,
    /// A shadow ray from each neighbour to the winner, so that only the neighbours it reaches
    /// share its weight: unbiased. Off: a neighbour facing the winner shares it though it is
    /// shadowed from it, which darkens shadow edges a little and saves a ray a neighbour;
    /// a still view then reuses neighbours in its first frame only, so that its mean converges
    /// to the unbiased light.
    pub unbiased: bool,
    /// A still view's candidates pick along one golden-ratio sequence through its frames, each
    /// pixel's turned by interleaved gradient noise, instead of independently every frame
    /// (docs/frame.md). On: the running mean's noise falls faster and neighbouring pixels' noise
    /// cancels where the eye blurs them (H100, 320×240, direct light after 64 frames:
    /// many-lights' FLIP 0.0334 → 0.0260, four-halls' 0.0354 → 0.0284), for 0.3 to 1.1 % more
    /// time in `frame/direct_reuse`. Frames where pixels share reservoirs (in every preset: a
    /// cut, a moving view, and every frame with `unbiased`) draw independently either way.
    /// Off: every frame independent, for comparing.
    pub pick_sequence: bool,
}

impl Default for ResamplingSettings {
    fn default() -> Self {
        Self::balanced()
    }
}

impl ResamplingSettings {
    fn balanced() -> Self {
        Self {
            // Through the emitter grid 16 converge better than 32 power-picked ones did, in
            // less time (BENCHMARKS.md, "Emitters picked through a grid").
            candidates: 16,
            history: 20,
            neighbours: 4,
            radius: 24.0,
            cut_candidates: 64,
            cut_neighbours: 8,
            unbiased: false,
            pick_sequence: true,
        }
    }
}

/// Temporal anti-aliasing: primary rays jittered inside the pixel, blended over frames.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TaaSettings {
    /// Off: one ray through each pixel centre, as the frame traced before TAA (aliased edges,
    /// and each frame exactly repeatable pixel by pixel).
    pub enabled: bool,
    /// Share of the new frame once the history is warm (1/blend frames of memory). Lower: smoother
    /// edges and less noise on a still view, more blur and lag in motion; 0.1 is the common
    /// choice, 0.05 suits stills.
    pub blend: f32,
    /// Half-width of the neighbourhood box the history is clipped to, in standard deviations.
    /// Lower: less ghosting after motion or a light change, more flicker; 1 to 1.5 is usual.
    pub clip_sigma: f32,
}

/// How linear radiance becomes display values.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ToneSettings {
    /// Multiplier before the curve; raise it for dim scenes.
    pub exposure: f32,
    /// Filmic (ACES fit) rolls highlights off; plain clamps them (for side-by-side checks
    /// with renderers that clamp).
    pub filmic: bool,
}

impl Default for ToneSettings {
    fn default() -> Self {
        Self {
            exposure: 1.0,
            filmic: true,
        }
    }
}

impl Default for FrameSettings {
    fn default() -> Self {
        Self::balanced()
    }
}

crate::settings::presets_from_inherent!(FrameSettings);

impl FrameSettings {
    /// 8 emitter candidates and two neighbours a pixel (one area-light sample without
    /// resampling) and a shorter TAA memory (blend 0.2).
    pub fn fast() -> Self {
        Self {
            area_light_samples: 1,
            resampling: ResamplingSettings {
                // Half of `balanced`'s: along the picks' sequence a still view's mean comes within
                // 2–5 % of 16's FLIP by 64 frames, and its direct light takes 15–25 % less time
                // (docs/frame.md).
                candidates: 8,
                neighbours: 2,
                cut_candidates: 32,
                cut_neighbours: 4,
                ..ResamplingSettings::balanced()
            },
            taa: TaaSettings {
                blend: 0.2,
                ..Self::balanced().taa
            },
            ..Self::balanced()
        }
    }

    /// 16 emitter candidates and four neighbours a pixel (four area-light samples without
    /// resampling), TAA at blend 0.1.
    pub fn balanced() -> Self {
        Self {
            area_light_samples: 4,
            seed: 0,
            resampling: ResamplingSettings::balanced(),
            taa: TaaSettings {
                enabled: true,
                blend: 0.1,
                clip_sigma: 1.25,
            },
            tone: ToneSettings::default(),
            pyramid: PyramidSettings::default(),
        }
    }

    /// 64 emitter candidates and six neighbours a pixel (eight area-light samples without
    /// resampling) and a longer TAA memory (blend 0.05).
    pub fn quality() -> Self {
        Self {
            area_light_samples: 8,
            resampling: ResamplingSettings {
                candidates: 64,
                neighbours: 6,
                // Its candidates already: a cut takes two more neighbours (first frame 0.0925
                // → 0.0877 on many-lights, 0.0984 → 0.0927 on four-halls; docs/frame.md).
                cut_candidates: 64,
                cut_neighbours: 8,
                unbiased: true,
                ..ResamplingSettings::balanced()
            },
            taa: TaaSettings {
                blend: 0.05,
                ..Self::balanced().taa
            },
            ..Self::balanced()
        }
    }

    /// These settings without TAA: pixel-centre rays, as every frame was traced before TAA.
    pub fn without_taa(mut self) -> Self {
        self.taa.enabled = false;
        self
    }

    /// Refuses settings that cannot work, naming the field, the value and what is allowed.
    pub fn validate(&self) -> Result<(), SettingsError> {
        check_range("frame.area_light_samples", self.area_light_samples, 0, 256)?;
        let r = &self.resampling;
        check_range("frame.resampling.candidates", r.candidates, 0, 256)?;
        check_range("frame.resampling.history", r.history, 0, 100)?;
        check_range(
            "frame.resampling.neighbours",
            r.neighbours,
            0,
            super::constants::MAX_REUSE_NEIGHBOURS,
        )?;
        check_range("frame.resampling.radius", r.radius, 1.0, 256.0)?;
        check_range("frame.resampling.cut_candidates", r.cut_candidates, 1, 1024)?;
        check_range(
            "frame.resampling.cut_neighbours",
            r.cut_neighbours,
            0,
            super::constants::MAX_REUSE_NEIGHBOURS,
        )?;
        check_range("frame.taa.blend", self.taa.blend, 0.001, 1.0)?;
        check_range("frame.taa.clip_sigma", self.taa.clip_sigma, 0.1, 16.0)?;
        check_range("frame.tone.exposure", self.tone.exposure, 1e-6, 1e6)?;
        check_range(
            "frame.pyramid.pixel_sigma",
            self.pyramid.pixel_sigma,
            0.01,
            100.0,
        )?;
        check_range(
            "frame.pyramid.normal_sigma",
            self.pyramid.normal_sigma,
            0.001,
            100.0,
        )?;
        check_range(
            "frame.pyramid.depth_sigma",
            self.pyramid.depth_sigma,
            0.0001,
            100.0,
        )?;
        Ok(())
    }
}
