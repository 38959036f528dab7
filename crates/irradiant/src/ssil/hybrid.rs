//! `ssil+ddgi`: DDGI's probes light everything, then the screen-space light replaces them where
//! the screen sees a sender nearer than the probes resolve (`near_field`). Its settings are each
//! technique's own under its name, and that reach.

use std::any::Any;

use documented::DocumentedFields;
use irradiant_gpu::{GpuContext, Profiler, wgpu};
use irradiant_scene::Camera;
use serde::{Deserialize, Serialize};

use super::{Ssil, SsilSettings};
use crate::RenderError;
use crate::ddgi::{Ddgi, DdgiSettings};
use crate::frame::SceneChange;
use crate::technique::{Counter, ProbeView, Technique, TechniquePasses};

/// The settings of `ssil+ddgi`: each technique's own, under its name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, DocumentedFields)]
pub struct HybridSettings {
    /// The screen-space part's settings (`[technique.ssil]`).
    pub ssil: SsilSettings,
    /// The probes' settings (`[technique.ddgi]`).
    pub ddgi: DdgiSettings,
    /// How near a sender must be for the screen's light to replace the probes' in its
    /// direction, as a share of the finest probe spacing (0 to 4; 0: DDGI's light alone).
    /// The screen adds what lies between probes (contact light and occlusion); beyond that the
    /// probes hold the same light with the geometry traced, and replacing a share of their
    /// irradiance by coverage assumes it arrives evenly from every direction, which a bright
    /// wall beside a dark ceiling does not (docs/ssil.md). Higher: more of the screen's detail
    /// and more of that error.
    pub near_field: f32,
}

crate::settings::presets_from_inherent!(HybridSettings);
/// The near field of every preset: half the probe spacing (docs/ssil.md measures 0.5 against
/// wider reaches).
const NEAR_FIELD: f32 = 0.5;

crate::settings::setting_docs!(HybridSettings {
    "ssil" => SsilSettings,
    "ddgi" => DdgiSettings,
});

impl HybridSettings {
    /// Each technique's fast preset.
    pub fn fast() -> Self {
        Self {
            ssil: SsilSettings::fast(),
            ddgi: DdgiSettings::fast(),
            near_field: NEAR_FIELD,
        }
    }
    /// Each technique's balanced preset.
    pub fn balanced() -> Self {
        Self {
            ssil: SsilSettings::balanced(),
            ddgi: DdgiSettings::balanced(),
            near_field: NEAR_FIELD,
        }
    }
    /// Each technique's quality preset: the screen replaces only the near field, so DDGI's
    /// final gather and traced bounce still light the rest.
    pub fn quality() -> Self {
        Self {
            ssil: SsilSettings::quality(),
            ddgi: DdgiSettings::quality(),
            near_field: NEAR_FIELD,
        }
    }
    /// Refuses settings that cannot work, naming the field, the value and what is allowed.
    pub fn validate(&self) -> Result<(), crate::SettingsError> {
        self.ssil.validate()?;
        self.ddgi.validate()?;
        crate::settings::check_range("technique.near_field", self.near_field, 0.0, 4.0)
    }
}

/// `ssil+ddgi`: DDGI's probes light everything, then the screen-space light replaces them in
/// the share of each pixel's hemisphere the screen covers with senders in the near field.
pub struct SsilDdgi {
    /// The probes, which light every pixel first.
    pub ddgi: Ddgi,
    /// The screen-space light, built as the hybrid's part (over the probes' light).
    pub ssil: Ssil,
}

impl Technique for SsilDdgi {
    fn name(&self) -> &'static str {
        "ssil+ddgi"
    }
    fn passes(&self) -> TechniquePasses {
        let (d, s) = (self.ddgi.passes(), self.ssil.passes());
        TechniquePasses {
            update: d.update.into_iter().chain(s.update).collect(),
            resolve: d.resolve.into_iter().chain(s.resolve).collect(),
        }
    }
    fn prepare(&mut self, ctx: &GpuContext, camera: &Camera) {
        self.ddgi.prepare(ctx, camera);
        self.ssil.prepare(ctx, camera);
    }
    fn update(&mut self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut Profiler>) {
        self.ddgi.update(encoder, profiler);
    }
    fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, mut profiler: Option<&mut Profiler>) {
        self.ddgi.resolve(encoder, profiler.as_deref_mut());
        self.ssil.resolve(encoder, profiler);
    }
    fn visualize(&self, encoder: &mut wgpu::CommandEncoder, view: ProbeView) {
        self.ddgi.visualize(encoder, view);
    }
    fn invalidate(&mut self) {
        self.ddgi.invalidate();
        self.ssil.invalidate();
    }
    fn scene_changed(&mut self, change: &SceneChange) {
        self.ddgi.scene_changed(change);
    }
    fn pose_changed(&mut self, scene: &irradiant_scene::Scene, pose: &irradiant_scene::Pose) {
        self.ddgi.pose_changed(scene, pose);
    }
    fn check_state(&self, ctx: &GpuContext) -> Result<Vec<String>, RenderError> {
        let mut all = self.ddgi.check_state(ctx)?;
        all.extend(self.ssil.check_state(ctx)?);
        Ok(all)
    }
    fn inspect(&self, ctx: &GpuContext) -> Result<crate::inspect::Inspection, RenderError> {
        let mut out = self.ddgi.inspect(ctx)?;
        out.images.extend(self.ssil.inspect(ctx)?.images);
        Ok(out)
    }
    fn counters(&self, ctx: &GpuContext) -> Result<Vec<Counter>, RenderError> {
        let mut all = self.ddgi.counters(ctx)?;
        all.extend(self.ssil.counters(ctx)?);
        Ok(all)
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}
