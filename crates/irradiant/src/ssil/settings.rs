//! Screen-space indirect illumination's settings: what each trades, three presets, and checks
//! that name the field, the value and what is allowed.

use documented::DocumentedFields;
use serde::{Deserialize, Serialize};

use crate::settings::TechniqueSpec;
use crate::settings::{SettingsError, check_range, overlay};

/// The resolution the gathers start at: the first level of the G-buffer pyramid they use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StartResolution {
    /// Full resolution: pyramid level 0.
    Full,
    /// Half resolution: level 1.
    Half,
    /// Quarter resolution: level 2.
    Quarter,
}

impl StartResolution {
    /// The pyramid level of the first gather.
    pub fn level(self) -> u32 {
        match self {
            StartResolution::Full => 0,
            StartResolution::Half => 1,
            StartResolution::Quarter => 2,
        }
    }
}

/// Screen-space indirect illumination's settings (the `ssil` technique's keys).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct SsilSettings {
    /// Where the gathers start. Lower resolutions lose the high frequencies of close-range
    /// indirect light but cost a quarter (half) or a sixteenth (quarter) of the full one; the
    /// paper uses half and quarter.
    pub start: StartResolution,
    /// Pyramid levels gathered from the start on (4 or 5 in the paper). Each level doubles the
    /// reach of the rings at about a quarter of the cost of the one before; with r = 40 px, 4
    /// levels reach 320 px at 1280×720 from a half start.
    pub levels: u32,
    /// Radius r of the disc (first level) and outer radius of the rings r/2…r (the others), in
    /// pixels of each level at 1280×720 (scaled with the image height). Smaller: less noise and
    /// cheaper visibility marches, shorter reach per level (more levels needed).
    pub radius: f32,
    /// Samples a level gathers per pixel (64 in the paper). Noise falls as 1/√samples; the
    /// cost is linear.
    pub samples: u32,
    /// Visibility from the voxelized view frustum (128 depth slices): indirect shadows, at
    /// several times the cost of the gathers; off, light leaks through anything between two
    /// visible surfaces.
    pub visibility: bool,
    /// Steps of each visibility march through the level's voxel grid. More: thin occluders
    /// missed less often, at a linear cost.
    pub visibility_steps: u32,
    /// Share of each march skipped at its start and at its end (the surfaces' own voxels,
    /// which would otherwise read as occluders). Too low: everything self-occludes; too high:
    /// occluders near either end are missed.
    pub visibility_bias: f32,
    /// Bounces of indirect light; bounce n gathers the light bounce n − 1 left on the screen.
    /// Each costs the gathers again.
    pub bounces: u32,
    /// Glossy reflection of indirect light for the last bounce: each level's samples are
    /// importance-sampled around the projected mirror direction (the paper's f(θ)) and the
    /// full BRDF gathers them. Off: diffuse only, uniform samples.
    pub glossy: bool,
    /// The importance function's constant (α in f(θ) = α + exp(−s(θr − θ)²/2π); 0.1 in the
    /// paper): how many samples still go to directions far from the lobe.
    pub importance_alpha: f32,
    /// Share of last frame's filtered light kept each frame (eq. 6's a) for a still diffuse
    /// pixel; lowered for moving and glossy pixels, and in the frames after a reset, where the
    /// history is a running mean until it holds this share. Higher: less noise, more lag.
    pub hysteresis: f32,
    /// Motion, in pixels a frame, at which the hysteresis has fallen to a third.
    pub motion_pixels: f32,
    /// Relative depth difference past which last frame's pixel is another surface (eq. 6's
    /// depth test).
    pub depth_tolerance: f32,
    /// Smallest cosine between this and last frame's normal for the history to count.
    pub normal_tolerance: f32,
}

impl Default for SsilSettings {
    fn default() -> Self {
        Self::balanced()
    }
}

crate::settings::presets_from_inherent!(SsilSettings);
crate::settings::setting_docs!(SsilSettings);

impl SsilSettings {
    /// Balanced from a quarter-resolution start, with 32 samples and no visibility.
    pub fn fast() -> Self {
        Self {
            start: StartResolution::Quarter,
            samples: 32,
            visibility: false,
            ..Self::balanced()
        }
    }

