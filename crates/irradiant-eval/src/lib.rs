//! Image metrics for comparing a technique with the path-traced reference: FLIP (NVIDIA's
//! perceptual difference, through nv-flip), PSNR and relative MSE.
//!
//! Images are plain slices so that this crate needs no GPU: linear RGB radiance for PSNR and
//! relative MSE, tonemapped sRGB8 for FLIP (nv-flip implements LDR-FLIP). [`report`] turns a
//! comparison into a self-contained HTML page, [`plot`] curves into SVG.

#![warn(missing_docs)]

pub mod plot;
pub mod report;

/// Why two images cannot be compared.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum MetricError {
    /// The images differ in size: width and height of the first, then of the second. Not
    /// returned by the functions here, which see only slice lengths and report
    /// [`WrongLength`](Self::WrongLength) instead.
    #[error("the images differ in size: {0}×{1} against {2}×{3}; render both at the same --size")]
    SizeMismatch(u32, u32, u32, u32),
    /// A slice's length does not fit the image. [`flip`] checks each slice against
    /// `width`×`height`; [`psnr`], [`relative_mse`] and [`difference`] check the test slice
    /// against the reference's length, reported as an image of that many pixels × 1.
    #[error("an image of {width}×{height} needs {expected} values, got {got}")]
    WrongLength {
        /// Width of the image, in pixels.
        width: u32,
        /// Height of the image, in pixels.
        height: u32,
        /// Length the slice needs: bytes for [`flip`] (3 a pixel), pixels for the others.
        expected: usize,
        /// Length of the slice, in the same unit.
        got: usize,
    },
}

/// FLIP of a test image against a reference: the per-pixel error map (0…1) and its pooled
/// statistics.
#[derive(Clone, Debug)]
pub struct Flip {
    /// Mean of the per-pixel errors, FLIP's one-number score (0: identical).
    pub mean: f32,
    /// 95th percentile of the per-pixel errors: where the worst regions stand.
    pub p95: f32,
    /// The per-pixel error, 0…1, one value a pixel, row by row.
    pub error_map: Vec<f32>,
    /// The error map through FLIP's magma colour map, RGB8, for reports.
    pub error_map_rgb8: Vec<u8>,
}

/// LDR-FLIP of two sRGB8 RGB images of `width`×`height`, at the default viewing distance
/// (67 pixels per degree: a 0.7 m wide 4K monitor at 0.7 m).
pub fn flip(
    reference_srgb8: &[u8],
    test_srgb8: &[u8],
    width: u32,
    height: u32,
) -> Result<Flip, MetricError> {
    let expected = 3 * width as usize * height as usize;
    for got in [reference_srgb8.len(), test_srgb8.len()] {
        if got != expected {
            return Err(MetricError::WrongLength {
                width,
                height,
                expected,
                got,
            });
        }
    }
    let reference = nv_flip::FlipImageRgb8::with_data(width, height, reference_srgb8);
    let test = nv_flip::FlipImageRgb8::with_data(width, height, test_srgb8);
    let map = nv_flip::flip(reference, test, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mut pool = nv_flip::FlipPool::from_image(&map);
    Ok(Flip {
        mean: pool.mean(),
        p95: pool.get_percentile(0.95, false),
        error_map_rgb8: map.apply_color_lut(&nv_flip::magma_lut()).to_vec(),
        error_map: map.to_vec(),
    })
}

fn check(a: &[[f32; 3]], b: &[[f32; 3]]) -> Result<(), MetricError> {
    if a.len() != b.len() {
        return Err(MetricError::WrongLength {
            width: a.len() as u32,
            height: 1,
            expected: a.len(),
            got: b.len(),
        });
    }
    Ok(())
}

/// Peak signal-to-noise ratio in dB over linear RGB, with the reference's maximum as the peak
/// (HDR images have no fixed peak). Infinite for identical images.
pub fn psnr(reference: &[[f32; 3]], test: &[[f32; 3]]) -> Result<f64, MetricError> {
    check(reference, test)?;
    let peak = reference
        .iter()
        .flatten()
        .fold(0f32, |m, v| m.max(*v))
        .max(1e-12) as f64;
    let mse = reference
        .iter()
        .flatten()
        .zip(test.iter().flatten())
        .map(|(r, t)| ((r - t) as f64).powi(2))
        .sum::<f64>()
        / (3 * reference.len()).max(1) as f64;
    Ok(if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (peak * peak / mse).log10()
    })
}

/// Relative MSE: mean over pixels and channels of (t − r)² / (r² + ε), ε = 0.01, the form
/// used in rendering papers so that dark pixels do not dominate.
pub fn relative_mse(reference: &[[f32; 3]], test: &[[f32; 3]]) -> Result<f64, MetricError> {
    check(reference, test)?;
    let sum: f64 = reference
        .iter()
        .flatten()
        .zip(test.iter().flatten())
        .map(|(r, t)| ((t - r) as f64).powi(2) / ((*r as f64).powi(2) + 0.01))
        .sum();
    Ok(sum / (3 * reference.len()).max(1) as f64)
}

