//! The contact solved on the surface its own wear leaves: the implicit wear update.
//!
//! A pass of the ball wears each row of the track (fixed `y`) by `s int p(x, y) dx`
//! (eqs. 15-16; `s` is Archard's `k / H` summed over the passes a solve stands for). The
//! paper solves the contact on the surface before the pass and wears it with that pressure:
//! forward Euler in the cycles. A row raised by `delta` over a wavelength `lambda` across
//! the track carries about `pi E* delta / lambda` more pressure, so a pass changes the row's
//! excess by the factor `1 - r`, `r = pi s l E* / lambda` (`l` the contact's chord along
//! the track). Beyond `r = 2` the excess grows, alternating in sign. A smooth disc's groove
//! has no short wavelengths and its `r` is tiny; a rough disc's asperity rows reach the
//! cells' scale, where `r` is of order one on the default cells and twice that on cells of
//! half the size (`docs/accuracy.md`, "Rough wear: speed levers").
//!
//! Solving on the worn surface instead, with the gap `K p + h + s dx sum_x p - delta`, is
//! backward Euler: the factor becomes `1 / (1 + r)`, stable at every `r`. For a solve whose
//! wear `s` counts `m'` passes but which then stands for `m` of them, the factor is
//! `1 - m r / (1 + m' r)`, stable while `m <= 2 m'`; the cycle step at most doubles from
//! one solve to the next (`simulation::stepping`), so the run takes `m'` as the last step.
//!
//! The wear term is an operator, `W p = s dx sum_x p` on every cell of the row: symmetric,
//! positive semi-definite and nonnegative, so the solver runs unchanged on `K + W`
//! ([`WornRows`]) and the check of a windowed solve adds it ([`add_worn_rows`]). The
//! preconditioner stays `K`'s inverse.

use super::grid::Grid;
use super::operator::{Operator, Preconditioner};
use super::sums::sum;

/// An operator `K` plus the wear `W` its pressure wears in the passes of one solve.
pub struct WornRows<'a> {
    inner: &'a mut dyn Operator,
    /// `s dx`: the depth worn per unit of a row's pressure sum, m/Pa.
    per_row_sum: f64,
    /// The row sums of the input of the last [`Operator::keep`].
    kept_rows: Vec<f64>,
}

impl<'a> WornRows<'a> {
    /// `inner` plus the wear of `pass_wear_per_pa` (the depth per unit of `int p dx`, 1/Pa)
    /// on cells `dx_m` long along the sliding direction.
    pub fn new(inner: &'a mut dyn Operator, pass_wear_per_pa: f64, dx_m: f64) -> Self {
        Self {
            inner,
            per_row_sum: per_row_sum(pass_wear_per_pa, dx_m),
            kept_rows: Vec::new(),
        }
    }

    /// Adds the wear term of `pressure` to `output`: what [`Operator::apply`] adds to the
    /// inner operator's displacement.
    pub fn add_wear(&self, pressure: &[f64], output: &mut [f64]) {
        add_rows(self.per_row_sum, self.inner.shape().0, pressure, output);
    }
}

impl Operator for WornRows<'_> {
    fn shape(&self) -> (usize, usize) {
        self.inner.shape()
    }

    fn apply(&mut self, input: &[f64], output: &mut [f64]) {
        self.inner.apply(input, output);
        self.add_wear(input, output);
    }

    fn preconditioner(&mut self) -> Option<&mut dyn Preconditioner> {
        self.inner.preconditioner()
    }

    /// `K`'s half, plus `t . W t = s dx sum_rows (sum_x t)^2`.
    fn keep(&mut self, input: &[f64]) -> Option<f64> {
        let inner = self.inner.keep(input)?;
        let nx = self.inner.shape().0;
        self.kept_rows.clear();
        self.kept_rows.extend(input.chunks_exact(nx).map(sum));
        let rows: f64 = self.kept_rows.iter().map(|r| r * r).sum();
        Some(inner + self.per_row_sum * rows)
    }

    fn add_kept(&mut self, extra: Option<&[f64]>, scale: f64, output: &mut [f64]) {
        self.inner.add_kept(extra, scale, output);
        let nx = self.inner.shape().0;
        for (row, (out, &kept)) in output.chunks_exact_mut(nx).zip(&self.kept_rows).enumerate() {
            let extra = extra.map_or(0.0, |extra| sum(&extra[row * nx..(row + 1) * nx]));
            let worn = self.per_row_sum * (extra + scale * kept);
            out.iter_mut().for_each(|u| *u += worn);
        }
    }

    fn threads(&self) -> usize {
        self.inner.threads()
    }

    fn add_sparse(&mut self, cells: &[(usize, f64)], output: &mut [f64]) -> bool {
        if !self.inner.add_sparse(cells, output) {
            return false;
        }
        let nx = self.inner.shape().0;
        for &(i, value) in cells {
            let row = i / nx;
            let worn = self.per_row_sum * value;
            output[row * nx..(row + 1) * nx]
                .iter_mut()
                .for_each(|u| *u += worn);
        }
        true
    }

    fn is_periodic(&self) -> bool {
        self.inner.is_periodic()
    }

    fn is_nonnegative(&self) -> bool {
        self.inner.is_nonnegative()
    }
}

