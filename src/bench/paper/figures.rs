//! The figures of `docs/paper.md` as SVG, drawn like the paper's: lines for the runs,
//! markers for Table 3's measurements, a colour map for the pressures.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::simulation::PressureMap;

use super::numbers::{TABLE3, profile, record};
use super::{BenchError, PaperStudy};

/// Colours: elastic blue and EPP red as in the paper's Fig. 11, then the rest.
const BLUE: RGBColor = RGBColor(0x1f, 0x77, 0xb4);
const RED: RGBColor = RGBColor(0xd6, 0x27, 0x28);
const GREEN: RGBColor = RGBColor(0x2c, 0xa0, 0x2c);
const PURPLE: RGBColor = RGBColor(0x94, 0x67, 0xbd);

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Style {
    Line,
    Dashed,
    Markers,
}

/// One series of a figure.
struct Series {
    name: String,
    points: Vec<(f64, f64)>,
    colour: RGBColor,
    style: Style,
}

impl Series {
    fn new(name: &str, points: Vec<(f64, f64)>, colour: RGBColor, style: Style) -> Self {
        Self {
            name: name.to_owned(),
            points,
            colour,
            style,
        }
    }
}

/// A figure on linear axes.
struct Figure {
    title: String,
    x_label: &'static str,
    y_label: &'static str,
    series: Vec<Series>,
}

/// The range of `values` padded by 5% (a single value: +-1).
fn range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
    lo - pad..hi + pad
}

