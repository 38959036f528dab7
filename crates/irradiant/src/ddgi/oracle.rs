//! The oracles that split DDGI's error in two (issue 15, docs/ddgi.md "Oracles").
//!
//! - The **probe oracle** measures the update — rays, shading, bounces, encoding, hysteresis:
//!   the path tracer computes what every probe texel should hold (the cosine-weighted mean
//!   radiance in its direction at the probe's relocated centre, the atlas's E/π; the mean and
//!   mean square of the hit distance under the distance blend's cos^exponent weights) and
//!   compares the converged atlases with it.
//! - The **query oracle** measures the rest — trilinear interpolation, backface weights,
//!   Chebyshev visibility, bias: the path tracer's indirect irradiance at the G-buffer's points
//!   against DDGI's resolve there.

use glam::{UVec2, Vec3};
use irradiant_gpu::GpuContext;
use irradiant_scene::Region;

use super::Ddgi;
use super::volume::{Atlases, DdgiVolume};
use crate::frame::{GBufferSample, Image};
use crate::pathtrace::gather::luminance;
use crate::pathtrace::{GatherKind, GatherQuery, PathTraceSettings, gather};
use crate::probes::octahedral::texel_direction;
use crate::scene::GpuScene;
use crate::{RenderError, Session};

/// A texel's relative error is taken against at least this share of the volume's mean truth:
/// texels that face a black wall would otherwise turn a speck of noise into a huge ratio.
const ERROR_FLOOR: f32 = 0.02;

/// Edges of the histogram of per-probe errors: 5 % bins from −50 % to +50 %, and one bin
/// beyond each end.
pub const HISTOGRAM_STEP: f32 = 0.05;
/// Bins on each side of zero between the two open-ended bins.
pub const HISTOGRAM_HALF_BINS: i32 = 10;

/// One probe, measured.
#[derive(Clone, Debug)]
pub struct ProbeError {
    /// Its index in the volume.
    pub probe: u32,
    /// Its world position after relocation, where the truth was gathered.
    pub centre: Vec3,
    /// Σ DDGI ÷ Σ truth − 1 over the probe's irradiance texels (luminance): negative is dark.
    pub signed: f32,
    /// Median over its texels of |DDGI − truth| ÷ truth.
    pub texel_median: f32,
    /// Median over its distance texels of |DDGI mean − true mean| ÷ true mean.
    pub distance_median: f32,
}

/// A whole volume, measured by the probe oracle.
#[derive(Clone, Debug)]
pub struct ProbeOracle {
    /// Every updating probe (sleeping and switched-off ones are not read by the query). With
    /// none, the errors below are NaN.
    pub probes: Vec<ProbeError>,
    /// Probes not measured: those that do not update (sleeping or off).
    pub skipped_probes: u32,
    /// Probes relocation found tied (`DdgiVolume::read_tied_probes`), measured or not.
    pub tied_probes: u32,
    /// Interior texels a side of a probe's irradiance tile.
    pub irradiance_texels: u32,
    /// Interior texels a side of a probe's distance tile.
    pub distance_texels: u32,
    /// Per probe compared, its irradiance texels in row order: (DDGI, truth), linear rgb.
    pub irradiance: Vec<Vec<([f32; 3], [f32; 3])>>,
    /// Median over every compared texel of |DDGI − truth| ÷ truth (luminance).
    pub median_texel_error: f32,
    /// Σ DDGI ÷ Σ truth − 1 over every compared texel: the volume's overall bias.
    pub signed_error: f32,
    /// Median relative error of the distance texels' mean.
    pub median_distance_error: f32,
    /// Median of the truth's own standard error ÷ truth: how precise the oracle is.
    pub truth_precision: f32,
    /// Probes in each histogram bin of `signed` (see [`ProbeOracle::histogram_bin`]).
    pub histogram: Vec<u32>,
}

