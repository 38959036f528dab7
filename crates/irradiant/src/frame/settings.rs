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
    /// One area-light sample a pixel and a shorter TAA memory (blend 0.2).
    pub fn fast() -> Self {
        Self {
            area_light_samples: 1,
            taa: TaaSettings {
                blend: 0.2,
                ..Self::balanced().taa
            },
            ..Self::balanced()
        }
    }

    /// Four area-light samples a pixel, TAA at blend 0.1.
    pub fn balanced() -> Self {
        Self {
            area_light_samples: 4,
            seed: 0,
            taa: TaaSettings {
                enabled: true,
                blend: 0.1,
                clip_sigma: 1.25,
            },
            tone: ToneSettings::default(),
            pyramid: PyramidSettings::default(),
        }
    }

    /// Eight area-light samples a pixel and a longer TAA memory (blend 0.05).
    pub fn quality() -> Self {
        Self {
            area_light_samples: 8,
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