impl Figure {
    fn write_svg(&self, path: &Path) -> Result<(), BenchError> {
        let fail = |source| BenchError::Plot {
            path: path.to_owned(),
            source,
        };
        let all = || self.series.iter().flat_map(|s| s.points.iter());
        let root = SVGBackend::new(path, (760, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(fail)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 17))
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(64)
            .build_cartesian_2d(range(all().map(|p| p.0)), range(all().map(|p| p.1)))
            .map_err(fail)?;
        chart
            .configure_mesh()
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .draw()
            .map_err(fail)?;
        for s in &self.series {
            let colour = s.colour;
            let drawn = match s.style {
                Style::Line => chart
                    .draw_series(LineSeries::new(s.points.clone(), colour.stroke_width(2)))
                    .map_err(fail)?,
                Style::Dashed => chart
                    .draw_series(DashedLineSeries::new(
                        s.points.clone(),
                        6,
                        4,
                        colour.stroke_width(2),
                    ))
                    .map_err(fail)?,
                Style::Markers => chart
                    .draw_series(
                        s.points
                            .iter()
                            .map(|&p| TriangleMarker::new(p, 7, colour.filled())),
                    )
                    .map_err(fail)?,
            };
            drawn.label(&s.name).legend(move |(x, y)| {
                Rectangle::new([(x, y - 4), (x + 14, y + 4)], colour.filled())
            });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(fail)?;
        root.present().map_err(fail)
    }
}

/// Writes every figure into `folder`; returns how many.
pub(super) fn write_all(study: &PaperStudy, folder: &Path) -> Result<usize, BenchError> {
    let figures = [
        ("fig9_hardness.svg", hardness(study)),
        ("fig11_volume.svg", volume(study)),
        ("fig12a_profile_10.svg", profiles(study, 10)),
        ("fig12b_profile_300.svg", profiles(study, 300)),
        ("fig13_wac.svg", wac(study)),
        ("fig14_areas.svg", areas(study)),
    ];
    for (name, figure) in &figures {
        figure.write_svg(&folder.join(name))?;
    }
    let maps = [
        ("fig10a_pressure_6.svg", last_map(&study.first6)),
        ("fig10b_pressure_300.svg", last_map(&study.epp)),
    ];
    for (name, (map, cap)) in &maps {
        pressure_svg(map, *cap, &folder.join(name))?;
    }
    Ok(figures.len() + maps.len())
}

/// The last pressure map of `result` and the yield pressure of its cycle, MPa.
pub(super) fn last_map(result: &crate::simulation::SimulationResult) -> (&PressureMap, f64) {
    let map = result
        .pressure_maps
        .last()
        .expect("a run keeps its last map");
    let hardness = record(result, map.cycle).hardness_mpa;
    (map, hardness / result.scene.disc.yield_factor)
}

fn hardness(study: &PaperStudy) -> Figure {
    let law = study
        .whole
        .cycles
        .iter()
        .map(|r| (r.time_s, r.hardness_mpa))
        .collect();
    let mut points: Vec<(f64, f64)> = vec![(0.0, study.whole.scene.disc.hardness_mpa)];
    points.extend(TABLE3.iter().map(|&(t, h, ..)| (t as f64, h)));
    Figure {
        title: "Fig. 9: hardness of the disc in the track".to_owned(),
        x_label: "rubbing time (s) = cycles",
        y_label: "H (MPa)",
        series: vec![
            Series::new("fitted law (the run's records)", law, RED, Style::Line),
            Series::new("Table 3 (bulk at 0)", points, BLUE, Style::Markers),
        ],
    }
}

fn volume(study: &PaperStudy) -> Figure {
    let groove = |r: &crate::simulation::SimulationResult| {
        r.cycles
            .iter()
            .map(|c| (c.time_s, c.wear_volume_mm3 * 1e3))
            .collect()
    };
    let loaded = |r: &crate::simulation::SimulationResult| {
        r.profiles
            .iter()
            .map(|p| {
                let t = record(r, p.cycle).time_s;
                (t, super::numbers::loaded_volume_mm3(r, p.cycle) * 1e3)
            })
            .collect()
    };
    let measured = TABLE3
        .iter()
        .filter(|&&(t, ..)| t <= 300)
        .map(|&(t, _, v, _)| (t as f64, v))
        .collect();
    Figure {
        title: "Fig. 11: wear volume over the first 300 cycles".to_owned(),
        x_label: "rubbing time (s) = cycles",
        y_label: "volume (1e-3 mm^3)",
        series: vec![
            Series::new("elastic, groove", groove(&study.elastic), BLUE, Style::Line),
            Series::new("EPP, groove", groove(&study.epp), RED, Style::Line),
            Series::new(
                "elastic, loaded",
                loaded(&study.elastic),
                BLUE,
                Style::Dashed,
            ),
            Series::new("EPP, loaded", loaded(&study.epp), RED, Style::Dashed),
            Series::new("Table 3", measured, GREEN, Style::Markers),
        ],
    }
}

fn profiles(study: &PaperStudy, cycle: u64) -> Figure {
    let p = profile(&study.epp, cycle);
    let r = record(&study.epp, cycle);
    let radius_um = study.epp.scene.ball_radius_m() * 1e6;
    let line = |depths: &[f64]| p.y_um.iter().zip(depths).map(|(&y, &d)| (y, -d)).collect();
    // The ball's undeformed surface at the solved approach: its apex that far below the
    // original surface, where the loaded disc surface and the ball's loaded surface meet.
    let ball = p
        .y_um
        .iter()
        .map(|&y| (y, -(r.approach_um - y * y / (2.0 * radius_um))))
        .filter(|&(_, z)| z <= 0.2)
        .collect();
    Figure {
        title: format!("Fig. 12: profile across the track at cycle {cycle} (EPP)"),
        x_label: "y across the track (um)",
        y_label: "height (um)",
        series: vec![
            Series::new("groove", line(&p.depth_um), RED, Style::Line),
            Series::new(
                "loaded surface",
                line(&p.loaded_depth_um),
                RED,
                Style::Dashed,
            ),
            Series::new("ball, undeformed", ball, BLACK, Style::Line),
        ],
    }
}

fn wac(study: &PaperStudy) -> Figure {
    let points = study
        .whole
        .cycles
        .iter()
        .filter_map(|c| Some((c.time_s, c.wac_volume_mm3? * 1e3)))
        .collect();
    Figure {
        title: "Fig. 13: wear-accelerated corrosion volume".to_owned(),
        x_label: "rubbing time (s)",
        y_label: "V_WAC (1e-3 mm^3)",
        series: vec![Series::new("depassivated wake", points, RED, Style::Line)],
    }
}

fn areas(study: &PaperStudy) -> Figure {
    let load = study.whole.scene.load_n();
    let cycles = &study.whole.cycles;
    let real = cycles
        .iter()
        .map(|c| (c.time_s, load / c.hardness_mpa * 1e3))
        .collect();
    let anodic = cycles
        .iter()
        .filter_map(|c| Some((c.time_s, c.anodic_area_mm2? * 1e3)))
        .collect();
    let end = cycles.last().map_or(0.0, |c| c.time_s);
    let hertz = vec![
        (0.0, study.hertz_area_mm2 * 1e3),
        (end, study.hertz_area_mm2 * 1e3),
    ];
    Figure {
        title: "Fig. 14: real (F/H) and depassivated areas".to_owned(),
        x_label: "rubbing time (s)",
        y_label: "area (1e-3 mm^2)",
        series: vec![
            Series::new("A_r = F / H", real, BLUE, Style::Line),
            Series::new("A_a, depassivated wake", anodic, RED, Style::Line),
            Series::new("Hertz contact", hertz, PURPLE, Style::Dashed),
        ],
    }
}

/// Colour steps of the pressure maps below the cap: cells of one step in a row are drawn as
/// one rectangle, which keeps a map's SVG to a few hundred kB (one rectangle per 1 um cell
/// made 0.6-0.8 MB).
const SHADES: f64 = 16.0;

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

/// The pressure map as cells coloured up to the yield pressure `cap` (MPa, black at it).
fn pressure_svg(map: &PressureMap, cap: f64, path: &Path) -> Result<(), BenchError> {
    let fail = |source| BenchError::Plot {
        path: path.to_owned(),
        source,
    };
    let root: DrawingArea<SVGBackend, Shift> =
        SVGBackend::new(path, (640, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(fail)?;
    let half = |v: &[f64]| v.iter().fold(0.0_f64, |m, &x| m.max(x.abs())) + 1.0;
    let extent = half(&map.x_um).max(half(&map.y_um));
    let top = map
        .pressure_mpa
        .iter()
        .flatten()
        .fold(0.0_f64, |m, &p| m.max(p));
    let title = format!(
        "Fig. 10: pressure at cycle {} (white 0 to red {top:.0} MPa in 16 steps; black at Y = {cap:.0} MPa)",
        map.cycle
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 14))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(-extent..extent, -extent..extent)
        .map_err(fail)?;
    chart
        .configure_mesh()
        .x_desc("x, sliding direction (um)")
        .y_desc("y, across the track (um)")
        .draw()
        .map_err(fail)?;
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
    chart.draw_series(cells).map_err(fail)?;
    root.present().map_err(fail)
}