impl ProbeOracle {
    /// The histogram bin of a per-probe error, and each bin's range (`f32::INFINITY` ends).
    /// A probe whose truth is black reads a huge error (÷ 1e-12): the steps are clamped as
    /// floats, before the cast, so that it lands in the last bin instead of overflowing.
    pub fn histogram_bin(signed: f32) -> usize {
        let outer = (HISTOGRAM_HALF_BINS + 1) as f32;
        let steps = (signed / HISTOGRAM_STEP).floor().clamp(-outer, outer);
        let bin = steps as i32 + HISTOGRAM_HALF_BINS + 1;
        bin.clamp(0, 2 * HISTOGRAM_HALF_BINS + 1) as usize
    }

    /// The range of signed errors that bin `bin` holds, [low, high); the end bins are open.
    pub fn histogram_range(bin: usize) -> (f32, f32) {
        let edge = |b: i32| {
            if b <= 0 {
                f32::NEG_INFINITY
            } else if b > 2 * HISTOGRAM_HALF_BINS + 1 {
                f32::INFINITY
            } else {
                (b - HISTOGRAM_HALF_BINS - 1) as f32 * HISTOGRAM_STEP
            }
        };
        (edge(bin as i32), edge(bin as i32 + 1))
    }

    /// The `count` probes furthest from the truth (by |signed|), worst first.
    pub fn worst(&self, count: usize) -> Vec<&ProbeError> {
        let mut sorted: Vec<&ProbeError> = self.probes.iter().collect();
        sorted.sort_by(|a, b| b.signed.abs().total_cmp(&a.signed.abs()));
        sorted.truncate(count);
        sorted
    }
}

/// Renders `frames` frames of a DDGI session, then `average` more, and returns the mean of the
/// first volume's atlases over those last frames (the probe oracle's DDGI side).
pub fn converged_atlases(
    session: &mut Session,
    frames: u32,
    average: u32,
) -> Result<Atlases, RenderError> {
    for _ in 0..frames {
        session.render()?;
    }
    let mut read = Vec::new();
    for _ in 0..average.max(1) {
        session.render()?;
        let ddgi = session.technique_as::<Ddgi>().ok_or_else(|| {
            RenderError::Settings("the probe oracle measures DDGI: pick a ddgi technique".into())
        })?;
        read.push(ddgi.volume().read_atlases(session.ctx())?);
    }
    Ok(Atlases::mean(&read).expect("at least one frame was read"))
}

/// The queries of the probe oracle for the probes that update: every irradiance texel (cosine
/// lobe) then every distance texel (the distance blend's lobe), probe after probe.
fn probe_queries(volume: &DdgiVolume, centres: &[(Vec3, bool)]) -> Vec<GatherQuery> {
    let settings = volume.settings();
    let (irradiance_texels, distance_texels) = (
        settings.volume.irradiance_texels,
        settings.volume.distance_texels,
    );
    let lobe = |texels: u32, exponent: f32, kind: GatherKind, centre: Vec3| {
        (0..texels * texels).map(move |t| GatherQuery {
            origin: centre,
            axis: texel_direction(UVec2::new(t % texels, t / texels), texels),
            exponent,
            kind,
            on_surface: false,
        })
    };
    let distance = GatherKind::Distance {
        far: volume.max_ray_distance(),
    };
    centres
        .iter()
        .filter(|(_, updates)| *updates)
        .flat_map(|&(centre, _)| {
            lobe(irradiance_texels, 1.0, GatherKind::Radiance, centre).chain(lobe(
                distance_texels,
                settings.update.distance_exponent,
                distance,
                centre,
            ))
        })
        .collect()
}

