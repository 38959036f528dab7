//! Line plots as SVG documents (plotters' SVG backend): the comparison report's curves over
//! time, and the docs' curves of how cost grows (log axes, `tools/device/growth.sh`).

/// How a curve is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum CurveStyle {
    /// Points joined in the order given: a quantity swept along the x axis.
    #[default]
    Line,
    /// Unjoined dots: separate things (scenes) placed by their x value.
    Points,
}

/// One curve of a plot: a name, its (x, y) points and how they are drawn.
pub struct Curve {
    /// Label of the curve in the legend.
    pub name: String,
    /// The (x, y) points, joined in the order given where the style is a line. On a log axis,
    /// points at zero or below are left out.
    pub points: Vec<(f64, f64)>,
    /// Line or points.
    pub style: CurveStyle,
}

impl Curve {
    /// A curve drawn as a line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
            style: CurveStyle::Line,
        }
    }
}

/// How an axis maps values: linear from zero, or logarithmic over whole decades (for
/// quantities swept over orders of magnitude, where a straight line of slope 1 is linear
/// growth).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// From 0 to the largest value.
    Linear,
    /// Base 10, from the decade below the smallest value to the one above the largest.
    Log,
}

/// A plot's title, axis labels and scales.
pub struct Axes<'a> {
    /// Caption above the plot.
    pub title: &'a str,
    /// Label of the horizontal axis.
    pub x_label: &'a str,
    /// Label of the vertical axis.
    pub y_label: &'a str,
    /// Scale of the horizontal axis.
    pub x: Scale,
    /// Scale of the vertical axis.
    pub y: Scale,
}

/// A line plot with linear axes from zero, for inlining in the report.
pub fn line_plot_svg(title: &str, x_label: &str, y_label: &str, curves: &[Curve]) -> String {
    let axes = Axes {
        title,
        x_label,
        y_label,
        x: Scale::Linear,
        y: Scale::Linear,
    };
    plot_svg(&axes, curves)
}

/// Where a value lands on an axis of `scale`: itself, or its base-10 logarithm (None where it
/// has none).
fn to_axis(value: f64, scale: Scale) -> Option<f64> {
    match scale {
        Scale::Linear => value.is_finite().then_some(value),
        Scale::Log => (value > 0.0 && value.is_finite()).then(|| value.log10()),
    }
}

/// The range an axis spans: linear from 0 to the largest value (with `headroom` above it), or
/// log over whole decades around the values.
fn axis_range(values: impl Iterator<Item = f64>, scale: Scale, headroom: f64) -> (f64, f64) {
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    match scale {
        Scale::Linear => (0.0, if high > 0.0 { high * headroom } else { 1.0 }),
        Scale::Log if low.is_finite() => {
            let (low, high) = (low.floor(), high.ceil());
            (low, if high > low { high } else { low + 1.0 })
        }
        Scale::Log => (0.0, 1.0),
    }
}

/// A tick's label: the value, or on a log axis ten to the tick, with k, M and G for thousands.
fn tick_label(tick: f64, scale: Scale) -> String {
    let value = match scale {
        Scale::Linear => return format!("{tick}"),
        Scale::Log => 10f64.powf(tick),
    };
    let (scaled, suffix) = [(1e9, "G"), (1e6, "M"), (1e3, "k")]
        .into_iter()
        .find(|(unit, _)| value >= *unit)
        .map_or((value, ""), |(unit, s)| (value / unit, s));
    let digits = if scaled >= 10.0 || scaled == scaled.round() {
        0
    } else if scaled >= 1.0 {
        1
    } else {
        2
    };
    format!("{scaled:.digits$}{suffix}")
}

/// A plot of `curves` on `axes` as an SVG document.
pub fn plot_svg(axes: &Axes, curves: &[Curve]) -> String {
    use plotters::prelude::*;
    let placed: Vec<Vec<(f64, f64)>> = curves
        .iter()
        .map(|c| {
            c.points
                .iter()
                .filter_map(|&(x, y)| Some((to_axis(x, axes.x)?, to_axis(y, axes.y)?)))
                .collect()
        })
        .collect();
    let (x_low, x_high) = axis_range(placed.iter().flatten().map(|p| p.0), axes.x, 1.0);
    let (y_low, y_high) = axis_range(placed.iter().flatten().map(|p| p.1), axes.y, 1.1);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (640, 320)).into_drawing_area();
        let _ = root.fill(&WHITE);
        let chart = ChartBuilder::on(&root)
            .caption(axes.title, ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(50)
            .build_cartesian_2d(x_low..x_high, y_low..y_high);
        let Ok(mut chart) = chart else {
            return svg_fallback(axes.title);
        };
        // On a log axis, one label a decade.
        let labels = |scale: Scale, low: f64, high: f64| match scale {
            Scale::Linear => 10,
            Scale::Log => (high - low) as usize + 1,
        };
        let x_format = |v: &f64| tick_label(*v, axes.x);
        let y_format = |v: &f64| tick_label(*v, axes.y);
        let _ = chart
            .configure_mesh()
            .x_desc(axes.x_label)
            .y_desc(axes.y_label)
            .x_labels(labels(axes.x, x_low, x_high))
            .y_labels(labels(axes.y, y_low, y_high))
            .x_label_formatter(&x_format)
            .y_label_formatter(&y_format)
            .draw();
        let palette = [RED, BLUE, GREEN, MAGENTA, CYAN, BLACK];
        for (i, (c, points)) in curves.iter().zip(&placed).enumerate() {
            let color = palette[i % palette.len()];
            let drawn = match c.style {
                CurveStyle::Line => chart.draw_series(LineSeries::new(
                    points.iter().copied(),
                    color.stroke_width(2),
                )),
                CurveStyle::Points => chart.draw_series(
                    points
                        .iter()
                        .map(|&p| Circle::new(p, 4, color.filled()).into_dyn()),
                ),
            };
            if let Ok(series) = drawn {
                series.label(c.name.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2))
                });
            }
        }
        let corner = emptiest_corner(&placed, (x_low, x_high), (y_low, y_high));
        let _ = chart
            .configure_series_labels()
            .position(corner)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw();
        let _ = root.present();
    }
    svg
}

