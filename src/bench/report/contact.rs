//! The contact sections: the Hertz and capped grid tables, their plots, and the solver
//! tolerance study.

use crate::bench::contact::{
    CAPPED_HARDNESS_CYCLES, CAPPED_REFERENCE_N, CAPPED_YIELD_FACTOR, CAPPED_YIELD_PRESSURE_PA,
    ContactCase, ContactRow, DOMAIN_M, TIGHT_TOLERANCE, ToleranceRow, paper_case, paper_hertz,
};
use crate::bench::plot::{Point, Series};

use super::format::{error, sig, table};
use super::{BenchError, PLOT_NOTE, Report};

/// Cells per Hertz contact radius on the contact benchmark's grid of `n` cells.
pub(super) fn hertz_cells_per_radius(n: usize) -> f64 {
    paper_hertz().1.contact_radius_m() / (DOMAIN_M / n as f64)
}

const CONTACT_HEADERS: [&str; 12] = [
    "N",
    "cells per contact radius",
    "wall s",
    "build s",
    "solve s",
    "iterations",
    "uniform start: solve s",
    "iterations",
    "iteration / FFT pair",
    "p_max error",
    "area error",
    "approach error",
];

fn contact_cells(r: &ContactRow) -> Vec<String> {
    vec![
        r.n.to_string(),
        format!("{:.1}", hertz_cells_per_radius(r.n)),
        sig(r.wall_s, 3),
        sig(r.build_s, 3),
        sig(r.solve_s, 3),
        r.iterations.to_string(),
        sig(r.uniform_solve_s, 3),
        r.uniform_iterations.to_string(),
        format!("{:.2}", r.iteration_per_fft_pair),
        error(r.err_pmax),
        error(r.err_area),
        error(r.err_delta),
    ]
}

/// One Hertz error of a contact row.
type ContactMeasure = fn(&ContactRow) -> f64;

/// The Hertz errors, each plotted against wall time: file name, words, value.
const CONTACT_MEASURES: [(&str, &str, ContactMeasure); 3] = [
    ("pmax", "peak pressure", |r| r.err_pmax),
    ("area", "contact area", |r| r.err_area),
    ("approach", "approach", |r| r.err_delta),
];

/// One study's points for one Hertz error.
fn contact_series(study: &str, rows: &[ContactRow], measure: ContactMeasure) -> Series {
    Series {
        name: study.to_owned(),
        points: rows
            .iter()
            .map(|r| Point {
                x: r.wall_s,
                y: measure(r).abs(),
                label: format!("N={}", r.n),
            })
            .collect(),
    }
}

/// The section's opening: the case and what the times cover.
pub(super) fn intro() -> String {
    format!(
        "## Contact: the Hertz case\n\n\
         The paper's case {} against Hertz's solution. Wall time is the kernel and operator \
         construction plus the cold solve as the simulation's first cycle and `tribosim contact` \
         make it: from the coarse-to-fine start (the same contact solved on grids of half the \
         cells per side, interpolated; coarse operators and solves are in the solve time, \
         their iterations not in the count). The uniform start's solve, run alternately with it, \
         is beside it, and its time per iteration in \"FFT pairs\": one forward and inverse real \
         FFT of the padded 2N x 2N grid, timed in the same run. Medians of repeated runs.\n\n\
         ### Grid\n",
        paper_case()
    )
}

/// The capped table's heading and what its errors are against.
pub(super) fn capped_intro() -> String {
    format!(
        "### Capped at Y = {:.1} MPa\n\n\
         The same case with the pressure cap (the paper's H({CAPPED_HARDNESS_CYCLES} cycles) / \
         {CAPPED_YIELD_FACTOR}). No analytic answer exists: the errors are against our own \
         N = {CAPPED_REFERENCE_N} solution solved to {TIGHT_TOLERANCE:.0e}, and \"p_max / Y - 1\" \
         checks that the cap is reached and held.",
        CAPPED_YIELD_PRESSURE_PA / 1e6
    )
}

/// The tolerance study's heading and its solve error, for a study on `n` cells.
pub(super) fn tolerance_intro(n: usize) -> String {
    format!(
        "### Solver tolerance\n\n\
         The grid held at N = {n}; \"solve error\" is max |p - p*| / max p* against the same \
         grid solved to {TIGHT_TOLERANCE:.0e}, the part of the error the tolerance alone leaves. \
         The other errors are those of the grid table (against Hertz, or the capped reference)."
    )
}

