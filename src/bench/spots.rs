//! `tribosim bench spots`: the depassivated area predicted from the solved contact's spots
//! with literature kinetics (the paper's Section 5.1 next step), against the paper's reading
//! of Fig. 14 at Table 3's times. `--markdown docs/corrosion.md` rewrites that page's section
//! between its markers; `tests/spots.rs` reruns the cheap rows and compares.
//!
//! Like with like: the paper's A_a is eq. 18 as printed inverted at the measured potential,
//! so each model's potential is set beside the paper's (eq. 18 at A_a = 50 F / H with
//! Table 3's hardness, `docs/calibration/paper_ocp.csv`), and its A_a / (F / H) beside the
//! paper's 50 both as the model's own bare-equivalent area and as eq. 18 as printed would
//! read the model's potential.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use serde::Serialize;

use crate::corrosion::galvanic::Balance;
use crate::scene::{PAPER_TABLE3, Scene, paper_surface};
use crate::simulation::{
    CycleRecord, Plan, RunOptions, Setup, SimulationError, parse_scene_str, run_setup,
};

use super::BenchError;

/// The section's markers in the page.
pub const BEGIN: &str = "<!-- bench spots: begin -->";
/// The end marker.
pub const END: &str = "<!-- bench spots: end -->";

/// One model of the comparison: its label and its scene's overrides.
#[derive(Debug, Clone, Copy)]
pub struct SpotCase {
    /// What the row is.
    pub label: &'static str,
    /// Whether anything in it was fitted to the potential.
    pub fitted: &'static str,
    /// Whether the disc has the paper's polished surface ([`paper_surface`]) or is smooth.
    pub rough: bool,
    /// The `corrosion` section, JSON.
    pub corrosion: &'static str,
}

/// The cases, the smooth ones first (cheap: `tests/spots.rs` reruns them).
pub const CASES: [SpotCase; 6] = [
    SpotCase {
        label: "depassivated_wake (default), smooth disc",
        fitted: "tau = 0.148 s fitted to these potentials",
        rough: false,
        corrosion: "{}",
    },
    SpotCase {
        label: "contact_spots, smooth disc, exp. tau 10 ms",
        fitted: "nothing",
        rough: false,
        corrosion: r#"{"anodic_area": "contact_spots"}"#,
    },
    SpotCase {
        label: "asperity_spots, smooth disc, exp. tau 10 ms",
        fitted: "nothing",
        rough: false,
        corrosion: r#"{"anodic_area": "asperity_spots"}"#,
    },
    SpotCase {
        label: "contact_spots, smooth disc, power law n 1/2 after t0 1 ms",
        fitted: "nothing; t0 and n not sourced (sensitivity)",
        rough: false,
        corrosion: r#"{"anodic_area": "contact_spots", "repassivation_kinetics": "power_law",
            "repassivation_time_s": 0.001, "repassivation_exponent": 0.5}"#,
    },
    SpotCase {
        label: "contact_spots, the paper's rough surface, exp. tau 10 ms",
        fitted: "nothing",
        rough: true,
        corrosion: r#"{"anodic_area": "contact_spots"}"#,
    },
    SpotCase {
        label: "asperity_spots, the paper's rough surface, exp. tau 10 ms",
        fitted: "nothing",
        rough: true,
        corrosion: r#"{"anodic_area": "asperity_spots"}"#,
    },
];

/// How many of [`CASES`] are on the smooth disc.
pub const SMOOTH_CASES: usize = 4;

/// One model at one of Table 3's times.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpotPoint {
    /// Rubbing time, s.
    pub time_s: f64,
    /// The model's A_a over F / H at that cycle's hardness.
    pub ratio: f64,
    /// The run's potential (eq. 18 as printed, capped at E_corr), V.
    pub potential_v: f64,
    /// The balanced cell's potential at the same A_a, V.
    pub balanced_v: f64,
    /// Eq. 18 at A_a = 50 F / H with Table 3's hardness, V.
    pub paper_v: f64,
}

/// One model's points and how far they are from the paper.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpotRow {
    /// The case's label.
    pub label: &'static str,
    /// What was fitted.
    pub fitted: &'static str,
    /// At each of Table 3's times.
    pub points: Vec<SpotPoint>,
    /// Wall time of the run, s.
    pub wall_s: f64,
}

impl SpotRow {
    /// Root-mean-square of the run's potential less the paper's, V.
    pub fn rms_v(&self) -> f64 {
        self.rms_of(|p| p.potential_v)
    }

    /// Root-mean-square of the balanced cell's potential less the paper's, V.
    pub fn balanced_rms_v(&self) -> f64 {
        self.rms_of(|p| p.balanced_v)
    }

    fn rms_of(&self, potential: impl Fn(&SpotPoint) -> f64) -> f64 {
        let sum: f64 = self
            .points
            .iter()
            .map(|p| (potential(p) - p.paper_v).powi(2))
            .sum();
        (sum / self.points.len() as f64).sqrt()
    }

    /// The ratio's largest over its smallest; `None` when some time has no anodic area.
    pub fn ratio_spread(&self) -> Option<f64> {
        let (low, high) = self
            .points
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(l, h), p| {
                (l.min(p.ratio), h.max(p.ratio))
            });
        (low > 0.0).then(|| high / low)
    }
}

/// The scene of `case` over `cycles` cycles.
pub fn scene_json(case: &SpotCase, cycles: u64) -> String {
    let surface = if case.rough {
        serde_json::to_value(paper_surface()).unwrap_or(serde_json::Value::Null)
    } else {
        serde_json::Value::Null
    };
    format!(
        r#"{{"name": "{}", "test": {{"cycles": {cycles}}}, "disc": {{"surface": {surface}}},
            "corrosion": {}}}"#,
        case.label, case.corrosion
    )
}

