//! The section on the `auto` choices: grid, domain, cycle step, coupling and plasticity.

use std::fmt::Write as _;

use crate::bench::auto::AutoStudies;
use crate::bench::contact::{ContactCase, ContactRow};
use crate::bench::wear::{QUICK_GRID, WearRow, WearStudy};
use crate::simulation::{
    CELLS_PER_CONTACT_RADIUS, DOMAIN_PER_CONTACT_RADIUS, MAX_STEP, STEP_CHANGE_BOUND,
};

use super::contact::hertz_cells_per_radius;
use super::format::{bullets, error, short, sig, table};
use super::wear::{versus, wear_table};
use super::{BenchError, Measurements, PLOT_NOTE, Report, coupling};

/// The contact row nearest the auto cell density, and the one at half of it.
fn nearest_density(rows: &[ContactRow]) -> Option<(&ContactRow, Option<&ContactRow>)> {
    let distance = |r: &ContactRow| {
        (hertz_cells_per_radius(r.n) / CELLS_PER_CONTACT_RADIUS)
            .ln()
            .abs()
    };
    let hertz = || rows.iter().filter(|r| r.case == ContactCase::Hertz);
    let best = hertz().min_by(|a, b| distance(a).total_cmp(&distance(b)))?;
    let coarser = hertz().find(|r| 2 * r.n == best.n);
    Some((best, coarser))
}

/// The section's opening, for wear runs of `cycles` cycles.
pub(super) fn intro(cycles: u64) -> String {
    format!(
        "## The auto choices and the numbers behind them\n\n\
         What `\"auto\"` decides for each scene (`src/simulation/setup.rs`, `stepping.rs`) and \
         what each threshold buys, measured in this run. The wear runs of this section use grid \
         {QUICK_GRID} ({cycles} cycles) where the grid is not the question, to keep the whole \
         command to a few minutes."
    )
}

/// What the paper-scene runs of this section ran with, in words.
fn quick_runs(cycles: u64) -> String {
    format!("grid {QUICK_GRID}, {cycles} cycles")
}

pub(super) fn section(
    report: &mut Report,
    auto: &AutoStudies,
    measured: &Measurements,
) -> Result<(), BenchError> {
    let cycles = auto.wear.first().map_or(0, |r| r.cycles);
    report.push(&intro(cycles));
    grid_choice(report, auto, measured);
    let of = |study: WearStudy| -> Vec<&WearRow> {
        auto.wear.iter().filter(|r| r.study == study).collect()
    };
    domain_choice(report, auto, &of(WearStudy::Domain));
    step_choice(report, measured);
    coupling::section(report, auto)?;
    report.push(&format!("In the paper scene ({}):", quick_runs(cycles)));
    report.push(&wear_table(&of(WearStudy::Coupling), false));
    report.push(&plasticity_intro(auto.loads_n));
    report.push(&bullets(&auto.plasticity));
    report.push(&format!(
        "What the other choice would change ({}):",
        quick_runs(cycles)
    ));
    let rows = [of(WearStudy::Plasticity), of(WearStudy::ElasticLoad)].concat();
    report.push(&wear_table(&rows, false));
    report.push(&format!(
        "The domain, coupling and plasticity alternatives against wall time. {PLOT_NOTE}"
    ));
    let everything: Vec<&WearRow> = auto.wear.iter().collect();
    report.wear_plots("auto", &everything)
}

fn grid_choice(report: &mut Report, auto: &AutoStudies, measured: &Measurements) {
    let g = &auto.grid;
    let mut text = format!(
        "### Grid: `CELLS_PER_CONTACT_RADIUS` = {CELLS_PER_CONTACT_RADIUS}\n\n\
         The paper scene gets {} x {} cells of {:.3} um: {:.1} cells per contact radius of \
         {:.1} um (the side rounds up to a fast FFT size).",
        g.cells, g.cells, g.cell_um, g.cells_per_radius, g.contact_radius_um
    );
    if let Some((best, coarser)) = nearest_density(&measured.contact) {
        let _ = write!(
            text,
            " On the Hertz case the nearest grid, N = {} ({:.1} cells per radius), errs by {} \
             (peak pressure), {} (area) and {} (approach) in {} s",
            best.n,
            hertz_cells_per_radius(best.n),
            error(best.err_pmax),
            error(best.err_area),
            error(best.err_delta),
            sig(best.wall_s, 3)
        );
        if let Some(c) = coarser {
            let _ = write!(
                text,
                "; half the density (N = {}) is {:.1} times faster and errs {:.1} times more in \
                 peak pressure and {:.1} times more in area",
                c.n,
                best.wall_s / c.wall_s,
                (c.err_pmax / best.err_pmax).abs(),
                (c.err_area / best.err_area).abs()
            );
        }
        text += ". The contact table above has every density.";
    }
    report.push(&text);
    let rows: Vec<Vec<String>> = measured
        .wear
        .iter()
        .filter(|r| r.study == WearStudy::Grid)
        .map(|r| {
            let [volume, depth, _] = versus(r);
            vec![
                format!("{:.1}", r.grid as f64 / DOMAIN_PER_CONTACT_RADIUS),
                r.setting.clone(),
                sig(r.wall_s, 3),
                volume,
                depth,
            ]
        })
        .collect();
    if !rows.is_empty() {
        report.push(&format!(
            "On the paper scene (the wear grid study; its domain is auto, so the first grid \
             spans {DOMAIN_PER_CONTACT_RADIUS} contact radii):"
        ));
        let headers = [
            "cells per contact radius",
            "grid",
            "wall s",
            "volume error",
            "depth error",
        ];
        report.push(&table(&headers, &rows));
    }
}

