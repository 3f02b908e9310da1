//! The computational domain: a regular grid of rectangular cells centred on the ball apex,
//! and rectangular windows of its cells.

use std::ops::Range;

use super::error::ContactError;

/// A regular `nx` x `ny` grid of cells of size `dx` x `dy` (metres) covering
/// `[-nx dx / 2, nx dx / 2] x [-ny dy / 2, ny dy / 2]`.
///
/// Convention: the origin (the ball apex) lies on a cell corner when `nx` and `ny` are even,
/// so the grid is mirror-symmetric about both axes. Fields are stored row-major with x
/// (the sliding direction) varying fastest: `index = iy * nx + ix`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Cells along x (sliding direction).
    pub nx: usize,
    /// Cells along y (across the track).
    pub ny: usize,
    /// Cell size along x, m.
    pub dx: f64,
    /// Cell size along y, m.
    pub dy: f64,
}

impl Grid {
    /// The largest cells per side accepted: the DC-FFT pads a grid to 2N x 2N, and a 4096
    /// grid's padded spectra (8192^2 complex values, 0.5 GiB each, several alive at once)
    /// would need gigabytes.
    pub const MAX_CELLS_PER_SIDE: usize = 2048;

    /// A square grid of `n` x `n` cells covering a square of side `side_m`.
    pub fn square(n: usize, side_m: f64) -> Result<Self, ContactError> {
        Self::new(n, n, side_m / n as f64, side_m / n as f64)
    }

    /// A grid of `nx` x `ny` cells of size `dx` x `dy`.
    pub fn new(nx: usize, ny: usize, dx: f64, dy: f64) -> Result<Self, ContactError> {
        let sizes_ok = (2..=Self::MAX_CELLS_PER_SIDE).contains(&nx)
            && (2..=Self::MAX_CELLS_PER_SIDE).contains(&ny);
        if !sizes_ok {
            return Err(ContactError::InvalidProblem(format!(
                "grid {nx} x {ny}: cells per side must be in 2..={}",
                Self::MAX_CELLS_PER_SIDE
            )));
        }
        if !(dx.is_finite() && dy.is_finite() && dx > 0.0 && dy > 0.0) {
            return Err(ContactError::InvalidProblem(format!(
                "cell size {dx} x {dy} m: must be finite and > 0"
            )));
        }
        Ok(Self { nx, ny, dx, dy })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a grid has at least 2 x 2 cells.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Cell area, m^2.
    pub fn cell_area(&self) -> f64 {
        self.dx * self.dy
    }

    /// Domain area, m^2.
    pub fn area(&self) -> f64 {
        self.cell_area() * self.len() as f64
    }

    /// x of the centre of column `ix`, m.
    pub fn x(&self, ix: usize) -> f64 {
        (ix as f64 + 0.5 - self.nx as f64 / 2.0) * self.dx
    }

    /// y of the centre of row `iy`, m.
    pub fn y(&self, iy: usize) -> f64 {
        (iy as f64 + 0.5 - self.ny as f64 / 2.0) * self.dy
    }

    /// The indices of the cells of the whole rows `rows`, row-major.
    pub fn row_cells(&self, rows: Range<usize>) -> Range<usize> {
        rows.start * self.nx..rows.end * self.nx
    }

    /// Whether the cell at `index` lies in the outermost ring.
    pub fn is_edge(&self, index: usize) -> bool {
        let (ix, iy) = (index % self.nx, index / self.nx);
        ix == 0 || iy == 0 || ix + 1 == self.nx || iy + 1 == self.ny
    }

    /// A field sampled at the cell centres.
    pub fn sample(&self, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.len());
        for iy in 0..self.ny {
            let y = self.y(iy);
            out.extend((0..self.nx).map(|ix| f(self.x(ix), y)));
        }
        out
    }
}

/// A rectangle of cells `[x0, x0 + nx) x [y0, y0 + ny)` of a grid: the part of a field a
/// windowed solve works on, the loaded part of a pressure map, or where a grid sits inside
/// a grown one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Window {
    /// First column.
    pub x0: usize,
    /// First row.
    pub y0: usize,
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
}

impl Window {
    /// The bounding box of the cells of `field` (on `grid`) with positive values, or `None`
    /// if there are none.
    pub fn loaded(grid: &Grid, field: &[f64]) -> Option<Self> {
        Self::bounding(grid, field, |v| v > 0.0)
    }

    /// The bounding box of the cells of `field` (on `grid`) whose value meets `test`, or
    /// `None` if none does.
    pub fn bounding(grid: &Grid, field: &[f64], test: impl Fn(f64) -> bool) -> Option<Self> {
        let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
        // Row by row, each row tested from both ends to its first and last hit only: a
        // windowed solve takes two boxes a solve over the whole grid, and a test of every
        // cell was 1% of the 4 um rough disc's `perf` samples for each.
        for (iy, row) in field.chunks_exact(grid.nx).enumerate() {
            let Some(first) = first_where(row, &test) else {
                continue;
            };
            let last = first + last_where(&row[first..], &test).unwrap_or(0);
            (x0, x1, y0, y1) = (x0.min(first), x1.max(last), y0.min(iy), y1.max(iy));
        }
        (x0 != usize::MAX).then_some(Self {
            x0,
            y0,
            nx: x1 - x0 + 1,
            ny: y1 - y0 + 1,
        })
    }

