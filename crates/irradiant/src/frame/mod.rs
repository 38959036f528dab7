//! The real-time frame: G-buffer from (jittered) primary rays → direct light → (the G-buffer
//! pyramid, where a technique asks for it) → the technique's indirect light → compose → TAA →
//! tonemap (ARCHITECTURE.md, "The frame"). The session drives it; a technique reads its
//! resources by name (resources.rs).

mod change;
pub mod constants;
mod image_io;
mod resources;
mod settings;
pub mod types;

pub use change::{LightingChange, SceneChange};
pub use image_io::{Image, write_atomically, write_png};
pub use resources::{FrameNeeds, FrameResources};
pub use settings::{FrameSettings, PyramidSettings, ResamplingSettings, TaaSettings, ToneSettings};

use glam::Vec2;
use irradiant_gpu::{
    Allocation, BoundPass, GpuContext, PassDesc, Profiler, ResourceTable, Workgroups, read_texture,
    wgpu,
};
use irradiant_scene::Camera;

use crate::RenderError;
use crate::scene::GpuScene;
use crate::scene::types::GpuCamera;
use types::GpuFrameParams;

/// Image passes run 8×8 pixels a workgroup.
pub const IMAGE_TILE: (u32, u32) = (8, 8);

/// Frames in the jitter sequence (Halton 2, 3): enough sub-pixel positions that a still view's
/// blend over them is a smooth box filter.
const JITTER_FRAMES: u32 = 16;

/// One pixel of the G-buffer, read back for measurements (regions, tests).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GBufferSample {
    /// World position of the visible surface (reconstructed from depth).
    pub position: [f32; 3],
    /// Distance along the primary ray; negative where it left the scene.
    pub depth: f32,
    /// Radiance the surface emits towards the camera.
    pub emission: [f32; 3],
    /// Shading normal.
    pub normal: [f32; 3],
    /// What diffuse light the surface reflects: brdf.wgsl's diffuse_weight (albedo less metal
    /// and the specular layer's share), so that indirect diffuse light is this × E/π.
    pub diffuse: [f32; 3],
}

struct FramePasses {
    gbuffer: BoundPass,
    direct: BoundPass,
    /// frame/direct_reuse: the emitter reservoirs' spatial reuse and shading (scenes that can
    /// hold emitters).
    direct_reuse: Option<BoundPass>,
    compose: BoundPass,
    taa: BoundPass,
    /// frame/taa for a frame with no history under emitters (scenes that can hold them): a
    /// pipeline of its own, so that the other frames' TAA keeps its registers.
    taa_cut: Option<BoundPass>,
    tonemap: BoundPass,
    /// frame/pyramid, then frame/pyramid_down for each level above 0.
    pyramid: Vec<BoundPass>,
}

/// The real-time frame: its resources (G-buffer, light buffers, history), passes and
/// accumulation state.
pub struct Frame {
    /// Its textures and buffers, which techniques read by name.
    pub resources: FrameResources,
    settings: FrameSettings,
    passes: FramePasses,
    frame_index: u32,
    /// Frames in the direct-light running mean (restarts when the view or the scene changes).
    accumulated_frames: u32,
    /// Frames in the TAA history (restarts only on invalidation: motion is reprojected).
    history_frames: u32,
    camera: Camera,
    previous_camera: Option<Camera>,
    /// Whether last frame's emitter reservoirs hold samples of this scene's emitters (not after
    /// a reset).
    reservoirs_valid: bool,
    /// Whether this frame's frame/direct_reuse draws the candidates and frame/direct is left
    /// out (`GpuFrameParams::direct_in_reuse`), as `prepare` found.
    direct_in_reuse: bool,
    /// Whether frames that allow it light in one pass ([`Frame::set_one_pass_direct`]).
    one_pass_direct: bool,
}

