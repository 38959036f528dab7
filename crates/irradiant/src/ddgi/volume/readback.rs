//! What a volume reads back from the GPU: its probe states and counts, probe centres, tied
//! probes and atlases — for tests, the oracles, soak checks and bench counters.

// The volume's types and imports, from volume.rs.
use super::*;

/// Probes in each state (003 §6; see ddgi::constants).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProbeStateCounts {
    /// Near static geometry: trace and update every frame.
    pub vigilant: u32,
    /// Inside static geometry: never trace or shade.
    pub off: u32,
    /// No geometry within a cell: never trace or shade.
    pub sleeping: u32,
    /// Sleeping probes that an animated instance woke.
    pub awake: u32,
    /// Classified near geometry in the last frame: converge in the next, then vigilant.
    pub newly_vigilant: u32,
    /// Woken in the last frame: converge in the next, then awake.
    pub newly_awake: u32,
}

impl ProbeStateCounts {
    /// Probes whose state updates (vigilant and awake, newly or not): those the query reads,
    /// and with probe states on those that trace (with them off every probe traces).
    pub fn updating(&self) -> u32 {
        self.vigilant + self.awake + self.newly_vigilant + self.newly_awake
    }

    /// The counts of a list of state words.
    pub fn of(words: &[u32]) -> Self {
        let mut counts = Self::default();
        for word in words {
            match word & PROBE_STATE_MASK {
                PROBE_VIGILANT => counts.vigilant += 1,
                PROBE_OFF => counts.off += 1,
                PROBE_SLEEPING => counts.sleeping += 1,
                PROBE_AWAKE => counts.awake += 1,
                PROBE_NEWLY_VIGILANT => counts.newly_vigilant += 1,
                _ => counts.newly_awake += 1,
            }
        }
        counts
    }
}

impl DdgiVolume {
    /// Shadow rays ddgi/shade queued in the last update (0 without the shadow queue).
    pub fn read_queued_shadow_rays(&self, ctx: &GpuContext) -> Result<u32, RenderError> {
        if self.passes.shadow.is_none() {
            return Ok(0);
        }
        read_count(ctx, &self.resources.shadow_queue)
    }

    /// Probes listed to trace and blend in the next frame (ddgi/probe_states' list): the
    /// vigilant and awake ones, or every probe with `speed.probe_states` off.
    pub fn read_updating_probes(&self, ctx: &GpuContext) -> Result<u32, RenderError> {
        read_count(ctx, &self.resources.active_probes)
    }

    /// How many probes are in each state (003 §6), read back from the GPU.
    pub fn read_state_counts(&self, ctx: &GpuContext) -> Result<ProbeStateCounts, RenderError> {
        let words: Vec<u32> = read_buffer_as(ctx, &self.resources.states)?;
        Ok(ProbeStateCounts::of(
            &words[..self.grid.probe_count as usize],
        ))
    }

    /// The atlases, decoded: irradiance as cosine-weighted mean radiance (rgb), distance as
    /// (mean, mean²); each with its width and height in texels.
    /// Non-finite texels of the atlases as the blends wrote them (soak checks).
    pub fn check_state(&self, ctx: &GpuContext) -> Result<Vec<String>, RenderError> {
        let irradiance: Vec<half::f16> = read_buffer_as(ctx, &self.resources.irradiance)?;
        let distance: Vec<f32> = read_buffer_as(ctx, &self.resources.distance)?;
        Ok([
            non_finite(
                "ddgi irradiance atlas",
                irradiance.iter().map(|h| h.to_f32()),
            ),
            non_finite("ddgi distance atlas", distance.into_iter()),
        ]
        .into_iter()
        .flatten()
        .collect())
    }

    /// Each probe's centre after relocation and whether it updates (vigilant or awake):
    /// where the probe oracle measures it.
    pub fn read_probe_centres(&self, ctx: &GpuContext) -> Result<Vec<(Vec3, bool)>, RenderError> {
        let offsets: Vec<[f32; 4]> = read_buffer_as(ctx, &self.resources.offsets)?;
        let states: Vec<u32> = read_buffer_as(ctx, &self.resources.states)?;
        Ok((0..self.grid.probe_count)
            .map(|p| {
                let offset = Vec3::from_slice(&offsets[p as usize][..3]);
                let state = states[p as usize] & PROBE_STATE_MASK;
                let updates = !self.settings.speed.probe_states
                    || !matches!(state, PROBE_OFF | PROBE_SLEEPING);
                (self.grid.probe_position(p) + offset, updates)
            })
            .collect())
    }