/// The domain choice's heading and what its table compares.
pub(super) fn domain_intro() -> String {
    format!(
        "### Domain: `DOMAIN_PER_CONTACT_RADIUS` = {DOMAIN_PER_CONTACT_RADIUS}, grown near the \
         edge\n\n\
         DC-FFT convolves without wrap-around, so any domain holding the contact gives the same \
         answer: the run starts at {DOMAIN_PER_CONTACT_RADIUS} contact radii and grows the \
         domain when pressure nears its edge. The paper scene at the cells of grid {QUICK_GRID}, \
         against fixed domains:"
    )
}

fn domain_choice(report: &mut Report, auto: &AutoStudies, rows: &[&WearRow]) {
    report.push(&domain_intro());
    report.push(&wear_table(rows, false));
    if auto.domain_growth.is_empty() {
        report.push("The auto-domain run did not grow.");
    } else {
        report.push("The auto-domain run grew as follows (the run's own words):");
        report.push(&bullets(&auto.domain_growth));
    }
}

/// The cycle-step choice's heading and what decides a step.
pub(super) fn step_intro() -> String {
    format!(
        "### Cycle step: `STEP_CHANGE_BOUND` = {STEP_CHANGE_BOUND}, `MAX_STEP` = {MAX_STEP}\n\n\
         A solve stands for the next cycles while the per-pass wear profile changes by less than \
         the bound (relative, L1) per step, the step at most doubling each time and never \
         beyond `MAX_STEP`. The bound is the scene's `numerics.cycle_step_bound` (`auto`: \
         {STEP_CHANGE_BOUND} on a smooth disc, every cycle solved on a rough one); the \
         cycle-step study above sweeps it against solving every cycle:"
    )
}

fn step_choice(report: &mut Report, measured: &Measurements) {
    report.push(&step_intro());
    let steps: Vec<&WearRow> = measured
        .wear
        .iter()
        .filter(|r| r.study == WearStudy::CycleStep)
        .collect();
    if steps.is_empty() {
        report.push("(Measured by `bench wear`; not part of this run.)");
        return;
    }
    let lines: Vec<String> = steps
        .iter()
        .filter(|r| !r.reference)
        .map(|r| {
            format!(
                "{} cycles, {}: {} solves, the longest step {} cycles; {} solves stood for `MAX_STEP` \
                 cycles ({:.0}% of the cycles), the bound, the doubling limit or yielding (steps \
                 of 1 while pressures sit at Y) set the others.",
                r.cycles,
                short(&r.setting),
                r.solves,
                r.longest_step,
                r.steps_at_max,
                100.0 * (r.steps_at_max as u64 * MAX_STEP) as f64 / r.cycles as f64
            )
        })
        .collect();
    report.push(&bullets(&lines));
    if steps.iter().all(|r| r.longest_step < MAX_STEP) {
        report.push(
            "No step reached `MAX_STEP` here: in the paper scene it only bounds how rarely a \
             cycle is recorded, so the accuracy above is the bound's.",
        );
    }
}

/// The plasticity choice's heading, for decisions at `loads_n`.
pub(super) fn plasticity_intro(loads_n: [f64; 2]) -> String {
    format!(
        "### Plasticity: Hertz's p0 against the lowest yield pressure\n\n\
         Pressures are highest on the unworn surface, so `auto` caps them at Y only when \
         Hertz's peak pressure reaches the lowest Y of the run. The decisions at {} N and {} N, \
         in the runs' own words:",
        loads_n[0], loads_n[1]
    )
}
