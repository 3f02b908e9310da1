//! The report's line figures as inline SVG, drawn by plotters into a string (its SVG
//! backend estimates text sizes, so no font is loaded): lines, markers with error bars,
//! a grey reference and rings that flag points, every series in its own colour and with a
//! legend sample drawn as the series is.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::prelude::*;
use thiserror::Error;

use super::html::escape;
use super::palette::series_colours;
use super::ticks::Ticks;

/// The figures' drawing size, px: a 1.73 aspect that, scaled to the 180 mm of A4's
/// printable width, is 104 mm tall, so two fit a page with their captions.
const SIZE: (u32, u32) = (760, 440);

/// The reference lines' grey, the grid's and the flags' black.
const GREY: RGBColor = RGBColor(90, 90, 90);
const GRID: RGBColor = RGBColor(225, 225, 225);

/// Why a figure could not be drawn.
#[derive(Debug, Error)]
#[error("drawing the figure `{title}`: {source}")]
pub struct FigureError {
    /// The figure's title.
    pub title: String,
    /// What plotters reported.
    pub source: DrawingAreaErrorKind<std::io::Error>,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A line through the points.
    Line,
    /// A line through the points with a dot on each: a few discrete values (a study's
    /// members), where a lone point would otherwise draw nothing.
    Joined,
    /// A dashed grey line, for a reference (the ball, E_corr).
    Reference,
    /// A marker at each point (measured values), with its spread as an error bar; each
    /// marker series of a figure has its own shape as well as its own colour, so points
    /// that coincide stay apart.
    Markers,
    /// A black ring around each point: points whose numbers carry a caveat.
    Flagged,
}

/// One series of a line figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend's entry.
    pub name: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Each point's spread (half the error bar), 0 for none; as long as `points`.
    pub spread: Vec<f64>,
    /// How it is drawn.
    pub style: Style,
}

impl Series {
    /// A series of `points` named `name`, drawn in `style`, its non-finite points left out.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        Self::measured(
            name,
            points.into_iter().map(|(x, y)| (x, y, None)).collect(),
        )
        .with_style(style)
    }

    /// Measured points `(x, y, spread)`, drawn as markers with error bars where a spread
    /// is given; non-finite points are left out, and a non-finite spread counts as none.
    pub fn measured(name: impl Into<String>, points: Vec<(f64, f64, Option<f64>)>) -> Self {
        let (points, spread) = points
            .into_iter()
            .filter(|(x, y, _)| x.is_finite() && y.is_finite())
            .map(|(x, y, s)| ((x, y), s.filter(|s| s.is_finite()).map_or(0.0, f64::abs)))
            .unzip();
        Self {
            name: name.into(),
            points,
            spread,
            style: Style::Markers,
        }
    }

    fn with_style(self, style: Style) -> Self {
        Self { style, ..self }
    }

    /// The points' extent with their error bars: `(x, low y, high y)`.
    fn extent(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        self.points
            .iter()
            .zip(&self.spread)
            .map(|(&(x, y), &s)| (x, y - s, y + s))
    }
}

/// A figure of lines and markers on linear axes.
#[derive(Debug, Clone, PartialEq)]
pub struct LineFigure {
    /// The caption under the figure.
    pub title: String,
    /// The horizontal axis in words, with its unit.
    pub x_label: String,
    /// The vertical axis in words, with its unit.
    pub y_label: String,
    /// The series; those without points are left out.
    pub series: Vec<Series>,
}

/// `[low, high]` covering `values` with 5% to spare at each end; a single value gets a
/// range around it.
fn range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !low.is_finite() || !high.is_finite() {
        return None;
    }
    let spare = if high > low {
        0.05 * (high - low)
    } else {
        0.05 * low.abs().max(1e-12)
    };
    Some((low - spare, high + spare))
}

