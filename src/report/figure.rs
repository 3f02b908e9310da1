//! The report's figures as inline SVG: line figures drawn by plotters into a string (its
//! SVG backend estimates text sizes, so no font is loaded), and the pressure maps as a
//! heat map of rectangles.

use std::fmt::Write;

use plotters::prelude::*;
use thiserror::Error;

use super::html::{escape, number};

/// The figures' drawing size, px: a 1.73 aspect that, scaled to the 180 mm of A4's
/// printable width, is 104 mm tall, so two fit a page with their captions.
const SIZE: (u32, u32) = (760, 440);

/// The series' colours, distinct in print and to the colour-blind (Okabe and Ito).
const COLOURS: [RGBColor; 6] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(230, 159, 0),
];

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
    /// A grey line, for a reference (the ball, E_corr).
    Reference,
    /// A marker at each point (measured values).
    Markers,
}

/// One series of a line figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend's entry.
    pub name: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: Style,
}

impl Series {
    /// A series of `points` named `name`, drawn in `style`, its non-finite points left out.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        let points = points
            .into_iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        Self {
            name: name.into(),
            points,
            style,
        }
    }
}

/// A figure of lines and markers on linear axes.
#[derive(Debug, Clone, PartialEq)]
pub struct LineFigure {
    /// The caption under the figure.
    pub title: String,
    /// The horizontal axis, with its unit.
    pub x_label: String,
    /// The vertical axis, with its unit.
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

/// A tick's label: [`number`], with 0 for a value that is zero but for rounding (below a
/// billionth of the axis's range, e.g. 5.6e-17 for the tick at 0).
fn tick(value: f64, range: (f64, f64)) -> String {
    if value.abs() < 1e-9 * (range.1 - range.0).abs() {
        return "0".to_owned();
    }
    number(value)
}

impl LineFigure {
    /// The figure as an SVG element, or `None` when it has no point to draw.
    pub fn svg(&self) -> Result<Option<String>, FigureError> {
        let all = || self.series.iter().flat_map(|s| s.points.iter());
        let (Some(x), Some(y)) = (range(all().map(|p| p.0)), range(all().map(|p| p.1))) else {
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
    fn draw(
        &self,
        svg: &mut String,
        x: (f64, f64),
        y: (f64, f64),
    ) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
        let root = SVGBackend::with_string(svg, SIZE).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .margin(14)
            .x_label_area_size(44)
            .y_label_area_size(78)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&|v| tick(*v, x))
            .y_label_formatter(&|v| tick(*v, y))
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 16))
            .draw()?;
        for (i, series) in self
            .series
            .iter()
            .filter(|s| !s.points.is_empty())
            .enumerate()
        {
            let colour = COLOURS[i % COLOURS.len()];
            let points = series.points.iter().copied();
            let drawn = match series.style {
                Style::Line => chart.draw_series(LineSeries::new(points, colour.stroke_width(2))),
                Style::Reference => chart.draw_series(LineSeries::new(
                    points,
                    RGBColor(90, 90, 90).stroke_width(1),
                )),
                Style::Markers => {
                    chart.draw_series(points.map(|p| Circle::new(p, 5, colour.stroke_width(2))))
                }
            }?;
            let legend = match series.style {
                Style::Reference => RGBColor(90, 90, 90),
                _ => colour,
            };
            drawn.label(&series.name).legend(move |(x, y)| {
                Rectangle::new([(x, y - 4), (x + 14, y + 4)], legend.filled())
            });
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

/// One pressure map: cell centres and pressures `[iy][ix]`, MPa.
#[derive(Debug, Clone, Copy)]
pub struct Map<'a> {
    /// The map's cycle.
    pub cycle: u64,
    /// Cell centres along the sliding direction, um.
    pub x_um: &'a [f64],
    /// Cell centres across the track, um.
    pub y_um: &'a [f64],
    /// Pressures, MPa.
    pub pressure_mpa: &'a [Vec<f64>],
}

/// The viridis scale sampled at ten points (perceptually ordered, readable in grey).
const VIRIDIS: [(u8, u8, u8); 10] = [
    (68, 1, 84),
    (72, 40, 120),
    (62, 74, 137),
    (49, 104, 142),
    (38, 130, 142),
    (31, 158, 137),
    (53, 183, 121),
    (109, 205, 89),
    (180, 222, 44),
    (253, 231, 37),
];

/// The colour of the fraction `f` of the scale, interpolated; white for no contact.
fn colour(f: f64) -> String {
    if f <= 0.0 {
        return "#fff".to_owned();
    }
    let at = f.min(1.0) * (VIRIDIS.len() - 1) as f64;
    let i = (at.floor() as usize).min(VIRIDIS.len() - 2);
    let u = at - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + (f64::from(q) - f64::from(p)) * u).round() as u8;
    format!(
        "#{:02x}{:02x}{:02x}",
        mix(a.0, b.0),
        mix(a.1, b.1),
        mix(a.2, b.2)
    )
}