/// The corner of the plot whose quarter (a third of the width, two fifths of the height) holds
/// the fewest points, for the legend, so that it hides as little of the curves as it can.
fn emptiest_corner(
    placed: &[Vec<(f64, f64)>],
    (x_low, x_high): (f64, f64),
    (y_low, y_high): (f64, f64),
) -> plotters::chart::SeriesLabelPosition {
    use plotters::chart::SeriesLabelPosition::*;
    let corners = [
        (UpperRight, true, true),
        (UpperLeft, false, true),
        (LowerRight, true, false),
        (LowerLeft, false, false),
    ];
    let inside = |&(x, y): &(f64, f64), right: bool, upper: bool| {
        let u = (x - x_low) / (x_high - x_low);
        let v = (y - y_low) / (y_high - y_low);
        (if right { u > 0.6 } else { u < 0.4 }) && (if upper { v > 0.6 } else { v < 0.4 })
    };
    corners
        .into_iter()
        .min_by_key(|&(_, right, upper)| {
            placed
                .iter()
                .flatten()
                .filter(|p| inside(p, right, upper))
                .count()
        })
        .map_or(UpperRight, |c| c.0)
}

fn svg_fallback(title: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"40\"><text x=\"10\" y=\"25\">{} (no data)</text></svg>",
        crate::report::escape(title)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plot_is_an_svg_with_a_path_per_curve() {
        let curves = vec![
            Curve::line(
                "ddgi",
                (0..30)
                    .map(|i| (i as f64, 1.0 / (1.0 + i as f64)))
                    .collect(),
            ),
            Curve::line("classic", (0..30).map(|i| (i as f64, 0.5)).collect()),
        ];
        let svg = line_plot_svg("error over time", "frame", "FLIP", &curves);
        assert!(
            svg.starts_with("<svg") && svg.contains("</svg>"),
            "{}",
            &svg[..svg.len().min(200)]
        );
        assert!(
            svg.matches("<polyline").count() + svg.matches("<path").count() >= 2,
            "one line a curve"
        );
        assert!(svg.contains("ddgi") && svg.contains("classic") && svg.contains("error over time"));
    }

    #[test]
    fn a_log_plot_labels_its_decades_and_draws_points_apart_from_lines() {
        let curves = vec![
            Curve::line(
                "instanced",
                vec![(75e3, 1394.0), (1.2e6, 1170.0), (10.8e6, 1129.0)],
            ),
            Curve {
                name: "shipped scenes".into(),
                // The point at zero has no logarithm and is left out.
                points: vec![(36.0, 11563.0), (330e3, 4265.0), (0.0, 1.0)],
                style: CurveStyle::Points,
            },
        ];
        let axes = Axes {
            title: "rays against triangles",
            x_label: "triangles",
            y_label: "Mrays/s",
            x: Scale::Log,
            y: Scale::Log,
        };
        let svg = plot_svg(&axes, &curves);
        let texts: Vec<&str> = svg
            .split('<')
            .filter_map(|t| Some(t.strip_prefix("text")?.split_once('>')?.1.trim()))
            .collect();
        // x spans 10 to 100M, a label a decade; y 1k to 100k.
        for label in ["10", "1k", "100k", "1M", "100M"] {
            assert!(texts.contains(&label), "no tick {label} in {texts:?}");
        }
        assert_eq!(
            svg.matches("<circle").count(),
            2,
            "two scenes drawn as dots"
        );
        assert!(svg.matches("<polyline").count() + svg.matches("<path").count() >= 1);
    }

    #[test]
    fn tick_labels_read_as_numbers() {
        assert_eq!(tick_label(3.0, Scale::Log), "1k");
        assert_eq!(tick_label(7.0, Scale::Log), "10M");
        assert_eq!(tick_label(-1.0, Scale::Log), "0.10");
        assert_eq!(tick_label(2.5, Scale::Log), "316");
        assert_eq!(tick_label(0.5, Scale::Linear), "0.5");
    }
}
