//! The coupling section: how far the friction coupling term moves the Hertz pressures.

use crate::bench::auto::{AutoStudies, CouplingRow};
use crate::bench::plot::{LogLogPlot, Point, Series};
use crate::simulation::COUPLING_SENSITIVITY;

use super::format::{sig, table};
use super::{BenchError, Report};

const COUPLING_HEADERS: [&str; 8] = [
    "N",
    "mu",
    "abs(mu delta-nu)",
    "max abs(pressure change) / p0",
    "ratio",
    "auto",
    "solve s",
    "coupled solve s",
];

fn coupling_cells(r: &CouplingRow) -> Vec<String> {
    vec![
        r.n.to_string(),
        format!("{:.0e}", r.friction_coefficient),
        format!("{:.2e}", r.strength),
        format!("{:.2e}", r.change),
        format!("{:.3}", r.ratio),
        if r.auto_on { "on" } else { "off" }.to_owned(),
        sig(r.normal_s, 3),
        sig(r.coupled_s, 3),
    ]
}

pub(super) fn section(report: &mut Report, auto: &AutoStudies) -> Result<(), BenchError> {
    let mut sizes: Vec<usize> = auto.coupling.iter().map(|r| r.n).collect();
    sizes.dedup();
    let lowest: Vec<String> = sizes
        .iter()
        .map(|&n| {
            let ratio = auto
                .coupling
                .iter()
                .filter(|r| r.n == n && r.auto_on)
                .map(|r| r.ratio)
                .fold(f64::INFINITY, f64::min);
            format!("{ratio:.3} at N = {n}")
        })
        .collect();
    let off = auto.coupling.iter().filter(|r| !r.auto_on);
    let below = off.clone().map(|r| r.change).fold(0.0, f64::max);
    let below_ratio = off.map(|r| r.ratio).fold(f64::INFINITY, f64::min);
    report.push(&format!(
        "### Coupling: `COUPLING_SENSITIVITY` = {COUPLING_SENSITIVITY}\n\n\
         `auto` models the friction coupling term when {COUPLING_SENSITIVITY} |mu delta-nu| \
         reaches the solver tolerance, here the scene's default ({:.0e}). On the Hertz case, \
         solved with and without the term at that tolerance, the largest pressure change \
         relative to p0 is at least {} times |mu delta-nu| (over the rows `auto` models). The \
         ratio grows with the grid (the change peaks at the contact edge), so \
         {COUPLING_SENSITIVITY} is the coarsest grid's: the side that models the term more \
         often. Below the threshold the term still moves the pressures by at least \
         {below_ratio:.3} times |mu delta-nu|, but by at most {below:.1e} of p0: of the order \
         of the tolerance (a relative residual) the solves themselves stop at, so leaving \
         the term out there errs about as much as stopping the solver does.\n",
        auto.tolerance,
        lowest.join(", ")
    ));
    let cells: Vec<Vec<String>> = auto.coupling.iter().map(coupling_cells).collect();
    report.push(&table(&COUPLING_HEADERS, &cells));
    report.plot(
        "coupling",
        &LogLogPlot {
            title: "Coupling term: pressure change against |mu delta-nu|".into(),
            x_label: "|mu delta-nu|".into(),
            y_label: "max |pressure change| / p0".into(),
            series: coupling_series(&auto.coupling, &sizes),
        },
    )
}

/// The threshold line, then one series per grid size in `sizes`.
fn coupling_series(rows: &[CouplingRow], sizes: &[usize]) -> Vec<Series> {
    let mut series: Vec<Series> = sizes
        .iter()
        .enumerate()
        .map(|(i, &n)| Series {
            name: format!("N = {n}"),
            points: rows
                .iter()
                .filter(|r| r.n == n)
                .map(|r| Point {
                    x: r.strength,
                    y: r.change,
                    // The same mu at every N: labelled once.
                    label: if i == 0 {
                        format!("mu={:.0e}", r.friction_coefficient)
                    } else {
                        String::new()
                    },
                })
                .collect(),
        })
        .collect();
    let mut strengths: Vec<f64> = rows.iter().map(|r| r.strength).collect();
    strengths.sort_by(f64::total_cmp);
    strengths.dedup();
    let threshold = Series {
        name: format!("{COUPLING_SENSITIVITY} |mu delta-nu|"),
        points: strengths
            .iter()
            .map(|&s| Point {
                x: s,
                y: COUPLING_SENSITIVITY * s,
                label: String::new(),
            })
            .collect(),
    };
    // Drawn first so the measured lines lie on top of it.
    series.insert(0, threshold);
    series
}