/// The maps side by side at one length scale and one colour scale (0 to the largest
/// pressure of all), as an SVG element, and the scales in words for its caption; `None`
/// without a loaded cell.
pub fn pressure_svg(maps: &[Map<'_>]) -> Option<(String, String)> {
    let p_max = maps
        .iter()
        .flat_map(|m| m.pressure_mpa.iter().flatten())
        .fold(0.0_f64, |a, &p| a.max(p));
    let cells = maps.iter().map(|m| m.x_um.len()).max()?;
    if p_max <= 0.0 || cells == 0 {
        return None;
    }
    let (side, gap, top, bottom) = (300.0, 40.0, 30.0, 10.0);
    let width = maps.len() as f64 * (side + gap) + gap;
    let height = top + side + bottom;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {width} {height}\" \
         width=\"{width}\" height=\"{height}\" font-family=\"sans-serif\" font-size=\"14\">"
    );
    let extent = |v: &[f64]| v.last().zip(v.first()).map_or(0.0, |(l, f)| l - f);
    let span = maps
        .iter()
        .map(|m| extent(m.x_um).max(extent(m.y_um)))
        .fold(0.0_f64, f64::max)
        .max(1e-9);
    for (k, map) in maps.iter().enumerate() {
        let left = gap + k as f64 * (side + gap);
        draw_map(&mut svg, map, (left, top), side / span, p_max);
        let _ = write!(
            svg,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">cycle {}</text>",
            left + side / 2.0,
            top - 10.0,
            map.cycle
        );
    }
    svg.push_str("</svg>");
    let scales = format!(
        "x along the sliding direction, y across the track, {} um across each square; \
         colour: the pressure from 0 (dark) to {} MPa (yellow), white where there is no \
         contact",
        number(span),
        number(p_max)
    );
    Some((svg, scales))
}

/// One map's cells at `scale` px per um, its corner at `origin`.
/// Cells per side a map is drawn with at most: its square is 300 px wide, so finer cells
/// cannot be seen, and a 2048-cell map would write millions of rectangles (about 90 bytes
/// each) into a report the service builds in memory.
const MAX_DRAWN_CELLS: usize = 150;

fn draw_map(svg: &mut String, map: &Map<'_>, origin: (f64, f64), scale: f64, p_max: f64) {
    let cells = map.x_um.len().max(map.y_um.len());
    let stride = cells.div_ceil(MAX_DRAWN_CELLS).max(1);
    let step = |v: &[f64]| if v.len() > 1 { v[1] - v[0] } else { 1.0 };
    let (dx, dy) = (
        step(map.x_um) * scale * stride as f64,
        step(map.y_um) * scale * stride as f64,
    );
    let (x0, y0) = (
        map.x_um.first().copied().unwrap_or(0.0),
        map.y_um.first().copied().unwrap_or(0.0),
    );
    let _ = write!(
        svg,
        "<rect x=\"{}\" y=\"{}\" width=\"300\" height=\"300\" fill=\"none\" stroke=\"#999\"/>",
        origin.0, origin.1
    );
    for (iy, row) in map.pressure_mpa.iter().enumerate().step_by(stride) {
        for (ix, &p) in row
            .iter()
            .enumerate()
            .step_by(stride)
            .filter(|(_, p)| **p > 0.0)
        {
            let x = origin.0 + (map.x_um[ix] - x0) * scale;
            let y = origin.1 + (map.y_um[iy] - y0) * scale;
            let _ = write!(
                svg,
                "<rect x=\"{x:.2}\" y=\"{y:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                dx + 0.05,
                dy + 0.05,
                colour(p / p_max)
            );
        }
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

    #[test]
    fn the_colour_scale_runs_from_no_contact_to_the_largest_pressure() {
        assert_eq!(colour(0.0), "#fff");
        assert_eq!(colour(1e-9), "#440154");
        assert_eq!(colour(1.0), "#fde725");
        let row = vec![0.0, 500.0, 1000.0];
        let map = Map {
            cycle: 1,
            x_um: &[0.0, 10.0, 20.0],
            y_um: &[0.0],
            pressure_mpa: std::slice::from_ref(&row),
        };
        let (svg, scales) = pressure_svg(&[map]).expect("loaded");
        assert_eq!(
            svg.matches("<rect").count(),
            3,
            "a frame and two loaded cells"
        );
        assert!(scales.contains("1000 MPa"), "{scales}");
    }

    #[test]
    fn a_fine_map_is_drawn_with_at_most_the_cells_its_square_can_show() {
        let n = 2048;
        let axis: Vec<f64> = (0..n).map(|i| i as f64 * 0.125).collect();
        let pressure = vec![vec![500.0; n]; n];
        let map = Map {
            cycle: 1,
            x_um: &axis,
            y_um: &axis,
            pressure_mpa: &pressure,
        };
        let (svg, _) = pressure_svg(&[map]).expect("drawn");
        // 2048 cells at a stride of 14: 147 per side, plus the frame.
        let rects = svg.matches("<rect").count();
        assert_eq!(rects, 147 * 147 + 1);
    }
}
