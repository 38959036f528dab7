//! Linear RGB images and their files: EXR keeps the linear values, PNG the tonemapped ones.

use std::path::Path;

use crate::RenderError;

/// Linear RGB radiance, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// One linear RGB value a pixel, row by row: `width × height` of them.
    pub pixels: Vec<[f32; 3]>,
}

impl Image {
    /// The mean of every pixel, per channel (zero for an empty image).
    pub fn mean(&self) -> [f64; 3] {
        let mut sum = [0f64; 3];
        for p in &self.pixels {
            for c in 0..3 {
                sum[c] += p[c] as f64;
            }
        }
        sum.map(|s| s / self.pixels.len().max(1) as f64)
    }

    /// sRGB8 RGB through the same exposure and curve as `frame/tonemap` (its CPU twin), for
    /// metrics such as FLIP that compare display values.
    pub fn to_srgb8(&self, exposure: f32, filmic: bool) -> Vec<u8> {
        let aces =
            |x: f32| ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0);
        let srgb = |c: f32| {
            if c <= 0.0031308 {
                c * 12.92
            } else {
                1.055 * c.powf(1.0 / 2.4) - 0.055
            }
        };
        self.pixels
            .iter()
            .flat_map(|p| {
                p.map(|v| {
                    let v = (v * exposure).max(0.0);
                    let v = if filmic { aces(v) } else { v.min(1.0) };
                    (srgb(v) * 255.0 + 0.5) as u8
                })
            })
            .collect()
    }

    /// Writes the linear values as OpenEXR, atomically.
    pub fn write_exr(&self, path: &Path) -> Result<(), RenderError> {
        let data: Vec<f32> = self.pixels.iter().flatten().copied().collect();
        let image = image::Rgb32FImage::from_raw(self.width, self.height, data)
            .expect("pixel count matches size");
        write_atomically(path, |temporary| {
            image
                .save_with_format(temporary, image::ImageFormat::OpenExr)
                .map_err(|e| e.to_string())
        })
    }

    /// Reads an OpenEXR file (a cache entry that a crashed or concurrent run may have left in
    /// any state). Its header is checked before anything is decoded (`check_exr_header`):
    /// with `expected`, a file of other dimensions is refused; sides past 16384 or more than
    /// 4 GiB decoded are refused in any case.
    pub fn read_exr(path: &Path, expected: Option<(u32, u32)>) -> Result<Self, RenderError> {
        let error = |e: String| RenderError::Input(path.to_owned(), e);
        check_exr_header(path, expected).map_err(error)?;
        let file = std::fs::File::open(path).map_err(|e| error(e.to_string()))?;
        let mut reader = image::ImageReader::with_format(
            std::io::BufReader::new(file),
            image::ImageFormat::OpenExr,
        );
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(16384);
        limits.max_image_height = Some(16384);
        limits.max_alloc = Some(4 << 30);
        reader.limits(limits);
        let image = reader
            .decode()
            .map_err(|e| error(e.to_string()))?
            .to_rgb32f();
        Ok(Self {
            width: image.width(),
            height: image.height(),
            pixels: image.pixels().map(|p| p.0).collect(),
        })
    }
}

/// Refuses, from its header alone, an OpenEXR file that is not what the caller expects
/// (`expected`: every layer's pixel size) or that claims more than a file can be: sides past
/// 16384, or more chunks than the file has bytes for (its offset table alone takes 8 bytes a
/// chunk). The decoder allocates what the header claims before reading a byte of pixels, and
/// damaged cache entries of under 1 KiB made it take 1.6 GB and seconds (found by fuzzing).
fn check_exr_header(path: &Path, expected: Option<(u32, u32)>) -> Result<(), String> {
    let length = std::fs::metadata(path).map_err(|e| e.to_string())?.len();
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| e.to_string())?;
    let chunks: u64 = meta.headers.iter().map(|h| h.chunk_count as u64).sum();
    if chunks.saturating_mul(8) > length {
        return Err(format!(
            "its header claims {chunks} chunks of pixels, more than a file of {length} bytes holds"
        ));
    }
    for header in meta.headers.iter() {
        let (width, height) = (header.layer_size.0, header.layer_size.1);
        if let Some((w, h)) = expected
            && (width, height) != (w as usize, h as usize)
        {
            return Err(format!("it is {width}×{height}, not the {w}×{h} expected"));
        }
        if width > 16384 || height > 16384 {
            return Err(format!(
                "its header claims {width}×{height} pixels, past 16384 a side"
            ));
        }
    }
    Ok(())
}

/// Writes packed sRGB RGBA8 bytes as a PNG, atomically: a half-written file never appears
/// under the name.
pub fn write_png(path: &Path, rgba8: &[u8], width: u32, height: u32) -> Result<(), RenderError> {
    write_atomically(path, |temporary| {
        image::save_buffer_with_format(
            temporary,
            rgba8,
            width,
            height,
            image::ExtendedColorType::Rgba8,
            image::ImageFormat::Png,
        )
        .map_err(|e| e.to_string())
    })
}

/// Runs `write` into a temporary file beside `path`, then renames it into place.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), RenderError> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default();
    // The temporary keeps the extension: the image crate picks the format from it. Its name
    // is this write's alone (process and a count), so that threads storing one entry at once
    // never write into each other's file.
    static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let write_number = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let temporary = path.with_file_name(format!(
        ".{name}.{}-{write_number}.partial.{extension}",
        std::process::id()
    ));
    let result = write(&temporary)
        .and_then(|()| std::fs::rename(&temporary, path).map_err(|e| e.to_string()));
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    result.map_err(|e| RenderError::Output(path.to_owned(), e))
}
