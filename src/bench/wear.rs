//! The wear benchmark on the paper scene: cycle stepping against every-cycle solving, grid
//! refinement, solver tolerance, the paper's own numerics, and the volumes against Table 3
//! with k calibrated on its last point. Each study's settings are the constants below, which
//! the report also reads for its words.

use std::sync::atomic::AtomicBool;

use serde::Serialize;

use crate::contact::Grid;
use crate::scene::PAPER_TABLE3;
use crate::scene::{
    CycleStep, DALMAU2018_316L, DomainSize, GridSize, Scene, StepBound, TestConditions, Tolerance,
    dalmau2018_316l,
};
use crate::simulation::{
    MAX_STEP, Plan, RunOptions, STEP_CHANGE_BOUND, Setup, SimulationError, SimulationResult, run,
};

/// Cycle counts of the cycle-step study: the preset's test and the paper's longest, where
/// steps have had time to grow.
pub const STEP_STUDY_CYCLES: [u64; 2] = [300, 3600];

/// Step bounds of the cycle-step study: the default and a factor of about 3 either side.
pub const STEP_BOUNDS: [f64; 3] = [0.003, STEP_CHANGE_BOUND, 0.03];

/// Cells across the first domain in the grid study, the finest (the reference) first.
pub const GRID_STUDY_CELLS: [usize; 3] = [256, 128, 64];

/// Solver tolerances of the tolerance study, the tightest (the reference) first.
pub const TOLERANCE_STUDY: [f64; 4] = [1e-10, 1e-8, 1e-6, 1e-4];

/// Cells per side where the grid is not the question: cells of about 2 um, whose volume
/// differs from the finest grid's by about 1e-4 (the grid study) in a fraction of its time.
pub const QUICK_GRID: usize = 64;

/// The paper's numerics: cells per side, domain side (um), every cycle solved.
pub const PAPER_NUMERICS: (usize, f64) = (256, 256.0);

/// The paper's Table 3: test time (s; one cycle per second at 60 rpm) and measured wear
/// volume (mm^3). The last point calibrates Archard's k.
pub const TABLE3: [(u64, f64); 5] = {
    let mut table = [(0, 0.0); 5];
    let mut i = 0;
    while i < table.len() {
        table[i] = (PAPER_TABLE3[i].time_s, PAPER_TABLE3[i].wear_volume_mm3);
        i += 1;
    }
    table
};

/// Which study a wear row belongs to; serialised as the JSON `study` field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WearStudy {
    /// [`STEP_BOUNDS`] against solving every cycle.
    CycleStep,
    /// [`GRID_STUDY_CELLS`].
    Grid,
    /// [`TOLERANCE_STUDY`].
    Tolerance,
    /// [`PAPER_NUMERICS`] against all auto.
    PaperNumerics,
    /// Volumes against [`TABLE3`].
    Table3,
    /// The auto domain against fixed ones.
    Domain,
    /// The friction coupling term modelled or left out.
    Coupling,
    /// Plasticity at the paper's load, modelled or left out.
    Plasticity,
    /// Plasticity at a load whose Hertz peak stays below the yield pressure.
    ElasticLoad,
}

impl WearStudy {
    /// The JSON name: `cycle_step`, `grid`, `tolerance`, `paper_numerics`, `table3`,
    /// `domain`, `coupling`, `plasticity`, `elastic_load`.
    pub fn name(self) -> &'static str {
        match self {
            Self::CycleStep => "cycle_step",
            Self::Grid => "grid",
            Self::Tolerance => "tolerance",
            Self::PaperNumerics => "paper_numerics",
            Self::Table3 => "table3",
            Self::Domain => "domain",
            Self::Coupling => "coupling",
            Self::Plasticity => "plasticity",
            Self::ElasticLoad => "elastic_load",
        }
    }
}

/// One run of the wear benchmark, with its errors against the reference of its table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WearRow {
    /// Which study.
    pub study: WearStudy,
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

/// The cycles of a paper run where a study does not choose its own: 300, Table 3's 300 s,
/// past the yielding phase and into Archard wear, and short enough to keep `bench all` to
/// minutes (the paper's whole test, 3600 cycles, is the scene's default).
pub(super) const STUDY_CYCLES: u64 = 300;

/// The scene every study starts from: the `dalmau2018-316l` preset at [`STUDY_CYCLES`].
pub fn paper_scene() -> Scene {
    let preset = dalmau2018_316l();
    Scene {
        test: TestConditions {
            cycles: STUDY_CYCLES,
            ..preset.test
        },
        ..preset
    }
}