/// Runs the probe oracle on `volume`: the truth by `settings.samples_per_pixel` samples a texel
/// against `atlases` (the volume's, read after convergence; averaged over frames by the
/// caller if it wants the noise out).
pub fn probe_oracle(
    ctx: &GpuContext,
    scene: &GpuScene,
    volume: &DdgiVolume,
    atlases: &Atlases,
    settings: &PathTraceSettings,
    progress: impl FnMut(u32, u32),
) -> Result<ProbeOracle, RenderError> {
    let centres = volume.read_probe_centres(ctx)?;
    let truth = gather(
        ctx,
        scene,
        &probe_queries(volume, &centres),
        settings,
        progress,
    )?;
    let v = &volume.settings().volume;
    let (it, dt) = (v.irradiance_texels, v.distance_texels);
    let per_probe = (it * it + dt * dt) as usize;
    let mut probes = Vec::new();
    let mut irradiance = Vec::new();
    let mut distances = Vec::new();
    let mut precision = Vec::new();
    for (slot, (probe, &(centre, _))) in centres
        .iter()
        .enumerate()
        .filter(|(_, (_, updates))| *updates)
        .enumerate()
    {
        let probe = probe as u32;
        let base = slot * per_probe;
        let atlas_texel = |texels: u32, t: u32| {
            let (x, y) = volume
                .atlas
                .texel(probe, texels, t % texels + 1, t / texels + 1);
            (y * volume.atlas.size(texels).0 + x) as usize
        };
        let texels: Vec<([f32; 3], [f32; 3])> = (0..it * it)
            .map(|t| {
                (
                    atlases.irradiance[atlas_texel(it, t)],
                    truth.radiance(base + t as usize),
                )
            })
            .collect();
        precision.extend((0..it * it).map(|t| {
            let i = base + t as usize;
            (
                truth.luminance_standard_error(i),
                luminance(truth.radiance(i)),
            )
        }));
        distances.push(
            (0..dt * dt)
                .map(|t| {
                    let ddgi = atlases.distance[atlas_texel(dt, t)][0];
                    let true_mean = truth.distance_moments(base + (it * it + t) as usize)[0];
                    ((ddgi - true_mean) / true_mean.max(1e-6)).abs()
                })
                .collect::<Vec<f32>>(),
        );
        probes.push(ProbeError {
            probe,
            centre,
            signed: 0.0,
            texel_median: 0.0,
            distance_median: 0.0,
        });
        irradiance.push(texels);
    }
    let mut oracle = summarize(
        probes,
        irradiance,
        distances,
        &precision,
        centres.len() as u32,
        (it, dt),
    );
    oracle.tied_probes = volume.read_tied_probes(ctx)?.iter().filter(|&&t| t).count() as u32;
    Ok(oracle)
}

/// The statistics of a probe oracle run from its per-texel values (separate from the GPU work
/// so that the arithmetic is tested on its own).
fn summarize(
    mut probes: Vec<ProbeError>,
    irradiance: Vec<Vec<([f32; 3], [f32; 3])>>,
    distances: Vec<Vec<f32>>,
    precision: &[(f32, f32)],
    probe_count: u32,
    (irradiance_texels, distance_texels): (u32, u32),
) -> ProbeOracle {
    let all_truth: Vec<f32> = irradiance
        .iter()
        .flatten()
        .map(|(_, t)| luminance(*t))
        .collect();
    let floor = ERROR_FLOOR * all_truth.iter().sum::<f32>() / all_truth.len().max(1) as f32;
    let floor = floor.max(1e-12);
    let relative = |(d, t): &([f32; 3], [f32; 3])| {
        ((luminance(*d) - luminance(*t)) / luminance(*t).max(floor)).abs()
    };
    let mut all_errors = Vec::new();
    let (mut sum_ddgi, mut sum_truth) = (0.0f64, 0.0f64);
    for ((probe, texels), distance) in probes.iter_mut().zip(&irradiance).zip(&distances) {
        let ddgi: f64 = texels.iter().map(|(d, _)| luminance(*d) as f64).sum();
        let truth: f64 = texels.iter().map(|(_, t)| luminance(*t) as f64).sum();
        sum_ddgi += ddgi;
        sum_truth += truth;
        probe.signed = (ddgi / truth.max(1e-12) - 1.0) as f32;
        let errors: Vec<f32> = texels.iter().map(relative).collect();
        probe.texel_median = median(errors.clone());
        probe.distance_median = median(distance.clone());
        all_errors.extend(errors);
    }
    let none = if probes.is_empty() { f32::NAN } else { 0.0 };
    let mut histogram = vec![0; (2 * HISTOGRAM_HALF_BINS + 2) as usize];
    for p in &probes {
        histogram[ProbeOracle::histogram_bin(p.signed)] += 1;
    }
    ProbeOracle {
        skipped_probes: probe_count - probes.len() as u32,
        tied_probes: 0,
        median_texel_error: median(all_errors) + none,
        signed_error: (sum_ddgi / sum_truth.max(1e-12) - 1.0) as f32 + none,
        median_distance_error: median(distances.into_iter().flatten().collect()) + none,
        truth_precision: median(
            precision
                .iter()
                .map(|(error, truth)| error / truth.max(floor))
                .collect(),
        ),
        probes,
        irradiance,
        irradiance_texels,
        distance_texels,
        histogram,
    }
}

