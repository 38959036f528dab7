//! Techniques and their registry.
//!
//! A technique turns the frame's G-buffer into indirect light: the session calls
//! [`Technique::update`] (its per-frame work) and [`Technique::resolve`] (indirect light into
//! the frame's `indirect`) between the frame's inputs and its compose pass. It is built from a
//! [`TechniqueSpec`] — a registered name, a preset and its own settings, as a settings file or
//! a manifest writes them — already bound to the frame: there is no separate call to forget.
//!
//! The registry that lists the techniques lives above this module, in [`crate::registry`]: the
//! techniques import the trait and types from here, and nothing here imports a technique.

use std::any::Any;

use irradiant_gpu::{Allocation, GpuContext, Profiler, Workgroups, wgpu};
use irradiant_scene::Scene;

use crate::RenderError;
use crate::frame::{Frame, FrameNeeds, SceneChange};
use crate::scene::GpuScene;
use crate::settings::TechniqueSpec;

/// What a technique is built from.
pub struct TechniqueContext<'a> {
    /// The GPU it is built on.
    pub ctx: &'a GpuContext,
    /// The scene on the CPU (bounds, lights, materials).
    pub scene: &'a Scene,
    /// The scene on the GPU, whose resources its passes bind.
    pub gpu_scene: &'a GpuScene,
    /// The frame it is bound to, whose resources its passes bind.
    pub frame: &'a Frame,
    /// Where a technique may cache what it bakes (None: bake every time).
    pub cache_dir: Option<&'a std::path::Path>,
    /// Where long one-off work (a bake) reports how far it has got.
    pub progress: Option<&'a Progress>,
}

/// What a [`Progress`] calls: (what, steps done, steps in all).
pub type ProgressFn = dyn Fn(&str, u32, u32) + Send + Sync;

/// A callback told how far a long step has got.
#[derive(Clone)]
pub struct Progress(pub std::sync::Arc<ProgressFn>);

impl Progress {
    /// Tells the callback that `done` of `all` steps of `what` are done.
    pub fn report(&self, what: &str, done: u32, all: u32) {
        (self.0)(what, done, all)
    }
}

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Progress(..)")
    }
}

/// A registered technique: its name, what it needs and how to build it.
pub trait TechniqueKind: Sync {
    /// The registry name (`ddgi`), also the label prefix of its passes.
    fn name(&self) -> &'static str;
    /// One line for tool listings.
    fn description(&self) -> &'static str;
    /// Parses and validates the spec's settings, returning the warnings (unknown keys): what
    /// tools call before any GPU work, so that a settings error comes first.
    fn check(&self, spec: &TechniqueSpec) -> Result<Vec<String>, RenderError>;
    /// Every setting the spec resolves to — its preset with the spec's own keys over it — as a
    /// settings file's `[technique]` table writes them (without `name` and `preset`): what the
    /// viewer's panel shows and edits, key by key.
    fn resolved_settings(&self, spec: &TechniqueSpec) -> Result<toml::Table, RenderError>;
    /// The doc comment of the setting at `path` (`["update", "hysteresis"]`): what it does
    /// and what it trades (the viewer's tooltips). `spec` picks the settings type where a kind
    /// has more than one.
    fn setting_doc(&self, _spec: &TechniqueSpec, _path: &[&str]) -> Option<&'static str> {
        None
    }
    /// What it needs of the frame beyond the G-buffer and the light buffers.
    fn frame_needs(&self, _spec: &TechniqueSpec) -> FrameNeeds {
        FrameNeeds::default()
    }
    /// Warnings about the scene for this technique (a scene it cannot handle well).
    fn scene_warnings(&self, _spec: &TechniqueSpec, _scene: &Scene) -> Vec<String> {
        Vec::new()
    }
    /// Every GPU allocation it would make for this scene, before making any.
    fn plan(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<Allocation>, RenderError>;
    /// Every dispatch it would record for this scene at this image size, with its label
    /// (the test that every pass fits the adapter at the largest sizes reads these).
    fn dispatches(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<(&'static str, Workgroups)>, RenderError>;
    /// Builds it, bound to the frame.
    fn build(
        &self,
        cx: &TechniqueContext,
        spec: &TechniqueSpec,
    ) -> Result<Box<dyn Technique>, RenderError>;
}

/// The pass labels a technique records, in order: its update's and its resolve's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TechniquePasses {
    /// The labels [`Technique::update`] records.
    pub update: Vec<&'static str>,
    /// The labels [`Technique::resolve`] records.
    pub resolve: Vec<&'static str>,
}

/// A figure a technique reports about its last frame (probes updating, rays traced, …).
#[derive(Clone, Debug, PartialEq)]
pub struct Counter {
    /// What it counts (`updating_probes`).
    pub name: &'static str,
    /// Its value in the last frame.
    pub value: f64,
}

/// How a technique's debug overlay draws its probes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ProbeView {
    /// Each probe a small sphere lit by the light it stores (`render --show-probes`).
    #[default]
    Light,
    /// Each probe coloured by its state (vigilant, awake, sleeping, off; tied), with a line
    /// from its grid point to where relocation moved it.
    States,
    /// Each pixel coloured by the probe volumes that light it and their weights (DDGI's
    /// cascades and volumes, finest red, then green, blue): where they blend, and whether a
    /// border shows.
    Volumes,
}

