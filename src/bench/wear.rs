//! The wear benchmark of issue 3 on the paper scene: cycle stepping against every-cycle
//! solving, grid refinement, solver tolerance, the paper's own numerics, and the volumes
//! against Table 3 with k calibrated on its 3600 s point.

use std::sync::atomic::AtomicBool;

use serde::Serialize;

use crate::scene::parse_scene_str;
use crate::simulation::{
    MAX_STEP, STEP_CHANGE_BOUND, Setup, SimulationError, SimulationResult, run,
};

/// One run of the wear benchmark, with its errors against the reference of its table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WearRow {
    /// Which table: `cycle_step`, `grid`, `tolerance`, `paper_numerics`, `table3`.
    pub study: &'static str,
    /// The setting varied, in words.
    pub setting: String,
    /// Cycles simulated.
    pub cycles: u64,
    /// Cells per side of the first grid.
    pub grid: usize,
    /// Wall time of the run, s.
    pub wall_s: f64,
    /// Contact solves.
    pub solves: usize,
    /// Solver iterations over the run.
    pub iterations: usize,
    /// Final wear volume, mm^3.
    pub wear_volume_mm3: f64,
    /// Final deepest point, um.
    pub max_depth_um: f64,
    /// Relative volume error against the study's reference (0 for the reference).
    pub err_volume: f64,
    /// Relative depth error against the reference.
    pub err_depth: f64,
    /// Reference wall time over this row's wall time.
    pub speedup: f64,
    /// Whether this row is its study's reference (errors 0 by definition).
    pub reference: bool,
    /// Longest cycle step, cycles.
    pub longest_step: u64,
    /// Solves that stood for [`MAX_STEP`] cycles.
    pub steps_at_max: usize,
}

