//! The reciprocating rig's wear map as one SVG: the depth along and across the stroke, the
//! track's axis horizontal, with the pressure maps' colour scale and colour bar
//! (`pressure_map.rs`), white where the flat is unworn.

use std::fmt::Write;

use super::html::number;
use super::pressure_map::{
    BAR, BAR_ROOM, BAR_STRIPS, BOTTOM, LEFT, SIDE, TICK, TOP, colour, colour_bar,
};
use super::ticks::Ticks;
use crate::simulation::WearMapReport;

/// The map's width, px: the stroke is tens of contact widths long, so the map is drawn
/// wider than high, across the track stretched (the caption says so).
const WIDTH: f64 = 640.0;

/// Rows a map is drawn with at most: its 260 px cannot show more.
const MAX_DRAWN_ROWS: usize = 130;

/// The map, as an SVG element, and its scales in words for the caption; `None` for a map
/// without wear.
pub fn wear_map_svg(map: &WearMapReport) -> Option<(String, String)> {
    let deepest = map
        .depth_um
        .iter()
        .flatten()
        .fold(0.0_f64, |a, &d| a.max(d));
    if deepest <= 0.0 || map.x_um.is_empty() || map.y_um.is_empty() {
        return None;
    }
    let x = Span::of(&map.x_um);
    let y = Span::of(&map.y_um);
    let width = LEFT + WIDTH + 24.0 + BAR + BAR_ROOM;
    let height = TOP + SIDE + BOTTOM;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {width} {height}\" \
         width=\"{width}\" height=\"{height}\" font-family=\"sans-serif\" font-size=\"13\">"
    );
    draw_cells(&mut svg, map, &x, &y, deepest);
    axes(&mut svg, &x, &y);
    colour_bar(&mut svg, width - BAR_ROOM - BAR, deepest, "depth (um)");
    svg.push_str("</svg>");
    let scales = format!(
        "x along the stroke from its middle, y across the track (um; y stretched {:.0} times \
         against x); colour: the depth from 0 to {} um, white where the flat is unworn",
        (SIDE / (y.high - y.low)) / (WIDTH / (x.high - x.low)),
        number(deepest)
    );
    Some((svg, scales))
}

/// An axis's reach: the outer cell centres plus half a cell.
struct Span {
    low: f64,
    high: f64,
}

impl Span {
    fn of(centres: &[f64]) -> Self {
        let half_cell = if centres.len() > 1 {
            (centres[1] - centres[0]).abs() / 2.0
        } else {
            0.5
        };
        let (low, high) = centres
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &c| {
                (l.min(c), h.max(c))
            });
        Self {
            low: low - half_cell,
            high: high + half_cell,
        }
    }
}

/// The worn cells, each row's neighbours of one colour drawn as one rectangle: the track's
/// middle is uniform along it, so a row is a few rectangles, not hundreds. The colour is
/// the bar's strip the depth falls in.
fn draw_cells(svg: &mut String, map: &WearMapReport, x: &Span, y: &Span, deepest: f64) {
    let (sx, sy) = (WIDTH / (x.high - x.low), SIDE / (y.high - y.low));
    let stride = map.y_um.len().div_ceil(MAX_DRAWN_ROWS).max(1);
    let dy = (y.high - y.low) / map.y_um.len() as f64 * stride as f64 * sy;
    let dx = (x.high - x.low) / map.x_um.len() as f64 * sx;
    let strip = |d: f64| {
        if d <= 0.0 {
            None
        } else {
            Some(((d / deepest * BAR_STRIPS as f64).ceil() as usize).clamp(1, BAR_STRIPS))
        }
    };
    for (iy, row) in map.depth_um.iter().enumerate().step_by(stride) {
        let top = TOP + (y.high - map.y_um[iy]) * sy - dy / 2.0;
        let mut ix = 0;
        while ix < row.len() {
            let Some(k) = strip(row[ix]) else {
                ix += 1;
                continue;
            };
            let run = row[ix..]
                .iter()
                .take_while(|&&d| strip(d) == Some(k))
                .count();
            let left = LEFT + (map.x_um[ix] - x.low) * sx - dx / 2.0;
            let _ = write!(
                svg,
                "<rect x=\"{left:.2}\" y=\"{top:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                run as f64 * dx + 0.05,
                dy + 0.05,
                colour((k as f64 - 0.5) / BAR_STRIPS as f64)
            );
            ix += run;
        }
    }
}

