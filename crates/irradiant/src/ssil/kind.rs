//! The registry entries `ssil` and `ssil+ddgi`: their settings, what they need of the frame,
//! what they allocate and dispatch, and how they are built.

use irradiant_gpu::{Allocation, Workgroups};
use irradiant_scene::Scene;

use super::hybrid::{HybridSettings, SsilDdgi};
use super::{GATHER_LABELS, Ssil, SsilSettings, constants, resources};
use crate::RenderError;
use crate::ddgi::Ddgi;
use crate::frame::{FrameNeeds, IMAGE_TILE};
use crate::settings::TechniqueSpec;
use crate::technique::{Technique, TechniqueContext, TechniqueKind};

/// A registry entry of screen-space indirect illumination, alone or with DDGI's probes.
pub struct SsilKind {
    pub(super) hybrid: bool,
}

impl SsilKind {
    /// The screen-space settings a spec asks for (and, for the hybrid, all of its own).
    pub fn settings(
        &self,
        spec: &TechniqueSpec,
        warnings: &mut Vec<String>,
    ) -> Result<(SsilSettings, Option<HybridSettings>), RenderError> {
        if self.hybrid {
            let preset = <HybridSettings as crate::settings::Presets>::preset(spec.preset);
            let s: HybridSettings =
                crate::settings::overlay(&preset, &spec.settings, "technique", warnings)?;
            s.validate()?;
            Ok((s.ssil.clone(), Some(s)))
        } else {
            Ok((SsilSettings::from_spec(spec, warnings)?, None))
        }
    }
}

