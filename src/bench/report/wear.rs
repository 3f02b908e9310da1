//! The paper-scene sections: the grid, tolerance, cycle-step and paper-numerics studies, and
//! the volumes against the paper's Table 3.

use crate::bench::plot::{Point, Series};
use crate::bench::wear::{QUICK_GRID, TABLE3, WearRow, WearStudy};
use crate::scene::DALMAU2018_316L;
use crate::simulation::DOMAIN_PER_CONTACT_RADIUS;

use super::format::{error, short, sig, table};
use super::{BenchError, PLOT_NOTE, Report};

const WEAR_HEADERS: [&str; 7] = [
    "setting",
    "cycles",
    "wall s",
    "solves",
    "volume error",
    "depth error",
    "speed-up",
];

/// Added after `solves` where the cycle step is the question.
const STEP_HEADERS: [&str; 2] = ["longest step", "solves of MAX_STEP"];

/// Volume error, depth error and speed-up, or `reference`.
pub(super) fn versus(r: &WearRow) -> [String; 3] {
    if r.reference {
        ["reference".into(), "reference".into(), "1".into()]
    } else {
        [
            error(r.err_volume),
            error(r.err_depth),
            format!("{:.1}", r.speedup),
        ]
    }
}

fn wear_cells(r: &WearRow, steps: bool) -> Vec<String> {
    let mut cells = vec![
        r.setting.clone(),
        r.cycles.to_string(),
        sig(r.wall_s, 3),
        r.solves.to_string(),
    ];
    if steps {
        cells.extend([r.longest_step.to_string(), r.steps_at_max.to_string()]);
    }
    cells.extend(versus(r));
    cells
}

pub(super) fn wear_table(rows: &[&WearRow], steps: bool) -> String {
    let mut headers = WEAR_HEADERS.to_vec();
    if steps {
        headers.splice(4..4, STEP_HEADERS);
    }
    let cells: Vec<Vec<String>> = rows.iter().map(|r| wear_cells(r, steps)).collect();
    table(&headers, &cells)
}

/// One series per study (and cycle count, when a study has several references), the
/// references left out: their error is 0 by definition.
pub(super) fn wear_series(rows: &[&WearRow], measure: fn(&WearRow) -> f64) -> Vec<Series> {
    let mut keys: Vec<(WearStudy, u64)> = Vec::new();
    for r in rows {
        if !keys.contains(&(r.study, r.cycles)) {
            keys.push((r.study, r.cycles));
        }
    }
    keys.iter()
        .map(|&(study, cycles)| {
            let several = keys.iter().filter(|k| k.0 == study).count() > 1;
            Series {
                name: if several {
                    format!("{}, {cycles} cycles", study.name().replace('_', " "))
                } else {
                    study.name().replace('_', " ")
                },
                points: rows
                    .iter()
                    .filter(|r| r.study == study && r.cycles == cycles && !r.reference)
                    .map(|r| Point {
                        x: r.wall_s,
                        y: measure(r).abs(),
                        label: short(&r.setting).to_owned(),
                    })
                    .collect(),
            }
        })
        .filter(|s| !s.points.is_empty())
        .collect()
}

/// A study's heading and what its errors are against, for runs of the given cycles.
type Heading = fn(u64) -> String;

/// The wear studies in report order, with their headings.
pub(super) const WEAR_STUDIES: [(WearStudy, Heading); 4] = [
    (WearStudy::Grid, grid_heading),
    (WearStudy::Tolerance, tolerance_heading),
    (WearStudy::CycleStep, step_heading),
    (WearStudy::PaperNumerics, paper_heading),
];

/// The section's opening.
pub(super) fn intro() -> String {
    format!(
        "## Wear: the paper scene\n\n\
         The `{DALMAU2018_316L}` preset; errors are those of the final wear volume and deepest \
         point, relative to each study's reference; speed-up is the reference's wall time over \
         the row's.\n"
    )
}

fn grid_heading(cycles: u64) -> String {
    format!(
        "### Grid\n\nCells across the first domain ({DOMAIN_PER_CONTACT_RADIUS} contact radii, \
         grown with the track), {cycles} cycles; errors against the finest grid."
    )
}

fn tolerance_heading(cycles: u64) -> String {
    format!(
        "### Solver tolerance\n\nGrid {QUICK_GRID}, {cycles} cycles; errors against the \
         tightest tolerance."
    )
}