/// The paper scene with `change` applied.
pub(super) fn paper_scene_with(change: impl FnOnce(&mut Scene)) -> Scene {
    let mut scene = paper_scene();
    change(&mut scene);
    scene
}

/// Checks `scene` as a parsed scene is checked, and runs it.
pub(super) fn simulate(scene: &Scene) -> Result<SimulationResult, SimulationError> {
    run(
        &Plan::new(scene.clone())?,
        &mut |_| {},
        &AtomicBool::new(false),
    )
}

/// The paper scene with `change` applied, run.
pub(super) fn simulate_with(
    change: impl FnOnce(&mut Scene),
) -> Result<SimulationResult, SimulationError> {
    simulate(&paper_scene_with(change))
}

/// The first grid the simulation sets up for `scene`.
pub(super) fn first_grid(scene: &Scene) -> Result<Grid, SimulationError> {
    Ok(Setup::new(&Plan::new(scene.clone())?, &RunOptions::default())?.grid)
}

/// The row of `result` in `study`, with its errors against `reference` (the same run for the
/// reference row itself).
pub(super) fn row(
    study: WearStudy,
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
        grid: first_grid(&result.scene).map_or(0, |grid| grid.nx),
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
    let mut rows = cycle_step_rows()?;
    rows.extend(grid_rows()?);
    rows.extend(tolerance_rows()?);
    rows.extend(paper_numerics_rows()?);
    rows.extend(table3_rows()?);
    Ok(rows)
}

/// Each step bound against solving every cycle, with the scene's own (auto) grid and domain.
fn cycle_step_rows() -> Result<Vec<WearRow>, SimulationError> {
    let mut rows = Vec::new();
    for cycles in STEP_STUDY_CYCLES {
        let every = simulate_with(|s| {
            s.test.cycles = cycles;
            s.numerics.cycle_step = CycleStep::EveryCycle;
        })?;
        let study = WearStudy::CycleStep;
        rows.push(row(study, "every cycle (reference)".into(), &every, &every));
        for bound in STEP_BOUNDS {
            let auto = simulate_with(|s| {
                s.test.cycles = cycles;
                s.numerics.cycle_step_bound = StepBound::Share(bound);
            })?;
            let default = if bound == STEP_CHANGE_BOUND {
                " (default)"
            } else {
                ""
            };
            let setting = format!("bound {bound}{default}, auto");
            rows.push(row(study, setting, &auto, &every));
        }
    }
    Ok(rows)
}

/// Cells across the first domain (auto: it spans a fixed number of contact radii and grows
/// with the track), the finest grid the reference.
fn grid_rows() -> Result<Vec<WearRow>, SimulationError> {
    let mut runs = Vec::new();
    for n in GRID_STUDY_CELLS {
        let scene = paper_scene_with(|s| s.numerics.grid = GridSize::Cells(n));
        let cell_um = first_grid(&scene)?.dx * 1e6;
        runs.push((n, cell_um, simulate(&scene)?));
    }
    let reference = &runs[0].2;
    Ok(runs
        .iter()
        .enumerate()
        .map(|(i, (n, cell_um, result))| {
            let tag = if i == 0 { " (reference)" } else { "" };
            let setting = format!("{n} cells, {cell_um:.2} um{tag}");
            row(WearStudy::Grid, setting, result, reference)
        })
        .collect())
}

/// Each solver tolerance on the quick grid, the tightest the reference.
fn tolerance_rows() -> Result<Vec<WearRow>, SimulationError> {
    let runs: Vec<(f64, SimulationResult)> = TOLERANCE_STUDY
        .into_iter()
        .map(|t| {
            simulate_with(|s| {
                s.numerics.grid = GridSize::Cells(QUICK_GRID);
                s.numerics.tolerance = Tolerance::Relative(t);
            })
            .map(|r| (t, r))
        })
        .collect::<Result<_, _>>()?;
    let reference = &runs[0].1;
    Ok(runs
        .iter()
        .enumerate()
        .map(|(i, (t, result))| {
            let tag = if i == 0 { " (reference)" } else { "" };
            let setting = format!("{t:.0e}, grid {QUICK_GRID}{tag}");
            row(WearStudy::Tolerance, setting, result, reference)
        })
        .collect())
}

/// The paper's own numerics, every cycle solved, against all auto.
fn paper_numerics_rows() -> Result<Vec<WearRow>, SimulationError> {
    let (cells, domain_um) = PAPER_NUMERICS;
    let paper = simulate_with(|s| {
        s.numerics.grid = GridSize::Cells(cells);
        s.numerics.domain_um = DomainSize::Micrometres(domain_um);
        s.numerics.cycle_step = CycleStep::EveryCycle;
    })?;
    let auto = simulate_with(|_| {})?;
    let study = WearStudy::PaperNumerics;
    Ok(vec![
        row(
            study,
            format!("{cells} x {cells} over {domain_um} um, every cycle (reference)"),
            &paper,
            &paper,
        ),
        row(
            study,
            "all auto (grid, domain, cycle step)".into(),
            &auto,
            &paper,
        ),
    ])
}