/// One image's signed difference from another, in luminance: what a change of settings adds
/// (warm colours) or removes (blue), for reports.
#[derive(Clone, Debug)]
pub struct Difference {
    /// Mean of (test − base) luminance.
    pub mean: f64,
    /// Mean of |test − base| luminance.
    pub mean_abs: f64,
    /// |Δ luminance| that saturates the map: the 99th percentile of |Δ|, so that a few hot
    /// pixels do not wash the rest out.
    pub scale: f32,
    /// RGB8: black where equal, orange where `test` is brighter, blue where it is darker.
    pub map_rgb8: Vec<u8>,
}

/// The signed luminance difference `test` − `base` of two linear RGB images.
pub fn difference(base: &[[f32; 3]], test: &[[f32; 3]]) -> Result<Difference, MetricError> {
    check(base, test)?;
    let lum = |c: &[f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    let delta: Vec<f32> = base
        .iter()
        .zip(test)
        .map(|(b, t)| lum(t) - lum(b))
        .collect();
    let mut magnitudes: Vec<f32> = delta.iter().map(|d| d.abs()).collect();
    magnitudes.sort_by(f32::total_cmp);
    let scale = magnitudes
        .get(magnitudes.len() * 99 / 100)
        .copied()
        .unwrap_or(0.0)
        .max(1e-6);
    let map_rgb8 = delta
        .iter()
        .flat_map(|&d| {
            let v = (d.abs() / scale).min(1.0);
            let byte = |x: f32| (x * 255.0).round() as u8;
            if d >= 0.0 {
                [byte(v), byte(0.55 * v), 0]
            } else {
                [0, byte(0.45 * v), byte(v)]
            }
        })
        .collect();
    let n = delta.len().max(1) as f64;
    Ok(Difference {
        mean: delta.iter().map(|&d| d as f64).sum::<f64>() / n,
        mean_abs: delta.iter().map(|&d| d.abs() as f64).sum::<f64>() / n,
        scale,
        map_rgb8,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_difference_is_signed_and_scaled_to_its_99th_percentile() {
        let base = vec![[0.5f32; 3]; 100];
        let mut test = base.clone();
        test[0] = [1.5; 3];
        for p in &mut test[1..50] {
            *p = [0.25; 3];
        }
        let d = difference(&base, &test).unwrap();
        assert!(
            (d.mean - (1.0 - 49.0 * 0.25) / 100.0).abs() < 1e-5,
            "{}",
            d.mean
        );
        assert!((d.mean_abs - (1.0 + 49.0 * 0.25) / 100.0).abs() < 1e-5);
        assert!(
            (d.scale - 1.0).abs() < 1e-5,
            "the largest |Δ| is the 99th percentile of 100: {}",
            d.scale
        );
        assert_eq!(&d.map_rgb8[0..3], &[255, 140, 0], "brighter: orange");
        assert_eq!(
            &d.map_rgb8[3..6],
            &[0, 29, 64],
            "darker by a quarter of the scale: blue"
        );
        assert_eq!(&d.map_rgb8[150..153], &[0, 0, 0], "equal: black");
        assert!(difference(&base, &test[..10]).is_err());
    }

    #[test]
    fn identical_images_have_no_error() {
        let img: Vec<u8> = (0..16 * 16 * 3).map(|i| (i * 7 % 251) as u8).collect();
        let f = flip(&img, &img, 16, 16).unwrap();
        assert!(f.mean < 1e-6 && f.p95 < 1e-6);
        let lin: Vec<[f32; 3]> = (0..64).map(|i| [i as f32 / 64.0; 3]).collect();
        assert_eq!(psnr(&lin, &lin).unwrap(), f64::INFINITY);
        assert_eq!(relative_mse(&lin, &lin).unwrap(), 0.0);
    }

    #[test]
    fn larger_differences_score_worse() {
        let base = vec![128u8; 32 * 32 * 3];
        let small: Vec<u8> = base.iter().map(|v| v + 10).collect();
        let large: Vec<u8> = base.iter().map(|v| v + 100).collect();
        let (fs, fl) = (
            flip(&base, &small, 32, 32).unwrap(),
            flip(&base, &large, 32, 32).unwrap(),
        );
        assert!(
            fs.mean > 0.0 && fl.mean > fs.mean,
            "{} {}",
            fs.mean,
            fl.mean
        );
        assert_eq!(fl.error_map_rgb8.len(), 32 * 32 * 3);
        let r = vec![[0.5f32; 3]; 100];
        let a: Vec<[f32; 3]> = r.iter().map(|p| p.map(|v| v * 1.1)).collect();
        let b: Vec<[f32; 3]> = r.iter().map(|p| p.map(|v| v * 1.5)).collect();
        assert!(psnr(&r, &a).unwrap() > psnr(&r, &b).unwrap());
        let (ra, rb) = (relative_mse(&r, &a).unwrap(), relative_mse(&r, &b).unwrap());
        assert!((ra - 0.0025 / 0.26).abs() < 1e-6 && rb > ra);
    }

    #[test]
    fn mismatched_sizes_are_errors() {
        assert!(matches!(
            flip(&[0; 12], &[0; 12], 3, 3),
            Err(MetricError::WrongLength { .. })
        ));
        assert!(psnr(&[[0.0; 3]; 2], &[[0.0; 3]; 3]).is_err());
    }
}