    /// The window moved by `x0` columns and `y0` rows: a window of a window's cells as a
    /// window of the grid the outer one lies in, when `(x0, y0)` is the outer one's corner.
    pub fn shifted(&self, x0: usize, y0: usize) -> Self {
        Self {
            x0: self.x0 + x0,
            y0: self.y0 + y0,
            ..*self
        }
    }

    /// The whole of `grid`.
    pub fn whole(grid: &Grid) -> Self {
        Self {
            x0: 0,
            y0: 0,
            nx: grid.nx,
            ny: grid.ny,
        }
    }

    /// The bounding box of both windows.
    pub fn union(&self, other: &Self) -> Self {
        let (x0, y0) = (self.x0.min(other.x0), self.y0.min(other.y0));
        let x1 = (self.x0 + self.nx).max(other.x0 + other.nx);
        let y1 = (self.y0 + self.ny).max(other.y0 + other.ny);
        Self {
            x0,
            y0,
            nx: x1 - x0,
            ny: y1 - y0,
        }
    }

    /// `nx` x `ny` cells centred on the cell `(cx, cy)` of `grid`, shifted (and cut) to
    /// stay inside it.
    pub fn centred(grid: &Grid, (cx, cy): (usize, usize), nx: usize, ny: usize) -> Self {
        let span = |centre: usize, n: usize, len: usize| {
            let n = n.min(len);
            (centre.saturating_sub(n / 2).min(len - n), n)
        };
        let (x0, nx) = span(cx, nx, grid.nx);
        let (y0, ny) = span(cy, ny, grid.ny);
        Self { x0, y0, nx, ny }
    }

    /// The window grown by `cells` on every side, cut at the edges of `grid`.
    pub fn padded(&self, cells: usize, grid: &Grid) -> Self {
        let (x0, y0) = (self.x0.saturating_sub(cells), self.y0.saturating_sub(cells));
        let x1 = (self.x0 + self.nx - 1 + cells).min(grid.nx - 1);
        let y1 = (self.y0 + self.ny - 1 + cells).min(grid.ny - 1);
        Self {
            x0,
            y0,
            nx: x1 - x0 + 1,
            ny: y1 - y0 + 1,
        }
    }

    /// The cell at the window's centre (of an even side's middle two, the later one).
    pub fn centre(&self) -> (usize, usize) {
        (self.x0 + self.nx / 2, self.y0 + self.ny / 2)
    }

    /// Column indices of `grid` inside the window.
    pub fn columns(&self) -> Range<usize> {
        self.x0..self.x0 + self.nx
    }

    /// Row indices of `grid` inside the window.
    pub fn rows(&self) -> Range<usize> {
        self.y0..self.y0 + self.ny
    }

    /// Whether every cell of `other` lies inside this window.
    pub fn holds(&self, other: &Self) -> bool {
        self.union(other) == *self
    }

    /// Whether the window is the whole of `grid`.
    pub fn covers(&self, grid: &Grid) -> bool {
        self.nx == grid.nx && self.ny == grid.ny
    }

    /// Whether the cell at `index` of `grid` lies inside the window.
    pub fn contains(&self, grid: &Grid, index: usize) -> bool {
        let (ix, iy) = (index % grid.nx, index / grid.nx);
        self.columns().contains(&ix) && self.rows().contains(&iy)
    }

    /// The window's part of `field` (on `grid`), row-major.
    pub fn extract(&self, grid: &Grid, field: &[f64]) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.nx * self.ny);
        for iy in self.rows() {
            out.extend_from_slice(&field[iy * grid.nx + self.x0..][..self.nx]);
        }
        out
    }

    /// The indices in `grid` of the window's cells, row by row.
    pub fn indices(&self, grid: &Grid) -> impl Iterator<Item = usize> {
        let (nx, columns) = (grid.nx, self.columns());
        self.rows()
            .flat_map(move |iy| columns.clone().map(move |ix| iy * nx + ix))
    }

    /// `field` (the window's cells, row-major) placed in a field of `grid`, zero outside.
    pub fn embed(&self, grid: &Grid, field: &[f64]) -> Vec<f64> {
        // Written once, in order, into memory the allocator reuses: a zeroed allocation
        // (`vec![0.0; n]`) of a whole grid is handed back to the system and faulted in
        // again page by page on every call, and the window then written over it.
        let mut out = Vec::with_capacity(grid.len());
        out.resize(self.y0 * grid.nx, 0.0);
        let after = grid.nx - self.x0 - self.nx;
        for row in field.chunks_exact(self.nx) {
            out.resize(out.len() + self.x0, 0.0);
            out.extend_from_slice(row);
            out.resize(out.len() + after, 0.0);
        }
        out.resize(grid.len(), 0.0);
        out
    }

    /// Copies `field` (the window's cells, row-major) onto the window's cells of `out`, a
    /// field of `grid`; the other cells are left as they are.
    pub fn place(&self, grid: &Grid, field: &[f64], out: &mut [f64]) {
        for (row, iy) in field.chunks_exact(self.nx).zip(self.y0..) {
            out[iy * grid.nx + self.x0..][..self.nx].copy_from_slice(row);
        }
    }
}