    /// Whether relocation found each probe tied: inside geometry with no single way out
    /// (ddgi/relocate), so that the query counts it at `update.tied_probe_weight`.
    pub fn read_tied_probes(&self, ctx: &GpuContext) -> Result<Vec<bool>, RenderError> {
        let offsets: Vec<[f32; 4]> = read_buffer_as(ctx, &self.resources.offsets)?;
        Ok(offsets.iter().map(|o| o[3] > 0.5).collect())
    }

    /// The atlases as pictures and the probes' places (the viewer's inspector); `label` names
    /// the volume.
    pub fn inspect(
        &self,
        ctx: &GpuContext,
        label: &str,
        out: &mut crate::inspect::Inspection,
    ) -> Result<(), RenderError> {
        use crate::inspect::{
            DebugImage, InspectedProbe, TileLayout, distance_pixel, radiance_pixel,
        };
        let atlases = self.read_atlases(ctx)?;
        let tiles = |texels: u32| TileLayout {
            size: (texels + 2, texels + 2),
            per_row: self.atlas.probes_per_row,
        };
        let v = &self.settings.volume;
        // Distances past a few cells are all "far": the shading only looks that far.
        let far = 4.0 * self.grid.min_spacing();
        let first = out.images.len();
        out.images.push(
            DebugImage::from_texels(
                format!("ddgi/irradiance atlas{label}"),
                atlases.irradiance_size,
                &atlases.irradiance,
                |&rgb| radiance_pixel(rgb),
            )
            .tiled(tiles(v.irradiance_texels)),
        );
        out.images.push(
            DebugImage::from_texels(
                format!("ddgi/distance atlas{label}"),
                atlases.distance_size,
                &atlases.distance,
                |d| distance_pixel(d[0], far),
            )
            .tiled(tiles(v.distance_texels)),
        );
        let radius = 0.1 * self.grid.min_spacing();
        for (tile, (position, _)) in self.read_probe_centres(ctx)?.into_iter().enumerate() {
            out.probes.push(InspectedProbe {
                position,
                radius,
                tile: tile as u32,
                images: (first, 2),
            });
        }
        Ok(())
    }

    /// Reads back the irradiance atlas (decoded to linear) and the distance atlas.
    pub fn read_atlases(&self, ctx: &GpuContext) -> Result<Atlases, RenderError> {
        let packed: Vec<[half::f16; 4]> = read_buffer_as(ctx, &self.resources.irradiance)?;
        let distance: Vec<[f32; 2]> = read_buffer_as(ctx, &self.resources.distance)?;
        let gamma = self.settings.volume.irradiance_gamma;
        let irradiance = packed
            .iter()
            .map(|p| [p[0], p[1], p[2]].map(|c| c.to_f32().max(0.0).powf(gamma)))
            .collect();
        Ok(Atlases {
            irradiance,
            irradiance_size: self.atlas.size(self.settings.volume.irradiance_texels),
            distance,
            distance_size: self.atlas.size(self.settings.volume.distance_texels),
        })
    }
}

/// Decoded probe atlases (see [`DdgiVolume::read_atlases`]).
pub struct Atlases {
    /// Linear irradiance, one RGB a texel, row by row.
    pub irradiance: Vec<[f32; 3]>,
    /// Width and height of the irradiance atlas in texels, borders included.
    pub irradiance_size: (u32, u32),
    /// Distance moments (mean distance, mean squared distance), one a texel, row by row.
    pub distance: Vec<[f32; 2]>,
    /// Width and height of the distance atlas in texels, borders included.
    pub distance_size: (u32, u32),
}

impl Atlases {
    /// The texel-wise mean of several frames' atlases of one volume: the converged value with
    /// the frame-to-frame noise averaged out. None for none.
    pub fn mean(frames: &[Atlases]) -> Option<Atlases> {
        let first = frames.first()?;
        let n = frames.len() as f32;
        let mut mean = Atlases {
            irradiance: vec![[0.0; 3]; first.irradiance.len()],
            irradiance_size: first.irradiance_size,
            distance: vec![[0.0; 2]; first.distance.len()],
            distance_size: first.distance_size,
        };
        for frame in frames {
            for (m, v) in mean.irradiance.iter_mut().zip(&frame.irradiance) {
                (0..3).for_each(|c| m[c] += v[c] / n);
            }
            for (m, v) in mean.distance.iter_mut().zip(&frame.distance) {
                (0..2).for_each(|c| m[c] += v[c] / n);
            }
        }
        Some(mean)
    }
}

/// The count a list buffer starts with (the shadow queue's, the active probes').
fn read_count(ctx: &GpuContext, list: &wgpu::Buffer) -> Result<u32, RenderError> {
    let count = irradiant_gpu::read_buffer(ctx, list, 0, 4)?;
    Ok(u32::from_le_bytes([count[0], count[1], count[2], count[3]]))
}
