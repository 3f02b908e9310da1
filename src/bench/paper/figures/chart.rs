//! A line figure drawn: the chart, with a second vertical axis when a series reads against
//! one, over the legend strip of [`super::legend`].

use std::ops::Range;
use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::element::{DashedPathElement, DynElement};
use plotters::prelude::*;

use super::super::BenchError;
use super::{Axis, Figure, Marker, Series, Style, dashes_px, legend};

/// The figure's width and the chart's height above the legend, px.
const SIZE_PX: (u32, u32) = (760, 440);
/// Half the width of an error bar's caps, as a share of the x range (4 px of the chart's
/// ~650; of its decades on a log axis).
const CAP_SHARE: f64 = 0.006;

/// The range of `values` padded by 5% (a single value: +-1).
fn range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
    lo - pad..hi + pad
}

/// Every y of the series on `axis`, error bars' ends included.
fn heights(series: &[Series], axis: Axis) -> Vec<f64> {
    series
        .iter()
        .filter(|s| s.axis == axis)
        .flat_map(|s| {
            s.points.iter().enumerate().flat_map(|(i, &(_, y))| {
                let spread = s.spreads.get(i).copied().unwrap_or(0.0);
                [y - spread, y + spread]
            })
        })
        .collect()
}

/// What draws `s`: its line or markers, and its error bars with caps from `cap(x)`'s first
/// x to its second.
fn elements<DB: DrawingBackend>(
    s: &Series,
    cap: &dyn Fn(f64) -> (f64, f64),
) -> Vec<DynElement<'static, DB, (f64, f64)>> {
    let stroke = s.colour.stroke_width(2);
    let mut out = match s.style {
        Style::Line => vec![PathElement::new(s.points.clone(), stroke).into_dyn()],
        Style::Dashed => {
            let (dash, gap) = dashes_px();
            let path = DashedPathElement::new(s.points.clone(), dash, gap, stroke);
            vec![path.into_dyn()]
        }
        Style::Markers(Marker::Triangle) => s
            .points
            .iter()
            .map(|&p| TriangleMarker::new(p, 7, s.colour.filled()).into_dyn())
            .collect(),
        Style::Markers(Marker::Circle) => s
            .points
            .iter()
            .map(|&p| Circle::new(p, 5, s.colour.filled()).into_dyn())
            .collect(),
    };
    let thin = s.colour.stroke_width(1);
    for (&(x, y), &spread) in s.points.iter().zip(&s.spreads) {
        out.push(PathElement::new(vec![(x, y - spread), (x, y + spread)], thin).into_dyn());
        for end in [y - spread, y + spread] {
            let (left, right) = cap(x);
            out.push(PathElement::new(vec![(left, end), (right, end)], thin).into_dyn());
        }
    }
    out
}

impl Figure {
    /// Writes the figure to `path` as SVG.
    pub(super) fn write_svg(&self, path: &Path) -> Result<(), BenchError> {
        let fail = |source| BenchError::Plot {
            path: path.to_owned(),
            source,
        };
        let strip = legend::height_px(self.series.len());
        let root = SVGBackend::new(path, (SIZE_PX.0, SIZE_PX.1 + strip)).into_drawing_area();
        root.fill(&WHITE).map_err(fail)?;
        let (top, bottom) = root.split_vertically(SIZE_PX.1);
        self.draw_chart(&top).map_err(fail)?;
        legend::draw(&bottom, &self.series).map_err(fail)?;
        root.present().map_err(fail)
    }

    fn draw_chart(
        &self,
        area: &DrawingArea<SVGBackend<'_>, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
        let xs = || {
            self.series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.0))
        };
        if !self.log_x {
            let x = range(xs());
            let cap = CAP_SHARE * (x.end - x.start);
            return self.draw_on(area, x, &|v| (v - cap, v + cap));
        }
        // A decade's worth of padding, as the linear axis pads by 5%.
        let (lo, hi) = xs().fold((f64::INFINITY, 0.0_f64), |(l, h), v| (l.min(v), h.max(v)));
        let pad = (hi / lo).powf(0.05);
        let cap = (hi / lo).powf(CAP_SHARE);
        self.draw_on(area, (lo / pad..hi * pad).log_scale(), &|v| {
            (v / cap, v * cap)
        })
    }

    /// The chart on the x axis `x`; `cap` gives the ends of an error bar's cap at an x.
    fn draw_on<X>(
        &self,
        area: &DrawingArea<SVGBackend<'_>, Shift>,
        x: X,
        cap: &dyn Fn(f64) -> (f64, f64),
    ) -> Result<(), DrawingAreaErrorKind<std::io::Error>>
    where
        X: AsRangedCoord<Value = f64> + Clone,
        X::CoordDescType: ValueFormatter<f64>,
    {
        let left = range(heights(&self.series, Axis::Left).into_iter());
        let right_heights = heights(&self.series, Axis::Right);
        let right = if right_heights.is_empty() {
            left.clone()
        } else {
            range(right_heights.into_iter())
        };
        let mut chart = ChartBuilder::on(area)
            .caption(&self.title, ("sans-serif", 17))
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(64)
            .right_y_label_area_size(if self.right_label.is_some() { 64 } else { 0 })
            .build_cartesian_2d(x.clone(), left)?
            .set_secondary_coord(x, right);
        chart
            .configure_mesh()
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .draw()?;
        if let Some(label) = self.right_label {
            chart.configure_secondary_axes().y_desc(label).draw()?;
        }
        for s in &self.series {
            match s.axis {
                Axis::Left => chart.draw_series(elements(s, cap))?,
                Axis::Right => chart.draw_secondary_series(elements(s, cap))?,
            };
        }
        Ok(())
    }
}
