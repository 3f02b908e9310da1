//! `tribosim bench paper`: the paper's Section 4 figure by figure (Figs. 9-14, Table 3),
//! reproduced by the runs below and written to `docs/paper.md` with its SVG figures in
//! `docs/paper/`. The markdown holds only numbers the runs give, so `tests/paper.rs` can
//! regenerate it and compare.

mod caps;
mod figures;
mod numbers;
mod readings;
mod statements;
mod text;

use std::path::Path;
use std::sync::atomic::AtomicBool;

use crate::simulation::{
    Plan, RunOptions, Setup, SimulationError, SimulationResult, disc_share, parse_scene_str,
    run_setup,
};

use super::BenchError;

pub use caps::{CapRun, INITIAL_YIELDS_MPA};
pub use numbers::{CapNumbers, PaperNumbers, TABLE3};
pub use readings::{CYCLES as READING_CYCLES, Reading, ReadingRun, run_all as run_readings};
pub use statements::{AROUND_10_CYCLES, HALF_MICRON_UM, Statement, Verdict, statements};
pub use text::markdown;

/// The paper's own mesh for Figs. 10-12 (Section 4.5: 0.256 x 0.256 mm in 256 x 256 cells
/// of 1 um), every cycle solved: the loaded profile's area depends on the window's width
/// (the elastic dent decays as 1 / distance), so it is taken over the paper's.
pub const PAPER_GRID: &str = r#""numerics": {"grid": 256, "domain_um": 256, "cycle_step": 1}"#;

/// The same window in 128 cells of 2 um: the grid study behind the tolerances of
/// `tests/paper.rs`.
pub const COARSE_GRID: &str = r#""numerics": {"grid": 128, "domain_um": 256, "cycle_step": 1}"#;

/// The runs behind the figures.
#[derive(Debug, Clone)]
pub struct PaperStudy {
    /// The elastic-perfectly-plastic disc (the default), 300 cycles on [`PAPER_GRID`].
    pub epp: SimulationResult,
    /// The same with the cap off (`wear.plasticity: "off"`): Fig. 11's perfectly elastic
    /// material.
    pub elastic: SimulationResult,
    /// The first 6 cycles on [`PAPER_GRID`]: Fig. 10a's pressure map is its last.
    pub first6: SimulationResult,
    /// The paper's whole test, `{}` as it stands (auto grid and cycle steps): Table 3, Figs.
    /// 9, 13 and 14.
    pub whole: SimulationResult,
    /// The disc's share of the elastic displacement.
    pub disc_share: f64,
    /// Hertz's contact area of the unworn ball, mm^2 (Fig. 14's comparison).
    pub hertz_area_mm2: f64,
    /// Each reading of eq. 13 cycled on the paper's scene ([`Reading::ALL`]'s order).
    pub readings: Vec<ReadingRun>,
    /// The cap that hardens from each of [`INITIAL_YIELDS_MPA`], 300 cycles on the same
    /// grid as `epp`.
    pub caps: Vec<CapRun>,
}

impl PaperStudy {
    /// Runs the study on the paper's mesh (`grid` [`PAPER_GRID`]) or another one.
    pub fn run(grid: &str) -> Result<Self, BenchError> {
        let epp = simulate(&format!(r#"{{"test": {{"cycles": 300}}, {grid}}}"#))?;
        let elastic = simulate(&format!(
            r#"{{"test": {{"cycles": 300}}, "wear": {{"plasticity": "off"}}, {grid}}}"#
        ))?;
        let first6 = simulate(&format!(r#"{{"test": {{"cycles": 6}}, {grid}}}"#))?;
        let whole = simulate("{}")?;
        let plan = plan("{}")?;
        let setup = Setup::new(&plan, &RunOptions::default())?;
        Ok(Self {
            epp,
            elastic,
            first6,
            whole,
            disc_share: disc_share(&setup),
            hertz_area_mm2: plan.hertz().contact_area_m2() * 1e6,
            readings: readings::run_all(COARSE_GRID)?,
            caps: caps::run_all(grid)?,
        })
    }

    /// The numbers the tests hold.
    pub fn numbers(&self) -> PaperNumbers {
        PaperNumbers::of(self)
    }

    /// The run of `reading`.
    pub fn reading(&self, reading: Reading) -> &ReadingRun {
        self.readings
            .iter()
            .find(|r| r.reading == reading)
            .expect("the study runs every reading")
    }
}

/// Runs the study and writes the markdown to `path`, its figures to the folder of the same
/// name (`docs/paper.md` puts them in `docs/paper/`); returns how many figures.
pub fn write(path: &Path) -> Result<usize, BenchError> {
    let study = PaperStudy::run(PAPER_GRID)?;
    let folder = path.with_extension("");
    std::fs::create_dir_all(&folder).map_err(|source| BenchError::Write {
        path: folder.clone(),
        source,
    })?;
    let figures = write_figures(&study, &folder)?;
    let text = markdown(&study);
    std::fs::write(path, text).map_err(|source| BenchError::Write {
        path: path.to_owned(),
        source,
    })?;
    Ok(figures)
}

/// Writes the figures of `study` as SVG into `folder` (which exists); returns how many.
pub fn write_figures(study: &PaperStudy, folder: &Path) -> Result<usize, BenchError> {
    figures::write_all(study, folder)
}

fn plan(json: &str) -> Result<Plan, SimulationError> {
    Ok(parse_scene_str(json)?)
}

fn simulate(json: &str) -> Result<SimulationResult, SimulationError> {
    let setup = Setup::new(&plan(json)?, &RunOptions::default())?;
    run_setup(&setup, &mut |_| {}, &AtomicBool::new(false))
}
