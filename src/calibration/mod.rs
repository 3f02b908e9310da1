//! Calibration: the model's parameters fitted to a lab's own measurements, as the paper does
//! by hand (Section 4.5, Table 2, Fig. 14). Each fit takes a small table (CSV or JSON, units
//! in the column names, [`Table`]) and a scene, and returns the fitted values with their
//! standard errors, each point's residual, and the scene with the values filled in.
//!
//! - [`fit_hardness`]: H = A + B ln n from `cycles`, `hardness_mpa` (Fig. 9);
//! - [`fit_tafel`]: a_c, b_c from a cathodic polarization curve (Table 2);
//! - [`fit_ocp`]: the depassivated area from a measured open-circuit potential (eq. 18,
//!   Figs. 6 and 14) and the parameter of the scene's anodic area
//!   (`corrosion.repassivation_time_s` or `anodic_area_factor`);
//! - [`fit_archard`]: Archard's k from wear volumes over whole simulated runs (Table 3);
//! - [`fit_archard_regimes`]: the same with a change of regime, two k's, against one.
//!
//! Standard errors come from the least-squares covariance scaled by the residual variance,
//! s^2 (J^T J)^-1 with s^2 = RSS / (points - parameters): they describe the scatter of the
//! table itself, not a stated measurement spread.

mod archard;
mod command;
mod hardness;
mod kind;
mod line;
mod minimise;
mod ocp;
mod regime;
mod table;
mod tafel;

use serde::Serialize;
use thiserror::Error;

use crate::hardness::HardnessError;
use crate::scene::{GridSize, Scene, SceneErrors};
use crate::simulation::SimulationError;

pub use archard::{
    ArchardFit, ArchardOptions, VolumeCompared, VolumeResidual, fit_archard, fit_archard_until,
};
pub use command::{CommandError, calibrate_files};
pub use hardness::{HardnessFit, HardnessOptions, HardnessResidual, fit_hardness};
pub use kind::{
    CommandOptions, Fit, FitKind, RunSize, calibrate, calibrate_until, check, default_scene,
    run_size,
};
pub use minimise::Trial;
pub use ocp::{OcpFit, OcpOptions, OcpParameter, OcpPoint, fit_ocp};
pub use regime::{
    Candidate, ChangeCycle, ChangeCycleError, Comparison, MIN_POINTS_PER_REGIME, ModelScore,
    RegimeFit, RegimeOptions, RegimePoint, Regimes, TwoRegimeFit, fit_archard_regimes,
    fit_archard_regimes_until,
};
pub use table::{Table, TableError, UNITS, column_name, quoted, spellings};
pub use tafel::{
    CorrosionPotentialSource, MIN_DOMAIN_SPAN_V, MIN_TAFEL_POINTS, TafelDomain, TafelFit,
    TafelOptions, TafelResidual, fit_tafel,
};

/// A fitted value and its standard error, in the units of the field that holds it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// The fitted value.
    pub value: f64,
    /// One standard error from the least-squares covariance.
    pub standard_error: f64,
}

