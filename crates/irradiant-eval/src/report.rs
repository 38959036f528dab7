//! The comparison lab's report: one self-contained HTML page (images inline, no server, no
//! external files) and the data behind it, which is also written as JSON.

use base64::prelude::{BASE64_STANDARD, Engine};
use serde::Serialize;

use crate::plot::{Curve, line_plot_svg};

/// Everything measured for one technique against the reference.
#[derive(Clone, Debug, Serialize)]
pub struct TechniqueResult {
    /// The technique's label as compared, settings included (`ssil{visibility = false}`).
    pub technique: String,
    /// Mean FLIP error against the reference (see [`Flip`](crate::Flip)).
    pub flip_mean: f32,
    /// 95th percentile of the per-pixel FLIP error.
    pub flip_p95: f32,
    /// PSNR against the reference over linear RGB, in dB (see [`psnr`](crate::psnr)).
    pub psnr_db: f64,
    /// Relative MSE against the reference (see [`relative_mse`](crate::relative_mse)).
    pub relative_mse: f64,
    /// Mean indirect luminance in each named region: (region, technique, reference).
    pub regions: Vec<(String, f64, f64)>,
    /// GPU milliseconds per pass of the last frame (label, ms).
    pub passes: Vec<(String, f64)>,
    /// PNG file of the technique's image, relative to the report.
    pub image: String,
    /// PNG file of its FLIP error map (magma colours), relative to the report.
    pub error_map: String,
    /// Its difference from another technique of the comparison (`--difference-from`).
    pub difference: Option<DifferenceResult>,
}

/// One technique's image against another's: what a change of technique or setting does.
#[derive(Clone, Debug, Serialize)]
pub struct DifferenceResult {
    /// The technique subtracted.
    pub from: String,
    /// Mean luminance difference, this − from.
    pub mean: f64,
    /// Mean absolute luminance difference, |this − from|.
    pub mean_abs: f64,
    /// |Δ luminance| at which the map saturates.
    pub scale: f32,
    /// PNG file: orange where this is brighter, blue where darker.
    pub image: String,
}

/// A whole comparison: the scene, the path-traced reference and each technique measured
/// against it. Serialised as the report's JSON; [`html`] renders it.
#[derive(Clone, Debug, Serialize)]
pub struct Comparison {
    /// Name of the scene compared.
    pub scene: String,
    /// Width of every image, in pixels.
    pub width: u32,
    /// Height of every image, in pixels.
    pub height: u32,
    /// Name of the GPU adapter the comparison ran on.
    pub adapter: String,
    /// Samples per pixel of the path-traced reference.
    pub reference_spp: u32,
    /// Indirect bounces the reference follows; None: every bounce (full global illumination).
    pub reference_indirect_bounces: Option<u32>,
    /// PNG file of the reference, relative to the report.
    pub reference_image: String,
    /// Whether the reference came from the cache.
    pub reference_cached: bool,
    /// Frames each real-time technique ran before its image was taken.
    pub frames: u32,
    /// One result a technique, in the order compared.
    pub results: Vec<TechniqueResult>,
    /// Over time, for animated scenes (`--over-time`).
    pub over_time: Vec<TimeSeries>,
}

/// One technique through an animation: per sampled frame the FLIP against a reference of that
/// frame, per frame the flicker (mean absolute luminance change from the previous frame).
#[derive(Clone, Debug, Serialize)]
pub struct TimeSeries {
    /// The technique's label, as in [`TechniqueResult::technique`].
    pub technique: String,
    /// (frame, FLIP mean against that frame's reference)
    pub error: Vec<(u32, f32)>,
    /// (frame, mean |Δ luminance| from the previous frame)
    pub flicker: Vec<(u32, f64)>,
    /// Frame of the first large lighting change, if any.
    pub change_frame: Option<u32>,
    /// Frames after it until the error is back under `lag_bound`; None if it never is.
    pub lag_frames: Option<u32>,
    /// The FLIP under which the error counts as recovered (`--lag-bound`).
    pub lag_bound: f32,
    /// Frames in which a probe window stepped (techniques with windows that follow).
    pub window_steps: Vec<u32>,
}

impl TimeSeries {
    /// The mean flicker of the frames `k` frames after the last window step, for k from 0 to
    /// `most` (the last: `most` or more), with how many frames each holds: a step that shows
    /// stands out at its k. Frames before the first step are left out.
    pub fn flicker_since_step(&self, most: u32) -> Vec<(u32, f64, usize)> {
        let mut sums = vec![(0.0, 0usize); most as usize + 1];
        for &(frame, change) in &self.flicker {
            let Some(step) = self.window_steps.iter().rev().find(|&&s| s <= frame) else {
                continue;
            };
            let k = (frame - step).min(most) as usize;
            sums[k].0 += change;
            sums[k].1 += 1;
        }
        sums.into_iter()
            .enumerate()
            .map(|(k, (sum, n))| (k as u32, if n > 0 { sum / n as f64 } else { 0.0 }, n))
            .collect()
    }
}

pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The HTML page. `png` gives the bytes of each image the comparison names.
pub fn html(c: &Comparison, png: &dyn Fn(&str) -> Vec<u8>) -> String {
    let img = |file: &str, alt: &str| {
        format!(
            "<img src=\"data:image/png;base64,{}\" alt=\"{}\">",
            BASE64_STANDARD.encode(png(file)),
            escape(alt)
        )
    };
    let mut s = String::new();
    s.push_str("<!doctype html><html><head><meta charset=\"utf-8\"><title>Irradiant comparison: ");
    s.push_str(&escape(&c.scene));
    s.push_str("</title><style>body{font-family:sans-serif;margin:2em;background:#fafafa}table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}th{background:#eee}.grid{display:flex;flex-wrap:wrap;gap:12px}.grid figure{margin:0}img{image-rendering:pixelated;max-width:100%}</style></head><body>");
    s.push_str(&format!(
        "<h1>{}</h1><p>{}×{} on {}; reference: path tracer, {} samples per pixel, {}{}; real-time techniques after {} frames.</p>",
        escape(&c.scene),
        c.width,
        c.height,
        escape(&c.adapter),
        c.reference_spp,
        match c.reference_indirect_bounces {
            None => "every bounce".to_string(),
            Some(1) => "one indirect bounce".to_string(),
            Some(n) => format!("{n} indirect bounces"),
        },
        if c.reference_cached { " (from the cache)" } else { "" },
        c.frames
    ));
    s.push_str("<h2>Figures</h2><table id=\"figures\"><tr><th>technique</th><th>FLIP mean</th><th>FLIP p95</th><th>PSNR dB</th><th>relative MSE</th>");
    let regions: Vec<&String> = c
        .results
        .first()
        .map(|r| r.regions.iter().map(|x| &x.0).collect())
        .unwrap_or_default();
    for r in &regions {
        s.push_str(&format!("<th>indirect in {} (reference)</th>", escape(r)));
    }
    s.push_str("<th>GPU ms, last frame</th></tr>");
    for r in &c.results {
        s.push_str(&format!("<tr><td style=\"text-align:left\">{}</td><td>{:.4}</td><td>{:.4}</td><td>{:.2}</td><td>{:.5}</td>", escape(&r.technique), r.flip_mean, r.flip_p95, r.psnr_db, r.relative_mse));
        for (_, t, reference) in &r.regions {
            s.push_str(&format!("<td>{t:.5} ({reference:.5})</td>"));
        }
        s.push_str(&format!(
            "<td>{:.3}</td></tr>",
            r.passes.iter().map(|p| p.1).sum::<f64>()
        ));
    }
    s.push_str("</table><h2>Images</h2><div class=\"grid\">");
    s.push_str(&format!(
        "<figure>{}<figcaption>reference (path tracer)</figcaption></figure>",
        img(&c.reference_image, "reference")
    ));
    for r in &c.results {
        s.push_str(&format!(
            "<figure>{}<figcaption>{}</figcaption></figure>",
            img(&r.image, &r.technique),
            escape(&r.technique)
        ));
    }
    s.push_str("</div><h2>FLIP error maps</h2><div class=\"grid\">");
    for r in &c.results {
        s.push_str(&format!(
            "<figure>{}<figcaption>{} (mean {:.4})</figcaption></figure>",
            img(&r.error_map, &format!("{} error", r.technique)),
            escape(&r.technique),
            r.flip_mean
        ));
    }
    s.push_str("</div>");
    let differences: Vec<(&TechniqueResult, &DifferenceResult)> = c
        .results
        .iter()
        .filter_map(|r| r.difference.as_ref().map(|d| (r, d)))
        .collect();
    if let Some((_, first)) = differences.first() {
        s.push_str(&format!(
            "<h2>Differences from {}</h2><p>Luminance of each technique minus that of {}: orange where it is brighter, blue where darker, full colour at the |Δ| given (the 99th percentile).</p><div class=\"grid\">",
            escape(&first.from),
            escape(&first.from)
        ));
        for (r, d) in differences {
            s.push_str(&format!(
                "<figure>{}<figcaption>{} − {}: mean {:+.5}, mean |Δ| {:.5}, full colour at {:.4}</figcaption></figure>",
                img(&d.image, &format!("{} minus {}", r.technique, d.from)),
                escape(&r.technique),
                escape(&d.from),
                d.mean,
                d.mean_abs,
                d.scale
            ));
        }
        s.push_str("</div>");
    }
    s.push_str("<h2>GPU time per pass (last frame, ms)</h2><table id=\"passes\"><tr><th>technique</th><th>pass</th><th>ms</th></tr>");
    for r in &c.results {
        for (label, ms) in &r.passes {
            s.push_str(&format!("<tr><td style=\"text-align:left\">{}</td><td style=\"text-align:left\">{}</td><td>{ms:.3}</td></tr>", escape(&r.technique), escape(label)));
        }
    }
    s.push_str("</table>");
    if !c.over_time.is_empty() {
        s.push_str("<h2>Over time</h2><table id=\"lag\"><tr><th>technique</th><th>light change at frame</th><th>lag (frames until the error is back under its bound)</th><th>bound (FLIP)</th><th>mean flicker</th></tr>");
        for t in &c.over_time {
            let flicker =
                t.flicker.iter().map(|f| f.1).sum::<f64>() / t.flicker.len().max(1) as f64;
            s.push_str(&format!(
                "<tr><td style=\"text-align:left\">{}</td><td>{}</td><td>{}</td><td>{:.4}</td><td>{:.5}</td></tr>",
                escape(&t.technique),
                t.change_frame.map_or("–".into(), |f| f.to_string()),
                t.lag_frames.map_or("never".into(), |f| f.to_string()),
                t.lag_bound,
                flicker
            ));
        }
        s.push_str("</table><div class=\"plots\">");
        let error: Vec<Curve> = c
            .over_time
            .iter()
            .map(|t| {
                let points = t.error.iter().map(|&(f, e)| (f as f64, e as f64));
                Curve::line(t.technique.clone(), points.collect())
            })
            .collect();
        s.push_str(&line_plot_svg(
            "FLIP against each frame's reference",
            "frame",
            "FLIP mean",
            &error,
        ));
        let flicker: Vec<Curve> = c
            .over_time
            .iter()
            .map(|t| {
                let points = t.flicker.iter().map(|&(f, v)| (f as f64, v));
                Curve::line(t.technique.clone(), points.collect())
            })
            .collect();
        s.push_str(&line_plot_svg(
            "flicker: mean |Δ luminance| from the previous frame",
            "frame",
            "|Δ|",
            &flicker,
        ));
        s.push_str("</div>");
    }
    // Marks the page once loaded with how many images decoded and how many plots there are,
    // so that a headless browser can check the report as a person would see it.
    s.push_str("<script>window.addEventListener('load',function(){var n=0;for(var i=0;i<document.images.length;i++){var m=document.images[i];if(m.complete&&m.naturalWidth>0){n++;}}document.body.setAttribute('data-images-loaded',String(n));document.body.setAttribute('data-plots',String(document.querySelectorAll('svg').length));});</script>");
    s.push_str("</body></html>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_inlines_every_image_and_escapes_names() {
        let result = TechniqueResult {
            technique: "ddgi <full>".into(),
            flip_mean: 0.1,
            flip_p95: 0.2,
            psnr_db: 30.0,
            relative_mse: 0.01,
            regions: vec![("dark-room".into(), 0.07, 0.069)],
            passes: vec![("ddgi/trace".into(), 1.5)],
            image: "ddgi.png".into(),
            error_map: "ddgi-flip.png".into(),
            difference: Some(DifferenceResult {
                from: "none".into(),
                mean: 0.02,
                mean_abs: 0.03,
                scale: 0.1,
                image: "ddgi-minus-none.png".into(),
            }),
        };
        let c = Comparison {
            scene: "two-rooms".into(),
            width: 4,
            height: 4,
            adapter: "test".into(),
            reference_spp: 64,
            reference_indirect_bounces: Some(1),
            reference_image: "reference.png".into(),
            reference_cached: false,
            frames: 10,
            results: vec![result],
            over_time: vec![TimeSeries {
                technique: "ddgi".into(),
                error: vec![(0, 0.1), (4, 0.3), (8, 0.1)],
                flicker: vec![(1, 0.01), (2, 0.02)],
                window_steps: Vec::new(),
                change_frame: Some(4),
                lag_frames: Some(4),
                lag_bound: 0.125,
            }],
        };
        let page = html(&c, &|name| name.as_bytes().to_vec());
        assert_eq!(page.matches("data:image/png;base64,").count(), 4);
        assert!(page.contains("one indirect bounce"));
        assert!(page.contains("Differences from none") && page.contains("mean +0.02000"));
        assert!(page.contains("ddgi &lt;full&gt;") && !page.contains("<full>"));
        assert!(page.contains("dark-room") && page.contains("ddgi/trace"));
        assert_eq!(
            page.matches("<svg").count(),
            2,
            "an error plot and a flicker plot"
        );
    }

    /// Frames are grouped by how long ago the last window step was; those before the first
    /// step, and none at a k, count nowhere.
    #[test]
    fn flicker_is_grouped_by_frames_since_the_last_step() {
        let series = TimeSeries {
            technique: "ddgi".into(),
            error: Vec::new(),
            flicker: (1..=9).map(|f| (f, f as f64)).collect(),
            window_steps: vec![3, 5],
            change_frame: None,
            lag_frames: None,
            lag_bound: 0.1,
        };
        // Frame 3 and 5 are steps (k 0), 4 and 6 one after (k 1), 7 two after, 8 and 9 three
        // or more (k 3 with most 3); 1 and 2 come before the first step.
        assert_eq!(
            series.flicker_since_step(3),
            vec![(0, 4.0, 2), (1, 5.0, 2), (2, 7.0, 1), (3, 8.5, 2)]
        );
        assert_eq!(series.flicker_since_step(5)[4], (4, 9.0, 1));
        assert_eq!(series.flicker_since_step(5)[5], (5, 0.0, 0));
    }
}
