//! Applying the kernel to a field that is zero but at a few cells, by direct summation: one
//! multiply-add per grid cell and loaded cell, against the transforms' `O(n log n)` of an
//! apply. The solver changes a few cells at the rim of the contact in most iterations
//! (truncated at a bound, or re-entering), and this brings the displacement along without
//! another apply.

use super::super::influence::{Kernel, offset_index};

/// The most grid cells for which the real-space kernel is kept: four times the grid's
/// cells (every offset), 8 MB at 512 x 512. Beyond it the kernel's memory would rival the
/// transforms' buffers, and the contacts are large enough that few iterations change only
/// a few cells.
pub(crate) const MAX_CELLS: usize = 512 * 512;

/// Cells a sparse update may hold and still cost less than an apply, per `log2` of the
/// padded cells: an apply is a few passes of `4 n log2(4 n)` butterflies, a sparse update
/// `n` multiply-adds per cell. Measured by `cargo test --release --lib sparse_update_cost
/// -- --ignored --nocapture`: an apply costs as much as 2.9 to 4.1 cells per `log2` (52 to
/// 67 cells) from 64 x 64 to 512 x 512. 2.5 stays below, since the timing runs with the
/// kernel in cache and the solver's updates do not.
const CELLS_PER_LOG2: f64 = 2.5;

/// The kernel in real space, laid out as [`Kernel`] keeps it ([`offset_index`]).
#[derive(Debug, Clone)]
pub(crate) struct KernelRows {
    nx: usize,
    ny: usize,
    values: Vec<f64>,
    /// The most cells an update takes before an apply is cheaper.
    max_cells: usize,
}

impl KernelRows {
    /// The sum of `kernels`, if its grid is small enough to keep it ([`MAX_CELLS`]).
    pub(crate) fn of(kernels: &[&Kernel]) -> Option<Self> {
        let (first, rest) = kernels.split_first()?;
        let (nx, ny) = first.shape();
        if nx * ny > MAX_CELLS {
            return None;
        }
        let mut values = first.values().to_vec();
        for kernel in rest {
            for (sum, &value) in values.iter_mut().zip(kernel.values()) {
                *sum += value;
            }
        }
        let padded = (4 * nx * ny) as f64;
        Some(Self {
            nx,
            ny,
            values,
            max_cells: (CELLS_PER_LOG2 * padded.log2()).floor() as usize,
        })
    }

    /// Adds the kernel applied to `cells` (index and value; zero elsewhere) to `output`;
    /// false, with `output` untouched, when so many cells would cost more than an apply.
    pub(crate) fn add(&self, cells: &[(usize, f64)], output: &mut [f64]) -> bool {
        if cells.len() > self.max_cells {
            return false;
        }
        let (nx, ny) = (self.nx, self.ny);
        for &(j, value) in cells {
            let (jx, jy) = ((j % nx) as isize, (j / nx) as isize);
            for (iy, row) in output.chunks_exact_mut(nx).enumerate() {
                // Offsets (ix - jx, iy - jy) for ix = 0..nx: one contiguous run of the kernel.
                let start = offset_index(nx, ny, -jx, iy as isize - jy);
                let kernel = &self.values[start..start + nx];
                for (out, &k) in row.iter_mut().zip(kernel) {
                    *out += value * k;
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use std::time::Instant;

    use super::*;
    use crate::contact::{DcFft, DenseOperator, ElasticPair, Grid, Material, Operator};

    fn pair() -> ElasticPair {
        ElasticPair::new(
            Material::new(210e9, 0.3).expect("valid"),
            Material::new(195e9, 0.25).expect("valid"),
        )
    }

    #[test]
    fn a_sparse_update_equals_direct_summation_of_its_cells() {
        // Odd sizes and a non-square cell, so a transposed or mirrored offset shows.
        let grid = Grid::new(13, 9, 1e-6, 1.4e-6).expect("valid");
        let normal = Kernel::normal(&grid, &pair());
        let coupling = Kernel::coupling(&grid, &pair(), 0.45);
        let cells = [(0, 2e8), (7, -1e8), (60, 3e8), (116, 5e7)];
        let mut field = vec![0.0; grid.len()];
        for &(j, v) in &cells {
            field[j] = v;
        }
        let mut dense = vec![0.0; grid.len()];
        crate::contact::SumOperator::new(
            DenseOperator::new(normal.clone()),
            DenseOperator::new(coupling.clone()),
        )
        .apply(&field, &mut dense);
        // Added on top of an existing field, as the solver adds to its displacement.
        let base = 1e-10;
        let mut sparse = vec![base; grid.len()];
        assert!(DcFft::sum(&normal, &coupling).add_sparse(&cells, &mut sparse));
        let scale = dense.iter().fold(base, |m, v| m.max(v.abs()));
        for (s, d) in sparse.iter().zip(&dense) {
            // Five terms summed in another order: a few ulps of the largest.
            assert!((s - base - d).abs() < 1e-14 * scale, "{s} vs {d}");
        }
    }

    #[test]
    fn too_many_cells_or_too_large_a_grid_leave_it_to_an_apply() {
        let grid = Grid::new(16, 16, 1e-6, 1e-6).expect("valid");
        let rows = KernelRows::of(&[&Kernel::normal(&grid, &pair())]).expect("small grid");
        let many: Vec<(usize, f64)> = (0..=rows.max_cells).map(|j| (j, 1.0)).collect();
        let mut output = vec![0.0; grid.len()];
        assert!(!rows.add(&many, &mut output));
        assert!(output.iter().all(|&v| v == 0.0), "untouched");
        let large = Grid::new(1024, 512, 1e-6, 1e-6).expect("valid");
        assert!(KernelRows::of(&[&Kernel::normal(&large, &pair())]).is_none());
    }

    /// The apply's time over one cell's sparse update, per `log2` of the padded cells.
    #[test]
    #[ignore = "a timing: run with --release --ignored --nocapture"]
    fn sparse_update_cost() {
        for (nx, ny) in [(64, 64), (144, 240), (256, 256), (512, 512)] {
            let grid = Grid::new(nx, ny, 1e-6, 1e-6).expect("valid");
            let kernel = Kernel::normal(&grid, &pair());
            let mut op = DcFft::new(&kernel);
            let input = vec![1e8; grid.len()];
            let mut output = vec![0.0; grid.len()];
            let median = |f: &mut dyn FnMut()| {
                let mut times: Vec<f64> = (0..31)
                    .map(|_| {
                        let start = Instant::now();
                        f();
                        start.elapsed().as_secs_f64()
                    })
                    .collect();
                times.sort_by(f64::total_cmp);
                times[15]
            };
            let apply = median(&mut || op.apply(&input, &mut output));
            let cells: Vec<(usize, f64)> = (0..8).map(|k| (k * 97 % grid.len(), 1e8)).collect();
            let rows = KernelRows::of(&[&kernel]).expect("small grid");
            let sparse = median(&mut || {
                rows.add(&cells, &mut output);
            }) / 8.0;
            let log2 = ((4 * nx * ny) as f64).log2();
            println!(
                "{nx} x {ny}: apply {apply:.3e} s, one cell {sparse:.3e} s, apply / cell {:.1}, per log2 {:.2}",
                apply / sparse,
                apply / sparse / log2
            );
        }
    }
}
