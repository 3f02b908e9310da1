//! Domain growth: as the groove deepens the contact widens across the track, and an auto
//! domain grows before the pressure reaches its edge (where the solve would fail, since the
//! half-space outside the domain would have carried load too).

use crate::contact::{Grid, Window};

use super::sizing::fitted_cells;

/// The domain grows when pressure reaches this fraction of the half-width from the centre...
pub(super) const GROW_AT_FRACTION: f64 = 0.8;
/// ... or comes within this many cells of the edge, whichever is first: on grids under 20
/// cells 20% is under two cells, and the contact reached the edge ring (failing the solve)
/// before the growth saw it.
pub(super) const GROW_AT_EDGE_CELLS: f64 = 2.0;

/// Growth factor of the domain side (then rounded up to an FFT-friendly size).
const GROWTH: f64 = 1.25;

/// Whether loaded cells lie outside `GROW_AT_FRACTION` of the half-width (or within
/// `GROW_AT_EDGE_CELLS` of the edge), along x and along y. The axes grow separately: as the
/// groove deepens the contact widens across the track but shortens along it (paper
/// Fig. 10), so only y keeps growing.
pub(super) fn near_edges(grid: &Grid, pressure: &[f64]) -> (bool, bool) {
    let limit = |n: usize, d: f64| {
        let half = n as f64 * d / 2.0;
        (GROW_AT_FRACTION * half).min(half - GROW_AT_EDGE_CELLS * d)
    };
    let (limit_x, limit_y) = (limit(grid.nx, grid.dx), limit(grid.ny, grid.dy));
    // The loaded cells farthest from the centre are on their box's edges.
    Window::loaded(grid, pressure).map_or((false, false), |loaded| {
        let far_x = grid
            .x(loaded.x0)
            .abs()
            .max(grid.x(loaded.x0 + loaded.nx - 1).abs());
        let far_y = grid
            .y(loaded.y0)
            .abs()
            .max(grid.y(loaded.y0 + loaded.ny - 1).abs());
        (far_x > limit_x, far_y > limit_y)
    })
}

/// The grid with the same cells and about `GROWTH` times the side along the crowded axes, or
/// `None` when neither can grow (the size limit).
pub(super) fn widen(grid: &Grid, (grow_x, grow_y): (bool, bool)) -> Option<Grid> {
    // FFT-friendly sizes are even, so each axis grows by the same cells on both sides.
    let grown = |n: usize, grow: bool| {
        if grow {
            fitted_cells((n as f64 * GROWTH).ceil() as usize)
        } else {
            n
        }
    };
    let (nx, ny) = (grown(grid.nx, grow_x), grown(grid.ny, grow_y));
    (nx > grid.nx || ny > grid.ny)
        .then(|| Grid::new(nx, ny, grid.dx, grid.dy).ok())
        .flatten()
}

/// `field` on `from` placed on the wider grid `to`, centred as [`widen`] grows it (the same
/// cells on both sides), zero on the new cells.
pub(super) fn embedded(field: &[f64], from: &Grid, to: &Grid) -> Vec<f64> {
    let (x0, y0) = ((to.nx - from.nx) / 2, (to.ny - from.ny) / 2);
    let mut wider = vec![0.0; to.len()];
    for (iy, row) in field.chunks_exact(from.nx).enumerate() {
        let start = (iy + y0) * to.nx + x0;
        wider[start..start + from.nx].copy_from_slice(row);
    }
    wider
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_crowded_axis_grows_and_the_largest_grid_does_not() {
        let grid = Grid::square(64, 64e-6).expect("valid");
        let mut pressure = vec![0.0; grid.len()];
        // A cell 29.5 um across the track from the centre: beyond 80% of the 32 um half-side.
        pressure[(32 + 29) * 64 + 32] = 1.0;
        assert_eq!(near_edges(&grid, &pressure), (false, true));
        let wider = widen(&grid, (false, true)).expect("grows");
        // 64 x 1.25 = 80 cells, rounded up to 2^5 x 3 = 96.
        assert_eq!((wider.nx, wider.ny), (64, 96));
        assert_eq!(wider.dy.to_bits(), grid.dy.to_bits());
        let largest = Grid::square(Grid::MAX_CELLS_PER_SIDE, 1e-3).expect("valid");
        assert!(widen(&largest, (true, true)).is_none());
    }

    #[test]
    fn an_embedded_field_keeps_its_cells_at_the_same_place_about_the_centre() {
        let from = Grid::new(4, 2, 1.0, 1.0).expect("valid");
        let to = Grid::new(6, 4, 1.0, 1.0).expect("valid");
        let field: Vec<f64> = (1..=8).map(f64::from).collect();
        let wider = embedded(&field, &from, &to);
        // Each cell's value sits at the cell of the wider grid with the same centre (x and
        // y about the grid's centre); the new cells hold zero.
        let mut carried = 0;
        for (j, &value) in wider.iter().enumerate() {
            let (x, y) = (to.x(j % to.nx), to.y(j / to.nx));
            let source = (0..from.len()).find(|&i| {
                from.x(i % from.nx).to_bits() == x.to_bits()
                    && from.y(i / from.nx).to_bits() == y.to_bits()
            });
            let expected = source.map_or(0.0, |i| field[i]);
            assert_eq!(value.to_bits(), expected.to_bits(), "cell {j}");
            carried += usize::from(source.is_some());
        }
        assert_eq!(carried, field.len());
    }
}