/// `s dx`: the depth `pass_wear_per_pa` (`s`) wears per unit of a row's pressure sum on
/// cells `dx_m` long along the sliding direction, m/Pa.
fn per_row_sum(pass_wear_per_pa: f64, dx_m: f64) -> f64 {
    pass_wear_per_pa * dx_m
}

/// Adds the wear `W p` of [`WornRows`] of `pass_wear_per_pa` on `grid` to `output`: each
/// row's sum of `pressure` times `s dx`, on every cell of that row. `pressure` and `output`
/// are the same rows of `grid`: all of them, or a band whose other rows carry no pressure.
pub fn add_worn_rows(pass_wear_per_pa: f64, grid: &Grid, pressure: &[f64], output: &mut [f64]) {
    add_rows(
        per_row_sum(pass_wear_per_pa, grid.dx),
        grid.nx,
        pressure,
        output,
    );
}

/// The depth `W p` of [`WornRows`] of `pass_wear_per_pa` wears on each row of `grid`, m,
/// in order (every cell of a row the same): what [`add_worn_rows`] adds to the row's cells.
pub fn worn_row_depths_m(
    pass_wear_per_pa: f64,
    grid: &Grid,
    pressure: &[f64],
) -> impl Iterator<Item = f64> {
    row_depths(per_row_sum(pass_wear_per_pa, grid.dx), grid.nx, pressure)
}

/// `per_row_sum` times each row's sum of `pressure` (rows of `nx` cells), in order.
fn row_depths(per_row_sum: f64, nx: usize, pressure: &[f64]) -> impl Iterator<Item = f64> {
    pressure.chunks_exact(nx).map(move |row| {
        if per_row_sum == 0.0 {
            0.0
        } else {
            per_row_sum * sum(row)
        }
    })
}

