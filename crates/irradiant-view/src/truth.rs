//! The truth beside the frame (`T`): the path-traced reference of the view, rendered a few
//! samples a frame with a progress bar (or found in the cache `irradiant compare` keeps), then
//! compared with the technique's frame on a worker thread — FLIP, as `compare` measures it —
//! and shown as a wipe, a difference image or the FLIP map.

use std::sync::mpsc;

use irradiant::frame::Image;
use irradiant::pathtrace::reference_cache::ReferenceEntry;
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{GpuContext, GpuScene};
use irradiant_gpu::wgpu;
use irradiant_scene::Camera;

use crate::ViewError;

/// How the truth is shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TruthShow {
    /// The technique left of the split, the reference right of it.
    #[default]
    Wipe,
    /// Where the technique is brighter (red) or darker (blue) than the reference.
    Difference,
    /// FLIP's error map (magma: black none, yellow most).
    Flip,
}

impl TruthShow {
    /// Every way, in the panel's order, with its name.
    pub const ALL: [(TruthShow, &'static str); 3] = [
        (TruthShow::Wipe, "wipe"),
        (TruthShow::Difference, "difference"),
        (TruthShow::Flip, "FLIP"),
    ];
}

/// What the comparison found.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// FLIP's mean over the image (0: identical), as `irradiant compare` reports it.
    pub flip_mean: f32,
    /// FLIP's 95th percentile.
    pub flip_p95: f32,
    /// The technique and preset compared.
    pub technique: String,
}

/// The pictures a comparison makes (RGBA8) and its verdict.
struct Compared {
    verdict: Verdict,
    flip: Vec<u8>,
    difference: Vec<u8>,
}

enum Stage {
    /// Tracing the reference, a few samples a frame.
    Rendering(Box<PathTracer>),
    /// The reference is there; the comparison waits for the technique's frame.
    Awaiting,
    /// The worker compares; the result comes on the channel.
    Comparing(mpsc::Receiver<Result<Compared, String>>),
    /// Shown.
    Ready {
        verdict: Verdict,
        flip: wgpu::TextureView,
        difference: wgpu::TextureView,
    },
}

/// The reference of one view and its comparison with the technique.
pub struct Truth {
    /// The view it is the truth of: another view drops it.
    pub camera: Camera,
    /// Its size in pixels (the frame's).
    pub size: (u32, u32),
    /// The path tracer's settings (the reference `compare` renders at this spp).
    pub settings: PathTraceSettings,
    entry: ReferenceEntry,
    reference: Option<Image>,
    /// The reference as the frame shows it (sRGB at the frame's tone), for the wipe.
    shown: Option<wgpu::TextureView>,
    stage: Stage,
    /// How it is shown.
    pub show: TruthShow,
    /// Where the wipe splits the image, 0 (all reference) … 1 (all technique).
    pub split: f32,
    /// Whether the reference came from the cache.
    pub cached: bool,
}

impl Truth {
    /// The truth of `camera`'s view: from the cache entry when there is one, else a path
    /// tracer ready to accumulate.
    pub fn new(
        ctx: &GpuContext,
        gpu_scene: &GpuScene,
        camera: Camera,
        size: (u32, u32),
        settings: PathTraceSettings,
        entry: ReferenceEntry,
    ) -> Result<Self, ViewError> {
        let reference = entry.load(size);
        let stage = match reference {
            Some(_) => Stage::Awaiting,
            None => {
                let mut tracer = PathTracer::new(ctx, gpu_scene, size.0, size.1)?;
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                tracer.reset(&mut encoder);
                ctx.queue.submit([encoder.finish()]);
                Stage::Rendering(Box::new(tracer))
            }
        };
        Ok(Self {
            camera,
            size,
            settings,
            cached: reference.is_some(),
            entry,
            reference,
            shown: None,
            stage,
            show: TruthShow::Wipe,
            split: 0.5,
        })
    }

    /// GPU memory its path tracer holds while it renders.
    pub fn allocations(&self) -> Vec<irradiant_gpu::Allocation> {
        match &self.stage {
            Stage::Rendering(tracer) => tracer.allocations(),
            _ => Vec::new(),
        }
    }

    /// Samples a pixel done and wanted: the progress bar's.
    pub fn progress(&self) -> (u32, u32) {
        let all = self.settings.samples_per_pixel;
        match &self.stage {
            Stage::Rendering(tracer) => (tracer.samples_done.min(all), all),
            _ => (all, all),
        }
    }

    /// The verdict, once compared.
    pub fn verdict(&self) -> Option<&Verdict> {
        match &self.stage {
            Stage::Ready { verdict, .. } => Some(verdict),
            _ => None,
        }
    }

    /// Whether the reference still renders.
    pub fn rendering(&self) -> bool {
        matches!(self.stage, Stage::Rendering(_))
    }

