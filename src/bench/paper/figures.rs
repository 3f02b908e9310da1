//! The figures of `docs/paper.md` as SVG, drawn like the paper's: lines for the runs,
//! markers with their spreads for Table 3's measurements, a colour map for the pressures.

mod chart;
mod legend;
mod pressure;

use std::path::Path;

use plotters::prelude::*;

use crate::scene::{PAPER_BULK_HARDNESS_SPREAD_MPA, PAPER_TABLE3};
use crate::simulation::{PressureMap, SimulationResult};

use super::numbers::{TABLE3, profile, record};
use super::{BenchError, PaperStudy};

/// Colours: elastic blue and EPP red as in the paper's Fig. 11, then the rest.
const BLUE: RGBColor = RGBColor(0x1f, 0x77, 0xb4);
const RED: RGBColor = RGBColor(0xd6, 0x27, 0x28);
const GREEN: RGBColor = RGBColor(0x2c, 0xa0, 0x2c);
const PURPLE: RGBColor = RGBColor(0x94, 0x67, 0xbd);

/// A dashed line's dash and gap, px: the data's and its legend sample's.
const fn dashes_px() -> (i32, i32) {
    (6, 4)
}

/// The shape of a series' markers.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Marker {
    Triangle,
    Circle,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Style {
    Line,
    Dashed,
    Markers(Marker),
}

/// The vertical axis a series reads against.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Axis {
    Left,
    Right,
}

/// One series of a figure.
struct Series {
    name: String,
    points: Vec<(f64, f64)>,
    colour: RGBColor,
    style: Style,
    /// The half-length of each point's error bar, in the unit of y (empty: no bars).
    spreads: Vec<f64>,
    axis: Axis,
}

impl Series {
    fn new(name: &str, points: Vec<(f64, f64)>, colour: RGBColor, style: Style) -> Self {
        Self {
            name: name.to_owned(),
            points,
            colour,
            style,
            spreads: Vec::new(),
            axis: Axis::Left,
        }
    }

    /// The same with error bars of half-length `spreads`, one per point.
    fn with_spreads(self, spreads: Vec<f64>) -> Self {
        assert_eq!(spreads.len(), self.points.len(), "a spread per point");
        Self { spreads, ..self }
    }

    /// The same read against the right axis.
    fn on_right(self) -> Self {
        Self {
            axis: Axis::Right,
            ..self
        }
    }
}

/// A figure on linear axes (x logarithmic when `log_x`): the left one, and a right one when
/// `right_label` names it.
struct Figure {
    title: String,
    x_label: &'static str,
    log_x: bool,
    y_label: &'static str,
    right_label: Option<&'static str>,
    series: Vec<Series>,
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
        pressure::write_svg(map, *cap, &folder.join(name))?;
    }
    Ok(figures.len() + maps.len())
}

/// The last pressure map of `result` and the yield pressure of its cycle, MPa.
pub(super) fn last_map(result: &SimulationResult) -> (&PressureMap, f64) {
    let map = result
        .pressure_maps
        .last()
        .expect("a run keeps its last map");
    let hardness = record(result, map.cycle).hardness_mpa;
    (map, hardness / result.scene.disc.yield_factor)
}

/// The law as the run applied it, Table 3's hardness with its spreads, and the bulk value
/// at n = 1, where the scene's `hardness_fit_includes_bulk` puts it in the fit (the legend
/// says whether it does).
fn hardness(study: &PaperStudy) -> Figure {
    let disc = &study.whole.scene.disc;
    let law = study
        .whole
        .cycles
        .iter()
        .map(|r| (r.cycle as f64, r.hardness_mpa))
        .collect();
    let table = PAPER_TABLE3
        .iter()
        .map(|r| (r.time_s as f64, r.hardness_mpa))
        .collect();
    let spreads = PAPER_TABLE3.iter().map(|r| r.hardness_spread_mpa).collect();
    let bulk = if disc.hardness_fit_includes_bulk {
        "bulk, at n = 1 (in the fit)"
    } else {
        "bulk, at n = 1 (left out of the fit)"
    };
    Figure {
        title: "Fig. 9: hardness of the disc in the track".to_owned(),
        x_label: "cycles n (= rubbing time in s at 60 rpm), log scale: the law is a line",
        log_x: true,
        y_label: "H (MPa)",
        right_label: None,
        series: vec![
            Series::new("fitted law H = A + B ln n", law, RED, Style::Line),
            Series::new(
                "Table 3, in the track",
                table,
                BLUE,
                Style::Markers(Marker::Triangle),
            )
            .with_spreads(spreads),
            Series::new(
                bulk,
                vec![(1.0, disc.hardness_mpa)],
                GREEN,
                Style::Markers(Marker::Circle),
            )
            .with_spreads(vec![PAPER_BULK_HARDNESS_SPREAD_MPA]),
        ],
    }
}

fn volume(study: &PaperStudy) -> Figure {
    let groove = |r: &SimulationResult| {
        r.cycles
            .iter()
            .map(|c| (c.time_s, c.wear_volume_mm3 * 1e3))
            .collect()
    };
    let loaded = |r: &SimulationResult| {
        r.profiles
            .iter()
            .map(|p| {
                let t = record(r, p.cycle).time_s;
                (t, super::numbers::loaded_volume_mm3(r, p.cycle) * 1e3)
            })
            .collect()
    };
    let early = || TABLE3.iter().filter(|&&(t, ..)| t <= 300);
    let measured = early().map(|&(t, _, v, _)| (t as f64, v)).collect();
    let spreads = early().map(|&(.., spread)| spread).collect();
    Figure {
        title: "Fig. 11: wear volume over the first 300 cycles".to_owned(),
        x_label: "rubbing time (s) = cycles",
        log_x: false,
        y_label: "volume (1e-3 mm^3)",
        right_label: None,
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
            Series::new(
                "Table 3, measured (+- spread)",
                measured,
                GREEN,
                Style::Markers(Marker::Triangle),
            )
            .with_spreads(spreads),
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
        log_x: false,
        y_label: "height (um)",
        right_label: None,
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
        log_x: false,
        y_label: "V_WAC (1e-3 mm^3)",
        right_label: None,
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
        title: "Fig. 14: real (F/H, right axis) and depassivated areas".to_owned(),
        x_label: "rubbing time (s)",
        log_x: false,
        y_label: "A_a and Hertz's area (1e-3 mm^2)",
        right_label: Some("A_r = F / H (1e-3 mm^2)"),
        series: vec![
            Series::new("A_r = F / H (right axis)", real, BLUE, Style::Line).on_right(),
            Series::new("A_a, depassivated wake", anodic, RED, Style::Line),
            Series::new("Hertz contact", hertz, PURPLE, Style::Dashed),
        ],
    }
}
