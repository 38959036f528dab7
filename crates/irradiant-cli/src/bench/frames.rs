//! Whole real-time frames timed pass by pass through the session: the frame's passes and the
//! technique's, grouped by the labels the technique reports (update, resolve).

use std::sync::Arc;
use std::time::Instant;

use irradiant::technique::Counter;
use irradiant::{GpuContext, GpuSceneSettings, Session, SessionSettings, TechniqueSpec};
use serde::Serialize;

use super::Warmup;
use crate::CliError;

#[derive(Serialize)]
pub struct FrameRecord {
    pub scene: String,
    /// Which run over the scene list: "forward", or "reverse" under --check-order.
    pub order: &'static str,
    pub technique: String,
    /// Probes per axis of the first volume (probe techniques; zeros otherwise).
    pub probes: [u32; 3],
    pub rays_per_probe: u32,
    /// The technique as the command line named it, with the --vary values it took.
    pub variant: String,
    /// The camera while timed: "still", "moving" (`--moving-camera`) or "path"
    /// (`--camera-path`).
    pub camera: &'static str,
    /// Every probe's rays a frame (probes × rays per probe): the paper's Table 2 count.
    pub rays: u64,
    /// Probes that traced rays in the timed frames.
    pub updating_probes: u32,
    /// Rays actually traced a frame: updating probes × rays per probe.
    pub traced_rays: u64,
    /// Shadow rays queued for a dense pass in the last frame (DDGI's shadow queue).
    pub queued_shadow_rays: u32,
    /// Median milliseconds of each pass of the frame, in the order they ran.
    pub passes: Vec<(String, f64)>,
    /// Rays ÷ the technique's trace pass alone.
    pub trace_mrays_per_s: f64,
    /// The technique's update passes (as it reports them).
    pub update_ms: f64,
    /// Rays ÷ update time: the paper's Table 2 figure.
    pub update_mrays_per_s: f64,
    /// Rays actually traced ÷ update time (lower than the above when probes sleep).
    pub update_traced_mrays_per_s: f64,
    /// Update + resolve: all of the frame's GI work (the sum of the passes' medians).
    pub gi_ms: f64,
    /// The largest update + resolve of any one timed frame (along a camera path: the frames
    /// where windows step or probes wake).
    pub gi_worst_ms: f64,
    /// Every pass of the frame.
    pub frame_ms: f64,
    /// What the technique reports about its last frame.
    pub counters: Vec<(String, f64)>,
    /// GPU memory the technique allocates (its plan: probe atlases, ray buffers, …), MiB.
    pub technique_mib: f64,
}

/// What every timed frame shares.
pub struct FrameBench<'a> {
    pub ctx: Arc<GpuContext>,
    pub scene: &'a irradiant_scene::Scene,
    pub scene_settings: &'a GpuSceneSettings,
    pub size: (u32, u32),
    /// The frame's settings (balanced, or `bench --settings`), before `taa`.
    pub frame: irradiant::frame::FrameSettings,
    pub taa: bool,
    /// Sway the camera every frame (`bench --moving-camera`).
    pub moving_camera: bool,
    /// Play the scene's animation over this many seconds, spread over the timed frames
    /// (`bench --camera-path`).
    pub path_length: Option<f32>,
    pub iterations: u32,
    /// Which run over the scene list this is (`bench --check-order`).
    pub order: &'static str,
}