    /// Moves the truth on by one frame: traces up to `samples` more samples a pixel, or takes
    /// the comparison's result. Returns true while the reference waits for its comparison (the
    /// caller then starts it with the technique's frame).
    pub fn step(
        &mut self,
        ctx: &GpuContext,
        gpu_scene: &GpuScene,
        samples: u32,
    ) -> Result<bool, ViewError> {
        match &mut self.stage {
            Stage::Rendering(tracer) => {
                let left = self.settings.samples_per_pixel - tracer.samples_done;
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                tracer.record(
                    ctx,
                    &mut encoder,
                    gpu_scene,
                    &self.camera,
                    &self.settings,
                    samples.min(left),
                    None,
                )?;
                ctx.queue.submit([encoder.finish()]);
                if tracer.samples_done < self.settings.samples_per_pixel {
                    return Ok(false);
                }
                let image = tracer.image(ctx)?;
                self.entry.store(&image);
                self.reference = Some(image);
                self.stage = Stage::Awaiting;
                Ok(true)
            }
            Stage::Comparing(rx) => {
                match rx.try_recv() {
                    Ok(Ok(compared)) => {
                        let upload = |label, rgba: &[u8]| {
                            upload_rgba8(ctx, label, self.size, rgba)
                                .create_view(&Default::default())
                        };
                        self.stage = Stage::Ready {
                            flip: upload("view/truth_flip", &compared.flip),
                            difference: upload("view/truth_difference", &compared.difference),
                            verdict: compared.verdict,
                        };
                    }
                    Ok(Err(problem)) => return Err(ViewError::Settings(problem)),
                    Err(mpsc::TryRecvError::Empty) => {}
                    Err(mpsc::TryRecvError::Disconnected) => {
                        return Err(ViewError::Settings(
                            "the truth's comparison stopped without a result".into(),
                        ));
                    }
                }
                Ok(false)
            }
            Stage::Awaiting => Ok(true),
            Stage::Ready { .. } => Ok(false),
        }
    }

    /// Compares `frame` (the technique's linear image, named `technique`) with the reference
    /// on a worker thread, and makes the reference's picture at the frame's tone.
    pub fn compare(
        &mut self,
        ctx: &GpuContext,
        frame: Image,
        technique: String,
        (exposure, filmic): (f32, bool),
    ) {
        let Some(reference) = self.reference.clone() else {
            return;
        };
        let shown = rgba(&reference.to_srgb8(exposure, filmic));
        self.shown = Some(
            upload_rgba8(ctx, "view/truth_reference", self.size, &shown)
                .create_view(&Default::default()),
        );
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(compare(&reference, &frame, technique));
        });
        self.stage = Stage::Comparing(rx);
    }

    /// What to show over the frame: the reference beside it (the wipe, from a column on) or a
    /// map instead of it. None until compared.
    pub fn shown(&self) -> Option<(&wgpu::TextureView, Option<u32>)> {
        let Stage::Ready {
            flip, difference, ..
        } = &self.stage
        else {
            return None;
        };
        Some(match self.show {
            TruthShow::Wipe => {
                let column = (self.split.clamp(0.0, 1.0) * self.size.0 as f32) as u32;
                (self.shown.as_ref()?, Some(column))
            }
            TruthShow::Difference => (difference, None),
            TruthShow::Flip => (flip, None),
        })
    }
}

/// FLIP of the frame against the reference (both through `compare`'s tone: exposure 1, filmic),
/// and the signed difference of their luminance.
fn compare(reference: &Image, frame: &Image, technique: String) -> Result<Compared, String> {
    let (w, h) = (reference.width, reference.height);
    let flip = irradiant_eval::flip(
        &reference.to_srgb8(1.0, true),
        &frame.to_srgb8(1.0, true),
        w,
        h,
    )
    .map_err(|e| format!("the truth's comparison failed: {e}"))?;
    let luminance = |p: &[f32; 3]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    let difference = reference
        .pixels
        .iter()
        .zip(&frame.pixels)
        .flat_map(|(r, f)| difference_pixel(luminance(f), luminance(r)))
        .collect();
    Ok(Compared {
        verdict: Verdict {
            flip_mean: flip.mean,
            flip_p95: flip.p95,
            technique,
        },
        flip: rgba(&flip.error_map_rgb8),
        difference,
    })
}

/// The frame's luminance against the reference's as a colour: red where brighter, blue where
/// darker, full at a relative error of 100 % (and a floor that keeps black from dividing by 0).
pub fn difference_pixel(frame: f32, reference: f32) -> [u8; 4] {
    let relative = ((frame - reference) / (reference.abs() + 0.02)).clamp(-1.0, 1.0);
    let relative = if relative.is_finite() { relative } else { 0.0 };
    let v = (relative.abs().sqrt() * 255.0 + 0.5) as u8;
    if relative >= 0.0 {
        [v, v / 4, v / 4, 255]
    } else {
        [v / 4, v / 4, v, 255]
    }
}

/// RGB8 to RGBA8, opaque.
pub fn rgba(rgb: &[u8]) -> Vec<u8> {
    rgb.chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect()
}

/// A texture the blit and the inspector read, filled with RGBA8 texels.
pub fn upload_rgba8(ctx: &GpuContext, label: &str, size: (u32, u32), rgba: &[u8]) -> wgpu::Texture {
    let texture = irradiant_gpu::texture_2d(
        &ctx.device,
        label,
        size,
        wgpu::TextureFormat::Rgba8Unorm,
        1,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    ctx.queue.write_texture(
        texture.as_image_copy(),
        rgba,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * size.0),
            rows_per_image: None,
        },
        texture.size(),
    );
    texture
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_difference_is_red_where_brighter_and_blue_where_darker() {
        assert_eq!(difference_pixel(1.0, 1.0), [0, 0, 0, 255]);
        let brighter = difference_pixel(2.0, 1.0);
        let darker = difference_pixel(0.5, 1.0);
        assert!(brighter[0] > 200 && brighter[2] < 80, "{brighter:?}");
        assert!(darker[2] > 150 && darker[0] < 60, "{darker:?}");
        assert_eq!(difference_pixel(f32::NAN, 1.0), [0, 0, 0, 255]);
    }
}