/// Why a calibration could not be done.
#[derive(Debug, Error)]
pub enum CalibrationError {
    /// The table could not be read, or lacks a column.
    #[error(transparent)]
    Table(#[from] TableError),
    /// Too few rows to fit and estimate the scatter.
    #[error("column `{column}`: {got} points, the fit needs at least {needed}")]
    TooFewPoints {
        /// The column counted.
        column: &'static str,
        /// How many points the fit needs.
        needed: usize,
        /// How many the table has.
        got: usize,
    },
    /// A time or cycle column that does not increase strictly.
    #[error("column `{column}`: row {row} ({value}) does not increase on the row before it")]
    NotIncreasing {
        /// The column.
        column: &'static str,
        /// The row, from 1.
        row: usize,
        /// Its value.
        value: f64,
    },
    /// A value below its column's lower bound (a negative volume, a cycle below 1, ...).
    #[error("column `{column}`: row {row} is {value}, below the smallest allowed {minimum}")]
    BelowMinimum {
        /// The column.
        column: &'static str,
        /// The row, from 1.
        row: usize,
        /// Its value.
        value: f64,
        /// The bound.
        minimum: f64,
    },
    /// A potential during rubbing at or above the corrosion potential: no galvanic coupling,
    /// so eq. 18 gives no anodic area.
    #[error(
        "column `potential_v`: row {row} is {value} V, not below E_corr = {corrosion_potential_v} V, so eq. 18 gives no depassivated area"
    )]
    AboveCorrosionPotential {
        /// The row, from 1.
        row: usize,
        /// Its potential, V.
        value: f64,
        /// The scene's E_corr, V.
        corrosion_potential_v: f64,
    },
    /// No part of a polarization curve is a straight Tafel line.
    #[error("column `potential_v`: no Tafel domain below E_corr: {0}")]
    NoTafelDomain(String),
    /// A cathodic-only polarization curve without E_corr: its top is not the corrosion
    /// potential.
    #[error(
        "column `current_density_a_cm2`: the current never changes sign, so the curve does not show E_corr, and its top is not E_corr (the anodic current bends the curve well below it); give E_corr with `--e-corr V` (`options.e_corr_v`) or in a scene's `corrosion.corrosion_potential_v` (`--scene`)"
    )]
    CorrosionPotentialUnknown,
    /// A Tafel domain too narrow to measure a Tafel line on.
    #[error("column `potential_v`: the Tafel domain is too narrow: {0}")]
    NarrowTafelDomain(String),
    /// A current column whose neighbouring rows jump by decades, more steeply than any Tafel
    /// line: rows in different units.
    #[error(
        "column `current_density_a_cm2`: rows {} and {} differ by {decades:.1} decades over {millivolts:.1} mV, more steeply than any Tafel line (b_c >= 0.015 V/decade): does the column mix units? mA/cm^2 rows among A/cm^2 ones differ by 3 decades, A/m^2 among A/cm^2 by 4",
        rows.0, rows.1
    )]
    MixedUnits {
        /// The two rows, from 1.
        rows: (usize, usize),
        /// Their difference in log10 |i|, decades.
        decades: f64,
        /// Their difference in potential, mV.
        millivolts: f64,
    },
    /// A fitted value no real cell gives: a unit slip, named.
    #[error("the fitted {what}: {message}")]
    Implausible {
        /// Which value.
        what: &'static str,
        /// The value, the range and the likely slip.
        message: String,
    },
    /// A Tafel domain bound out of its range.
    #[error("{flag} (options.{option}) = {value} V: {why}")]
    DomainOption {
        /// The option as the service names it.
        option: &'static str,
        /// The option as the command line names it.
        flag: &'static str,
        /// Its value, V.
        value: f64,
        /// The allowed range and the likely slip.
        why: String,
    },
    /// An OCP fit asked of a scene whose potential is not eq. 18 of a fittable area.
    #[error(
        "corrosion.{field} = \"{value}\": the OCP fit adjusts tau or the factor of an area that eq. 18 as printed turns into a potential; the spot models and the balanced cell predict the potential from the solved contact and literature kinetics, with nothing to fit (run the scene and compare, or choose `anodic_area` depassivated_wake, hertz_band, wear_track, real_contact or bem_contact with `galvanic_cell` eq18)"
    )]
    NotFittable {
        /// The field that makes it a prediction.
        field: &'static str,
        /// Its value.
        value: &'static str,
    },
    /// A rubbing stop given without its start.
    #[error(
        "a rubbing stop needs the rubbing start (`--rubbing-start S`, `options.rubbing_start_s`)"
    )]
    StopWithoutStart,
    /// A rubbing stop at or before its start.
    #[error("the rubbing stop ({stop_s} s) must come after its start ({start_s} s)")]
    StopBeforeStart {
        /// The start, s.
        start_s: f64,
        /// The stop, s.
        stop_s: f64,
    },
    /// A change of regime outside the measured cycles.
    #[error(
        "change of regime at cycle {cycle}: outside the table's cycles; it must be at least the first ({first}) and below the last ({last})"
    )]
    ChangeOutsideTable {
        /// The cycle asked for.
        cycle: u64,
        /// The table's first cycle.
        first: f64,
        /// The table's last cycle.
        last: f64,
    },
    /// A change of regime that leaves a regime too few points to fit its k.
    #[error(
        "change of regime at cycle {cycle}: {got} point(s) {regime}, each regime needs at least {needed}"
    )]
    TooFewInRegime {
        /// The cycle asked for.
        cycle: u64,
        /// Which regime: "up to it" or "after it".
        regime: &'static str,
        /// Points each regime needs.
        needed: usize,
        /// Points the regime has.
        got: usize,
    },
    /// The scene lacks a section the fit needs.
    #[error("the scene has no `{0}` section, which this fit needs")]
    MissingSection(&'static str),
    /// A 1-D search ended at the edge of its bracket: the fit did not converge.
    #[error(
        "{parameter}: the least-squares minimum lies at the edge of the bracket [{low:e}, {high:e}], not inside it; tried {} values",
        tried.len()
    )]
    NotConverged {
        /// The parameter searched.
        parameter: &'static str,
        /// The bracket's ends.
        low: f64,
        /// The bracket's ends.
        high: f64,
        /// Every value tried and its residual sum of squares.
        tried: Vec<Trial>,
    },
    /// The scene is invalid.
    #[error("invalid scene: {0}")]
    Scene(#[from] SceneErrors),
    /// The hardness law could not be fitted.
    #[error("hardness: {0}")]
    Hardness(#[from] HardnessError),
    /// The run the fit would make to the table's last point is one the simulation refuses
    /// (a cycle count past its limit, say), found before any run.
    #[error(
        "the fit's runs go to the table's last point, cycle {cycles}, and the simulation refuses such a run: {source}"
    )]
    RunRefused {
        /// The cycles the runs would go to.
        cycles: u64,
        /// What the simulation's check said.
        #[source]
        source: SceneErrors,
    },
    /// A simulated run failed.
    #[error("simulation: {0}")]
    Simulation(#[from] SimulationError),
}

