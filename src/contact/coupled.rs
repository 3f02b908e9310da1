//! The friction-coupled contact (eq. 7 with `mu != 0` and dissimilar materials). The coupling
//! kernel is odd in x, so the full operator `K_n + K_c` is not symmetric and conjugate
//! gradients cannot run on it directly. Instead an outer fixed point moves the coupling
//! displacement into the separation:
//!
//! `h_(k+1) = h + K_c p_k`, then `p_(k+1)` solves the symmetric problem on `h_(k+1)`,
//! warm-started from `p_k`.
//!
//! The map contracts because the coupling is weak next to the normal term: the coupling
//! coefficients carry `(1/2) mu delta_nu` against `(1 - nu*)` (eq. 7), and `|delta_nu| < 1`.
//! Success is declared on the full operator: the complementarity residual of `p` with
//! `u = K_n p + K_c p` must meet the tolerance.
//!
//! The inner solves are inexact: each stops at [`INNER_FRACTION`] of the previous outer
//! residual, since solving to the final tolerance against a coupling displacement that is
//! about to change is wasted work. They never stop above [`INNER_FLOOR`] times the target:
//! an inner solve that just meets the target leaves no room for the coupling update, and
//! the outer loop can stall a hair above the tolerance. Measured on the paper's Hertz case
//! at N = 256 (mu 0.45): 114 inner iterations with exact inner solves, 52 with these.

use super::blocks::Blocks;
use super::error::ContactError;
use super::fft::DcFft;
use super::influence::Kernel;
use super::operator::Operator;
use super::problem::{ContactProblem, ContactSolution, ContactSolver, KnownStart, SolverOptions};
use super::residual::{approach, complementarity_residual};
use super::solver::{Keeping, solve, solve_from};
use super::transform::Real;

/// Outer iterations allowed; each is a warm-started inner solve.
pub const MAX_OUTER_ITERATIONS: usize = 100;

/// Inner tolerance as a fraction of the last outer residual.
pub const INNER_FRACTION: f64 = 0.1;

/// The tightest inner tolerance, as a fraction of the target: half of the target is left for
/// the change of the coupling displacement, which contracts by far more than 2 per pass.
pub const INNER_FLOOR: f64 = 0.5;

/// Solves the contact with the coupling term by the outer fixed point above. The reported
/// `iterations`, `operator_applies`, `preconditioner_fallbacks` and `uniform_restarts` add
/// up every inner solve (and the coupling applies).
pub fn solve_coupled(
    normal: &mut dyn Operator,
    coupling: &mut dyn Operator,
    problem: &ContactProblem,
    options: &SolverOptions,
    warm_start: Option<&[f64]>,
) -> Result<ContactSolution, ContactError> {
    let n = problem.grid.len();
    let mut coupling_u = vec![0.0; n];
    let mut separation = problem.separation.to_vec();
    let mut warm: Option<Vec<f64>> = warm_start.map(<[f64]>::to_vec);
    if let Some(p) = &warm {
        if p.len() == n {
            coupling.apply(p, &mut coupling_u);
            shift_separation(&mut separation, problem.separation, &coupling_u);
        }
    }
    let (mut iterations, mut applies, mut fallbacks, mut restarts) = (0, 0, 0, 0);
    let mut residual = f64::INFINITY;
    for _ in 0..MAX_OUTER_ITERATIONS {
        let inner = ContactProblem {
            separation: &separation,
            ..*problem
        };
        let budget = SolverOptions {
            max_iterations: options.max_iterations.saturating_sub(iterations).max(1),
            tolerance: (INNER_FLOOR * options.tolerance).max(INNER_FRACTION * residual.min(1.0)),
            ..*options
        };
        let mut solution = solve(normal, &inner, &budget, warm.as_deref())
            .map_err(|e| as_outer_failure(e, iterations, options))?;
        iterations += solution.iterations;
        applies += solution.operator_applies + 1;
        fallbacks += solution.preconditioner_fallbacks;
        restarts += solution.uniform_restarts;
        coupling.apply(&solution.pressure, &mut coupling_u);

        // The residual of this pressure on the full operator.
        for (u, &c) in solution.displacement.iter_mut().zip(&coupling_u) {
            *u += c;
        }
        let cap = problem.yield_pressure_pa;
        let (p, u, h) = (
            &solution.pressure,
            &solution.displacement,
            problem.separation,
        );
        let delta = approach(Blocks::of(p.len(), 1), p, u, h, cap);
        residual = complementarity_residual(p, u, h, delta, cap);
        if residual <= options.tolerance {
            solution.approach_m = delta;
            solution.iterations = iterations;
            solution.operator_applies = applies;
            solution.preconditioner_fallbacks = fallbacks;
            solution.uniform_restarts = restarts;
            solution.residual = residual;
            return Ok(solution);
        }
        shift_separation(&mut separation, problem.separation, &coupling_u);
        warm = Some(solution.pressure);
    }
    Err(ContactError::NotConverged {
        iterations,
        residual,
        tolerance: options.tolerance,
    })
}

/// `shifted = h + K_c p`: the coupling displacement moved into the separation.
fn shift_separation(shifted: &mut [f64], separation: &[f64], coupling_u: &[f64]) {
    for ((s, &h), &c) in shifted.iter_mut().zip(separation).zip(coupling_u) {
        *s = h + c;
    }
}