impl Frame {
    /// Every allocation a frame of this size makes (checked before any is made).
    pub fn plan(width: u32, height: u32, needs: FrameNeeds) -> Vec<Allocation> {
        FrameResources::plan(width, height, needs)
    }

    /// Validates the settings, allocates the resources for this size and needs, and builds
    /// the passes bound to the scene.
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        (width, height): (u32, u32),
        settings: FrameSettings,
        needs: FrameNeeds,
    ) -> Result<Self, RenderError> {
        settings.validate()?;
        let resources = FrameResources::new(ctx, width, height, needs, scene.sky)?;
        let passes = {
            let scene_table = scene.resources();
            let frame_table = resources.table();
            let tables: &[&ResourceTable] = &[&scene_table, &frame_table];
            let tracing = scene.shader_constants();
            let bind = |desc: PassDesc| {
                crate::shaders::pass(ctx, &desc)?
                    .bind(ctx, tables)
                    .map_err(RenderError::from)
            };
            let pass = |label, source, tracing_pass: bool| {
                let mut desc = PassDesc::new(label, source);
                if tracing_pass {
                    desc = desc.constants(tracing.clone());
                }
                bind(desc)
            };
            // frame/taa, and with emitters its variant for a frame with no history, which
            // takes each pixel's colour over the light on its surface (taa.wgsl,
            // reconstruct_current): one emitter sample a pixel is one emitter's colour.
            let taa = |colour_from_surface: bool| {
                bind(
                    PassDesc::new("frame/taa", include_str!("taa.wgsl")).constants([(
                        "COLOUR_FROM_SURFACE",
                        format!("{}u", colour_from_surface as u32),
                    )]),
                )
            };
            let mut pyramid = Vec::new();
            if needs.pyramid_levels > 0 {
                pyramid.push(pass("frame/pyramid", include_str!("pyramid.wgsl"), false)?);
                let down = crate::shaders::pass(
                    ctx,
                    &PassDesc::new("frame/pyramid_down", include_str!("pyramid_down.wgsl")),
                )?;
                for level in 1..needs.pyramid_levels {
                    let view = |name: &str, k: u32| {
                        resources
                            .textures
                            .iter()
                            .find(|t| t.name == name)
                            .map(|t| &t.levels[k as usize].1)
                            .expect("pyramid textures exist when levels are asked for")
                    };
                    let table = ResourceTable::new()
                        .texture(
                            "source_normal_depth",
                            view("pyramid_normal_depth", level - 1),
                        )
                        .texture("source_radiance", view("pyramid_radiance", level - 1))
                        .texture("source_albedo", view("pyramid_albedo", level - 1))
                        .texture("target_normal_depth", view("pyramid_normal_depth", level))
                        .texture("target_radiance", view("pyramid_radiance", level))
                        .texture("target_albedo", view("pyramid_albedo", level));
                    pyramid.push(down.bind(ctx, &[&table, &frame_table])?);
                }
            }
            FramePasses {
                gbuffer: pass("frame/gbuffer", include_str!("gbuffer.wgsl"), true)?,
                direct: pass("frame/direct", include_str!("direct.wgsl"), true)?,
                direct_reuse: if scene.has_emitters() {
                    Some(pass(
                        "frame/direct_reuse",
                        include_str!("direct_reuse.wgsl"),
                        true,
                    )?)
                } else {
                    None
                },
                compose: pass("frame/compose", include_str!("compose.wgsl"), false)?,
                taa: taa(false)?,
                taa_cut: if scene.has_emitters() {
                    Some(taa(true)?)
                } else {
                    None
                },
                tonemap: pass("frame/tonemap", include_str!("tonemap.wgsl"), false)?,
                pyramid,
            }
        };
        Ok(Self {
            resources,
            settings,
            passes,
            frame_index: 0,
            accumulated_frames: 0,
            history_frames: 0,
            camera: Camera::default(),
            previous_camera: None,
            reservoirs_valid: false,
            direct_in_reuse: false,
            one_pass_direct: true,
        })
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.resources.width, self.resources.height)
    }

    /// The current settings.
    pub fn settings(&self) -> &FrameSettings {
        &self.settings
    }

    /// Changes settings between frames. Every frame setting is live; turning TAA on or off
    /// restarts the history, since the two sample different points.
    pub fn set_settings(&mut self, settings: FrameSettings) -> Result<(), RenderError> {
        settings.validate()?;
        if settings.taa.enabled != self.settings.taa.enabled || settings.seed != self.settings.seed
        {
            self.invalidate();
        }
        if settings.area_light_samples != self.settings.area_light_samples
            || settings.resampling != self.settings.resampling
        {
            self.restart_direct();
        }
        self.settings = settings;
        Ok(())
    }

    /// Forgets all accumulated history: the direct-light running mean and the TAA history.
    pub fn invalidate(&mut self) {
        self.accumulated_frames = 0;
        self.history_frames = 0;
        self.reservoirs_valid = false;
    }

    /// Restarts the direct-light running mean (the scene moved); TAA keeps its history, which
    /// its neighbourhood clip adapts.
    pub fn restart_direct(&mut self) {
        self.accumulated_frames = 0;
    }

    /// Whether a frame in which no pixel takes another's reservoir or last frame's (a still
    /// view after its first frame) draws the emitter candidates in frame/direct_reuse and
    /// leaves frame/direct out: on by default. Off, both passes run as in any other frame:
    /// the same image, one more pass (for the test that holds the two to it, and for timing
    /// them apart). From the next `prepare` on.
    pub fn set_one_pass_direct(&mut self, on: bool) {
        self.one_pass_direct = on;
    }

    /// Frames in the current direct-light running mean.
    pub fn accumulated_frames(&self) -> u32 {
        self.accumulated_frames
    }

    /// This frame's sub-pixel offset of the primary rays (zero without TAA).
    pub fn jitter(&self) -> Vec2 {
        if !self.settings.taa.enabled {
            return Vec2::ZERO;
        }
        let i = self.frame_index % JITTER_FRAMES + 1;
        Vec2::new(halton(i, 2), halton(i, 3)) - 0.5
    }

    /// Writes this frame's parameters for `camera`; call before recording the frame.
    pub fn prepare(&mut self, ctx: &GpuContext, camera: &Camera) {
        let (w, h) = self.size();
        if self.previous_camera.as_ref() != Some(camera) {
            self.accumulated_frames = 0;
        }
        let previous = self
            .previous_camera
            .clone()
            .unwrap_or_else(|| camera.clone());
        let s = &self.settings;
        // Reuse that is not unbiased serves only frames with no mean to join: in a still view
        // its bias would stay in the mean (FLIP 0.016 against 0.009 unbiased on the Cornell box
        // after 64 frames, H200), so from the view's second frame on each pixel keeps its own
        // candidates.
        let reuse_neighbours = if s.resampling.unbiased || self.accumulated_frames == 0 {
            s.resampling.neighbours
        } else {
            0
        };
        let cut_frame = self.accumulated_frames == 0 && s.resampling.history > 0;
        let reservoir_history = if self.reservoirs_valid && self.accumulated_frames == 0 {
            s.resampling.history * s.resampling.candidates
        } else {
            0
        };
        let cut_neighbours = if cut_frame {
            s.resampling.cut_neighbours
        } else {
            reuse_neighbours
        };
        let shares_reservoirs = reservoir_history > 0 || reuse_neighbours > 0 || cut_neighbours > 0;
        // Where each pixel keeps its own candidates, the reservoir frame/direct would make is
        // read by that pixel alone: frame/direct_reuse draws it, one pass instead of two (a
        // still view's frames after its first).
        self.direct_in_reuse = self.one_pass_direct
            && self.passes.direct_reuse.is_some()
            && s.resampling.candidates > 0
            && !shares_reservoirs;
        let params = GpuFrameParams {
            camera: GpuCamera::new(camera, w, h),
            previous_camera: GpuCamera::new(&previous, w, h),
            width: w,
            height: h,
            frame_index: self.frame_index,
            area_light_samples: s.area_light_samples,
            seed: s.seed,
            accumulated_frames: self.accumulated_frames,
            jitter: self.jitter().to_array(),
            taa_blend: if s.taa.enabled { s.taa.blend } else { 1.0 },
            history_frames: self.history_frames,
            taa_clip_sigma: s.taa.clip_sigma,
            exposure: s.tone.exposure,
            tone_curve: if s.tone.filmic {
                constants::TONE_FILMIC
            } else {
                constants::TONE_CLAMP
            },
            pyramid_pixel_sigma: s.pyramid.pixel_sigma,
            pyramid_normal_sigma: s.pyramid.normal_sigma,
            pyramid_depth_sigma: s.pyramid.depth_sigma,
            emitter_candidates: s.resampling.candidates,
            // A still view's running mean already averages independent frames; last frame's
            // reservoir would only correlate them (blotches that 64 frames did not smooth on
            // the many-lights hall), so temporal reuse serves moving views.
            reservoir_history,
            reuse_neighbours,
            reuse_radius: s.resampling.radius,
            reuse_visibility: s.resampling.unbiased as u32,
            // Where temporal reuse finds no history in a frame with no mean to join, a pixel
            // draws more. A still view's later frames seek no history and draw what every
            // pixel draws; so does every pixel with temporal reuse off.
            cut_candidates: if cut_frame {
                s.resampling.cut_candidates
            } else {
                s.resampling.candidates
            },
            cut_neighbours,
            direct_in_reuse: self.direct_in_reuse as u32,
            // A pixel's frames that only add to its own mean may pick along its sequence.
            pick_sequence: (s.resampling.pick_sequence && !shares_reservoirs) as u32,
            _pad: [0; 3],
        };
        ctx.queue
            .write_buffer(&self.resources.params, 0, bytemuck::bytes_of(&params));
        self.camera = camera.clone();
    }

    /// Every dispatch a frame of this size records, with its label, in order: one function
    /// for the recording and for the test that every dispatch fits the adapter.
    pub fn dispatches((w, h): (u32, u32), needs: FrameNeeds) -> Vec<(&'static str, Workgroups)> {
        let image = Workgroups::for_image(w, h, IMAGE_TILE);
        // frame/direct_reuse only where the scene can hold emitters and resampling is on.
        let mut all = vec![
            ("frame/gbuffer", image),
            ("frame/direct", image),
            ("frame/direct_reuse", image),
        ];
        for level in 0..needs.pyramid_levels {
            let label = if level == 0 {
                "frame/pyramid"
            } else {
                "frame/pyramid_down"
            };
            all.push((
                label,
                Workgroups::for_image((w >> level).max(1), (h >> level).max(1), IMAGE_TILE),
            ));
        }
        all.extend([
            ("frame/compose", image),
            ("frame/taa", image),
            ("frame/tonemap", image),
        ]);
        all
    }

    /// The workgroups of a pass over the image.
    pub fn image_groups(&self) -> Workgroups {
        let (w, h) = self.size();
        Workgroups::for_image(w, h, IMAGE_TILE)
    }

    /// Records frame/gbuffer, the direct light (frame/direct and frame/direct_reuse, or the
    /// latter alone: `GpuFrameParams::direct_in_reuse`) and (where asked for) the G-buffer
    /// pyramid: what a technique reads.
    pub fn record_inputs(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        self.passes
            .gbuffer
            .dispatch(encoder, profiler.as_deref_mut(), self.image_groups());
        self.record_lighting(encoder, profiler, true);
    }

    /// Records the direct light (where `direct`: frame/direct and frame/direct_reuse, or the
    /// latter alone) and the G-buffer pyramid over a G-buffer already written (by
    /// frame/gbuffer, or a host's through host/import).
    pub fn record_lighting(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
        direct: bool,
    ) {
        let groups = self.image_groups();
        if direct {
            if !self.direct_in_reuse {
                self.passes
                    .direct
                    .dispatch(encoder, profiler.as_deref_mut(), groups);
            }
            // As `prepare` decided: settings changed since reach the next frame.
            if let Some(reuse) = &self.passes.direct_reuse
                && (self.direct_in_reuse || self.settings.resampling.candidates > 0)
            {
                reuse.dispatch(encoder, profiler.as_deref_mut(), groups);
            }
        }
        let pyramid = Self::dispatches(self.size(), self.resources.needs)
            .into_iter()
            .filter(|(label, _)| label.starts_with("frame/pyramid"));
        for (pass, (_, groups)) in self.passes.pyramid.iter().zip(pyramid) {
            pass.dispatch(encoder, profiler.as_deref_mut(), groups);
        }
    }

    /// Records frame/compose: emission + direct + indirect into `radiance`.
    pub fn record_compose(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
    ) {
        self.passes
            .compose
            .dispatch(encoder, profiler, self.image_groups());
    }

    /// Records frame/taa (into `resolved`), keeps the result as next frame's history, and
    /// frame/tonemap (into `output`).
    pub fn record_output(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut Profiler>,
    ) {
        let groups = self.image_groups();
        let taa = match &self.passes.taa_cut {
            Some(cut) if self.history_frames == 0 => cut,
            _ => &self.passes.taa,
        };
        taa.dispatch(encoder, profiler.as_deref_mut(), groups);
        let r = &self.resources;
        encoder.copy_texture_to_texture(
            r.texture("resolved").as_image_copy(),
            r.texture("previous_radiance").as_image_copy(),
            r.texture("resolved").size(),
        );
        self.passes.tonemap.dispatch(encoder, profiler, groups);
    }

    /// Counts the recorded frame: call after submitting it.
    pub fn finish(&mut self) {
        self.frame_index += 1;
        self.accumulated_frames += 1;
        self.history_frames += 1;
        self.reservoirs_valid = true;
        self.previous_camera = Some(self.camera.clone());
    }

    /// The last frame's final linear radiance (after TAA).
    pub fn image(&self, ctx: &GpuContext) -> Result<Image, RenderError> {
        let texels: Vec<[half::f16; 4]> = bytemuck::pod_collect_to_vec(&read_texture(
            ctx,
            self.resources.texture("resolved"),
            8,
        )?);
        let (width, height) = self.size();
        Ok(Image {
            width,
            height,
            pixels: texels
                .iter()
                .map(|p| [p[0].to_f32(), p[1].to_f32(), p[2].to_f32()])
                .collect(),
        })
    }

    /// The last frame's light before TAA: `direct` or `indirect` (rgb; indirect normalised
    /// by its weight, as compose reads it).
    pub fn read(&self, ctx: &GpuContext, texture: &str) -> Result<Image, RenderError> {
        let sums: Vec<[f32; 4]> =
            bytemuck::pod_collect_to_vec(&read_texture(ctx, self.resources.texture(texture), 16)?);
        let (width, height) = self.size();
        Ok(Image {
            width,
            height,
            pixels: sums
                .iter()
                .map(|s| {
                    let w = s[3].max(1.0);
                    [s[0] / w, s[1] / w, s[2] / w]
                })
                .collect(),
        })
    }

    /// The last frame's G-buffer: depth, reconstructed position and emission of every pixel.
    pub fn read_gbuffer(&self, ctx: &GpuContext) -> Result<Vec<GBufferSample>, RenderError> {
        let (width, height) = self.size();
        let depth: Vec<f32> = bytemuck::pod_collect_to_vec(&read_texture(
            ctx,
            self.resources.texture("gbuffer_depth"),
            4,
        )?);
        let emission: Vec<half::f16> = bytemuck::pod_collect_to_vec(&read_texture(
            ctx,
            self.resources.texture("gbuffer_emission"),
            8,
        )?);
        let half_texels = |name: &str| -> Result<Vec<half::f16>, RenderError> {
            Ok(bytemuck::pod_collect_to_vec(&read_texture(
                ctx,
                self.resources.texture(name),
                8,
            )?))
        };
        let normal = half_texels("gbuffer_normal")?;
        let albedo = half_texels("gbuffer_albedo")?;
        let motion: Vec<f32> = bytemuck::pod_collect_to_vec(&read_texture(
            ctx,
            self.resources.texture("gbuffer_motion"),
            16,
        )?);
        let camera = GpuCamera::new(&self.camera, width, height);
        let jitter = self.last_jitter();
        Ok((0..(width * height) as usize)
            .map(|i| {
                let pixel =
                    Vec2::new((i as u32 % width) as f32, (i as u32 / width) as f32) + 0.5 + jitter;
                let d = depth[i];
                let position =
                    glam::Vec3::from(camera.position) + camera.ray_dir(pixel, width, height) * d;
                GBufferSample {
                    position: position.to_array(),
                    depth: d,
                    emission: [0, 1, 2].map(|c| emission[4 * i + c].to_f32()),
                    normal: crate::probes::octahedral::oct_decode(Vec2::new(
                        normal[4 * i].to_f32(),
                        normal[4 * i + 1].to_f32(),
                    ))
                    .to_array(),
                    diffuse: {
                        // brdf.wgsl's diffuse_weight: its twin.
                        let metallic = emission[4 * i + 3].to_f32();
                        let specular = motion[4 * i + 2];
                        [0, 1, 2].map(|c| {
                            albedo[4 * i + c].to_f32() * (1.0 - metallic) * (1.0 - 0.04 * specular)
                        })
                    },
                }
            })
            .collect())
    }

    /// The jitter the last recorded frame used.
    fn last_jitter(&self) -> Vec2 {
        if !self.settings.taa.enabled || self.frame_index == 0 {
            return Vec2::ZERO;
        }
        let i = (self.frame_index - 1) % JITTER_FRAMES + 1;
        Vec2::new(halton(i, 2), halton(i, 3)) - 0.5
    }

    /// The last frame, tonemapped: sRGB RGBA8 bytes, rows top to bottom.
    pub fn tonemapped(&self, ctx: &GpuContext) -> Result<Vec<u8>, RenderError> {
        Ok(read_texture(ctx, self.resources.texture("output"), 4)?)
    }
}

/// Element `index` of the Halton sequence in `base` (in [0, 1)).
fn halton(mut index: u32, base: u32) -> f32 {
    let mut result = 0.0;
    let mut f = 1.0;
    while index > 0 {
        f /= base as f32;
        result += f * (index % base) as f32;
        index /= base;
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_jitter_sequence_covers_the_pixel_evenly() {
        let points: Vec<Vec2> = (1..=JITTER_FRAMES)
            .map(|i| Vec2::new(halton(i, 2), halton(i, 3)) - 0.5)
            .collect();
        let mean = points.iter().sum::<Vec2>() / points.len() as f32;
        assert!(mean.length() < 0.05, "mean offset {mean}");
        for quadrant in 0..4 {
            let inside = points
                .iter()
                .filter(|p| {
                    (p.x >= 0.0) == (quadrant & 1 == 1) && (p.y >= 0.0) == (quadrant & 2 == 2)
                })
                .count();
            assert!(
                (3..=5).contains(&inside),
                "quadrant {quadrant} holds {inside} of 16"
            );
        }
        assert!(points.iter().all(|p| p.x.abs() <= 0.5 && p.y.abs() <= 0.5));
    }
}
