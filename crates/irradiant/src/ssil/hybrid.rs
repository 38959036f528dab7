//! `ssil+ddgi`: DDGI's probes light everything, then the screen-space light replaces them where
//! the screen sees. Its settings are each technique's own under its name.

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
}

crate::settings::presets_from_inherent!(HybridSettings);
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
        }
    }
    /// Each technique's balanced preset.
    pub fn balanced() -> Self {
        Self {
            ssil: SsilSettings::balanced(),
            ddgi: DdgiSettings::balanced(),
        }
    }
    /// Each technique's quality preset, less DDGI's final gather and traced and blind
    /// bounces (512 rays a probe instead).
    pub fn quality() -> Self {
        let mut ddgi = DdgiSettings::quality();
        // The screen-space light stands in for the probes where the screen sees; DDGI's traced
        // final gather would only be replaced there, at its full cost (docs/ddgi.md).
        ddgi.gather.rays_per_pixel = 0;
        // Nor the traced bounce at the probe rays' hits: without the gather's mean over frames,
        // its noise reaches the image (a still scene's image mean varies three times as much,
        // docs/ssil.md), and the probes light only what the screen misses. 512 rays a probe
        // instead, as before it. Nor its blind bounces, for the same noise.
        ddgi.update.traced_bounce = false;
        ddgi.update.blind_bounces = 0;
        ddgi.volume.rays_per_probe = 512;
        Self {
            ssil: SsilSettings::quality(),
            ddgi,
        }
    }
}

/// `ssil+ddgi`: DDGI's probes light everything, then the screen-space light replaces them in
/// the share of each pixel's hemisphere the screen covers.
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
