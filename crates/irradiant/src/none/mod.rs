//! `none`: no indirect light at all — direct light only, the baseline every technique improves
//! on.

use std::any::Any;

use irradiant_gpu::{Allocation, Profiler, Workgroups, wgpu};
use irradiant_scene::Scene;

use crate::RenderError;
use crate::settings::TechniqueSpec;
use crate::technique::{Technique, TechniqueContext, TechniqueKind, TechniquePasses};

/// The `none` technique's kind: builds a technique that leaves `indirect` black.
pub struct NoneKind;

/// The registry entry.
pub static NONE: NoneKind = NoneKind;

impl TechniqueKind for NoneKind {
    fn name(&self) -> &'static str {
        "none"
    }
    fn description(&self) -> &'static str {
        "direct light only"
    }
    fn check(&self, spec: &TechniqueSpec) -> Result<Vec<String>, RenderError> {
        Ok(spec
            .settings
            .keys()
            .map(|k| format!("unknown setting technique.{k} is ignored: 'none' has no settings"))
            .collect())
    }
    fn resolved_settings(&self, _spec: &TechniqueSpec) -> Result<toml::Table, RenderError> {
        Ok(toml::Table::new())
    }
    fn plan(
        &self,
        _: &TechniqueSpec,
        _: &Scene,
        _: (u32, u32),
    ) -> Result<Vec<Allocation>, RenderError> {
        Ok(Vec::new())
    }
    fn dispatches(
        &self,
        _: &TechniqueSpec,
        _: &Scene,
        _: (u32, u32),
    ) -> Result<Vec<(&'static str, Workgroups)>, RenderError> {
        Ok(Vec::new())
    }
    fn build(
        &self,
        cx: &TechniqueContext,
        _spec: &TechniqueSpec,
    ) -> Result<Box<dyn Technique>, RenderError> {
        Ok(Box::new(NoIndirect {
            indirect: cx.frame.resources.texture("indirect").clone(),
        }))
    }
}

/// Clears the frame's indirect light each frame.
pub struct NoIndirect {
    indirect: wgpu::Texture,
}

impl Technique for NoIndirect {
    fn name(&self) -> &'static str {
        "none"
    }
    fn passes(&self) -> TechniquePasses {
        TechniquePasses::default()
    }
    fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, _profiler: Option<&mut Profiler>) {
        encoder.clear_texture(&self.indirect, &wgpu::ImageSubresourceRange::default());
    }
    fn invalidate(&mut self) {}
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}
