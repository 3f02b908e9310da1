//! The computational domain: a regular grid of rectangular cells centred on the ball apex.

use super::ContactError;

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
    /// The largest cells per side accepted: the padded 2N x 2N spectra of a 4096 grid
    /// would need several gigabytes.
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
    fn rejects_bad_sizes() {
        assert!(Grid::square(1, 1e-3).is_err());
        assert!(Grid::square(4096, 1e-3).is_err());
        assert!(Grid::square(64, 0.0).is_err());
        assert!(Grid::square(64, f64::NAN).is_err());
    }
}