    /// Half-resolution start, 4 levels, 64 samples, visibility, one glossy bounce.
    pub fn balanced() -> Self {
        Self {
            start: StartResolution::Half,
            levels: 4,
            radius: 40.0,
            samples: 64,
            visibility: true,
            visibility_steps: 8,
            visibility_bias: 0.15,
            bounces: 1,
            glossy: true,
            importance_alpha: 0.1,
            hysteresis: 0.9,
            motion_pixels: 4.0,
            depth_tolerance: 0.05,
            normal_tolerance: 0.8,
        }
    }

    /// Balanced with 5 levels, 128 samples, 12 visibility steps and two bounces.
    pub fn quality() -> Self {
        Self {
            levels: 5,
            samples: 128,
            visibility_steps: 12,
            bounces: 2,
            ..Self::balanced()
        }
    }

    /// The settings a spec describes: its preset with its keys over it, validated.
    pub fn from_spec(
        spec: &TechniqueSpec,
        warnings: &mut Vec<String>,
    ) -> Result<Self, SettingsError> {
        let s = overlay(
            &<Self as crate::settings::Presets>::preset(spec.preset),
            &spec.settings,
            "technique",
            warnings,
        )?;
        s.validate()?;
        Ok(s)
    }

    /// The pyramid levels the technique reads: the start plus its levels.
    pub fn pyramid_levels(&self) -> u32 {
        self.start.level() + self.levels
    }

    /// The ring radius in pixels of every level for an image `height` pixels tall.
    pub fn radius_at(&self, height: u32) -> f32 {
        self.radius * height as f32 / 720.0
    }

    /// Refuses settings that cannot work, naming the field, the value and what is allowed.
    pub fn validate(&self) -> Result<(), SettingsError> {
        check_range("technique.levels", self.levels, 1, 6)?;
        check_range("technique.radius", self.radius, 2.0, 512.0)?;
        check_range("technique.samples", self.samples, 1, 1024)?;
        check_range("technique.visibility_steps", self.visibility_steps, 1, 64)?;
        check_range("technique.visibility_bias", self.visibility_bias, 0.0, 0.45)?;
        check_range("technique.bounces", self.bounces, 1, 4)?;
        check_range(
            "technique.importance_alpha",
            self.importance_alpha,
            0.001,
            100.0,
        )?;
        check_range("technique.hysteresis", self.hysteresis, 0.0, 0.99)?;
        check_range("technique.motion_pixels", self.motion_pixels, 0.01, 1000.0)?;
        check_range(
            "technique.depth_tolerance",
            self.depth_tolerance,
            0.001,
            10.0,
        )?;
        check_range(
            "technique.normal_tolerance",
            self.normal_tolerance,
            -1.0,
            1.0,
        )?;
        Ok(())
    }

    /// Refuses an image on which the coarsest level would be under one pixel or the rings
    /// wider than the level, naming the settings to change.
    pub fn check_size(&self, (width, height): (u32, u32)) -> Result<(), SettingsError> {
        let coarsest = self.pyramid_levels() - 1;
        let (w, h) = (width >> coarsest, height >> coarsest);
        if w == 0 || h == 0 {
            return Err(SettingsError::invalid(
                "technique.levels",
                self.levels,
                format!(
                    "at most {} levels from a {:?} start at {width}×{height} (the coarsest level would be under one pixel); use fewer levels, a fuller start or a larger image",
                    (32 - width.min(height).leading_zeros()).saturating_sub(self.start.level()),
                    self.start
                ),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::{Preset, Presets};

    #[test]
    fn presets_round_trip_and_sizes_are_checked() {
        for preset in Preset::ALL {
            let s = SsilSettings::preset(preset);
            let spec = TechniqueSpec::with_settings("ssil", &s);
            let back: TechniqueSpec = toml::from_str(&toml::to_string(&spec).unwrap()).unwrap();
            assert_eq!(SsilSettings::from_spec(&back, &mut Vec::new()).unwrap(), s);
        }
        let s = SsilSettings::balanced();
        assert!(s.check_size((1280, 720)).is_ok());
        let e = s.check_size((8, 8)).unwrap_err().to_string();
        assert!(
            e.contains("technique.levels") && e.contains("under one pixel"),
            "{e}"
        );
        let spec: TechniqueSpec = toml::from_str("name = \"ssil\"\nsamples = 0\n").unwrap();
        let e = SsilSettings::from_spec(&spec, &mut Vec::new())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("technique.samples = 0") && e.contains("1 to 1024"),
            "{e}"
        );
        let spec: TechniqueSpec = toml::from_str("name = \"ssil\"\nstart = \"eighth\"\n").unwrap();
        assert!(SsilSettings::from_spec(&spec, &mut Vec::new()).is_err());
    }
}