/// The median (the upper one of an even count); 0 for none.
pub fn median(mut values: Vec<f32>) -> f32 {
    if values.is_empty() {
        return 0.0;
    }
    let middle = values.len() / 2;
    *values.select_nth_unstable_by(middle, f32::total_cmp).1
}

/// DDGI's indirect light against the truth at the G-buffer's points.
#[derive(Clone, Debug)]
pub struct QueryOracle {
    /// Per pixel (DDGI − truth) ÷ truth of the indirect diffuse light's luminance; NaN where
    /// no surface is seen or the surface reflects no diffuse light.
    pub error: Vec<f32>,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The truth's indirect diffuse light (diffuse weight × E/π) at each pixel.
    pub truth: Image,
    /// Median |error| over the measured pixels.
    pub median_error: f32,
    /// Shares of the measured pixels more than twice as bright as the truth, and under half
    /// of it: specks and blotches.
    pub specks: (f32, f32),
    /// Σ DDGI ÷ Σ truth − 1 over the measured pixels.
    pub signed_error: f32,
    /// (region, DDGI mean, truth mean) of indirect luminance over the pixels inside each region.
    pub regions: Vec<(String, f32, f32)>,
}

/// Runs the query oracle: `indirect` is DDGI's indirect light (the frame's indirect channel,
/// diffuse weight × DDGI's irradiance), `gbuffer` the same frame's G-buffer.
pub fn query_oracle(
    ctx: &GpuContext,
    scene: &GpuScene,
    gbuffer: &[GBufferSample],
    indirect: &Image,
    regions: &[Region],
    settings: &PathTraceSettings,
    progress: impl FnMut(u32, u32),
) -> Result<QueryOracle, RenderError> {
    let measured = measured_pixels(gbuffer);
    let queries: Vec<GatherQuery> = measured
        .iter()
        .map(|&i| GatherQuery {
            origin: Vec3::from(gbuffer[i].position),
            axis: Vec3::from(gbuffer[i].normal),
            exponent: 1.0,
            kind: GatherKind::Radiance,
            on_surface: true,
        })
        .collect();
    let truth = gather(ctx, scene, &queries, settings, progress)?;
    let mut truth_image = Image {
        width: indirect.width,
        height: indirect.height,
        pixels: vec![[0.0; 3]; gbuffer.len()],
    };
    for (k, &i) in measured.iter().enumerate() {
        let e = truth.radiance(k);
        truth_image.pixels[i] = [0, 1, 2].map(|c| gbuffer[i].diffuse[c] * e[c]);
    }
    Ok(compare_with_truth(indirect, &truth_image, gbuffer, regions))
}

/// The pixels the query oracle measures: a surface that reflects diffuse light.
fn measured_pixels(gbuffer: &[GBufferSample]) -> Vec<usize> {
    (0..gbuffer.len())
        .filter(|&i| gbuffer[i].depth >= 0.0 && luminance(gbuffer[i].diffuse) > 0.0)
        .collect()
}

