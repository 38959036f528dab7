//! The light field's baked state read back: one probe's maps and every min-mip (tests), and
//! each probe's radiance, normal and distance maps as tiles of three pictures with the probes'
//! places (the viewer's inspector).

use super::{Lightfield, ProbeTexel};
use crate::RenderError;
use irradiant_gpu::GpuContext;

impl Lightfield {
    /// One probe's maps as baked: (radiance rgb, normal, distance) a texel, rows of
    /// `resolution` texels.
    pub fn read_probe(&self, ctx: &GpuContext, probe: u32) -> Result<Vec<ProbeTexel>, RenderError> {
        let res = self.settings.bake.resolution as usize;
        let layer = res * res * 4;
        let at = probe as usize * layer;
        let radiance = irradiant_gpu::read_texture(ctx, &self.resources.maps.radiance.texture, 4)?;
        let geometry = irradiant_gpu::read_texture(ctx, &self.resources.maps.geometry.texture, 4)?;
        let words =
            |bytes: &[u8]| -> Vec<u32> { bytemuck::pod_collect_to_vec(&bytes[at..at + layer]) };
        Ok(words(&radiance)
            .into_iter()
            .zip(words(&geometry))
            .map(|(r, g)| ProbeTexel::unpack(r, g))
            .collect())
    }

    /// Every probe's min-mip, layer after layer: the nearest distance of each 16×16 block.
    pub fn read_min_mip(&self, ctx: &GpuContext) -> Result<Vec<f32>, RenderError> {
        let bytes = irradiant_gpu::read_texture(ctx, &self.resources.maps.low.texture, 4)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// Every probe's baked maps as tiles (radiance, normal, distance; one tile a probe) and
    /// the probes' places (the viewer's inspector).
    pub(super) fn inspect_maps(
        &self,
        ctx: &GpuContext,
    ) -> Result<crate::inspect::Inspection, RenderError> {
        use crate::inspect::{
            DebugImage, InspectedProbe, TileLayout, direction_pixel, distance_pixel, radiance_pixel,
        };
        let res = self.settings.bake.resolution;
        let probes = self.grid.probe_count;
        let per_row = (probes as f32).sqrt().ceil() as u32;
        let rows = probes.div_ceil(per_row);
        let radiance = irradiant_gpu::read_texture(ctx, &self.resources.maps.radiance.texture, 4)?;
        let geometry = irradiant_gpu::read_texture(ctx, &self.resources.maps.geometry.texture, 4)?;
        let radiance: Vec<u32> = bytemuck::pod_collect_to_vec(&radiance);
        let geometry: Vec<u32> = bytemuck::pod_collect_to_vec(&geometry);
        // The layers side by side: texel (x, y) of the atlas is texel (x mod res, y mod res) of
        // probe (y ÷ res) × per_row + x ÷ res.
        let (w, h) = (per_row * res, rows * res);
        let texels: Vec<Option<ProbeTexel>> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                let probe = (y / res) * per_row + x / res;
                (probe < probes).then(|| {
                    let at = (probe * res * res + (y % res) * res + x % res) as usize;
                    ProbeTexel::unpack(radiance[at], geometry[at])
                })
            })
            .collect();
        let far = self.grid.spacing.max_element() * 2.0;
        let tiles = TileLayout {
            size: (res, res),
            per_row,
        };
        let picture = |name: &str, encode: &dyn Fn(&ProbeTexel) -> [u8; 4]| {
            DebugImage::from_texels(format!("lightfield/{name}"), (w, h), &texels, |t| {
                t.as_ref().map_or([0, 0, 0, 255], encode)
            })
            .tiled(tiles)
        };
        let images = vec![
            picture("radiance", &|t| radiance_pixel(t.radiance.to_array())),
            picture("normal", &|t| direction_pixel(t.normal)),
            picture("distance", &|t| distance_pixel(t.distance, far)),
        ];
        let radius = 0.1 * self.grid.min_spacing();
        let probes = (self.probe_positions(ctx)?.into_iter().zip(0..))
            .map(|(position, tile)| InspectedProbe {
                position,
                radius,
                tile,
                images: (0, images.len()),
            })
            .collect();
        Ok(crate::inspect::Inspection { images, probes })
    }
}
