//! Solving on a window of the grid around the contact. DC-FFT convolves without
//! wrap-around, so the displacements inside any window that holds all the pressure are
//! exact: the solve only needs the contact's bounding box plus a margin, however large the
//! domain. Each solve is then checked on the whole grid with one apply: no cell outside the
//! window may penetrate. A contact that touches the window's edge, a load the window cannot
//! carry at the yield pressure, or a penetration outside it enlarges the window and the
//! solve is repeated; so the answer is the whole grid's, at the cost of the window's cells.

use std::collections::HashMap;

use crate::contact::{
    ContactError, ContactProblem, ContactSolution, Grid, Operator, SolverOptions,
};

use super::setup::fft_friendly;
use super::{ContactOperators, Setup};

/// Margin around the last contact's bounding box, as a fraction of its extent...
pub(crate) const MARGIN_FRACTION: f64 = 0.15;
/// ... and at least this many cells: the contact moves by a cell or two per solve.
pub(crate) const MIN_MARGIN: usize = 4;
/// Growth of a window that turned out too small.
const ENLARGE: f64 = 1.5;

/// A rectangle of cells `[x0, x0 + nx) x [y0, y0 + ny)` of a grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Window {
    x0: usize,
    y0: usize,
    nx: usize,
    ny: usize,
}

/// `n` cells centred on `centre`, kept inside `0..len`.
fn span(centre: usize, n: usize, len: usize) -> (usize, usize) {
    let n = n.min(len);
    (centre.saturating_sub(n / 2).min(len - n), n)
}

impl Window {
    /// The window around the loaded cells of `pressure`, or `None` if there are none.
    fn around(grid: &Grid, pressure: &[f64]) -> Option<Self> {
        let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
        for (i, _) in pressure.iter().enumerate().filter(|(_, p)| **p > 0.0) {
            let (ix, iy) = (i % grid.nx, i / grid.nx);
            (x0, x1, y0, y1) = (x0.min(ix), x1.max(ix), y0.min(iy), y1.max(iy));
        }
        if x0 == usize::MAX {
            return None;
        }
        let sized = |extent: usize| {
            let margin = MIN_MARGIN.max((MARGIN_FRACTION * extent as f64).ceil() as usize);
            fft_friendly(extent + 2 * margin)
        };
        let (x0, nx) = span((x0 + x1) / 2, sized(x1 - x0 + 1), grid.nx);
        let (y0, ny) = span((y0 + y1) / 2, sized(y1 - y0 + 1), grid.ny);
        Some(Self { x0, y0, nx, ny })
    }

    fn enlarged(&self, grid: &Grid) -> Self {
        let grow = |n: usize| fft_friendly((n as f64 * ENLARGE).ceil() as usize);
        let (x0, nx) = span(self.x0 + self.nx / 2, grow(self.nx), grid.nx);
        let (y0, ny) = span(self.y0 + self.ny / 2, grow(self.ny), grid.ny);
        Self { x0, y0, nx, ny }
    }

    fn covers(&self, grid: &Grid) -> bool {
        self.nx == grid.nx && self.ny == grid.ny
    }

    fn contains(&self, grid: &Grid, i: usize) -> bool {
        let (ix, iy) = (i % grid.nx, i / grid.nx);
        (self.x0..self.x0 + self.nx).contains(&ix) && (self.y0..self.y0 + self.ny).contains(&iy)
    }

    fn extract(&self, grid: &Grid, field: &[f64]) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.nx * self.ny);
        for iy in self.y0..self.y0 + self.ny {
            out.extend_from_slice(&field[iy * grid.nx + self.x0..][..self.nx]);
        }
        out
    }

    fn embed(&self, grid: &Grid, field: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; grid.len()];
        for (row, iy) in field.chunks_exact(self.nx).zip(self.y0..) {
            out[iy * grid.nx + self.x0..][..self.nx].copy_from_slice(row);
        }
        out
    }
}

/// The contact solver of one grid, working on windows around the contact.
#[derive(Debug)]
pub struct WindowedSolver {
    grid: Grid,
    full: ContactOperators,
    by_shape: HashMap<(usize, usize), ContactOperators>,
    /// Cells solved over cells of the grid, summed over solves (for the report).
    pub window_fraction_sum: f64,
}

impl WindowedSolver {
    /// The solver of `grid` with the operators `setup` chooses.
    pub fn new(setup: &Setup, grid: Grid) -> Self {
        Self {
            grid,
            full: setup.operators(&grid),
            by_shape: HashMap::new(),
            window_fraction_sum: 0.0,
        }
    }