impl FrameBench<'_> {
    /// Times `iterations` frames of a technique after `warmup` and keeps the median of each
    /// pass.
    pub fn time(&self, spec: &TechniqueSpec, warmup: Warmup) -> Result<FrameRecord, CliError> {
        let mut frame = self.frame.clone();
        frame.taa.enabled = self.taa;
        let mut session = Session::new(
            self.ctx.clone(),
            self.scene.clone(),
            SessionSettings {
                size: self.size,
                frame,
                technique: spec.clone(),
                scene: self.scene_settings.clone(),
                time: 0.0,
                // Bakes are timed: never read from a cache.
                cache_dir: None,
                progress: Some(crate::cache::bake_progress()),
            },
        )?;
        let mut per_pass: Vec<(String, Vec<f64>)> = Vec::new();
        let (warm_start, mut warm_runs, mut timed) = (Instant::now(), 0, 0);
        let still = session.camera().clone();
        let labels = session.technique().passes();
        let gi_labels: Vec<String> = labels
            .update
            .iter()
            .chain(&labels.resolve)
            .map(|l| l.to_string())
            .collect();
        let mut gi_worst = 0.0f64;
        while timed < self.iterations {
            if let Some(length) = self.path_length {
                // Warm-up at the path's start; then each timed frame a step along it.
                let along = if warmup.done(warm_runs, warm_start) {
                    (timed as f32 + 0.5) / self.iterations as f32
                } else {
                    0.0
                };
                session.seek(along * length);
            } else if self.moving_camera {
                let turn = if (warm_runs + timed) % 2 == 0 {
                    1e-2_f32
                } else {
                    -1e-2
                };
                session.set_camera(swayed(&still, turn.to_radians()));
            }
            let timings = session.render_profiled()?;
            if !warmup.done(warm_runs, warm_start) {
                warm_runs += 1;
                continue;
            }
            timed += 1;
            let gi: f64 = (timings.iter())
                .filter(|t| gi_labels.contains(&t.label))
                .map(|t| t.milliseconds)
                .sum();
            gi_worst = gi_worst.max(gi);
            // A label recorded several times in a frame (a pass per probe volume or per
            // level) counts once, as the sum of its dispatches.
            let mut frame: Vec<(String, f64)> = Vec::new();
            for t in timings {
                match frame.iter_mut().find(|(l, _)| *l == t.label) {
                    Some((_, ms)) => *ms += t.milliseconds,
                    None => frame.push((t.label, t.milliseconds)),
                }
            }
            for (label, ms) in frame {
                match per_pass.iter_mut().find(|(l, _)| *l == label) {
                    Some((_, v)) => v.push(ms),
                    None => per_pass.push((label, vec![ms])),
                }
            }
        }
        let passes: Vec<(String, f64)> = per_pass
            .into_iter()
            .map(|(label, mut v)| {
                v.sort_by(f64::total_cmp);
                (label, v.get(v.len() / 2).copied().unwrap_or(0.0))
            })
            .collect();
        let ms = |label: &str| passes.iter().find(|(l, _)| l == label).map_or(0.0, |p| p.1);
        let update: f64 = labels.update.iter().map(|l| ms(l)).sum();
        let resolve: f64 = labels.resolve.iter().map(|l| ms(l)).sum();
        let counters = session.technique().counters(session.ctx())?;
        let counter = |name: &str| {
            counters
                .iter()
                .find(|c: &&Counter| c.name == name)
                .map_or(0.0, |c| c.value)
        };
        let planned = irradiant::registry::find(&spec.name)?.plan(spec, self.scene, self.size)?;
        let technique_mib = planned.iter().map(|a| a.bytes as f64).sum::<f64>() / (1024.0 * 1024.0);
        let rays = counter("probe_rays");
        let traced = counter("traced_rays");
        let trace_ms: f64 = labels
            .update
            .iter()
            .filter(|l| l.ends_with("/trace"))
            .map(|l| ms(l))
            .sum();
        let rate = |rays: f64, ms: f64| {
            if ms > 0.0 {
                rays / (ms * 1e-3) / 1e6
            } else {
                0.0
            }
        };
        let (probes, rays_per_probe) = match session.technique_as::<irradiant::ddgi::Ddgi>() {
            Some(d) => (
                d.volume().grid.counts.to_array(),
                d.settings().volume.rays_per_probe,
            ),
            None => match session.technique_as::<irradiant::lightfield::Lightfield>() {
                Some(lf) => (lf.grid().counts.to_array(), 0),
                None => ([0; 3], 0),
            },
        };
        Ok(FrameRecord {
            scene: self.scene.name.clone(),
            order: self.order,
            technique: spec.name.clone(),
            probes,
            rays_per_probe,
            variant: spec.name.clone(),
            camera: if self.path_length.is_some() {
                "path"
            } else if self.moving_camera {
                "moving"
            } else {
                "still"
            },
            rays: rays as u64,
            updating_probes: counter("updating_probes") as u32,
            traced_rays: traced as u64,
            queued_shadow_rays: counter("queued_shadow_rays") as u32,
            trace_mrays_per_s: rate(rays, trace_ms),
            update_ms: update,
            update_mrays_per_s: rate(rays, update),
            update_traced_mrays_per_s: rate(traced, update),
            gi_ms: update + resolve,
            gi_worst_ms: gi_worst,
            technique_mib,
            frame_ms: passes.iter().map(|p| p.1).sum(),
            counters: counters
                .iter()
                .map(|c| (c.name.to_owned(), c.value))
                .collect(),
            passes,
        })
    }
}

/// The camera turned by `angle` radians about the vertical through it.
fn swayed(camera: &irradiant_scene::Camera, angle: f32) -> irradiant_scene::Camera {
    let turn = glam::Quat::from_rotation_y(angle);
    irradiant_scene::Camera {
        target: camera.position + turn * (camera.target - camera.position),
        ..camera.clone()
    }
}