/// The query oracle against a truth already gathered for this G-buffer (another variant's
/// [`QueryOracle::truth`]: the truth does not depend on the technique).
pub fn compare_with_truth(
    indirect: &Image,
    truth: &Image,
    gbuffer: &[GBufferSample],
    regions: &[Region],
) -> QueryOracle {
    let measured = &measured_pixels(gbuffer)[..];
    let ddgi = |i: usize| luminance(indirect.pixels[i]);
    let true_value = |i: usize| luminance(truth.pixels[i]);
    let mean_truth =
        measured.iter().map(|&i| true_value(i)).sum::<f32>() / measured.len().max(1) as f32;
    let floor = (ERROR_FLOOR * mean_truth).max(1e-12);
    let mut error = vec![f32::NAN; gbuffer.len()];
    for &i in measured {
        error[i] = (ddgi(i) - true_value(i)) / true_value(i).max(floor);
    }
    let total = |f: &dyn Fn(usize) -> f32, pixels: &[usize]| {
        pixels.iter().map(|&i| f(i) as f64).sum::<f64>()
    };
    let regions = regions
        .iter()
        .filter_map(|r| {
            let inside: Vec<usize> = measured
                .iter()
                .copied()
                .filter(|&i| {
                    let p = Vec3::from(gbuffer[i].position);
                    p.cmpge(r.min).all() && p.cmple(r.max).all()
                })
                .collect();
            let n = inside.len() as f64;
            (n > 0.0).then(|| {
                (
                    r.name.clone(),
                    (total(&ddgi, &inside) / n) as f32,
                    (total(&true_value, &inside) / n) as f32,
                )
            })
        })
        .collect();
    let share = |test: fn(f32) -> bool| {
        measured.iter().filter(|&&i| test(error[i])).count() as f32 / measured.len().max(1) as f32
    };
    QueryOracle {
        specks: (share(|e| e > 1.0), share(|e| e < -0.5)),
        median_error: median(measured.iter().map(|&i| error[i].abs()).collect()),
        signed_error: (total(&ddgi, measured) / total(&true_value, measured).max(1e-12) - 1.0)
            as f32,
        error,
        width: indirect.width,
        height: indirect.height,
        truth: truth.clone(),
        regions,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn probe(signed: f32) -> ProbeError {
        ProbeError {
            probe: 0,
            centre: Vec3::ZERO,
            signed,
            texel_median: 0.0,
            distance_median: 0.0,
        }
    }

    #[test]
    fn a_probe_a_tenth_dark_reads_minus_ten_percent_and_lands_in_its_bin() {
        let grey = |v: f32| [v; 3];
        let texels = vec![(grey(0.9), grey(1.0)), (grey(1.8), grey(2.0))];
        let oracle = summarize(
            vec![probe(0.0)],
            vec![texels],
            vec![vec![0.1, 0.3, 0.2]],
            &[(0.01, 1.0), (0.02, 2.0)],
            3,
            (1, 1),
        );
        let p = &oracle.probes[0];
        assert!((p.signed + 0.1).abs() < 1e-5, "{}", p.signed);
        assert!((oracle.median_texel_error - 0.1).abs() < 1e-5);
        assert!((p.distance_median - 0.2).abs() < 1e-6);
        assert_eq!(oracle.skipped_probes, 2);
        let bin = ProbeOracle::histogram_bin(p.signed);
        assert_eq!(oracle.histogram[bin], 1);
        let (lo, hi) = ProbeOracle::histogram_range(bin);
        assert!(
            lo <= p.signed && p.signed < hi && (hi - lo - HISTOGRAM_STEP).abs() < 1e-6,
            "{lo} {hi}"
        );
        assert_eq!(ProbeOracle::histogram_range(0).0, f32::NEG_INFINITY);
        assert_eq!(ProbeOracle::histogram_bin(5.0), oracle.histogram.len() - 1);
        // A black truth (a few samples a texel, all dark) reads 1e12: the last bin, no overflow.
        for huge in [1e12, f32::MAX, f32::INFINITY] {
            assert_eq!(ProbeOracle::histogram_bin(huge), oracle.histogram.len() - 1);
            assert_eq!(ProbeOracle::histogram_bin(-huge), 0);
        }
    }

    #[test]
    fn a_black_texel_does_not_blow_up_the_median() {
        let texels = vec![
            ([1.0; 3], [1.0; 3]),
            ([1.0; 3], [1.0; 3]),
            ([0.001; 3], [0.0; 3]),
        ];
        let oracle = summarize(
            vec![probe(0.0)],
            vec![texels],
            vec![vec![0.0]],
            &[],
            1,
            (1, 1),
        );
        assert_eq!(oracle.median_texel_error, 0.0);
        // Against the floor (2 % of the mean truth 0.667), not against zero.
        assert!(oracle.probes[0].signed.is_finite());
    }
}