/// A linear axis whose key points are its [`Ticks`]: plotters' own numeric axis picks
/// ticks that the labels' shared decimals cannot be matched to, and light lines between
/// them that drown the data in print.
#[derive(Debug, Clone)]
struct Axis {
    low: f64,
    high: f64,
    ticks: Ticks,
}

impl Axis {
    fn of((low, high): (f64, f64)) -> Self {
        Self {
            low,
            high,
            ticks: Ticks::of(low, high),
        }
    }
}

impl Ranged for Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let f = (value - self.low) / (self.high - self.low);
        limit.0 + (f * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            return Vec::new();
        }
        self.ticks.values.clone()
    }

    fn range(&self) -> Range<f64> {
        self.low..self.high
    }
}

/// The chart the series are drawn on.
type Chart<'a> = ChartContext<'a, SVGBackend<'a>, Cartesian2d<Axis, Axis>>;
type Drawn = Result<(), DrawingAreaErrorKind<std::io::Error>>;

impl LineFigure {
    /// The figure as an SVG element, or `None` when it has no point to draw.
    pub fn svg(&self) -> Result<Option<String>, FigureError> {
        let all = || self.series.iter().flat_map(Series::extent);
        let x = range(all().map(|p| p.0));
        let y = range(all().flat_map(|p| [p.1, p.2]));
        let (Some(x), Some(y)) = (x, y) else {
            return Ok(None);
        };
        let mut svg = String::new();
        self.draw(&mut svg, x, y).map_err(|source| FigureError {
            title: self.title.clone(),
            source,
        })?;
        Ok(Some(svg))
    }

    /// Draws the figure into `svg`; the error is the SVG backend's, whose own error is an
    /// [`std::io::Error`].
    fn draw(&self, svg: &mut String, x: (f64, f64), y: (f64, f64)) -> Drawn {
        let root = SVGBackend::with_string(svg, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let (x_axis, y_axis) = (Axis::of(x), Axis::of(y));
        let (x_ticks, y_ticks) = (x_axis.ticks.clone(), y_axis.ticks.clone());
        let mut chart = ChartBuilder::on(&root)
            .margin(14)
            .x_label_area_size(44)
            .y_label_area_size(78)
            .build_cartesian_2d(x_axis, y_axis)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&|v| x_ticks.label(*v))
            .y_label_formatter(&|v| y_ticks.label(*v))
            .bold_line_style(GRID)
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 16))
            .draw()?;
        let drawn: Vec<&Series> = self
            .series
            .iter()
            .filter(|s| !s.points.is_empty())
            .collect();
        let coloured = drawn
            .iter()
            .filter(|s| matches!(s.style, Style::Line | Style::Joined | Style::Markers))
            .count();
        let mut colours = series_colours(coloured).into_iter();
        let mut shapes = 0..;
        for series in drawn {
            match series.style {
                Style::Line | Style::Joined | Style::Markers => {
                    let (r, g, b) = colours.next().unwrap_or_default();
                    let colour = RGBColor(r, g, b);
                    match series.style {
                        Style::Markers => {
                            markers(&mut chart, series, colour, shapes.next().unwrap_or(0))?;
                        }
                        style => line(&mut chart, series, colour, style == Style::Joined)?,
                    }
                }
                Style::Reference => reference(&mut chart, series)?,
                Style::Flagged => flags(&mut chart, series)?,
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .label_font(("sans-serif", 15))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()?;
        root.present()
    }
}