/// Cells a row is tested by at once before its cells one by one: runs of eight are tested
/// without a branch per cell, which the compiler turns into vector compares. Most rows of a
/// grown grid hold no hit, and the reach of a windowed solve's check, tested cell by cell
/// with a bounds check each, was two thirds of the windowed solver's own serial samples on
/// the 2 um example's grown grid (`perf annotate` of `tribosim run
/// scenes/bench-rough-2um-300um.json`).
const TESTED_AT_ONCE: usize = 8;

/// The first cell of `row` that meets `test`.
fn first_where(row: &[f64], test: &impl Fn(f64) -> bool) -> Option<usize> {
    let run = row
        .chunks(TESTED_AT_ONCE)
        .position(|run| any_of(run, test))?;
    let start = run * TESTED_AT_ONCE;
    row[start..]
        .iter()
        .position(|&v| test(v))
        .map(|i| start + i)
}

/// The last cell of `row` that meets `test`.
fn last_where(row: &[f64], test: &impl Fn(f64) -> bool) -> Option<usize> {
    let run = row
        .rchunks(TESTED_AT_ONCE)
        .position(|run| any_of(run, test))?;
    let end = row.len() - run * TESTED_AT_ONCE;
    row[..end].iter().rposition(|&v| test(v))
}

/// Whether any cell of `run` meets `test`, every cell tested.
fn any_of(run: &[f64], test: &impl Fn(f64) -> bool) -> bool {
    run.iter().fold(false, |hit, &v| hit | test(v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_are_symmetric_about_the_origin() {
        let g = Grid::square(8, 8e-6).expect("valid grid");
        for i in 0..8 {
            assert!((g.x(i) + g.x(7 - i)).abs() < 1e-18);
        }
        assert!((g.x(4) - 0.5e-6).abs() < 1e-18, "apex on a cell corner");
    }

    #[test]
    fn the_bounding_box_is_the_box_of_every_cell_that_meets_the_test() {
        // Rows of 21 cells (two whole runs of eight and a short one), with hits placed by a
        // fixed pseudo-random sequence: none, one, or a few per row, at the runs' edges too.
        let grid = Grid::new(21, 40, 1e-6, 1e-6).expect("valid");
        let mut state = 12345_u64;
        let mut next = |n: u64| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) % n
        };
        for _ in 0..50 {
            let mut field = vec![0.0; grid.len()];
            for _ in 0..next(6) {
                let cell = (next(40) * 21 + next(21)) as usize;
                field[cell] = 1.0;
            }
            let hits = (0..grid.len()).filter(|&i| field[i] > 0.5);
            let (x0, x1, y0, y1) = hits.fold((usize::MAX, 0, usize::MAX, 0), |b, i| {
                let (x, y) = (i % 21, i / 21);
                (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y))
            });
            let brute = (x0 != usize::MAX).then(|| Window {
                x0,
                y0,
                nx: x1 - x0 + 1,
                ny: y1 - y0 + 1,
            });
            assert_eq!(Window::bounding(&grid, &field, |v| v > 0.5), brute);
        }
    }

    #[test]
    fn windows_stay_inside_the_grid_and_round_trip_a_field() {
        let grid = Grid::square(64, 64e-6).expect("valid");
        let mut pressure = vec![0.0; grid.len()];
        pressure[2 * 64 + 60] = 1.0;
        pressure[10 * 64 + 50] = 1.0;
        let loaded = Window::loaded(&grid, &pressure).expect("loaded");
        assert_eq!(
            loaded,
            Window {
                x0: 50,
                y0: 2,
                nx: 11,
                ny: 9
            }
        );
        let w = Window::centred(&grid, loaded.centre(), 24, 24);
        assert!(w.x0 + w.nx <= 64 && w.y0 + w.ny <= 64);
        assert!(w.contains(&grid, 2 * 64 + 60) && w.contains(&grid, 10 * 64 + 50));
        assert_eq!(w.embed(&grid, &w.extract(&grid, &pressure)), pressure);
        assert_eq!(loaded.padded(4, &grid).columns(), 46..64);
        assert!(Window::loaded(&grid, &[0.0; 4096]).is_none());
    }

    #[test]
    fn rejects_bad_sizes() {
        assert!(Grid::square(1, 1e-3).is_err());
        assert!(Grid::square(4096, 1e-3).is_err());
        assert!(Grid::square(64, 0.0).is_err());
        assert!(Grid::square(64, f64::NAN).is_err());
    }
}
