//! What every contact solver shares: the problem, the settings, the solution, and the
//! [`ContactSolver`] interface that the normal ([`super::NormalSolver`]), the coupled
//! ([`super::CoupledSolver`]) and the windowed ([`super::WindowedSolver`]) solvers implement.

use std::num::NonZeroUsize;

use super::error::ContactError;
use super::grid::Grid;
use super::operator::Operator;

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Relative residual to reach (see [`super::residual`]).
    pub tolerance: f64,
    /// Iterations allowed before [`ContactError::NotConverged`].
    pub max_iterations: usize,
    /// How the conjugate gradient is preconditioned, where the operator offers an inverse.
    pub preconditioning: Preconditioning,
    /// Runs solving at the same time as this one (the service's workers, a study's
    /// threads), among which an automatic thread count shares the cores
    /// ([`super::split_threads`]). The results do not depend on it.
    pub concurrent_runs: NonZeroUsize,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-8,
            max_iterations: 2000,
            preconditioning: Preconditioning::default(),
            concurrent_runs: NonZeroUsize::MIN,
        }
    }
}

/// The preconditioner of the solver's conjugate gradient on the free cells, built from the
/// operator's inverse on the whole grid ([`Operator::preconditioner`]). Either converges to
/// the same tolerance; the choice only moves the iterations (`tribosim bench speed`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Preconditioning {
    /// The inverse on the whole grid, restricted to the free cells.
    WholeGrid,
    /// The same, corrected at the edges of the free set (see [`super::solver`]): fewer
    /// iterations for one more apply of the inverse per iteration (a quarter of an
    /// operator apply on the DC-FFT's grid, a whole one on the periodic grid). A solve that
    /// stalls with it finishes on [`Self::WholeGrid`].
    #[default]
    FreeSet,
}

/// One contact problem on a grid.
#[derive(Debug, Clone, Copy)]
pub struct ContactProblem<'a> {
    /// The grid the fields live on.
    pub grid: Grid,
    /// Separation `h` between the undeformed surfaces at zero approach, m, per cell.
    pub separation: &'a [f64],
    /// Normal load, N.
    pub load_n: f64,
    /// Pressure cap `Y`, Pa; `f64::INFINITY` for a purely elastic contact.
    pub yield_pressure_pa: f64,
    /// The depth the solved pressure wears from each row per unit of the row's pressure
    /// integral `int p dx` (Pa m), 1/Pa: Archard's `k / H` summed over the passes whose wear
    /// the solve includes. The gap of a row's cells then includes that wear, so the pressure
    /// is solved on the surface its own wear leaves (the implicit update of
    /// [`super::worn_rows`]); 0 solves on the surface as it is.
    pub pass_wear_per_pa: f64,
}

impl ContactProblem<'_> {
    /// Refuses malformed fields and settings before any work is done.
    pub(crate) fn validate(&self, options: &SolverOptions) -> Result<(), ContactError> {
        let invalid = |m: String| Err(ContactError::InvalidProblem(m));
        if self.separation.len() != self.grid.len() {
            return invalid(format!(
                "separation has {} values for {} cells",
                self.separation.len(),
                self.grid.len()
            ));
        }
        if let Some(i) = self.separation.iter().position(|h| !h.is_finite()) {
            return invalid(format!("separation[{i}] is not finite"));
        }
        if !(self.load_n.is_finite() && self.load_n > 0.0) {
            return invalid(format!("load {} N: must be finite and > 0", self.load_n));
        }
        if self.yield_pressure_pa.is_nan() || self.yield_pressure_pa <= 0.0 {
            return invalid(format!(
                "yield pressure {} Pa: must be > 0 (infinite for no cap)",
                self.yield_pressure_pa
            ));
        }
        if !(self.pass_wear_per_pa >= 0.0 && self.pass_wear_per_pa.is_finite()) {
            return invalid(format!(
                "pass wear {} 1/Pa: must be finite and >= 0",
                self.pass_wear_per_pa
            ));
        }
        if !(options.tolerance > 0.0 && options.tolerance.is_finite()) {
            return invalid(format!("tolerance {}: must be > 0", options.tolerance));
        }
        Ok(())
    }
}