pub(super) fn section(
    report: &mut Report,
    rows: &[ContactRow],
    tolerance: &[ToleranceRow],
) -> Result<(), BenchError> {
    report.push(&intro());
    let of = |case: ContactCase| -> Vec<ContactRow> {
        rows.iter().filter(|r| r.case == case).cloned().collect()
    };
    let (elastic, capped) = (of(ContactCase::Hertz), of(ContactCase::Capped));
    let cells: Vec<Vec<String>> = elastic.iter().map(contact_cells).collect();
    report.push(&table(&CONTACT_HEADERS, &cells));
    if !capped.is_empty() {
        report.push(&capped_intro());
        let cells: Vec<Vec<String>> = capped.iter().map(capped_cells).collect();
        report.push(&table(&CAPPED_HEADERS, &cells));
    }
    report.push(PLOT_NOTE);
    for (name, what, measure) in CONTACT_MEASURES {
        let mut series = vec![contact_series("Hertz", &elastic, measure)];
        // The capped p_max is the cap itself, not an error of the grid.
        if name != "pmax" && !capped.is_empty() {
            series.push(contact_series("capped", &capped, measure));
        }
        report.time_plot(
            &format!("contact-{name}"),
            format!("Contact {what}: |error| against wall time"),
            series,
        )?;
    }
    if let Some(first) = tolerance.first() {
        tolerance_section(report, first.n, tolerance)?;
    }
    Ok(())
}

const CAPPED_HEADERS: [&str; 7] = [
    "N",
    "wall s",
    "iterations",
    "p_max / Y - 1",
    "area error",
    "approach error",
    "capped area error",
];

fn capped_cells(r: &ContactRow) -> Vec<String> {
    vec![
        r.n.to_string(),
        sig(r.wall_s, 3),
        r.iterations.to_string(),
        error(r.err_pmax),
        error(r.err_area),
        error(r.err_delta),
        r.err_plastic_area.map_or_else(String::new, error),
    ]
}

const TOLERANCE_HEADERS: [&str; 8] = [
    "case",
    "tolerance",
    "solve s",
    "iterations",
    "residual",
    "solve error",
    "area error",
    "approach error",
];

fn tolerance_cells(r: &ToleranceRow) -> Vec<String> {
    vec![
        r.case.name().to_owned(),
        format!("{:.0e}", r.tolerance),
        sig(r.solve_s, 3),
        r.iterations.to_string(),
        format!("{:.1e}", r.residual),
        error(r.err_solve),
        error(r.err_area),
        error(r.err_delta),
    ]
}

fn tolerance_section(
    report: &mut Report,
    n: usize,
    rows: &[ToleranceRow],
) -> Result<(), BenchError> {
    report.push(&tolerance_intro(n));
    let cells: Vec<Vec<String>> = rows.iter().map(tolerance_cells).collect();
    report.push(&table(&TOLERANCE_HEADERS, &cells));
    let series: Vec<Series> = ContactCase::ALL
        .iter()
        .map(|&case| Series {
            name: case.name().to_owned(),
            points: rows
                .iter()
                .filter(|r| r.case == case)
                .map(|r| Point {
                    x: r.solve_s,
                    y: r.err_solve.abs(),
                    label: format!("{:.0e}", r.tolerance),
                })
                .collect(),
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    report.time_plot(
        "contact-tolerance",
        format!("Contact solve error against solve time, by tolerance (N = {n})"),
        series,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::contact::{ContactStudy, Reference};

    #[test]
    fn a_contact_row_formats_as_one_markdown_line() {
        let row = ContactRow {
            study: ContactStudy::Grid,
            case: ContactCase::Hertz,
            n: 256,
            runs: 9,
            residual: 9.7e-9,
            err_plastic_area: None,
            measures: Reference::hertz().measures,
            reference: Reference::hertz(),
            wall_s: 0.083_91,
            build_s: 0.0142,
            solve_s: 0.0697,
            iterations: 11,
            applies: 17,
            uniform_solve_s: 0.0866,
            uniform_iterations: 21,
            fft_pair_s: 1.5e-3,
            iteration_per_fft_pair: 1.181,
            err_pmax: -1.0751e-4,
            err_area: 6.3666e-3,
            err_delta: -2.2598e-5,
        };
        let text = table(&CONTACT_HEADERS, &[contact_cells(&row)]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(
            lines[1],
            "|---|---|---|---|---|---|---|---|---|---|---|---|"
        );
        assert_eq!(
            lines[2],
            "| 256 | 44.2 | 0.0839 | 0.0142 | 0.0697 | 11 | 0.0866 | 21 | 1.18 | -1.08e-4 | +6.37e-3 | -2.26e-5 |"
        );
    }
}
