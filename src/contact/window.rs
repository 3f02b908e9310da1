//! Solving on a window of the grid around the contact. DC-FFT convolves without
//! wrap-around, so the displacements inside any window that holds all the pressure are
//! exact: the solve only needs the contact's bounding box plus a margin, however large the
//! domain. Each solve is then checked with one apply: no cell outside the window may
//! penetrate. A contact that touches the window's edge, a load the window cannot carry at
//! the yield pressure, or a penetration outside it enlarges the window and the solve is
//! repeated; so the answer is the whole grid's, at the cost of the window's cells.
//!
//! The check needs only the cells that could penetrate. Under a nonnegative
//! kernel ([`Operator::is_nonnegative`]) the displacement is nonnegative, so a cell whose
//! separation alone keeps it open (`h - delta` above the tolerance) stays open: the check
//! applies on the box of the window and the other cells, exact there by the same argument
//! as the window's. On the paper scene (`tribosim run scenes/dalmau2018.json`, its
//! `solve_window` model) that box holds 60% of the grid's cells on average (the window
//! 39%); the whole grid's apply had taken a fifth of the run's samples in a `perf` profile,
//! and the run's CPU time fell by about a tenth (medians of 5 alternating runs).
//!
//! The check also computes the next solve's window, the last contact's box plus the margin,
//! so that a solve from the checked pressure starts from the check's displacement
//! ([`carried`]) without an apply of its own.

use std::ops::Range;

use super::error::ContactError;
use super::grid::{Grid, Window};
use super::operator::Operator;
use super::problem::{ContactProblem, ContactSolution, ContactSolver, KnownStart, SolverOptions};
use super::residual::displacement_scale;
use super::transform::fft_friendly;
use super::worn_rows::add_worn_rows;

mod carried;

use carried::Carried;

/// Margin around the last contact's bounding box, as a fraction of its extent... Every
/// apply of a solve costs the window's cells, and a warm solve's contact differs from the
/// last one by a row or two, which [`MIN_MARGIN`] holds. Measured with `tribosim run`: the
/// paper scene takes 3.9 s at 0.15 and 3.1 s at 0.03 (windows 54% and 39% of the grid),
/// 20 cycles of a 0.1 um rms disc (`simulation::run`'s test scene) 3.96 s and 2.72 s; no
/// window was enlarged at either.
pub const MARGIN_FRACTION: f64 = 0.03;
/// ... and at least this many cells: the contact moves by a cell or two per solve.
pub const MIN_MARGIN: usize = 4;
/// Growth of a window that turned out too small.
const ENLARGE: f64 = 1.5;
/// The window shapes' solvers kept, the least recently used dropped beyond: each holds its
/// operator's spectra and buffers, and a long rough run meets many shapes as its track
/// widens: the 2 um example of `docs/scene.md` over 3600 cycles peaked at 1.56 GB keeping
/// them all, 687 MB keeping 4, with the same results (`/usr/bin/time -f %M tribosim run`).
/// Counted once with a build that logged each solve's and check's shape: 13
/// shapes over the 4 um rough disc's 600 cycles (1198 lookups), 8 over the 2 um example's
/// first 300 (597); keeping 4 built no solver twice on either, keeping 2 built 3 and 2 more.
pub const KEPT_SHAPES: usize = 4;

/// The window around the loaded cells of `pressure` ([`around_box`]). `None` if no cell is
/// loaded.
fn around(grid: &Grid, pressure: &[f64]) -> Option<Window> {
    Window::loaded(grid, pressure).map(|loaded| around_box(grid, &loaded))
}

/// The window around `loaded`, a box of `grid`'s cells: the box plus the margin, each side
/// rounded up to an FFT-friendly size.
fn around_box(grid: &Grid, loaded: &Window) -> Window {
    let sized = |extent: usize| {
        let margin = MIN_MARGIN.max((MARGIN_FRACTION * extent as f64).ceil() as usize);
        fft_friendly(extent + 2 * margin)
    };
    // The middle of the first and the last loaded cell, rounded down.
    let middle = |first: usize, n: usize| (2 * first + n - 1) / 2;
    let centre = (middle(loaded.x0, loaded.nx), middle(loaded.y0, loaded.ny));
    Window::centred(grid, centre, sized(loaded.nx), sized(loaded.ny))
}