/// A solid line, with a dot on each point when `dotted`; its legend sample a short
/// stretch of it.
fn line<'a>(chart: &mut Chart<'a>, series: &Series, colour: RGBColor, dotted: bool) -> Drawn {
    let style = colour.stroke_width(2);
    let drawn = chart.draw_series(LineSeries::new(series.points.iter().copied(), style))?;
    if dotted {
        drawn.label(&series.name).legend(move |(x, y)| {
            EmptyElement::at((x, y))
                + PathElement::new(vec![(0, 0), (18, 0)], style)
                + Circle::new((9, 0), 3, colour.filled())
        });
        chart.draw_series(
            series
                .points
                .iter()
                .map(|&p| Circle::new(p, 3, colour.filled())),
        )?;
    } else {
        drawn
            .label(&series.name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
    }
    Ok(())
}

/// A dashed grey line, its legend sample two dashes.
fn reference<'a>(chart: &mut Chart<'a>, series: &Series) -> Drawn {
    let style = GREY.stroke_width(1);
    chart
        .draw_series(DashedLineSeries::new(series.points.clone(), 6, 4, style))?
        .label(&series.name)
        .legend(move |(x, y)| {
            EmptyElement::at((x, y))
                + PathElement::new(vec![(0, 0), (7, 0)], style)
                + PathElement::new(vec![(11, 0), (18, 0)], style)
        });
    Ok(())
}

/// Hollow markers of the `shape`th shape, over error bars where the points have a spread;
/// the legend's sample is the marker.
fn markers<'a>(chart: &mut Chart<'a>, series: &Series, colour: RGBColor, shape: usize) -> Drawn {
    let style = colour.stroke_width(2);
    let bars = series
        .points
        .iter()
        .zip(&series.spread)
        .filter(|(_, s)| **s > 0.0)
        .map(|(&(x, y), &s)| {
            ErrorBar::new_vertical(x, y - s, y, y + s, colour.stroke_width(1), 10)
        });
    chart.draw_series(bars)?;
    let points = series.points.iter().copied();
    let drawn = match shape % 4 {
        0 => chart.draw_series(points.map(|p| Circle::new(p, 5, style)))?,
        1 => chart.draw_series(
            points.map(|p| EmptyElement::at(p) + Rectangle::new([(-4, -4), (4, 4)], style)),
        )?,
        2 => chart.draw_series(points.map(|p| TriangleMarker::new(p, 6, style)))?,
        _ => chart.draw_series(points.map(|p| Cross::new(p, 5, style)))?,
    };
    let label = drawn.label(&series.name);
    match shape % 4 {
        0 => label.legend(move |(x, y)| Circle::new((x + 9, y), 5, style)),
        1 => label.legend(move |(x, y)| Rectangle::new([(x + 5, y - 4), (x + 13, y + 4)], style)),
        2 => label.legend(move |(x, y)| TriangleMarker::new((x + 9, y), 6, style)),
        _ => label.legend(move |(x, y)| Cross::new((x + 9, y), 5, style)),
    };
    Ok(())
}

/// A black ring around each point, drawn over the series it flags.
fn flags<'a>(chart: &mut Chart<'a>, series: &Series) -> Drawn {
    let style = BLACK.stroke_width(2);
    chart
        .draw_series(series.points.iter().map(|&p| Circle::new(p, 9, style)))?
        .label(&series.name)
        .legend(move |(x, y)| Circle::new((x + 9, y), 7, style));
    Ok(())
}