impl TechniqueKind for SsilKind {
    fn name(&self) -> &'static str {
        if self.hybrid { "ssil+ddgi" } else { "ssil" }
    }
    fn description(&self) -> &'static str {
        if self.hybrid {
            "screen-space indirect light, with DDGI's probes where the screen has none"
        } else {
            "hierarchical screen-space indirect illumination"
        }
    }
    fn check(&self, spec: &TechniqueSpec) -> Result<Vec<String>, RenderError> {
        let mut warnings = Vec::new();
        self.settings(spec, &mut warnings)?;
        Ok(warnings)
    }
    fn resolved_settings(&self, spec: &TechniqueSpec) -> Result<toml::Table, RenderError> {
        Ok(match self.settings(spec, &mut Vec::new())? {
            (_, Some(hybrid)) => crate::settings::as_table(&hybrid),
            (ssil, None) => crate::settings::as_table(&ssil),
        })
    }
    fn setting_doc(&self, _spec: &TechniqueSpec, path: &[&str]) -> Option<&'static str> {
        use crate::settings::SettingDocs;
        if self.hybrid {
            HybridSettings::setting_doc(path)
        } else {
            SsilSettings::setting_doc(path)
        }
    }
    fn frame_needs(&self, spec: &TechniqueSpec) -> FrameNeeds {
        let levels = match self.settings(spec, &mut Vec::new()) {
            Ok((s, hybrid)) if hybrid.as_ref().is_none_or(HybridSettings::screen_part) => {
                s.pyramid_levels()
            }
            _ => 0,
        };
        FrameNeeds {
            pyramid_levels: levels,
        }
    }
    fn scene_warnings(&self, spec: &TechniqueSpec, scene: &Scene) -> Vec<String> {
        let Ok((settings, _)) = self.settings(spec, &mut Vec::new()) else {
            return Vec::new();
        };
        let open: usize = scene
            .instances
            .iter()
            .map(|i| scene.meshes[i.mesh as usize].open_edges())
            .sum();
        if settings.visibility && open > 0 {
            vec![format!(
                "scene '{}' is not watertight ({open} open edges): screen-space visibility treats the space behind an open surface as solid until the next surface; close the meshes, or set technique.visibility = false",
                scene.name
            )]
        } else {
            Vec::new()
        }
    }
    fn plan(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<Allocation>, RenderError> {
        let (settings, hybrid) = self.settings(spec, &mut Vec::new())?;
        settings.check_size(size)?;
        let mut plan = Vec::new();
        if hybrid.as_ref().is_none_or(HybridSettings::screen_part) {
            let covered = hybrid.as_ref().is_some_and(|h| h.bent_fill);
            plan = resources::plan(&settings, size, self.hybrid, covered);
        }
        if let Some(hybrid) = hybrid {
            plan.extend(crate::ddgi::DDGI.plan(
                &TechniqueSpec::with_settings("ddgi", &hybrid.ddgi),
                scene,
                size,
            )?);
        }
        Ok(plan)
    }
    fn dispatches(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<(&'static str, Workgroups)>, RenderError> {
        let (settings, hybrid) = self.settings(spec, &mut Vec::new())?;
        let mut all = Vec::new();
        if hybrid.as_ref().is_none_or(HybridSettings::screen_part) {
            all = dispatches(&settings, size, self.hybrid);
        }
        if let Some(hybrid) = hybrid {
            all.extend(crate::ddgi::DDGI.dispatches(
                &TechniqueSpec::with_settings("ddgi", &hybrid.ddgi),
                scene,
                size,
            )?);
        }
        Ok(all)
    }
    fn build(
        &self,
        cx: &TechniqueContext,
        spec: &TechniqueSpec,
    ) -> Result<Box<dyn Technique>, RenderError> {
        let (settings, hybrid) = self.settings(spec, &mut Vec::new())?;
        settings.check_size(cx.frame.size())?;
        Ok(match hybrid {
            Some(hybrid) => {
                let ddgi = Ddgi::new(cx, "ddgi", &hybrid.ddgi)?;
                let reach = hybrid.near_field * ddgi.finest_spacing();
                let ssil = if hybrid.screen_part() {
                    let part = super::HybridPart {
                        reach,
                        probes_reflect_up_to: hybrid
                            .ddgi
                            .reflections
                            .enabled
                            .then_some(hybrid.ddgi.reflections.max_roughness),
                        bent_fill: hybrid.bent_fill.then(|| ddgi.finest_table()).flatten(),
                    };
                    Some(Ssil::new(cx, &settings, Some(part))?)
                } else {
                    None
                };
                Box::new(SsilDdgi {
                    ddgi,
                    ssil,
                    near_reach: reach,
                    far_field_while_young: hybrid.far_field_while_young,
                    far_in_history: false,
                })
            }
            None => Box::new(Ssil::new(cx, &settings, None)?),
        })
    }
}

/// Workgroups of a pass with a thread a texel of pyramid level `k`.
pub(super) fn level_groups((width, height): (u32, u32), k: u32) -> Workgroups {
    Workgroups::for_image((width >> k).max(1), (height >> k).max(1), IMAGE_TILE)
}

/// Workgroups of a gather at pyramid level `k` (GATHER_LANES threads a texel).
pub(super) fn gather_groups((width, height): (u32, u32), k: u32) -> Workgroups {
    let tile = (constants::GATHER_TILE, constants::GATHER_TILE);
    Workgroups::for_image((width >> k).max(1), (height >> k).max(1), tile)
}

/// Every dispatch, with its label (the frame's pyramid aside).
pub fn dispatches(
    settings: &SsilSettings,
    (width, height): (u32, u32),
    hybrid: bool,
) -> Vec<(&'static str, Workgroups)> {
    let level = |k: u32| level_groups((width, height), k);
    let gather_groups = |k: u32| gather_groups((width, height), k);
    let s = settings.start.level();
    let mut all = vec![("ssil/voxelize", level(s))];
    for j in 1..settings.levels {
        all.push(("ssil/voxel_down", level(s + j)));
    }
    for bounce in 0..settings.bounces {
        if bounce > 0 || hybrid {
            all.push((
                if bounce > 0 {
                    "ssil/bounce"
                } else {
                    "ssil/probe_light"
                },
                level(s),
            ));
            for j in 1..settings.levels {
                all.push(("ssil/bounce", level(s + j)));
            }
        }
        for j in 0..settings.levels {
            all.push((GATHER_LABELS[j as usize], gather_groups(s + j)));
        }
        for j in (0..settings.levels).rev() {
            all.push(("ssil/upsample", level(s + j)));
        }
    }
    all.extend([("ssil/upsample", level(0)), ("ssil/temporal", level(0))]);
    all
}