/// An inner failure is the run's: a non-convergence is reported against the user's
/// tolerance and with every iteration spent (`spent` before this inner solve), not the
/// inner solve's looser target.
fn as_outer_failure(error: ContactError, spent: usize, options: &SolverOptions) -> ContactError {
    match error {
        ContactError::NotConverged {
            iterations,
            residual,
            ..
        } => ContactError::NotConverged {
            iterations: spent + iterations,
            residual,
            tolerance: options.tolerance,
        },
        other => other,
    }
}

/// Iterations granted to the direct solve on the summed operator before falling back.
/// Cold Hertz solves of the paper's case take 31-51 direct iterations at N = 128-256; with
/// mu delta-nu = 0.5 the direct iteration still had a 3e-6 residual after 2000.
pub const DIRECT_BUDGET: usize = 150;

/// The coupled contact on one grid, by the cheaper of two routes. The direct route runs the
/// solver on the summed operator `K_n + K_c`: conjugate gradients are not guaranteed on a
/// non-symmetric operator, but for weak coupling they converge as fast as without it, at
/// one apply per iteration. Success is judged on the full operator either way, so a direct
/// solution is as checked as a fixed-point one. If the direct route does not converge within
/// [`DIRECT_BUDGET`], the fixed point takes over, for this and every later solve.
///
/// The fixed point's two operators are built only when it takes over: until then the
/// kernels are kept instead. At N = 2048 the two operators hold 450 MB (their transposed
/// work buffers and spectra), the kernels 130 MB; the summed operator alone is needed
/// otherwise.
#[derive(Debug)]
pub struct CoupledSolver<T: Real = f64> {
    summed: DcFft<T>,
    route: Route<T>,
    /// Threads of each apply, on either route.
    threads: usize,
    /// What the direct route's last solve's first step did, for the next one's.
    keeping: Keeping,
}

/// How the coupled solver solves: directly (keeping the kernels the fixed point would
/// need), or by the fixed point on its operators.
#[derive(Debug)]
enum Route<T: Real> {
    Direct {
        normal: Kernel,
        coupling: Kernel,
    },
    FixedPoint {
        normal: Box<DcFft<T>>,
        coupling: Box<DcFft<T>>,
    },
}

impl CoupledSolver {
    /// The operators of `normal` and `coupling` kernels on one grid, in `f64`.
    pub fn new(normal: &Kernel, coupling: &Kernel) -> Self {
        Self::of(normal, coupling)
    }
}

impl<T: Real> CoupledSolver<T> {
    /// The operators of `normal` and `coupling` kernels on one grid.
    pub fn of(normal: &Kernel, coupling: &Kernel) -> Self {
        Self {
            summed: DcFft::of_sum(normal, coupling),
            route: Route::Direct {
                normal: normal.clone(),
                coupling: coupling.clone(),
            },
            threads: 1,
            keeping: Keeping::default(),
        }
    }

    /// The same solver applying on `threads` threads ([`DcFft::threaded`]).
    pub fn threaded(mut self, threads: usize) -> Self {
        self.summed = self.summed.threaded(threads);
        self.threads = threads;
        self
    }

    /// Whether the direct route is still in use (false once it failed to converge).
    pub fn direct_works(&self) -> bool {
        matches!(self.route, Route::Direct { .. })
    }
}

impl<T: Real> ContactSolver for CoupledSolver<T> {
    fn solve(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
    ) -> Result<ContactSolution, ContactError> {
        self.solve_from(problem, options, warm_start, None)
    }

    /// On the direct route the known displacement is the summed operator's, and the solve
    /// skips its start's apply; the fixed point starts from the pressure alone.
    fn solve_known(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        start: KnownStart<'_>,
    ) -> Result<ContactSolution, ContactError> {
        let warm = Some(start.pressure);
        self.solve_from(problem, options, warm, Some(start.displacement))
    }

    /// The full operator `K_n + K_c`, applied in one pass.
    fn operator(&mut self) -> &mut dyn Operator {
        &mut self.summed
    }
}

impl<T: Real> CoupledSolver<T> {
    /// [`ContactSolver::solve`], from `warm_start` and, where known, its displacement under
    /// the summed operator.
    fn solve_from(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
        known: Option<&[f64]>,
    ) -> Result<ContactSolution, ContactError> {
        let mut spent = 0;
        if let Route::Direct { normal, coupling } = &self.route {
            let direct = SolverOptions {
                max_iterations: DIRECT_BUDGET.min(options.max_iterations),
                ..*options
            };
            let keeping = &mut self.keeping;
            match solve_from(
                &mut self.summed,
                problem,
                &direct,
                warm_start,
                known,
                keeping,
            ) {
                Err(ContactError::NotConverged { iterations, .. }) => {
                    spent = iterations;
                    self.route = Route::FixedPoint {
                        normal: Box::new(DcFft::of(normal).threaded(self.threads)),
                        coupling: Box::new(DcFft::of(coupling).threaded(self.threads)),
                    };
                }
                outcome => return outcome,
            }
        }
        let Route::FixedPoint { normal, coupling } = &mut self.route else {
            unreachable!("the direct route returned or was replaced above");
        };
        // The iterations of a failed direct attempt count as work done.
        let mut solution = solve_coupled(
            normal.as_mut(),
            coupling.as_mut(),
            problem,
            options,
            warm_start,
        )?;
        solution.iterations += spent;
        Ok(solution)
    }
}