/// A figure element: the SVG and its caption, or the caption and why nothing is drawn.
pub fn figure(svg: Option<&str>, caption: &str, empty: &str) -> String {
    match svg {
        Some(svg) => format!(
            "<figure>{svg}<figcaption>{}</figcaption></figure>\n",
            escape(caption)
        ),
        None => format!(
            "<figure class=\"empty\"><figcaption>{}: {}</figcaption></figure>\n",
            escape(caption),
            escape(empty)
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_figure_is_an_svg_that_scales_to_the_page() {
        let figure = LineFigure {
            title: "volume".into(),
            x_label: "cycles".into(),
            y_label: "mm^3".into(),
            series: vec![
                Series::new(
                    "model",
                    vec![(1.0, 1.0), (2.0, 4.0), (3.0, f64::NAN)],
                    Style::Line,
                ),
                Series::new("measured", vec![(2.0, 3.5)], Style::Markers),
            ],
        };
        assert_eq!(
            figure.series[0].points.len(),
            2,
            "the NaN point is left out"
        );
        let svg = figure.svg().expect("draws").expect("has points");
        assert!(
            svg.starts_with("<svg") && svg.contains("viewBox"),
            "{}",
            &svg[..200]
        );
        assert!(svg.contains("model") && svg.contains("measured"));
        let empty = LineFigure {
            series: vec![],
            ..figure
        };
        assert!(empty.svg().expect("nothing to fail").is_none());
    }

    /// The distinct stroke colours of the figure's polylines (its series' lines), less the
    /// legend box's black frame.
    fn line_colours(svg: &str) -> Vec<String> {
        let mut colours: Vec<String> = svg
            .split("<polyline")
            .skip(1)
            .filter_map(|tag| {
                let at = tag.find("stroke=\"")? + 8;
                Some(tag[at..at + 7].to_owned())
            })
            .collect();
        colours.retain(|c| c != "#000000");
        colours.sort_unstable();
        colours.dedup();
        colours
    }

    #[test]
    fn twelve_series_are_drawn_in_twelve_colours() {
        let series = (0..12)
            .map(|k| {
                let points = (0..5).map(|i| (f64::from(i), f64::from(i * k))).collect();
                Series::new(format!("series {k}"), points, Style::Line)
            })
            .collect();
        let figure = LineFigure {
            title: "many".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series,
        };
        let svg = figure.svg().expect("draws").expect("has points");
        // Each series' line and its legend sample share a colour, none another's.
        assert_eq!(line_colours(&svg).len(), 12, "{:?}", line_colours(&svg));
    }

    #[test]
    fn a_spread_is_an_error_bar_inside_the_axes() {
        let figure = LineFigure {
            title: "volume".into(),
            x_label: "cycles".into(),
            y_label: "volume".into(),
            series: vec![Series::measured(
                "measured",
                vec![
                    (1.0, 1.0, Some(0.5)),
                    (2.0, 2.0, None),
                    (3.0, f64::NAN, Some(1.0)),
                ],
            )],
        };
        assert_eq!(figure.series[0].spread, [0.5, 0.0]);
        let all: Vec<_> = figure.series[0].extent().collect();
        assert_eq!(all, [(1.0, 0.5, 1.5), (2.0, 2.0, 2.0)]);
        let svg = figure.svg().expect("draws").expect("has points");
        // One bar: its stem and two caps, in the series' colour, as lines.
        let bars = svg.matches("<line").count();
        let grid = svg
            .matches(&format!(
                "stroke=\"#{:02X}{:02X}{:02X}\"",
                GRID.0, GRID.1, GRID.2
            ))
            .count();
        assert_eq!(bars - grid, 3, "{svg}");
    }

    #[test]
    fn the_grid_has_a_line_at_each_tick_and_none_between() {
        let figure = LineFigure {
            title: "depth".into(),
            x_label: "cycles".into(),
            y_label: "depth (um)".into(),
            series: vec![Series::new(
                "depth",
                vec![(0.0, 0.0), (3600.0, 3.4)],
                Style::Line,
            )],
        };
        let svg = figure.svg().expect("draws").expect("has points");
        let (x, y) = (
            range([0.0, 3600.0].into_iter()),
            range([0.0, 3.4].into_iter()),
        );
        let ticks = |r: Option<(f64, f64)>| {
            let (low, high) = r.expect("a range");
            Ticks::of(low, high).values.len()
        };
        let grid = svg
            .matches(&format!(
                "stroke=\"#{:02X}{:02X}{:02X}\"",
                GRID.0, GRID.1, GRID.2
            ))
            .count();
        assert_eq!(grid, ticks(x) + ticks(y));
        // plotters writes each label on a line of its own inside its <text>.
        for label in ["0.0", "0.5", "3.0", "3000"] {
            assert!(svg.contains(&format!("\n{label}\n")), "{label}");
        }
    }
}