/// Table 3 with k from its last point (the scene's default, the paper's rule), on the quick
/// grid: the errors are against the measurements.
fn table3_rows() -> Result<Vec<WearRow>, SimulationError> {
    let (last_s, _) = TABLE3[TABLE3.len() - 1];
    let calibrated = simulate_with(|s| {
        s.test.cycles = last_s;
        s.numerics.grid = GridSize::Cells(QUICK_GRID);
    })?;
    let whole_run = row(WearStudy::Table3, String::new(), &calibrated, &calibrated);
    let mut rows = Vec::new();
    for (cycle, measured) in TABLE3 {
        // The last solved cycle at or before the measurement (cycle 1 is always solved).
        let Some(record) = calibrated.cycles.iter().rev().find(|r| r.cycle <= cycle) else {
            continue;
        };
        rows.push(WearRow {
            setting: format!(
                "{cycle} s: measured {measured:.2e} mm3, k from the {last_s} s point, grid {QUICK_GRID}"
            ),
            cycles: record.cycle,
            wear_volume_mm3: record.wear_volume_mm3,
            max_depth_um: record.max_depth_um,
            err_volume: record.wear_volume_mm3 / measured - 1.0,
            err_depth: f64::NAN,
            speedup: f64::NAN,
            reference: false,
            ..whole_run.clone()
        });
    }
    Ok(rows)
}

/// The rows as a fixed-width table.
pub fn table(rows: &[WearRow]) -> String {
    let mut out = format!(
        "Wear, paper scene ({DALMAU2018_316L}); errors relative to each study's reference\n\
         study           cycles   wall s  solves  step   iters   V mm3       depth um  err V      err depth  speed-up  setting\n",
    );
    for r in rows {
        out += &format!(
            "{:<15} {:>6} {:>8.2} {:>7} {:>5} {:>7}   {:<10.4e}  {:<8.4}  {:>+9.2e}  {:>+9.2e}  {:>7.1}  {}\n",
            r.study.name(),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn study_names_are_their_json() {
        let all = [
            WearStudy::CycleStep,
            WearStudy::Grid,
            WearStudy::Tolerance,
            WearStudy::PaperNumerics,
            WearStudy::Table3,
            WearStudy::Domain,
            WearStudy::Coupling,
            WearStudy::Plasticity,
            WearStudy::ElasticLoad,
        ];
        for study in all {
            let json = serde_json::to_value(study).expect("serialises");
            assert_eq!(json, study.name());
        }
    }

    /// The overrides the studies once wrote as JSON text give the same scenes as the
    /// changes made to the preset's values.
    #[test]
    fn scene_values_match_the_json_overrides() {
        let parsed = |overrides: &str| {
            crate::scene::parse_scene_str(&format!(
                r#"{{"preset": "{DALMAU2018_316L}", "overrides": {overrides}}}"#
            ))
            .expect("parses")
        };
        let built = paper_scene_with(|s| {
            s.test.cycles = 3600;
            s.numerics.grid = GridSize::Cells(64);
        });
        let json = r#"{"test": {"cycles": 3600}, "numerics": {"grid": 64}}"#;
        assert_eq!(built, parsed(json));
        let built = paper_scene_with(|s| {
            s.numerics.grid = GridSize::Cells(256);
            s.numerics.domain_um = DomainSize::Micrometres(256.0);
            s.numerics.cycle_step = CycleStep::EveryCycle;
        });
        let json = r#"{"test": {"cycles": 300},
            "numerics": {"grid": 256, "domain_um": 256, "cycle_step": 1}}"#;
        assert_eq!(built, parsed(json));
        assert_eq!(paper_scene(), parsed(r#"{"test": {"cycles": 300}}"#));
    }

    /// The grid study names each grid by its cell size, taken from the simulation's own
    /// setup; the committed report shows the same sizes.
    #[test]
    fn grid_settings_name_the_cells_of_the_committed_report() {
        let committed = include_str!("../../docs/accuracy.md");
        for n in GRID_STUDY_CELLS {
            let scene = paper_scene_with(|s| s.numerics.grid = GridSize::Cells(n));
            let cell_um = first_grid(&scene).expect("sets up").dx * 1e6;
            let setting = format!("| {n} cells, {cell_um:.2} um");
            assert!(committed.contains(&setting), "{setting}");
        }
    }
}