/// Checks that `values` has at least `needed` points.
fn require_points(
    column: &'static str,
    values: &[f64],
    needed: usize,
) -> Result<(), CalibrationError> {
    if values.len() < needed {
        return Err(CalibrationError::TooFewPoints {
            column,
            needed,
            got: values.len(),
        });
    }
    Ok(())
}

/// Checks that `values` increases strictly, row by row.
pub fn require_increasing(column: &'static str, values: &[f64]) -> Result<(), CalibrationError> {
    match values.windows(2).position(|w| w[1] <= w[0]) {
        Some(i) => Err(CalibrationError::NotIncreasing {
            column,
            row: i + 2,
            value: values[i + 1],
        }),
        None => Ok(()),
    }
}

/// Checks that every value is at least `minimum`.
pub fn require_at_least(
    column: &'static str,
    values: &[f64],
    minimum: f64,
) -> Result<(), CalibrationError> {
    match values.iter().position(|&v| v < minimum) {
        Some(i) => Err(CalibrationError::BelowMinimum {
            column,
            row: i + 1,
            value: values[i],
            minimum,
        }),
        None => Ok(()),
    }
}

/// The table's cycle counts, from a `cycles` column or a `time_s` column at the scene's speed;
/// with the column's name.
fn cycles_of(table: &Table, scene: &Scene) -> Result<(Vec<f64>, &'static str), CalibrationError> {
    if let Some(cycles) = table.optional("cycles") {
        return Ok((cycles.to_vec(), "cycles"));
    }
    if let Some(times) = table.optional("time_s") {
        return Ok((
            times.iter().map(|&t| scene.cycles_at(t)).collect(),
            "time_s",
        ));
    }
    Err(table.missing(&["cycles", "time_s"]).into())
}

/// Cells per side of the runs a calibration makes when the scene leaves the grid to the
/// simulation. On the paper scene at 3600 cycles, 32 cells give a wear volume within 0.01%
/// of 64 cells' (0.0118109 against 0.0118118 mm^3) in a quarter of the time (0.16 s
/// against 0.59 s): `tribosim run` of the preset with `numerics.grid` 32 and 64.
pub const CALIBRATION_GRID: usize = 32;

/// The scene a calibration runs: `scene` up to `last_cycle` (rounded up), on
/// [`CALIBRATION_GRID`] cells unless the scene fixes its grid; with the cells used.
fn calibration_scene(scene: &Scene, last_cycle: f64) -> (Scene, usize) {
    let mut run = scene.clone();
    run.test.cycles = last_cycle.ceil().max(1.0) as u64;
    let cells = match run.numerics.grid {
        GridSize::Cells(cells) => cells,
        GridSize::Auto => CALIBRATION_GRID,
    };
    run.numerics.grid = GridSize::Cells(cells);
    (run, cells)
}

/// Linear interpolation of `ys` over increasing `xs` at `x`, held constant beyond the ends.
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&v| v < x);
    if i == 0 {
        return ys[0];
    }
    if i == xs.len() {
        return ys[xs.len() - 1];
    }
    let t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
    ys[i - 1] + t * (ys[i] - ys[i - 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_name_the_column_and_row() {
        let err = require_increasing("time_s", &[1.0, 2.0, 2.0]).expect_err("repeated time");
        assert!(matches!(
            err,
            CalibrationError::NotIncreasing {
                column: "time_s",
                row: 3,
                ..
            }
        ));
        assert!(err.to_string().contains("time_s"));
        let err = require_at_least("volume_mm3", &[1.0, -1e-3], 0.0).expect_err("negative");
        assert!(err.to_string().contains("volume_mm3"), "{err}");
        assert!(require_points("cycles", &[1.0], 3).is_err());
    }

    #[test]
    fn interpolation_is_linear_inside_and_flat_outside() {
        let (xs, ys) = ([1.0, 3.0], [10.0, 30.0]);
        // One multiplication and addition: a rounding or two.
        assert!((interpolate(&xs, &ys, 2.0) - 20.0).abs() < 1e-12);
        assert!((interpolate(&xs, &ys, 0.5) - 10.0).abs() < 1e-12);
        assert!((interpolate(&xs, &ys, 9.0) - 30.0).abs() < 1e-12);
    }
}