/// The cycle-step study runs its own cycle counts and says so in its table.
fn step_heading(_: u64) -> String {
    "### Cycle step\n\nThe auto grid; errors against solving every cycle, at the same cycle \
     count."
        .to_owned()
}

fn paper_heading(cycles: u64) -> String {
    format!("### The paper's numerics against all auto\n\n{cycles} cycles.")
}

/// The Table 3 heading: what k is calibrated on and what the errors are against.
pub(super) fn table3_intro() -> String {
    let (last_s, _) = TABLE3[TABLE3.len() - 1];
    format!(
        "### Against the paper's Table 3\n\n\
         Archard's k calibrated on the {last_s} s volume, grid {QUICK_GRID}; errors against the \
         measured volumes (the last solved cycle at or before each time). One run, so no time \
         axis: this is the model's accuracy, not a numerical setting's.\n"
    )
}

pub(super) fn section(report: &mut Report, rows: &[WearRow]) -> Result<(), BenchError> {
    report.push(&intro());
    let mut plotted = Vec::new();
    for (study, heading) in WEAR_STUDIES {
        let of: Vec<&WearRow> = rows.iter().filter(|r| r.study == study).collect();
        let Some(first) = of.first() else {
            continue;
        };
        report.push(&heading(first.cycles));
        report.push(&wear_table(&of, study == WearStudy::CycleStep));
        plotted.extend(of);
    }
    report.push(&format!(
        "The grid, tolerance and cycle-step studies on one pair of axes. {PLOT_NOTE}\n"
    ));
    report.wear_plots("wear", &plotted)?;

    let measured: Vec<Vec<String>> = rows
        .iter()
        .filter(|r| r.study == WearStudy::Table3)
        .map(|r| {
            vec![
                r.setting.clone(),
                r.cycles.to_string(),
                format!("{:.3e}", r.wear_volume_mm3),
                error(r.err_volume),
            ]
        })
        .collect();
    if !measured.is_empty() {
        report.push(&table3_intro());
        report.push(&table(
            &["measurement", "solved cycle", "volume mm3", "error"],
            &measured,
        ));
    }
    Ok(())
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    pub(in crate::bench::report) fn wear_row(
        study: WearStudy,
        setting: &str,
        err: f64,
        reference: bool,
    ) -> WearRow {
        WearRow {
            study,
            setting: setting.to_owned(),
            cycles: 300,
            grid: 64,
            wall_s: 0.3125,
            solves: 87,
            iterations: 900,
            wear_volume_mm3: 1.2e-3,
            max_depth_um: 0.76,
            err_volume: err,
            err_depth: -err,
            speedup: 3.0,
            reference,
            longest_step: 16,
            steps_at_max: 0,
        }
    }

    #[test]
    fn a_wear_row_shows_its_errors_and_a_reference_says_so() {
        let cells = wear_cells(
            &wear_row(WearStudy::Grid, "64 cells, 2.07 um", 1.3e-4, false),
            true,
        );
        assert_eq!(
            cells,
            [
                "64 cells, 2.07 um",
                "300",
                "0.312",
                "87",
                "16",
                "0",
                "+1.30e-4",
                "-1.30e-4",
                "3.0"
            ]
        );
        let cells = wear_cells(&wear_row(WearStudy::Grid, "256 cells", 0.0, true), false);
        assert_eq!(&cells[4..], ["reference", "reference", "1"]);
        assert_eq!(error(f64::NAN), "n/a");
    }

    #[test]
    fn series_leave_references_out_and_split_studies_by_cycle_count() {
        let mut long = wear_row(WearStudy::CycleStep, "auto", 2e-4, false);
        long.cycles = 3600;
        let rows = [
            wear_row(WearStudy::CycleStep, "every cycle (reference)", 0.0, true),
            wear_row(WearStudy::CycleStep, "auto", 0.0, false),
            long,
            wear_row(WearStudy::Grid, "128 cells, 1.04 um", -3e-5, false),
        ];
        let refs: Vec<&WearRow> = rows.iter().collect();
        let series = wear_series(&refs, |r| r.err_volume);
        let names: Vec<&str> = series.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            ["cycle step, 300 cycles", "cycle step, 3600 cycles", "grid"]
        );
        assert_eq!(series[0].points.len(), 1, "the reference is left out");
        assert!(
            series[0].points[0].y == 0.0,
            "an exact zero is kept for the plot"
        );
        assert_eq!(series[2].points[0].label, "128 cells");
        assert!(series[2].points[0].y > 0.0, "|error|");
    }
}
