//! The pressure maps as one SVG: each map a square centred on the ball, all at one length
//! scale with axes in um, and one colour bar in MPa (the paper's Fig. 10 in print).

use std::fmt::Write;

use super::html::number;
use super::palette::{hex, viridis};
use super::ticks::Ticks;

/// One pressure map: cell centres (about the ball's centre) and pressures `[iy][ix]`.
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

/// A map's square, px.
pub(super) const SIDE: f64 = 260.0;
/// Room left of a square for its tick labels and the y axis's title, px.
pub(super) const LEFT: f64 = 72.0;
/// Room above a square for its title, px.
pub(super) const TOP: f64 = 28.0;
/// Room below a square for its tick labels and the x axis's title, px.
pub(super) const BOTTOM: f64 = 52.0;
/// The colour bar's width and the room right of it for its labels and title, px.
pub(super) const BAR: f64 = 16.0;
pub(super) const BAR_ROOM: f64 = 96.0;
/// A tick's length, px.
pub(super) const TICK: f64 = 5.0;

/// Cells per side a map is drawn with at most: its square is 260 px wide, so finer cells
/// cannot be seen, and a 2048-cell map would write millions of rectangles (about 90 bytes
/// each) into a report the service builds in memory.
const MAX_DRAWN_CELLS: usize = 150;

/// The colour of the fraction `f` of a colour scale; white for none (no contact, no wear).
pub(super) fn colour(f: f64) -> String {
    if f <= 0.0 {
        return "#fff".to_owned();
    }
    hex(viridis(f))
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
    // The outermost cell centre plus half a cell, so edge cells stay inside the square.
    let reach = |v: &[f64]| {
        let half_cell = if v.len() > 1 {
            (v[1] - v[0]).abs() / 2.0
        } else {
            0.5
        };
        v.iter().fold(0.0_f64, |a, c| a.max(c.abs())) + half_cell
    };
    let half = maps
        .iter()
        .map(|m| reach(m.x_um).max(reach(m.y_um)))
        .fold(0.0_f64, f64::max)
        .max(1e-9);
    let width = maps.len() as f64 * (LEFT + SIDE) + 24.0 + BAR + BAR_ROOM;
    let height = TOP + SIDE + BOTTOM;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {width} {height}\" \
         width=\"{width}\" height=\"{height}\" font-family=\"sans-serif\" font-size=\"13\">"
    );
    let ticks = Ticks::of(-half, half);
    for (k, map) in maps.iter().enumerate() {
        let left = LEFT + k as f64 * (LEFT + SIDE);
        draw_map(&mut svg, map, left, half, p_max);
        axes(&mut svg, left, &ticks, half, k == 0);
        let _ = write!(
            svg,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"14\">cycle {}</text>",
            left + SIDE / 2.0,
            TOP - 10.0,
            map.cycle
        );
    }
    colour_bar(&mut svg, width - BAR_ROOM - BAR, p_max, "pressure (MPa)");
    svg.push_str("</svg>");
    let scales = format!(
        "x along the sliding direction, y across the track, both from the ball's centre \
         (um); colour: the pressure from 0 to {} MPa, white where there is no contact",
        number(p_max)
    );
    Some((svg, scales))
}

