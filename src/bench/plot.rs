//! Log-log plots for the accuracy report, written as SVG by plotters. Text sizes are estimated
//! (no font is loaded) and the viewer renders the text, so the build needs no font stack.
//!
//! An error of exactly 0 has no place on a log axis: such a point is drawn on the bottom edge
//! (one decade below the smallest non-zero value) with an open marker and `= 0` after its
//! label. Negative and non-finite values are left out.

use std::path::Path;

use plotters::prelude::*;

use super::BenchError;

/// One point: its coordinates and the setting it stands for.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Horizontal value (wall time, s, in the speed plots).
    pub x: f64,
    /// Vertical value (|error| in the speed plots).
    pub y: f64,
    /// The setting, written next to the marker.
    pub label: String,
}

/// Points of one study, joined in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// The points.
    pub points: Vec<Point>,
}

/// A log-log plot.
#[derive(Debug, Clone, PartialEq)]
pub struct LogLogPlot {
    /// Caption.
    pub title: String,
    /// Horizontal axis description.
    pub x_label: String,
    /// Vertical axis description.
    pub y_label: String,
    /// One series per study.
    pub series: Vec<Series>,
}

/// A logarithmic axis range in whole decades.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogAxis {
    /// Lower end; exact zeros are drawn here.
    pub low: f64,
    /// Upper end.
    pub high: f64,
}

impl LogAxis {
    /// The decades covering every positive finite value, one more below when a value is exactly
    /// 0 (to draw it apart from the smallest non-zero one). Without positive values: `[0.1, 1]`.
    pub fn covering(values: impl IntoIterator<Item = f64>) -> Self {
        let (mut min, mut max, mut zero) = (f64::INFINITY, 0.0_f64, false);
        for v in values {
            if v.is_finite() && v > 0.0 {
                min = min.min(v);
                max = max.max(v);
            }
            zero |= v == 0.0;
        }
        if max <= 0.0 {
            return Self {
                low: 0.1,
                high: 1.0,
            };
        }
        let low = 10f64.powf(min.log10().floor());
        let mut high = 10f64.powf(max.log10().ceil());
        // A single value on a power of ten would give an empty range.
        if high <= low {
            high = low * 10.0;
        }
        Self {
            low: if zero { low / 10.0 } else { low },
            high,
        }
    }

    fn widened(&self) -> std::ops::Range<f64> {
        self.low * (1.0 - 1e-9)..self.high * (1.0 + 1e-9)
    }

    /// Where `v` lies between the ends, 0 to 1 on the log scale.
    fn fraction(&self, v: f64) -> f64 {
        (v / self.low).ln() / (self.high / self.low).ln()
    }

    /// Where `v` is drawn: itself if positive, the lower end if exactly 0, nowhere otherwise.
    pub fn place(&self, v: f64) -> Option<f64> {
        if v.is_finite() && v > 0.0 {
            Some(v)
        } else if v == 0.0 {
            Some(self.low)
        } else {
            None
        }
    }
}

/// Colours of the series, in order (then repeated).
const COLOURS: [RGBColor; 6] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x8c, 0x56, 0x4b),
];

/// The corner whose legend-sized box (about 40% x 35% of the plot) covers the fewest points,
/// upper right first on a tie.
fn legend_corner(points: &[(f64, f64)], x: LogAxis, y: LogAxis) -> SeriesLabelPosition {
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ];
    let covered = |right: bool, upper: bool| {
        points
            .iter()
            .filter(|&&(px, py)| {
                let (fx, fy) = (x.fraction(px), y.fraction(py));
                (if right { fx > 0.6 } else { fx < 0.4 })
                    && (if upper { fy > 0.65 } else { fy < 0.35 })
            })
            .count()
    };
    corners
        .into_iter()
        .min_by_key(|&(_, right, upper)| covered(right, upper))
        .map_or(SeriesLabelPosition::UpperRight, |(corner, ..)| corner)
}

fn scientific(v: &f64) -> String {
    format!("{v:.0e}")
}

/// The drawable points of `series` placed on the axes: coordinates, whether the value is an
/// exact 0 (drawn on the bottom edge), and the label to write, which then says `= 0`.
fn placed(series: &Series, x_axis: LogAxis, y_axis: LogAxis) -> Vec<(f64, f64, bool, String)> {
    series
        .points
        .iter()
        .filter_map(|p| {
            let (x, y) = (x_axis.place(p.x)?, y_axis.place(p.y)?);
            let zero = p.y == 0.0;
            let text = if zero {
                format!("{} = 0", p.label)
            } else {
                p.label.clone()
            };
            Some((x, y, zero, text))
        })
        .collect()
}

