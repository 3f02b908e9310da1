//! The legend of a line figure, in a strip of its own under the chart so that no entry
//! covers data. Each entry is drawn with its series' own sample: a solid line, a dashed
//! line with the series' dashes, or the series' marker with its error bar, so two series
//! of one colour tell apart.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{Marker, Series, Style, dashes_px};

/// Entries per row of the strip.
const COLUMNS: usize = 3;
/// Height of one row of entries, px.
const ROW_PX: i32 = 22;
/// Space between the strip's frame and its entries, px.
const PAD_PX: i32 = 8;
/// Left and right margin of the frame, px (the chart's own margin).
const MARGIN_PX: i32 = 12;
/// Length of an entry's sample, px: room for three dashes of [`dashes_px`].
const SAMPLE_PX: i32 = 30;

/// The strip's height for `entries` entries, px.
pub(super) fn height_px(entries: usize) -> u32 {
    let rows = entries.div_ceil(COLUMNS) as i32;
    (rows * ROW_PX + 2 * PAD_PX + 4) as u32
}

/// Draws the legend of `series` in `area`, a frame around the entries.
pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    series: &[Series],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (width, height) = area.dim_in_pixel();
    let (right, bottom) = (width as i32 - MARGIN_PX, height as i32 - 2);
    area.draw(&Rectangle::new(
        [(MARGIN_PX, 2), (right, bottom)],
        BLACK.stroke_width(1),
    ))?;
    let column_px = (right - MARGIN_PX) / COLUMNS as i32;
    let font =
        TextStyle::from(("sans-serif", 13).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (i, s) in series.iter().enumerate() {
        let x = MARGIN_PX + PAD_PX + (i % COLUMNS) as i32 * column_px;
        let y = 2 + PAD_PX + (i / COLUMNS) as i32 * ROW_PX + ROW_PX / 2;
        sample(area, s, x, y)?;
        area.draw(&Text::new(
            s.name.clone(),
            (x + SAMPLE_PX + 8, y),
            font.clone(),
        ))?;
    }
    Ok(())
}

/// The sample of `s` from `(x, y)` rightwards, px.
fn sample<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    s: &Series,
    x: i32,
    y: i32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let stroke = s.colour.stroke_width(2);
    let ends = vec![(x, y), (x + SAMPLE_PX, y)];
    match s.style {
        Style::Line => area.draw(&PathElement::new(ends, stroke)),
        Style::Dashed => {
            let (dash, gap) = dashes_px();
            area.draw(&DashedPathElement::new(ends, dash, gap, stroke))
        }
        Style::Markers(marker) => {
            let centre = (x + SAMPLE_PX / 2, y);
            if !s.spreads.is_empty() {
                let bar = [(centre.0, y - 8), (centre.0, y + 8)];
                area.draw(&PathElement::new(bar, s.colour.stroke_width(1)))?;
            }
            match marker {
                Marker::Triangle => area.draw(&TriangleMarker::new(centre, 7, s.colour.filled())),
                Marker::Circle => area.draw(&Circle::new(centre, 5, s.colour.filled())),
            }
        }
    }
}
