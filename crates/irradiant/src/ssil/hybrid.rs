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
    /// While the probes' light is provisional (the first frames after a start or a reset, as
    /// they are placed and classified), every sender on screen counts: the screen's first
    /// bounce is right from the first frame, where unplaced probes leak and miss light, and
    /// the far field's error (the fill's even-light assumption) is smaller than theirs. Off:
    /// the near field from the first frame, and the first frames read as DDGI's.
    pub far_field_while_young: bool,
    /// Reads the probes' light for what the screen leaves uncovered around those directions'
    /// mean (a bent normal), instead of taking the probes' light at the pixel as if the
    /// uncovered directions brought the mean of all of them. Where the screen covers a bright
    /// wall beside a dim ceiling, the fill then leans to the ceiling's light, not the wall's
    /// again: the Cornell box's FLIP 3 % lower, under DDGI's. Costs two probe queries a pixel
    /// the screen covers, the covered directions in the gathers (8 bytes a texel more, about
    /// 58 MiB at 1920×1080) and about 0.16–0.24 ms of GI at 1920×1080 (H200); it reads a
    /// little worse where light comes from every side (two-rooms +0.7 %) and in the first
    /// frames after a cut (docs/ssil.md). Off: the probes' light as it is.
    pub bent_fill: bool,
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
            far_field_while_young: true,
            bent_fill: true,
        }
    }
    /// Each technique's balanced preset.
    pub fn balanced() -> Self {
        Self {
            ssil: SsilSettings::balanced(),
            ddgi: DdgiSettings::balanced(),
            near_field: NEAR_FIELD,
            far_field_while_young: true,
            bent_fill: true,
        }
    }
    /// Each technique's quality preset: DDGI's final gather traces the near field, so the
    /// screen's part steps aside (`screen_part`).
    pub fn quality() -> Self {
        Self {
            ssil: SsilSettings::quality(),
            ddgi: DdgiSettings::quality(),
            near_field: NEAR_FIELD,
            far_field_while_young: true,
            bent_fill: true,
        }
    }
    /// Whether the screen's part runs. With DDGI's final gather (`ddgi.gather.rays_per_pixel`)
    /// each pixel traces its near field: the screen's estimate in that light's place loses
    /// what the rays see and the screen does not (the Cornell box at `quality`: FLIP 0.0268
    /// → 0.0416, H200; docs/ssil.md), so the hybrid is then DDGI's gather alone and spends
    /// nothing on the screen.
    pub fn screen_part(&self) -> bool {
        self.ddgi.gather.rays_per_pixel == 0
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
    /// The screen-space light, built as the hybrid's part (over the probes' light); none
    /// where DDGI gathers at the pixels (`HybridSettings::screen_part`).
    pub ssil: Option<Ssil>,
    /// The near field's reach (scene units), and whether the screen reaches past it while the
    /// probes' light is provisional.
    pub(super) near_reach: f32,
    pub(super) far_field_while_young: bool,
    /// Whether the screen's history holds light from past the near field.
    pub(super) far_in_history: bool,
}

impl SsilDdgi {
    /// How far the screen's senders count this frame (scene units), below 0 for no limit: the
    /// near field, or every sender while the finest volume's probes are provisional
    /// (`far_field_while_young`). A near field of 0 stays 0: DDGI's light alone.
    pub fn reach(&self) -> f32 {
        let young = self
            .ddgi
            .volumes
            .first()
            .is_some_and(|finest| finest.probes_provisional());
        if self.far_field_while_young && self.near_reach > 0.0 && young {
            -1.0
        } else {
            self.near_reach
        }
    }
}

impl Technique for SsilDdgi {
    fn name(&self) -> &'static str {
        "ssil+ddgi"
    }
    fn passes(&self) -> TechniquePasses {
        let mut all = self.ddgi.passes();
        if let Some(ssil) = &self.ssil {
            let s = ssil.passes();
            all.update.extend(s.update);
            all.resolve.extend(s.resolve);
        }
        all
    }
    fn prepare(&mut self, ctx: &GpuContext, camera: &Camera) {
        self.ddgi.prepare(ctx, camera);
        let reach = self.reach();
        if let Some(ssil) = &mut self.ssil {
            // The far field leaves the screen's history with the near field's first frame: its
            // temporal filter would carry it on for tens of frames over settled probes.
            let far = reach < 0.0;
            if self.far_in_history && !far {
                ssil.invalidate();
            }
            self.far_in_history = far;
            ssil.reach = reach;
            ssil.prepare(ctx, camera);
        }
    }
    fn update(&mut self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut Profiler>) {
        self.ddgi.update(encoder, profiler);
    }
    /// The probes' diffuse light, the screen's over it, then DDGI's traced reflections added
    /// whole: the screen's coverage C is a share of the diffuse lobe, not of a glossy one, so
    /// the reflections are not the fill's to scale (docs/ssil.md).
    fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, mut profiler: Option<&mut Profiler>) {
        self.ddgi.resolve_diffuse(encoder, profiler.as_deref_mut());
        if let Some(ssil) = &mut self.ssil {
            ssil.resolve(encoder, profiler.as_deref_mut());
        }
        self.ddgi.resolve_reflections(encoder, profiler);
    }
    fn visualize(&self, encoder: &mut wgpu::CommandEncoder, view: ProbeView) {
        self.ddgi.visualize(encoder, view);
    }
    fn invalidate(&mut self) {
        self.ddgi.invalidate();
        if let Some(ssil) = &mut self.ssil {
            ssil.invalidate();
        }
    }
    fn scene_changed(&mut self, change: &SceneChange) {
        self.ddgi.scene_changed(change);
    }
    fn pose_changed(&mut self, scene: &irradiant_scene::Scene, pose: &irradiant_scene::Pose) {
        self.ddgi.pose_changed(scene, pose);
    }
    fn check_state(&self, ctx: &GpuContext) -> Result<Vec<String>, RenderError> {
        let mut all = self.ddgi.check_state(ctx)?;
        if let Some(ssil) = &self.ssil {
            all.extend(ssil.check_state(ctx)?);
        }
        Ok(all)
    }
    fn inspect(&self, ctx: &GpuContext) -> Result<crate::inspect::Inspection, RenderError> {
        let mut out = self.ddgi.inspect(ctx)?;
        if let Some(ssil) = &self.ssil {
            out.images.extend(ssil.inspect(ctx)?.images);
        }
        Ok(out)
    }
    fn counters(&self, ctx: &GpuContext) -> Result<Vec<Counter>, RenderError> {
        let mut all = self.ddgi.counters(ctx)?;
        if let Some(ssil) = &self.ssil {
            all.extend(ssil.counters(ctx)?);
        }
        Ok(all)
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}