/// `window` grown by [`ENLARGE`] about its centre, to FFT-friendly sizes.
fn enlarged(window: &Window, grid: &Grid) -> Window {
    let grow = |n: usize| fft_friendly((n as f64 * ENLARGE).ceil() as usize);
    Window::centred(grid, window.centre(), grow(window.nx), grow(window.ny))
}

/// The contact solver of one grid, working on windows around the last contact. It builds
/// the solvers it needs (one for the whole grid, one per window shape, the last
/// [`KEPT_SHAPES`] kept) with `factory`.
pub struct WindowedSolver<F> {
    grid: Grid,
    factory: F,
    full: Box<dyn ContactSolver>,
    /// The solvers of the shapes used last, the most recent last.
    by_shape: Vec<((usize, usize), Box<dyn ContactSolver>)>,
    /// Where the next solve looks first: around the last solved contact.
    focus: Option<Window>,
    /// The shares of the grid solved and checked, summed over solves.
    fractions: WindowFractions,
    /// The last check's displacement, the start of a solve from the pressure it checked;
    /// `None` after a solve on the whole grid, which no check follows.
    carried: Option<Carried>,
}

/// The cells a windowed solver worked on, as shares of the grid's, summed over solves.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WindowFractions {
    /// The cells solved on (1 for a solve on the whole grid).
    pub solved: f64,
    /// The cells the check computed the displacement on (1 for a solve on the whole grid,
    /// which needs no check).
    pub checked: f64,
}

impl WindowFractions {
    /// The `solve_window` model's account of these fractions over `solves` solves.
    pub fn describe(&self, solves: usize) -> String {
        format!(
            "each solve on the last contact's bounding box plus {:.0}% (at least {} cells), checked on the cells that could touch: on average {:.0}% of the grid's cells solved, {:.0}% checked",
            100.0 * MARGIN_FRACTION,
            MIN_MARGIN,
            100.0 * self.solved / solves as f64,
            100.0 * self.checked / solves as f64
        )
    }
}

impl std::ops::AddAssign for WindowFractions {
    fn add_assign(&mut self, other: Self) {
        self.solved += other.solved;
        self.checked += other.checked;
    }
}

impl<F: FnMut(&Grid) -> Box<dyn ContactSolver>> WindowedSolver<F> {
    /// The solver of `grid`, building the solver of a grid or a window with `factory`. The
    /// first solve runs on the whole grid unless [`WindowedSolver::focus_on`] says where
    /// the contact is.
    pub fn new(grid: Grid, mut factory: F) -> Self {
        Self {
            grid,
            full: factory(&grid),
            factory,
            by_shape: Vec::new(),
            focus: None,
            fractions: WindowFractions::default(),
            carried: None,
        }
    }

    /// The next solve starts in a window around the loaded cells of `pressure` (a field of
    /// this grid, e.g. the last contact carried over from a smaller grid). Each solve
    /// focuses the next on its own contact.
    pub fn focus_on(&mut self, pressure: &[f64]) {
        self.focus = around(&self.grid, pressure);
    }

    /// Moves the solver onto `wider`, a grid of the same cells grown about the same centre
    /// (the domain's growth), its next solve focused on `pressure` (a field of `wider`).
    /// The solvers of the windows' shapes are kept, as their cells are the same, and so are
    /// the fractions so far: the report's shares are each solve's of its own grid.
    pub fn grow(&mut self, wider: Grid, pressure: &[f64]) {
        debug_assert!(
            wider.dx.to_bits() == self.grid.dx.to_bits()
                && wider.dy.to_bits() == self.grid.dy.to_bits(),
            "a grown grid keeps its cells"
        );
        self.grid = wider;
        self.full = (self.factory)(&wider);
        self.carried = None;
        self.focus_on(pressure);
    }