/// Adds `per_row_sum` times each row's sum of `pressure` (rows of `nx` cells) to every cell
/// of that row of `output`.
fn add_rows(per_row_sum: f64, nx: usize, pressure: &[f64], output: &mut [f64]) {
    if per_row_sum == 0.0 {
        return;
    }
    let rows = row_depths(per_row_sum, nx, pressure).zip(output.chunks_exact_mut(nx));
    for (worn, out) in rows {
        if worn != 0.0 {
            out.iter_mut().for_each(|u| *u += worn);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{
        ContactProblem, ContactSolver, DcFft, DenseOperator, ElasticPair, Grid, Hertz, Kernel,
        Material, NormalSolver, SolverOptions, verify,
    };

    fn pair() -> ElasticPair {
        ElasticPair::new(
            Material::new(300e9, 0.21).expect("valid"),
            Material::new(205e9, 0.28).expect("valid"),
        )
    }

    /// A deterministic field with values in [0, 1) and some zero rows.
    fn field(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| {
                if (i / 7) % 3 == 0 {
                    0.0
                } else {
                    ((i * 37 + 11) % 101) as f64 / 101.0
                }
            })
            .collect()
    }

    #[test]
    fn the_wear_term_is_the_row_sum_matrix_added_to_the_operator() {
        let grid = Grid::new(7, 5, 2e-6, 3e-6).expect("valid");
        let kernel = Kernel::normal(&grid, &pair());
        let (per_pa, n) = (2e-12, grid.len());
        let p = field(n);
        let mut plain = vec![0.0; n];
        DenseOperator::new(kernel.clone()).apply(&p, &mut plain);
        let mut dense = DenseOperator::new(kernel);
        let mut worn = vec![0.0; n];
        WornRows::new(&mut dense, per_pa, grid.dx).apply(&p, &mut worn);
        // W[i][j] = s dx where cells i and j share a row, 0 elsewhere.
        for i in 0..n {
            let expected = plain[i]
                + (0..n)
                    .filter(|&j| j / grid.nx == i / grid.nx)
                    .map(|j| per_pa * grid.dx * p[j])
                    .sum::<f64>();
            assert!((worn[i] - expected).abs() <= 1e-12 * expected.abs());
        }
    }

    #[test]
    fn a_sparse_update_adds_what_an_apply_of_the_cells_adds() {
        let grid = Grid::square(16, 32e-6).expect("valid");
        let mut fft = DcFft::new(&Kernel::normal(&grid, &pair()));
        let mut operator = WornRows::new(&mut fft, 5e-12, grid.dx);
        let cells = [(3, 1.5e8), (40, -2.0e8), (255, 0.7e8)];
        let mut sparse = vec![0.0; grid.len()];
        assert!(operator.add_sparse(&cells, &mut sparse));
        let mut field = vec![0.0; grid.len()];
        cells.iter().for_each(|&(i, v)| field[i] = v);
        let mut applied = vec![0.0; grid.len()];
        operator.apply(&field, &mut applied);
        let scale = applied.iter().fold(0.0f64, |m, u| m.max(u.abs()));
        // The FFT apply and the direct sum differ by the transforms' round-off.
        for (s, a) in sparse.iter().zip(&applied) {
            assert!((s - a).abs() <= 1e-12 * scale, "{s} against {a}");
        }
    }

    /// The defining property: the pressure solved with a pass's wear is in contact with the
    /// surface that pass leaves (the separation deepened by `s int p dx` row by row), on the
    /// plain operator, to the solver's tolerance; and it differs from the pressure on the
    /// unworn surface, so the term is not a no-op.
    #[test]
    fn the_solved_pressure_is_in_contact_with_the_surface_its_wear_leaves() {
        let grid = Grid::square(64, 200e-6).expect("valid");
        let hertz = Hertz {
            radius_m: 3e-3,
            load_n: 5.0,
            reduced_modulus_pa: pair().reduced_modulus_pa,
        };
        let separation = grid.sample(|x, y| hertz.separation_m(x, y));
        // A wear large enough to move the pressure: 0.2 um per GPa um of the row integral.
        let per_pa = 2e-13;
        let problem = ContactProblem {
            grid,
            separation: &separation,
            load_n: 5.0,
            yield_pressure_pa: 0.9e9,
            pass_wear_per_pa: per_pa,
        };
        let options = SolverOptions::default();
        let kernel = Kernel::normal(&grid, &pair());
        let mut solver = NormalSolver::new(DcFft::new(&kernel));
        let worn_solution = solver.solve(&problem, &options, None).expect("converges");
        let unworn = ContactProblem {
            pass_wear_per_pa: 0.0,
            ..problem
        };
        let plain_solution = solver.solve(&unworn, &options, None).expect("converges");

        let mut worn_separation = separation.clone();
        add_worn_rows(per_pa, &grid, &worn_solution.pressure, &mut worn_separation);
        let after_pass = ContactProblem {
            separation: &worn_separation,
            ..unworn
        };
        // The check recomputes K p by direct summation. The solver's residual is relative to
        // the largest K p + W p and the check's to the largest K p; the wear, under 20 nm
        // here (0.2 um per GPa um, rows carrying under 0.1 GPa um), is under 2% of it.
        let check = verify(&mut DenseOperator::new(kernel), &after_pass, &worn_solution);
        assert!(check.passes(1.05 * options.tolerance, 1e-9), "{check:?}");

        let moved = worn_solution
            .pressure
            .iter()
            .zip(&plain_solution.pressure)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            moved > 1e-3 * 0.9e9,
            "the wear moved the pressure by {moved} Pa only"
        );
    }
}
