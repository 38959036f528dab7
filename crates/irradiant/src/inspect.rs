//! What a technique shows a person of its state: its probe atlases, pyramid levels and voxel
//! grids as pictures, and where its probes are, so that a click on a probe finds its tiles.
//! Read back on request (the viewer's inspector): it waits for the GPU, so no frame reads it.

use glam::Vec3;

/// A picture of one of a technique's textures, encoded for the eye (sRGB, 8 bits).
#[derive(Clone, Debug, PartialEq)]
pub struct DebugImage {
    /// `technique/texture`, with the level or volume (`ddgi/irradiance atlas, volume 0`).
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// RGBA8 texels, row by row.
    pub rgba8: Vec<u8>,
    /// How it holds one tile a probe, for a probe atlas.
    pub tiles: Option<TileLayout>,
}

/// Tiles of one probe each, in rows from the top left, probe by probe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileLayout {
    /// A tile's width and height in texels (borders included).
    pub size: (u32, u32),
    /// Tiles a row.
    pub per_row: u32,
}

/// A probe, as the inspector picks it: where it is drawn and which tile of which images is
/// its own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InspectedProbe {
    /// Its centre (after relocation).
    pub position: Vec3,
    /// The radius its sphere is drawn with (`render --show-probes`).
    pub radius: f32,
    /// Its tile in each tiled image of its volume.
    pub tile: u32,
    /// Index of its volume's first image in [`Inspection::images`], and how many follow.
    pub images: (usize, usize),
}

/// Everything a technique shows of its state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Inspection {
    /// Its textures, as pictures.
    pub images: Vec<DebugImage>,
    /// Its probes (none for a screen-space technique).
    pub probes: Vec<InspectedProbe>,
}

impl DebugImage {
    /// A picture from one value a texel, encoded by `encode`.
    pub fn from_texels<T>(
        name: impl Into<String>,
        (width, height): (u32, u32),
        texels: &[T],
        encode: impl Fn(&T) -> [u8; 4],
    ) -> Self {
        Self {
            name: name.into(),
            width,
            height,
            rgba8: texels.iter().flat_map(encode).collect(),
            tiles: None,
        }
    }

    /// With one tile a probe, as `tiles` lays them out.
    pub fn tiled(self, tiles: TileLayout) -> Self {
        Self {
            tiles: Some(tiles),
            ..self
        }
    }

    /// Probe `tile`'s texels, as a picture of their own (None past the image, or untiled).
    pub fn tile(&self, tile: u32) -> Option<DebugImage> {
        let layout = self.tiles?;
        let (tw, th) = layout.size;
        let (x0, y0) = ((tile % layout.per_row) * tw, (tile / layout.per_row) * th);
        if x0 + tw > self.width || y0 + th > self.height {
            return None;
        }
        let mut rgba8 = Vec::with_capacity((4 * tw * th) as usize);
        for y in y0..y0 + th {
            let row = (4 * (y * self.width + x0)) as usize;
            rgba8.extend_from_slice(&self.rgba8[row..row + 4 * tw as usize]);
        }
        Some(DebugImage {
            name: format!("{}, probe {tile}", self.name),
            width: tw,
            height: th,
            rgba8,
            tiles: None,
        })
    }
}

/// Linear radiance as a pixel: a plain Reinhard curve, sRGB-encoded (as the viewer's radiance
/// views are).
pub fn radiance_pixel(rgb: [f32; 3]) -> [u8; 4] {
    let c = rgb.map(|v| {
        let v = if v.is_finite() { v.max(0.0) } else { 0.0 };
        srgb8(v / (1.0 + v))
    });
    [c[0], c[1], c[2], 255]
}

/// A value of 0…1 as grey (clamped; not finite is black).
pub fn grey_pixel(value: f32) -> [u8; 4] {
    let v = if value.is_finite() { value } else { 0.0 };
    let g = srgb8(v.clamp(0.0, 1.0));
    [g, g, g, 255]
}

/// A unit direction as colour, (n + 1) ÷ 2.
pub fn direction_pixel(n: Vec3) -> [u8; 4] {
    let c = ((n + 1.0) * 0.5 * 255.0 + 0.5).clamp(Vec3::ZERO, Vec3::splat(255.0));
    [c.x as u8, c.y as u8, c.z as u8, 255]
}

/// A distance as grey: near bright, `far` and past it dark.
pub fn distance_pixel(distance: f32, far: f32) -> [u8; 4] {
    grey_pixel(1.0 - distance / far.max(1e-6))
}

fn srgb8(linear: f32) -> u8 {
    let c = if linear <= 0.003_130_8 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    };
    (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tile_is_cut_from_its_place_in_the_atlas() {
        // 3 tiles a row of 2×1 texels, two rows: texel value = its x + 10 y.
        let texels: Vec<u8> = (0..2)
            .flat_map(|y| (0..6).map(move |x| x + 10 * y))
            .collect();
        let image = DebugImage::from_texels("atlas", (6, 2), &texels, |&v| [v, 0, 0, 255]).tiled(
            TileLayout {
                size: (2, 1),
                per_row: 3,
            },
        );
        let tile = image.tile(4).expect("tile 4 is in the second row");
        assert_eq!((tile.width, tile.height), (2, 1));
        assert_eq!(tile.rgba8, vec![12, 0, 0, 255, 13, 0, 0, 255]);
        assert!(image.tile(6).is_none(), "past the atlas");
    }

    #[test]
    fn encodings_are_bounded_and_monotonic() {
        assert_eq!(radiance_pixel([0.0; 3]), [0, 0, 0, 255]);
        assert!(radiance_pixel([1.0; 3])[0] < radiance_pixel([4.0; 3])[0]);
        assert_eq!(radiance_pixel([f32::NAN; 3]), [0, 0, 0, 255]);
        assert_eq!(grey_pixel(2.0), [255, 255, 255, 255]);
        assert!(distance_pixel(1.0, 10.0)[0] > distance_pixel(9.0, 10.0)[0]);
        assert_eq!(direction_pixel(Vec3::X), [255, 128, 128, 255]);
    }
}