    /// The shares of the grid solved and checked, summed over the solves so far (for the
    /// report).
    pub fn fractions(&self) -> WindowFractions {
        self.fractions
    }

    /// The rows that may carry the last solution's pressure: those of the window it was
    /// solved on (every row of the grid after a solve on the whole grid). Every cell of the
    /// other rows carries none, so a pass over the pressure can skip them.
    pub fn loaded_rows(&self) -> Range<usize> {
        self.carried
            .as_ref()
            .map_or(0..self.grid.ny, |carried| carried.solved.rows())
    }

    /// Solves `problem` on `window` and checks the answer on the cells that could touch
    /// ([`Self::reach`]), focusing the next solve on its contact. `None` when the window
    /// turned out too small.
    fn solve_in(
        &mut self,
        window: Window,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
    ) -> Result<Option<ContactSolution>, ContactError> {
        let grid = self.grid;
        let Some((sub, solution)) = self.solve_on(window, problem, options, warm_start)? else {
            return Ok(None);
        };
        let pressure = window.embed(&grid, &solution.pressure);
        // The next solve's window too, so that it starts from the check's displacement;
        // found among the window's cells, as no other is loaded (on the 2 um example's
        // grown grid, scanning the whole grid's rows was 1.2% of the samples of 100
        // cycles on a 300 um domain).
        let next = Window::loaded(&sub, &solution.pressure)
            .map(|loaded| around_box(&grid, &loaded.shifted(window.x0, window.y0)));
        let both = next.map_or(window, |next| next.union(&window));
        let reach = self.reach(&both, problem.separation, &solution, options.tolerance);
        let elastic = self.displacement_over(&reach, &pressure)?;
        let mut displacement = reach.embed(&grid, &elastic);
        // Only the window's rows carry pressure, so only they wear: the rows beyond (about a
        // third of the 2 um example's grown grid, late in its run) would add nothing.
        let rows = grid.row_cells(window.rows());
        add_worn_rows(
            problem.pass_wear_per_pa,
            &grid,
            &pressure[rows.clone()],
            &mut displacement[rows],
        );
        let scale = displacement_scale(&displacement);
        // The gap first: it rarely fails, and the window's test divides by the row length.
        let penetrates = reach.indices(&grid).any(|i| {
            displacement[i] + problem.separation[i] - solution.approach_m
                < -options.tolerance * scale
                && !window.contains(&grid, i)
        });
        if penetrates {
            return Ok(None);
        }
        self.focus = next;
        self.carried = Some(Carried {
            pressure: solution.pressure,
            solved: window,
            displacement: elastic,
            over: reach,
        });
        self.fractions.solved += (window.nx * window.ny) as f64 / grid.len() as f64;
        self.fractions.checked += (reach.nx * reach.ny) as f64 / grid.len() as f64;
        Ok(Some(ContactSolution {
            pressure,
            displacement,
            operator_applies: solution.operator_applies + 1,
            ..solution
        }))
    }

    /// The solve of [`Self::solve_in`] on `window`'s cells alone, from the carried check's
    /// displacement where it can start; the window's grid and the solution, or `None` when
    /// the window turned out too small.
    fn solve_on(
        &mut self,
        window: Window,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
    ) -> Result<Option<(Grid, ContactSolution)>, ContactError> {
        let grid = self.grid;
        let sub = Grid::new(window.nx, window.ny, grid.dx, grid.dy)?;
        let separation = window.extract(&grid, problem.separation);
        let warm = warm_start.map(|p| window.extract(&grid, p));
        let sub_problem = ContactProblem {
            grid: sub,
            separation: &separation,
            ..*problem
        };
        let known = self.carried.as_ref().zip(warm_start);
        let known = known.and_then(|(carried, warm)| carried.start_on(&grid, &window, warm));
        let solver = self.solver_of(&window)?;
        let outcome = match (warm.as_deref(), known.as_deref()) {
            (Some(pressure), Some(displacement)) => {
                let start = KnownStart {
                    pressure,
                    displacement,
                };
                solver.solve_known(&sub_problem, options, start)
            }
            (warm, _) => solver.solve(&sub_problem, options, warm),
        };
        // Either failure says the window, not the domain, is too small.
        match outcome {
            Err(ContactError::ContactAtEdge { .. } | ContactError::LoadExceedsCapacity { .. }) => {
                Ok(None)
            }
            outcome => Ok(Some((sub, outcome?))),
        }
    }