    /// Solves `problem` (on the whole grid) in a window around `previous`, the last
    /// pressure; on the whole grid when there is none.
    pub fn solve(
        &mut self,
        setup: &Setup,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
        previous: Option<&[f64]>,
    ) -> Result<ContactSolution, ContactError> {
        let grid = self.grid;
        let mut window = previous.and_then(|p| Window::around(&grid, p));
        loop {
            let Some(w) = window.filter(|w| !w.covers(&grid)) else {
                self.window_fraction_sum += 1.0;
                return self.full.solve(problem, options, warm_start);
            };
            let sub = Grid::new(w.nx, w.ny, grid.dx, grid.dy)?;
            let separation = w.extract(&grid, problem.separation);
            let warm = warm_start.map(|p| w.extract(&grid, p));
            let sub_problem = ContactProblem {
                grid: sub,
                separation: &separation,
                ..*problem
            };
            let operators = self
                .by_shape
                .entry((w.nx, w.ny))
                .or_insert_with(|| setup.operators(&sub));
            // Either failure says the window, not the domain, is too small.
            let solution = match operators.solve(&sub_problem, options, warm.as_deref()) {
                Err(
                    ContactError::ContactAtEdge { .. } | ContactError::LoadExceedsCapacity { .. },
                ) => {
                    window = Some(w.enlarged(&grid));
                    continue;
                }
                outcome => outcome?,
            };
            let pressure = w.embed(&grid, &solution.pressure);
            let mut displacement = vec![0.0; grid.len()];
            self.full.apply(&pressure, &mut displacement);
            let scale = displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let penetrates =
                displacement
                    .iter()
                    .zip(problem.separation)
                    .enumerate()
                    .any(|(i, (u, h))| {
                        !w.contains(&grid, i)
                            && u + h - solution.approach_m < -options.tolerance * scale
                    });
            if penetrates {
                window = Some(w.enlarged(&grid));
                continue;
            }
            self.window_fraction_sum += (w.nx * w.ny) as f64 / grid.len() as f64;
            return Ok(ContactSolution {
                pressure,
                displacement,
                operator_applies: solution.operator_applies + 1,
                ..solution
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::verify;
    use crate::scene::parse_scene_str;

    fn setup() -> Setup {
        let scene = parse_scene_str(
            r#"{"preset": "dalmau2018-316l", "overrides": {"numerics": {"grid": 96, "domain_um": 300}}}"#,
        )
        .expect("valid");
        Setup::new(&scene).expect("valid")
    }

    /// Solves the first cycle in a window around `previous` and checks the answer on the
    /// whole grid with the full operator, as the solver's own stopping test promises.
    fn check_window_from(previous_load_n: f64) -> f64 {
        let setup = setup();
        let grid = setup.grid;
        let separation = setup.ball_separation(&grid);
        let cap = setup.yield_pressure_pa(1.0);
        let problem = |load_n| ContactProblem {
            grid,
            separation: &separation,
            load_n,
            yield_pressure_pa: cap,
        };
        let mut solver = WindowedSolver::new(&setup, grid);
        let previous = solver
            .solve(
                &setup,
                &problem(previous_load_n),
                &setup.options,
                None,
                None,
            )
            .expect("converges");
        let windowed = solver
            .solve(
                &setup,
                &problem(5.0),
                &setup.options,
                None,
                Some(&previous.pressure),
            )
            .expect("converges");
        let mut full = setup.operators(&grid);
        let check = verify(&mut full, &problem(5.0), &windowed);
        // The solver's tolerance plus the 1e-12 FFT round-off bound (tests/contact.rs).
        assert!(
            check.passes(setup.options.tolerance + 1e-12, 1e-9),
            "{check:?}"
        );
        solver.window_fraction_sum
    }

    #[test]
    fn windowed_solution_is_a_solution_on_the_whole_grid() {
        // First solve on the whole grid (fraction 1), the second on a window.
        let fraction = check_window_from(5.0);
        assert!(fraction < 1.6, "the second solve used a window: {fraction}");
    }

    #[test]
    fn a_window_too_small_for_the_contact_is_enlarged() {
        // Around a 0.05 N contact the window cannot hold the 5 N one: it must grow.
        check_window_from(0.05);
    }

    #[test]
    fn windows_stay_inside_the_grid_and_hold_the_contact() {
        let grid = Grid::square(64, 64e-6).expect("valid");
        let mut pressure = vec![0.0; grid.len()];
        pressure[2 * 64 + 60] = 1.0;
        pressure[10 * 64 + 50] = 1.0;
        let w = Window::around(&grid, &pressure).expect("loaded");
        assert!(w.x0 + w.nx <= 64 && w.y0 + w.ny <= 64);
        assert!(w.contains(&grid, 2 * 64 + 60) && w.contains(&grid, 10 * 64 + 50));
        let back = w.embed(&grid, &w.extract(&grid, &pressure));
        assert_eq!(back, pressure);
        assert!(Window::around(&grid, &[0.0; 4096]).is_none());
    }
}
