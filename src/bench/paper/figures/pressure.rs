//! Fig. 10's pressure maps: the cells coloured white to red in [`SHADES`] steps up to the
//! map's peak, black at the yield pressure, with a colour bar in MPa beside the map.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::simulation::PressureMap;

use super::super::BenchError;

/// Colour steps of the pressure maps below the cap: cells of one step in a row are drawn as
/// one rectangle, which keeps a map's SVG to a few hundred kB (one rectangle per 1 um cell
/// made 0.6-0.8 MB).
pub(super) const SHADES: f64 = 16.0;

/// The figure's size, and the width of the colour bar's part of it, px: the map's part is
/// as wide as its plot is high, so that x and y are drawn at one scale.
const SIZE_PX: (u32, u32) = (700, 560);
const BAR_PART_PX: u32 = 140;

/// The step of `p` on the scale up to the map's peak `top`: 0 to `SHADES - 1`, `SHADES`
/// at the cap `cap` (MPa).
fn step(p: f64, top: f64, cap: f64) -> u8 {
    if p >= cap * (1.0 - 1e-9) {
        SHADES as u8
    } else {
        ((p / top).clamp(0.0, 1.0) * SHADES)
            .floor()
            .min(SHADES - 1.0) as u8
    }
}

/// The colour of a step: white to red at the middle of each step, black at the cap.
fn shade(step: u8) -> RGBColor {
    if f64::from(step) >= SHADES {
        return BLACK;
    }
    let f = (f64::from(step) + 0.5) / SHADES;
    let fade = |full: u8| (255.0 - f * (255.0 - f64::from(full))) as u8;
    RGBColor(fade(0xd6), fade(0x27), fade(0x28))
}

/// The loaded cells of a map row as runs of one step: (first x, last x, step).
fn runs(x_um: &[f64], row: &[f64], top: f64, cap: f64) -> Vec<(f64, f64, u8)> {
    let mut out: Vec<(f64, f64, u8)> = Vec::new();
    let mut previous_loaded = false;
    for (&x, &p) in x_um.iter().zip(row) {
        let loaded = p > 0.0;
        if loaded {
            let k = step(p, top, cap);
            match out.last_mut() {
                Some(run) if previous_loaded && run.2 == k => run.1 = x,
                _ => out.push((x, x, k)),
            }
        }
        previous_loaded = loaded;
    }
    out
}

/// The pressure map as cells coloured up to the yield pressure `cap` (MPa, black at it),
/// with its colour bar.
pub(super) fn write_svg(map: &PressureMap, cap: f64, path: &Path) -> Result<(), BenchError> {
    let fail = |source| BenchError::Plot {
        path: path.to_owned(),
        source,
    };
    let root = SVGBackend::new(path, SIZE_PX).into_drawing_area();
    root.fill(&WHITE).map_err(fail)?;
    let title = format!("Fig. 10: contact pressure at cycle {}", map.cycle);
    let body = root.titled(&title, ("sans-serif", 17)).map_err(fail)?;
    let (map_part, bar_part) = body.split_horizontally(SIZE_PX.0 - BAR_PART_PX);
    let top = map
        .pressure_mpa
        .iter()
        .flatten()
        .fold(0.0_f64, |m, &p| m.max(p));
    draw_map(&map_part, map, top, cap).map_err(fail)?;
    draw_bar(&bar_part, top, cap).map_err(fail)?;
    root.present().map_err(fail)
}

fn draw_map(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    map: &PressureMap,
    top: f64,
    cap: f64,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let half = |v: &[f64]| v.iter().fold(0.0_f64, |m, &x| m.max(x.abs())) + 1.0;
    let extent = half(&map.x_um).max(half(&map.y_um));
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d(-extent..extent, -extent..extent)?;
    chart
        .configure_mesh()
        .x_desc("x, sliding direction (um)")
        .y_desc("y, across the track (um)")
        .draw()?;
    let dx = map.x_um.get(1).map_or(1.0, |x1| x1 - map.x_um[0]);
    let dy = map.y_um.get(1).map_or(1.0, |y1| y1 - map.y_um[0]);
    let cells = map
        .y_um
        .iter()
        .zip(&map.pressure_mpa)
        .flat_map(|(&y, row)| {
            runs(&map.x_um, row, top, cap)
                .into_iter()
                .map(move |(x0, x1, k)| {
                    Rectangle::new(
                        [(x0 - dx / 2.0, y - dy / 2.0), (x1 + dx / 2.0, y + dy / 2.0)],
                        shade(k).filled(),
                    )
                })
        });
    chart.draw_series(cells)?;
    Ok(())
}

/// The colour bar: a step of the scale per band from 0 to the map's peak `top`, ticks in
/// MPa, and under it the black of the cells at the yield pressure `cap`.
fn draw_bar(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    top: f64,
    cap: f64,
) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let (_, height) = area.dim_in_pixel();
    let (bar_area, key_area) = area.split_vertically(height - 60);
    let mut bar = ChartBuilder::on(&bar_area)
        .margin(12)
        .margin_left(4)
        .x_label_area_size(0)
        .right_y_label_area_size(72)
        .build_cartesian_2d(0.0..1.0, 0.0..top)?;
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("pressure (MPa)")
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .y_label_formatter(&|p| format!("{p:.0}"))
        .draw()?;
    let band = top / SHADES;
    bar.draw_series((0..SHADES as u8).map(|k| {
        let low = f64::from(k) * band;
        Rectangle::new([(0.0, low), (1.0, low + band)], shade(k).filled())
    }))?;
    let font =
        TextStyle::from(("sans-serif", 12).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    key_area.draw(&Rectangle::new(
        [(4, 8), (20, 24)],
        shade(SHADES as u8).filled(),
    ))?;
    key_area.draw(&Text::new("at the yield", (26, 12), font.clone()))?;
    key_area.draw(&Text::new(format!("Y = {cap:.0} MPa"), (26, 28), font))?;
    Ok(())
}