/// One map's cells in its square, whose left edge is at `left` px, the square spanning
/// `-half..half` um each way.
fn draw_map(svg: &mut String, map: &Map<'_>, left: f64, half: f64, p_max: f64) {
    let scale = SIDE / (2.0 * half);
    let cells = map.x_um.len().max(map.y_um.len());
    let stride = cells.div_ceil(MAX_DRAWN_CELLS).max(1);
    let step = |v: &[f64]| if v.len() > 1 { v[1] - v[0] } else { 1.0 };
    let (dx, dy) = (
        step(map.x_um) * scale * stride as f64,
        step(map.y_um) * scale * stride as f64,
    );
    for (iy, row) in map.pressure_mpa.iter().enumerate().step_by(stride) {
        for (ix, &p) in row
            .iter()
            .enumerate()
            .step_by(stride)
            .filter(|(_, p)| **p > 0.0)
        {
            // The cell's corner: x grows to the right, y upwards, as on the page's map.
            let x = left + (map.x_um[ix] + half) * scale - dx / 2.0;
            let y = TOP + (half - map.y_um[iy]) * scale - dy / 2.0;
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

/// A square's frame, its ticks and their labels in um, the x axis's title, and the y
/// axis's title when `first`.
fn axes(svg: &mut String, left: f64, ticks: &Ticks, half: f64, first: bool) {
    let scale = SIDE / (2.0 * half);
    let bottom = TOP + SIDE;
    let _ = write!(
        svg,
        "<rect x=\"{left}\" y=\"{TOP}\" width=\"{SIDE}\" height=\"{SIDE}\" fill=\"none\" stroke=\"#333\"/>"
    );
    for &v in &ticks.values {
        let label = ticks.label(v);
        let x = left + (v + half) * scale;
        let y = TOP + (half - v) * scale;
        let _ = write!(
            svg,
            "<path d=\"M{x:.2} {bottom}v{TICK}M{left} {y:.2}h-{TICK}\" stroke=\"#333\"/>\
             <text x=\"{x:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{label}</text>\
             <text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"end\">{label}</text>",
            bottom + TICK + 14.0,
            left - TICK - 3.0,
            y + 4.5
        );
    }
    let _ = write!(
        svg,
        "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"middle\">x along the sliding (um)</text>",
        left + SIDE / 2.0,
        bottom + 44.0
    );
    if first {
        let (x, y) = (16.0, TOP + SIDE / 2.0);
        let _ = write!(
            svg,
            "<text x=\"{x}\" y=\"{y}\" text-anchor=\"middle\" transform=\"rotate(-90 {x} {y})\">\
             y across the track (um)</text>"
        );
    }
}

/// Strips a colour bar is drawn with: as many as its 260 px can tell apart in print.
pub(super) const BAR_STRIPS: usize = 64;

/// The colour bar at `left` px, beside a plot [`SIDE`] px high below [`TOP`], from 0
/// (bottom) to `p_max` (top) in the unit of its `title`, with its ticks: drawn as strips,
/// since a gradient would need a `url(#...)` reference, which the reports keep out so that
/// nothing in them can point elsewhere.
pub(super) fn colour_bar(svg: &mut String, left: f64, p_max: f64, title: &str) {
    let strip = SIDE / BAR_STRIPS as f64;
    for k in 0..BAR_STRIPS {
        let f = (k as f64 + 0.5) / BAR_STRIPS as f64;
        let _ = write!(
            svg,
            "<rect x=\"{left}\" y=\"{:.2}\" width=\"{BAR}\" height=\"{:.2}\" fill=\"{}\"/>",
            TOP + SIDE - (k + 1) as f64 * strip,
            strip + 0.05,
            hex(viridis(f))
        );
    }
    let _ = write!(
        svg,
        "<rect x=\"{left}\" y=\"{TOP}\" width=\"{BAR}\" height=\"{SIDE}\" fill=\"none\" stroke=\"#333\"/>"
    );
    let ticks = Ticks::of(0.0, p_max);
    let right = left + BAR;
    for &p in &ticks.values {
        let y = TOP + SIDE * (1.0 - p / p_max);
        let _ = write!(
            svg,
            "<path d=\"M{right} {y:.2}h{TICK}\" stroke=\"#333\"/>\
             <text x=\"{:.2}\" y=\"{:.2}\">{}</text>",
            right + TICK + 3.0,
            y + 4.5,
            ticks.label(p)
        );
    }
    let (x, y) = (right + 80.0, TOP + SIDE / 2.0);
    let _ = write!(
        svg,
        "<text x=\"{x}\" y=\"{y}\" text-anchor=\"middle\" transform=\"rotate(-90 {x} {y})\">\
         {title}</text>"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_colour_scale_runs_from_no_contact_to_the_largest_pressure() {
        assert_eq!(colour(0.0), "#fff");
        assert_eq!(colour(1e-9), "#440154");
        assert_eq!(colour(1.0), "#fde725");
        let row = vec![0.0, 500.0, 1000.0];
        let map = Map {
            cycle: 1,
            x_um: &[-10.0, 0.0, 10.0],
            y_um: &[0.0],
            pressure_mpa: std::slice::from_ref(&row),
        };
        let (svg, scales) = pressure_svg(&[map]).expect("loaded");
        assert_eq!(
            svg.matches("<rect").count(),
            4 + BAR_STRIPS,
            "two loaded cells, the frame, the colour bar's strips and its frame"
        );
        assert!(scales.contains("1000 MPa"), "{scales}");
        assert!(
            svg.contains("pressure (MPa)") && svg.contains(">1000</text>"),
            "the bar's top tick"
        );
    }

    #[test]
    fn a_map_is_centred_on_the_ball_with_axes_in_um() {
        // One loaded cell at the ball's centre, on a map reaching 20 um each way.
        let axis = [-20.0, 0.0, 20.0];
        let rows = vec![vec![0.0; 3], vec![0.0, 800.0, 0.0], vec![0.0; 3]];
        let map = Map {
            cycle: 7,
            x_um: &axis,
            y_um: &axis,
            pressure_mpa: &rows,
        };
        let (svg, _) = pressure_svg(&[map]).expect("loaded");
        // The square spans 30 um each way (the outer centres plus half a cell); the cell,
        // 20 um wide, sits at its centre.
        let cell_px = 20.0 * SIDE / 60.0;
        let centre = (LEFT + SIDE / 2.0, TOP + SIDE / 2.0);
        let corner = format!(
            "x=\"{:.2}\" y=\"{:.2}\"",
            centre.0 - cell_px / 2.0,
            centre.1 - cell_px / 2.0
        );
        assert!(svg.contains(&corner), "{corner} in {svg}");
        for label in [
            "x along the sliding (um)",
            "y across the track (um)",
            ">-20</text>",
            ">0</text>",
            ">20</text>",
            "cycle 7",
        ] {
            assert!(svg.contains(label), "{label}");
        }
    }

    #[test]
    fn a_fine_map_is_drawn_with_at_most_the_cells_its_square_can_show() {
        let n = 2048;
        let axis: Vec<f64> = (0..n).map(|i| (i as f64 - 1024.0) * 0.125).collect();
        let pressure = vec![vec![500.0; n]; n];
        let map = Map {
            cycle: 1,
            x_um: &axis,
            y_um: &axis,
            pressure_mpa: &pressure,
        };
        let (svg, _) = pressure_svg(&[map]).expect("drawn");
        // 2048 cells at a stride of 14: 147 per side, plus the frame and the colour bar.
        let rects = svg.matches("<rect").count();
        assert_eq!(rects, 147 * 147 + 2 + BAR_STRIPS);
    }
}