/// A built technique, bound to the frame it was built for.
pub trait Technique: Any + Send {
    /// The registry name it was built from.
    fn name(&self) -> &'static str;
    /// The labels of the passes it records (bench groups timings by them).
    fn passes(&self) -> TechniquePasses;
    /// Uploads this frame's parameters (before the frame's commands are submitted); `camera`
    /// is the view the frame renders.
    fn prepare(&mut self, _ctx: &GpuContext, _camera: &irradiant_scene::Camera) {}
    /// Records the per-frame update (DDGI: trace, shade, blend; nothing for a baked technique).
    fn update(&mut self, _encoder: &mut wgpu::CommandEncoder, _profiler: Option<&mut Profiler>) {}
    /// Records the resolve: indirect light into the frame's `indirect`.
    fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut Profiler>);
    /// Records a debug overlay of its probes, drawn as `view` says, into the frame's
    /// `radiance` (after compose).
    fn visualize(&self, _encoder: &mut wgpu::CommandEncoder, _view: ProbeView) {}
    /// Forgets all history (the next frame starts from scratch).
    fn invalidate(&mut self);
    /// Told when the scene changes between frames, so that it can adapt.
    fn scene_changed(&mut self, _change: &SceneChange) {}
    /// The scene's pose, at the start and whenever it changes: where its instances stand (a
    /// DDGI volume that follows an instance reads it).
    fn pose_changed(&mut self, _scene: &irradiant_scene::Scene, _pose: &irradiant_scene::Pose) {}
    /// Applies new settings between frames if only settings that can change live differ;
    /// returns false when they need a rebuild (the session then builds it anew).
    fn reconfigure(
        &mut self,
        _ctx: &GpuContext,
        _spec: &TechniqueSpec,
    ) -> Result<bool, RenderError> {
        Ok(false)
    }
    /// Non-finite values in what the technique carries from frame to frame (probe atlases,
    /// histories), read back from the GPU: one line per place holding any. For soak runs.
    fn check_state(&self, _ctx: &GpuContext) -> Result<Vec<String>, RenderError> {
        Ok(Vec::new())
    }
    /// Its state as pictures (probe atlases, pyramid levels, voxel grids) and its probes'
    /// places, read back from the GPU: the viewer's inspector.
    fn inspect(&self, _ctx: &GpuContext) -> Result<crate::inspect::Inspection, RenderError> {
        Ok(Default::default())
    }
    /// Figures about the last frame, read back from the GPU where needed.
    fn counters(&self, _ctx: &GpuContext) -> Result<Vec<Counter>, RenderError> {
        Ok(Vec::new())
    }
    /// Itself as [`Any`], for [`crate::Session::technique_as`]'s downcast.
    fn as_any(&self) -> &dyn Any;
    /// Itself as mutable [`Any`], for [`crate::Session::technique_as_mut`]'s downcast.
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

/// "label: n of m values are not finite" when some are (for [`Technique::check_state`]).
pub fn non_finite(label: &str, values: impl Iterator<Item = f32>) -> Option<String> {
    let (mut bad, mut all) = (0usize, 0usize);
    for v in values {
        all += 1;
        bad += !v.is_finite() as usize;
    }
    (bad > 0).then(|| format!("{label}: {bad} of {all} values are not finite"))
}