/// Runs the paper scene (`dalmau2018-316l`) with `overrides` (a JSON object).
pub(super) fn simulate(overrides: &str) -> Result<SimulationResult, SimulationError> {
    let json = format!(r#"{{"preset": "dalmau2018-316l", "overrides": {overrides}}}"#);
    let scene = parse_scene_str(&json)?;
    run(&scene, &mut |_| {}, &AtomicBool::new(false))
}

/// The row of `result` in `study`, with its errors against `reference` (the same run for the
/// reference row itself).
pub(super) fn row(
    study: &'static str,
    setting: String,
    result: &SimulationResult,
    reference: &SimulationResult,
) -> WearRow {
    let s = &result.summary;
    let r = &reference.summary;
    // Solved cycles are recorded; the gaps between them are the steps (the last is 1).
    let steps: Vec<u64> = result
        .cycles
        .windows(2)
        .map(|w| w[1].cycle - w[0].cycle)
        .collect();
    WearRow {
        study,
        setting,
        cycles: s.cycles,
        // The scene as run always sets up again.
        grid: Setup::new(&result.scene).map_or(0, |setup| setup.grid.nx),
        wall_s: s.wall_s,
        solves: s.solves,
        iterations: s.iterations,
        wear_volume_mm3: s.wear_volume_mm3,
        max_depth_um: s.max_depth_um,
        err_volume: s.wear_volume_mm3 / r.wear_volume_mm3 - 1.0,
        err_depth: s.max_depth_um / r.max_depth_um - 1.0,
        speedup: r.wall_s / s.wall_s,
        reference: std::ptr::eq(result, reference),
        longest_step: steps.iter().copied().max().unwrap_or(1),
        steps_at_max: steps.iter().filter(|&&m| m == MAX_STEP).count(),
    }
}

/// Runs every study. Takes a few minutes: the every-cycle reference of 3600 cycles solves
/// 3600 contacts.
pub fn wear_rows() -> Result<Vec<WearRow>, SimulationError> {
    let mut rows = Vec::new();

    // Cycle stepping with the scene's own (auto) grid and domain.
    for cycles in [300, 3600] {
        let every = simulate(&format!(
            r#"{{"test": {{"cycles": {cycles}}}, "numerics": {{"cycle_step": 1}}}}"#
        ))?;
        rows.push(row(
            "cycle_step",
            "every cycle (reference)".into(),
            &every,
            &every,
        ));
        // The step bound (`numerics.cycle_step_bound`) around its default.
        for bound in [0.003, STEP_CHANGE_BOUND, 0.03] {
            let auto = simulate(&format!(
                r#"{{"test": {{"cycles": {cycles}}}, "numerics": {{"cycle_step_bound": {bound}}}}}"#
            ))?;
            let default = if bound == STEP_CHANGE_BOUND {
                " (default)"
            } else {
                ""
            };
            rows.push(row(
                "cycle_step",
                format!("bound {bound}{default}, auto"),
                &auto,
                &every,
            ));
        }
    }

    // Grid: cells across the first domain (3 contact radii, growing with the track).
    let grids: Vec<(usize, SimulationResult)> = [256, 128, 64]
        .into_iter()
        .map(|n| simulate(&format!(r#"{{"numerics": {{"grid": {n}}}}}"#)).map(|r| (n, r)))
        .collect::<Result<_, _>>()?;
    for (n, result) in &grids {
        let setting = format!(
            "{n} cells, {:.2} um{}",
            132.6 / *n as f64,
            if *n == 256 { " (reference)" } else { "" }
        );
        rows.push(row("grid", setting, result, &grids[0].1));
    }

    // Solver tolerance.
    let tolerances: Vec<(f64, SimulationResult)> = [1e-10, 1e-8, 1e-6, 1e-4]
        .into_iter()
        .map(|t| {
            simulate(&format!(
                r#"{{"numerics": {{"grid": 64, "tolerance": {t:e}}}}}"#
            ))
            .map(|r| (t, r))
        })
        .collect::<Result<_, _>>()?;
    for (i, (t, result)) in tolerances.iter().enumerate() {
        let reference = if i == 0 { " (reference)" } else { "" };
        rows.push(row(
            "tolerance",
            format!("{t:.0e}, grid 64{reference}"),
            result,
            &tolerances[0].1,
        ));
    }

    // The paper's numerics: 256 x 256 cells over 0.256 mm, every cycle solved.
    let paper = simulate(r#"{"numerics": {"grid": 256, "domain_um": 256, "cycle_step": 1}}"#)?;
    let auto = simulate("{}")?;
    rows.push(row(
        "paper_numerics",
        "256 x 256 over 256 um, every cycle (reference)".into(),
        &paper,
        &paper,
    ));
    rows.push(row(
        "paper_numerics",
        "all auto (grid, domain, cycle step)".into(),
        &auto,
        &paper,
    ));

    // Table 3 with k from its 3600 s point: the errors are against the measurements.
    let calibrated = simulate(
        r#"{"test": {"cycles": 3600}, "numerics": {"grid": 64},
            "wear": {"archard_k": null, "archard_calibration": {"time_s": 3600, "wear_volume_mm3": 11.72e-3}}}"#,
    )?;
    for (cycle, measured) in [
        (10, 0.97e-3),
        (60, 1.09e-3),
        (300, 1.18e-3),
        (1800, 5.33e-3),
        (3600, 11.72e-3),
    ] {
        // The last solved cycle at or before the measurement (cycle 1 is always solved).
        let Some(record) = calibrated.cycles.iter().rev().find(|r| r.cycle <= cycle) else {
            continue;
        };
        let whole_run = row("table3", String::new(), &calibrated, &calibrated);
        rows.push(WearRow {
            setting: format!(
                "{cycle} s: measured {measured:.2e} mm3, k from the 3600 s point, grid 64"
            ),
            cycles: record.cycle,
            wear_volume_mm3: record.wear_volume_mm3,
            max_depth_um: record.max_depth_um,
            err_volume: record.wear_volume_mm3 / measured - 1.0,
            err_depth: f64::NAN,
            speedup: f64::NAN,
            reference: false,
            ..whole_run
        });
    }
    Ok(rows)
}

/// The rows as a fixed-width table.
pub fn table(rows: &[WearRow]) -> String {
    let mut out = String::from(
        "Wear, paper scene (dalmau2018-316l); errors relative to each study's reference\n\
         study           cycles   wall s  solves  step   iters   V mm3       depth um  err V      err depth  speed-up  setting\n",
    );
    for r in rows {
        out += &format!(
            "{:<15} {:>6} {:>8.2} {:>7} {:>5} {:>7}   {:<10.4e}  {:<8.4}  {:>+9.2e}  {:>+9.2e}  {:>7.1}  {}\n",
            r.study,
            r.cycles,
            r.wall_s,
            r.solves,
            r.longest_step,
            r.iterations,
            r.wear_volume_mm3,
            r.max_depth_um,
            r.err_volume,
            r.err_depth,
            r.speedup,
            r.setting
        );
    }
    out
}