impl LogLogPlot {
    /// Writes the plot to `path` as SVG; returns how many points were drawn.
    pub fn write_svg(&self, path: &Path) -> Result<usize, BenchError> {
        let all = || self.series.iter().flat_map(|s| s.points.iter());
        let x_axis = LogAxis::covering(all().map(|p| p.x));
        let y_axis = LogAxis::covering(all().map(|p| p.y));
        let fail = |source| BenchError::Plot {
            path: path.to_owned(),
            source,
        };

        let drawable: Vec<(f64, f64)> = all()
            .filter_map(|p| Some((x_axis.place(p.x)?, y_axis.place(p.y)?)))
            .collect();
        let legend = legend_corner(&drawable, x_axis, y_axis);
        // Widened by a hair so rounding cannot drop the decade at either end from the ticks.
        let (x_range, y_range) = (x_axis.widened(), y_axis.widened());

        let root = SVGBackend::new(path, (760, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(fail)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 18))
            .margin(12)
            // Room for the labels of the rightmost points.
            .margin_right(48)
            .x_label_area_size(42)
            .y_label_area_size(64)
            .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())
            .map_err(fail)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&scientific)
            .y_label_formatter(&scientific)
            .draw()
            .map_err(fail)?;

        let mut drawn = 0;
        for (i, series) in self.series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            // Labels above the markers, every other series below, so coinciding points stay
            // readable.
            let label_dy = if i % 2 == 0 { -14 } else { 6 };
            let placed = placed(series, x_axis, y_axis);
            drawn += placed.len();
            chart
                .draw_series(LineSeries::new(
                    placed.iter().map(|&(x, y, ..)| (x, y)),
                    colour.stroke_width(2),
                ))
                .map_err(fail)?
                .label(&series.name)
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 4), (x + 14, y + 4)], colour.filled())
                });
            chart
                .draw_series(placed.iter().map(|(x, y, zero, text)| {
                    let marker = if *zero {
                        colour.stroke_width(2)
                    } else {
                        colour.filled()
                    };
                    EmptyElement::at((*x, *y))
                        + Circle::new((0, 0), 4, marker)
                        + Text::new(text.clone(), (6, label_dy), ("sans-serif", 12).into_font())
                }))
                .map_err(fail)?;
        }
        chart
            .configure_series_labels()
            .position(legend)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(fail)?;
        root.present().map_err(fail)?;
        Ok(drawn)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a / b - 1.0).abs() < 1e-12
    }

    fn point(x: f64, y: f64, label: &str) -> Point {
        Point {
            x,
            y,
            label: label.to_owned(),
        }
    }

    #[test]
    fn axis_covers_whole_decades_of_the_positive_values() {
        let axis = LogAxis::covering([3e-4, 2e-2, 0.5]);
        assert!(close(axis.low, 1e-4) && close(axis.high, 1.0), "{axis:?}");
    }

    #[test]
    fn exact_zero_gets_its_own_decade_at_the_bottom_and_negatives_are_ignored() {
        let axis = LogAxis::covering([0.0, 3e-4, -5.0, f64::NAN, 2e-2]);
        assert!(close(axis.low, 1e-5) && close(axis.high, 1e-1), "{axis:?}");
        assert_eq!(axis.place(0.0), Some(axis.low));
        assert_eq!(axis.place(3e-4), Some(3e-4));
        assert_eq!(axis.place(-5.0), None);
        assert_eq!(axis.place(f64::NAN), None);
    }

    #[test]
    fn degenerate_ranges_stay_drawable() {
        // Nothing positive: a default decade, zeros on its floor.
        let axis = LogAxis::covering([0.0, 0.0, -1.0]);
        assert!(axis.low > 0.0 && axis.high > axis.low, "{axis:?}");
        assert_eq!(axis.place(0.0), Some(axis.low));
        // One value on a power of ten.
        let axis = LogAxis::covering([1e-3]);
        assert!(axis.low <= 1e-3 && axis.high > 1e-3, "{axis:?}");
    }

    #[test]
    fn legend_avoids_the_points() {
        let axis = LogAxis {
            low: 1e-3,
            high: 1.0,
        };
        let upper_right = [(0.9, 0.9), (0.5, 0.8)];
        assert!(matches!(
            legend_corner(&upper_right, axis, axis),
            SeriesLabelPosition::UpperLeft
        ));
        assert!(matches!(
            legend_corner(&[], axis, axis),
            SeriesLabelPosition::UpperRight
        ));
    }

    #[test]
    fn svg_has_one_marker_per_drawable_point() {
        let dir = std::env::temp_dir().join(format!("tribosim-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("plot.svg");
        let plot = LogLogPlot {
            title: "test".into(),
            x_label: "wall time, s".into(),
            y_label: "|error|".into(),
            series: vec![
                Series {
                    name: "grid".into(),
                    points: vec![
                        point(0.01, 1e-3, "64"),
                        point(0.1, 1e-4, "128"),
                        point(1.0, 0.0, "256"),
                    ],
                },
                Series {
                    name: "tolerance".into(),
                    points: vec![point(0.05, 2e-5, "1e-8"), point(0.02, f64::NAN, "none")],
                },
            ],
        };
        let drawn = plot.write_svg(&path).expect("written");
        let svg = std::fs::read_to_string(&path).expect("readable");
        std::fs::remove_dir_all(&dir).expect("cleaned up");
        assert_eq!(drawn, 4, "the NaN point is left out");
        assert!(svg.trim_start().starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert_eq!(svg.matches("<circle").count(), 4);
        assert!(svg.contains("256 = 0"), "the exact zero is labelled");
        let text = |t: &str| svg.lines().any(|l| l.trim() == t);
        assert!(text("grid") && text("tolerance"), "legend");
    }
}