/// A converged contact.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSolution {
    /// Pressure per cell, Pa.
    pub pressure: Vec<f64>,
    /// Elastic displacement `K p` per cell (both bodies together), plus the pass's wear
    /// when the problem has one ([`ContactProblem::pass_wear_per_pa`]), m. A
    /// [`super::WindowedSolver`] under a nonnegative kernel computes it only on the cells
    /// whose gap could close and leaves 0 elsewhere, a lower bound there: those cells' gap
    /// is at least their separation's, beyond the tolerance.
    pub displacement: Vec<f64>,
    /// Rigid-body approach `delta`, m.
    pub approach_m: f64,
    /// CG iterations.
    pub iterations: usize,
    /// Operator applications (each one padded FFT round trip for [`super::DcFft`]).
    pub operator_applies: usize,
    /// The relative residual reached.
    pub residual: f64,
    /// Solves that stalled with the free-set preconditioner and finished on the whole grid
    /// ([`Preconditioning::FreeSet`]; see [`super::solver`]): 0 or 1 for one solve, summed
    /// over the inner solves of a coupled one.
    pub preconditioner_fallbacks: usize,
    /// Solves whose warm start stalled on the whole grid and that started again from the
    /// uniform pressure (see [`super::solver`]): 0 or 1 for one solve, summed like
    /// `preconditioner_fallbacks`.
    pub uniform_restarts: usize,
}

impl ContactSolution {
    /// The load carried, N.
    pub fn load_n(&self, grid: &Grid) -> f64 {
        self.pressure.iter().sum::<f64>() * grid.cell_area()
    }

    /// Largest pressure, Pa.
    pub fn max_pressure_pa(&self) -> f64 {
        self.pressure.iter().fold(0.0, |m, &p| m.max(p))
    }

    /// Area of the cells in contact (p > 0), m^2.
    pub fn contact_area_m2(&self, grid: &Grid) -> f64 {
        self.pressure.iter().filter(|&&p| p > 0.0).count() as f64 * grid.cell_area()
    }

    /// Area of the cells at the cap (p = Y), m^2.
    pub fn plastic_area_m2(&self, grid: &Grid, yield_pressure_pa: f64) -> f64 {
        let capped = self
            .pressure
            .iter()
            .filter(|&&p| p >= yield_pressure_pa)
            .count();
        capped as f64 * grid.cell_area()
    }

    /// The gap `u + h - delta` of each cell over the `separation` it was solved on, m: zero
    /// in contact, the distance the deformed surfaces keep elsewhere.
    pub fn gap_m(&self, separation: &[f64]) -> Vec<f64> {
        self.displacement
            .iter()
            .zip(separation)
            .map(|(u, h)| u + h - self.approach_m)
            .collect()
    }
}

/// A warm start whose displacement is known: `displacement = K pressure` on the problem's
/// grid, by the solver's own operator, without the wear term of
/// [`ContactProblem::pass_wear_per_pa`] (which the solve adds). A solve from it skips the
/// apply its start would otherwise take.
#[derive(Debug, Clone, Copy)]
pub struct KnownStart<'a> {
    /// The start's pressure per cell, Pa.
    pub pressure: &'a [f64],
    /// `K pressure` per cell, m.
    pub displacement: &'a [f64],
}

/// A way of solving contact problems on one grid.
pub trait ContactSolver {
    /// Solves `problem`, optionally warm-started from `warm_start` (e.g. the previous wear
    /// cycle's pressure). Fails with a named [`ContactError`], never silently: an
    /// impossible load, a contact reaching the domain edge, or no convergence.
    fn solve(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
    ) -> Result<ContactSolution, ContactError>;

    /// Solves `problem` from `start`, whose displacement is known; a solver that cannot use
    /// it starts from the pressure alone.
    fn solve_known(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        start: KnownStart<'_>,
    ) -> Result<ContactSolution, ContactError> {
        self.solve(problem, options, Some(start.pressure))
    }

    /// The full operator whose complementarity conditions the solutions meet (the normal
    /// kernel, plus the coupling kernel when the solver models it): what an independent
    /// check ([`super::verify`]) must recompute the displacement with.
    fn operator(&mut self) -> &mut dyn Operator;
}