/// Runs `case` to the last of `times_s` and reads it at each.
pub fn run_case(case: &SpotCase, times_s: &[f64]) -> Result<SpotRow, BenchError> {
    let parse = |json: &str| -> Result<Plan, SimulationError> { Ok(parse_scene_str(json)?) };
    let last = times_s.iter().fold(0.0_f64, |m, &t| m.max(t));
    let cycles = parse(&scene_json(case, 1))?.scene().cycles_at(last).ceil() as u64;
    let plan = parse(&scene_json(case, cycles))?;
    let setup = Setup::new(&plan, &RunOptions::default())?;
    let result = run_setup(&setup, &mut |_| {}, &AtomicBool::new(false))?;
    let scene = setup.scene();
    let points = times_s
        .iter()
        .map(|&t| point(scene, &result.cycles, t))
        .collect();
    Ok(SpotRow {
        label: case.label,
        fitted: case.fitted,
        points,
        wall_s: result.summary.wall_s,
    })
}

/// The record nearest `time_s`, as a point.
fn point(scene: &Scene, records: &[CycleRecord], time_s: f64) -> SpotPoint {
    let record = records
        .iter()
        .min_by(|a, b| {
            (a.time_s - time_s)
                .abs()
                .total_cmp(&(b.time_s - time_s).abs())
        })
        .expect("a run records its first cycle");
    let corrosion = scene.corrosion.clone().unwrap_or_default();
    let model = corrosion.model();
    let area_m2 = record.anodic_area_mm2.unwrap_or(0.0) * 1e-6;
    let real_m2 = scene.load_n() / (record.hardness_mpa * 1e6);
    let plain = Balance {
        bare_corrosion_potential_v: None,
        ohmic_resistance_ohm: 0.0,
    };
    let table3_mpa = PAPER_TABLE3
        .iter()
        .min_by(|a, b| {
            (a.time_s as f64 - time_s)
                .abs()
                .total_cmp(&(b.time_s as f64 - time_s).abs())
        })
        .map_or(record.hardness_mpa, |row| row.hardness_mpa);
    let paper_area = 50.0 * scene.load_n() / (table3_mpa * 1e6);
    SpotPoint {
        time_s,
        ratio: area_m2 / real_m2,
        potential_v: record.potential_v.unwrap_or(model.corrosion_potential_v),
        balanced_v: plain
            .couple(&model, area_m2)
            .map_or(f64::NAN, |c| c.potential_v),
        paper_v: model.coupled_potential_v(paper_area).unwrap_or(f64::NAN),
    }
}

/// Table 3's rubbing times, s.
pub fn table3_times_s() -> Vec<f64> {
    PAPER_TABLE3.iter().map(|r| r.time_s as f64).collect()
}

/// The section's markdown for `rows`.
pub fn markdown(rows: &[SpotRow]) -> String {
    let times = table3_times_s();
    let mut out = String::new();
    out.push_str(BEGIN);
    out.push_str("\n\n");
    out.push_str("| model | fitted |");
    for t in &times {
        out.push_str(&format!(
            " {t} s: A_a / (F/H); E (V, residual mV); balanced E (V, residual mV) |"
        ));
    }
    out.push_str(
        " rms E vs paper (mV) | rms balanced E (mV) | ratio max / min | run (s) |\n|---|---|",
    );
    out.push_str(&"---|".repeat(times.len() + 4));
    out.push('\n');
    out.push_str("| the paper, A_a = 50 F / H | A_a inferred from the measured E |");
    if let Some(first) = rows.first() {
        for p in &first.points {
            out.push_str(&format!(" 50; {:.3} |", p.paper_v));
        }
    }
    out.push_str(" | | 1 | |\n");
    for row in rows {
        out.push_str(&format!("| {} | {} |", row.label, row.fitted));
        for p in &row.points {
            out.push_str(&format!(
                " {:.1}; {:.3} ({:+.0}); {:.3} ({:+.0}) |",
                p.ratio,
                p.potential_v,
                (p.potential_v - p.paper_v) * 1e3,
                p.balanced_v,
                (p.balanced_v - p.paper_v) * 1e3
            ));
        }
        let spread = row
            .ratio_spread()
            .map_or("no area at some times".to_owned(), |s| format!("{s:.2}"));
        out.push_str(&format!(
            " {:.0} | {:.0} | {spread} | {:.0} |\n",
            row.rms_v() * 1e3,
            row.balanced_rms_v() * 1e3,
            row.wall_s
        ));
    }
    out.push('\n');
    out.push_str(END);
    out
}

/// Runs every case and rewrites the section of the page at `path` (between [`BEGIN`] and
/// [`END`]), or prints it without a path.
pub fn write(path: Option<&Path>) -> Result<(), BenchError> {
    let times = table3_times_s();
    let mut rows = Vec::new();
    for case in &CASES {
        eprintln!("spots: {}", case.label);
        rows.push(run_case(case, &times)?);
    }
    let section = markdown(&rows);
    let Some(path) = path else {
        println!("{section}");
        return Ok(());
    };
    let write_error = |source| BenchError::Write {
        path: path.to_path_buf(),
        source,
    };
    let page = std::fs::read_to_string(path).map_err(write_error)?;
    let (Some(begin), Some(end)) = (page.find(BEGIN), page.find(END)) else {
        return Err(BenchError::NoSection {
            path: path.to_path_buf(),
            begin: BEGIN,
            end: END,
        });
    };
    let updated = format!("{}{section}{}", &page[..begin], &page[end + END.len()..]);
    std::fs::write(path, updated).map_err(write_error)
}