    /// The cells the check of `solution` computes: the whole grid, or, under a nonnegative
    /// kernel, the box of `window` (at least the one solved on) and of the cells whose separation
    /// could let them penetrate, `h - delta < -tolerance * scale`, sized for the FFT. The
    /// scale is the window's largest displacement, at most the whole grid's: every cell the
    /// whole grid's test could flag is inside.
    fn reach(
        &mut self,
        window: &Window,
        separation: &[f64],
        solution: &ContactSolution,
        tolerance: f64,
    ) -> Window {
        let grid = self.grid;
        if !self.full.operator().is_nonnegative() {
            return Window::whole(&grid);
        }
        let threshold =
            solution.approach_m - tolerance * displacement_scale(&solution.displacement);
        let reach = Window::bounding(&grid, separation, |h| h < threshold)
            .map_or(*window, |closing| closing.union(window));
        Window::centred(
            &grid,
            reach.centre(),
            fft_friendly(reach.nx),
            fft_friendly(reach.ny),
        )
    }

    /// `K pressure` on the cells of `reach` (row by row, `reach.nx` to a row).
    fn displacement_over(
        &mut self,
        reach: &Window,
        pressure: &[f64],
    ) -> Result<Vec<f64>, ContactError> {
        let grid = self.grid;
        let mut displacement = vec![0.0; reach.nx * reach.ny];
        if reach.covers(&grid) {
            self.full.operator().apply(pressure, &mut displacement);
        } else {
            self.solver_of(reach)?
                .operator()
                .apply(&reach.extract(&grid, pressure), &mut displacement);
        }
        Ok(displacement)
    }

    /// The solver of `window`'s shape: kept from its last use, or built, dropping the least
    /// recently used beyond [`KEPT_SHAPES`].
    fn solver_of(&mut self, window: &Window) -> Result<&mut Box<dyn ContactSolver>, ContactError> {
        let shape = (window.nx, window.ny);
        let entry = match self.by_shape.iter().position(|(s, _)| *s == shape) {
            Some(at) => self.by_shape.remove(at),
            None => {
                let sub = Grid::new(window.nx, window.ny, self.grid.dx, self.grid.dy)?;
                if self.by_shape.len() == KEPT_SHAPES {
                    self.by_shape.remove(0);
                }
                (shape, (self.factory)(&sub))
            }
        };
        self.by_shape.push(entry);
        Ok(&mut self.by_shape.last_mut().expect("pushed above").1)
    }
}

impl<F: FnMut(&Grid) -> Box<dyn ContactSolver>> ContactSolver for WindowedSolver<F> {
    /// Solves `problem` (on the whole grid) in a window around the last contact, enlarged
    /// until the answer holds on the whole grid; on the whole grid when there is no last
    /// contact or the window has grown to cover it.
    fn solve(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
    ) -> Result<ContactSolution, ContactError> {
        let grid = self.grid;
        let mut window = self.focus;
        let solution = loop {
            let Some(w) = window.filter(|w| !w.covers(&grid)) else {
                self.fractions += WindowFractions {
                    solved: 1.0,
                    checked: 1.0,
                };
                let solution = self.full.solve(problem, options, warm_start)?;
                self.focus = around(&grid, &solution.pressure);
                // The last window's check is not of this pressure, and its rows are not
                // this solve's.
                self.carried = None;
                break solution;
            };
            // A window's solve focuses the next one itself, on the box its check covered.
            match self.solve_in(w, problem, options, warm_start)? {
                Some(solution) => break solution,
                None => window = Some(enlarged(&w, &grid)),
            }
        };
        Ok(solution)
    }

    fn operator(&mut self) -> &mut dyn Operator {
        self.full.operator()
    }
}

#[cfg(test)]
mod tests;