/// The frame, the ticks and their labels in um, and both axes' titles.
fn axes(svg: &mut String, x: &Span, y: &Span) {
    let (sx, sy) = (WIDTH / (x.high - x.low), SIDE / (y.high - y.low));
    let bottom = TOP + SIDE;
    let _ = write!(
        svg,
        "<rect x=\"{LEFT}\" y=\"{TOP}\" width=\"{WIDTH}\" height=\"{SIDE}\" fill=\"none\" stroke=\"#333\"/>"
    );
    let along = Ticks::of(x.low, x.high);
    for &v in &along.values {
        let px = LEFT + (v - x.low) * sx;
        let _ = write!(
            svg,
            "<path d=\"M{px:.2} {bottom}v{TICK}\" stroke=\"#333\"/>\
             <text x=\"{px:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{}</text>",
            bottom + TICK + 14.0,
            along.label(v)
        );
    }
    let across = Ticks::of(y.low, y.high);
    for &v in &across.values {
        let py = TOP + (y.high - v) * sy;
        let _ = write!(
            svg,
            "<path d=\"M{LEFT} {py:.2}h-{TICK}\" stroke=\"#333\"/>\
             <text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"end\">{}</text>",
            LEFT - TICK - 3.0,
            py + 4.5,
            across.label(v)
        );
    }
    let _ = write!(
        svg,
        "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"middle\">x along the stroke (um)</text>",
        LEFT + WIDTH / 2.0,
        bottom + 44.0
    );
    let (tx, ty) = (16.0, TOP + SIDE / 2.0);
    let _ = write!(
        svg,
        "<text x=\"{tx}\" y=\"{ty}\" text-anchor=\"middle\" transform=\"rotate(-90 {tx} {ty})\">\
         y across the track (um)</text>"
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::palette::{hex, viridis};

    fn map(depth_um: Vec<Vec<f64>>) -> WearMapReport {
        let nx = depth_um[0].len();
        WearMapReport {
            x_um: (0..nx)
                .map(|i| (i as f64 - (nx - 1) as f64 / 2.0) * 10.0)
                .collect(),
            y_um: (0..depth_um.len()).map(|i| i as f64 * 2.0 - 2.0).collect(),
            depth_um,
        }
    }

    #[test]
    fn a_uniform_middle_is_one_rectangle_per_row_and_unworn_cells_are_left_white() {
        // Three rows: unworn, worn 1 um along four columns with unworn ends, unworn.
        let depth = vec![
            vec![0.0; 6],
            vec![0.0, 1.0, 1.0, 1.0, 1.0, 0.0],
            vec![0.0; 6],
        ];
        let (svg, scales) = wear_map_svg(&map(depth)).expect("worn");
        assert_eq!(
            svg.matches("<rect").count(),
            1 + 1 + BAR_STRIPS + 1,
            "one run, the frame, the bar's strips and its frame"
        );
        // The run is the deepest strip's colour, and four columns of 10 um wide.
        assert!(
            svg.contains(&hex(viridis(1.0 - 0.5 / BAR_STRIPS as f64))),
            "{svg}"
        );
        let column_px = 10.0 * WIDTH / 60.0;
        assert!(svg.contains(&format!("width=\"{:.2}\"", 4.0 * column_px + 0.05)));
        assert!(scales.contains("from 0 to 1 um") && scales.contains("stretched"));
        assert!(svg.contains("depth (um)") && svg.contains("x along the stroke (um)"));
    }

    #[test]
    fn an_unworn_map_draws_nothing() {
        assert!(wear_map_svg(&map(vec![vec![0.0; 4]; 2])).is_none());
    }

    #[test]
    fn the_rows_drawn_are_at_most_what_the_map_can_show() {
        // 400 rows, each with two depths alternating: every cell a run of its own.
        let row: Vec<f64> = (0..8).map(|i| if i % 2 == 0 { 1.0 } else { 0.5 }).collect();
        let (svg, _) = wear_map_svg(&map(vec![row; 400])).expect("worn");
        let drawn_rows = 400_usize.div_ceil(400_usize.div_ceil(MAX_DRAWN_ROWS));
        let rects = svg.matches("<rect").count() - 2 - BAR_STRIPS;
        assert_eq!(rects, drawn_rows * 8, "eight alternating cells a row");
    }
}
