//! How big the contact is and what grid it gets: the one home of the sizing rules that the
//! setup ([`super::Setup`]) applies and the checks of a plan ([`super::Plan`]) judge by.
//!
//! The grid is sized by a contact radius: Hertz's for the unworn ball, or, when the pressure
//! cap can act, the flat punch that carries the load at the lowest yield pressure of the run
//! (`F = pi r^2 Y`), whichever is wider. An auto grid puts [`CELLS_PER_CONTACT_RADIUS`] cells
//! across that radius and spans [`DOMAIN_PER_CONTACT_RADIUS`] radii, rounded up to an
//! FFT-friendly size of at most [`Grid::MAX_CELLS_PER_SIDE`].

use std::f64::consts::PI;

use crate::contact::{ContactError, ElasticPair, Grid, Hertz, Material, fft_friendly};
use crate::hardness::YieldCap;
use crate::scene::{GridSize, Numerics, Scene};

/// Auto domain side in contact radii. DC-FFT convolves without wrap-around, so the answer
/// does not depend on the domain as long as it holds the contact: the domain needs only the
/// contact plus room to widen, and the run grows it when pressure comes near the edge. With
/// 3 a the contact fills two thirds of the side, inside the 80% growth trigger. (The paper's
/// 0.256 mm is 5.8 a for its scene: 3.7 times the cells for the same answer.)
pub const DOMAIN_PER_CONTACT_RADIUS: f64 = 3.0;

/// Auto cell density: the paper's 1 um cells across its 44.2 um contact radius. At this
/// density the Hertz errors are -1.1e-4 (peak pressure), +6.4e-3 (area) and -2.3e-5
/// (approach): `tribosim bench contact`, N = 256.
pub const CELLS_PER_CONTACT_RADIUS: f64 = 44.0;

/// Auto cell density on the reciprocating rig, where the contact is solved at positions a
/// cell apart along the stroke, so a run costs about the cube of the density. Measured by
/// `scripts/stroke_accuracy.py` (20 cycles of a 2 mm stroke against grid 96, 32 per
/// radius, every cycle solved; `docs/rig-accuracy.md`): at 16 per radius (grid 48) the
/// deepest point errs by -1.6e-3, the profile across the middle by 5.2e-3 and along the
/// axis by 1.6e-3 of the deepest point, the volume by -1.2e-3, in 0.13 of the time; at
/// 10.7 (grid 32) by -2.1e-3, 1.0e-2 and 7.1e-3 in 0.04; at 21 (grid 64) by -4.5e-4,
/// 3.2e-3 and 1.3e-3 in 0.32. 16 keeps every error below the disc's grid error of a few
/// percent (`docs/accuracy.md`).
pub const STROKE_CELLS_PER_CONTACT_RADIUS: f64 = 16.0;

/// The auto cell density of `scene`'s rig, cells per contact radius.
pub fn cells_per_contact_radius(scene: &Scene) -> f64 {
    if scene.test.reciprocating.is_some() {
        STROKE_CELLS_PER_CONTACT_RADIUS
    } else {
        CELLS_PER_CONTACT_RADIUS
    }
}

/// The ball and the disc of `scene` as the contact core's materials. The scene's own checks
/// bound E and nu as the core does, so an error here means the two disagree.
pub fn elastic_pair(scene: &Scene) -> Result<ElasticPair, ContactError> {
    let ball = Material::new(scene.ball.youngs_modulus_pa(), scene.ball.poisson_ratio)?;
    let disc = Material::new(scene.disc.youngs_modulus_pa(), scene.disc.poisson_ratio)?;
    Ok(ElasticPair::new(ball, disc))
}

/// Hertz's contact of the unworn ball of `scene` on the disc, for the pair `pair`.
pub fn hertz(scene: &Scene, pair: &ElasticPair) -> Hertz {
    Hertz {
        radius_m: scene.ball_radius_m(),
        load_n: scene.load_n(),
        reduced_modulus_pa: pair.reduced_modulus_pa,
    }
}

/// Where and how low the yield pressure falls during a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LowestYield {
    /// The cycle of the lowest cap: 1 or the last.
    pub cycle: u64,
    /// The hardness there, Pa.
    pub hardness_pa: f64,
    /// The yield pressure there, Pa: `H / yield_factor`, or the disc's initial yield
    /// strength when the cap hardens from it (`from_initial`).
    pub yield_pa: f64,
    /// Whether the lowest cap is the unstrained disc's initial yield strength.
    pub from_initial: bool,
}

/// The lowest yield pressure of `cap` over `cycles` cycles ([`YieldCap::lowest`]).
pub fn lowest_yield(cap: &YieldCap, cycles: u64) -> LowestYield {
    let (cycle, hardness_pa, yield_pa) = cap.lowest(cycles);
    let (_, factor) = cap.hardness();
    LowestYield {
        cycle,
        hardness_pa,
        yield_pa,
        from_initial: yield_pa < hardness_pa / factor,
    }
}

/// Radius of the flat punch that carries `load_n` at the pressure `yield_pa`,
/// `sqrt(F / (pi Y))`, m.
pub fn punch_radius_m(load_n: f64, yield_pa: f64) -> f64 {
    (load_n / (PI * yield_pa)).sqrt()
}

/// The contact radius the grid is sized by: Hertz's, or the flat punch at the lowest yield
/// pressure `lowest_yield_pa` when that is larger and the cap can act (`capped`).
pub fn sizing_radius_m(hertz: &Hertz, lowest_yield_pa: f64, capped: bool) -> f64 {
    if capped {
        let punch = punch_radius_m(hertz.load_n, lowest_yield_pa);
        hertz.contact_radius_m().max(punch)
    } else {
        hertz.contact_radius_m()
    }
}

/// The auto cell size for a sizing radius at `per_radius` cells per radius, m.
pub fn auto_cell_m(radius_m: f64, per_radius: f64) -> f64 {
    radius_m / per_radius
}

/// The auto domain side for a sizing radius, m (before rounding to whole cells).
pub fn auto_domain_m(radius_m: f64) -> f64 {
    DOMAIN_PER_CONTACT_RADIUS * radius_m
}

/// The grid side for at least `cells` cells: FFT-friendly, and no larger than the core
/// accepts.
pub fn fitted_cells(cells: usize) -> usize {
    fft_friendly(cells).min(Grid::MAX_CELLS_PER_SIDE)
}

/// The first grid of a run: its cells per side, its side, and how they were chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct GridPlan {
    /// Cells per side.
    pub cells: usize,
    /// Side of the square domain, m.
    pub domain_m: f64,
    /// How, in words (for the `grid` model's reason).
    pub how: String,
}

/// The grid `numerics` asks for, with what it leaves to the simulation sized by the contact
/// radius `radius_m` at `per_radius` cells per radius ([`cells_per_contact_radius`]) and,
/// on a rough disc, by the finest cell its surface asks for (`surface_cell_m`, see
/// [`super::roughness::wanted_cell_m`]).
pub fn plan_grid(
    numerics: &Numerics,
    (radius_m, per_radius): (f64, f64),
    surface_cell_m: Option<f64>,
) -> GridPlan {
    let contact_cell = auto_cell_m(radius_m, per_radius);
    let cell = surface_cell_m.map_or(contact_cell, |c| c.min(contact_cell));
    let density = if cell < contact_cell {
        "cells auto, the surface's".to_owned()
    } else {
        format!("cells auto, {per_radius} per contact radius")
    };
    let fitted = |side: f64| fitted_cells((side / cell).ceil() as usize);
    let (cells, domain_m, how) = match (numerics.grid, numerics.domain_m()) {
        (GridSize::Cells(n), Some(domain)) => (n, domain, "as requested".to_owned()),
        (GridSize::Cells(n), None) => (
            n,
            auto_domain_m(radius_m),
            format!("cells as requested; domain auto, {DOMAIN_PER_CONTACT_RADIUS} contact radii"),
        ),
        (GridSize::Auto, Some(domain)) => (
            fitted(domain),
            domain,
            format!("domain as requested; {density}"),
        ),
        (GridSize::Auto, None) => {
            // Keep the cell size; the side grows to the next fast FFT size (cut at the
            // grid limit, where the cells grow instead).
            let n = fitted(auto_domain_m(radius_m));
            let side = (n as f64 * cell).max(auto_domain_m(radius_m));
            (
                n,
                side,
                format!("auto: {density}, at least {DOMAIN_PER_CONTACT_RADIUS} radii"),
            )
        }
    };
    GridPlan {
        cells,
        domain_m,
        how,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hardness::HardnessLaw;

    #[test]
    fn the_flat_punch_sizes_the_grid_only_where_it_is_wider_and_capped() {
        let hertz = Hertz {
            radius_m: 3e-3,
            load_n: 5.0,
            reduced_modulus_pa: 130.17e9,
        };
        let a = hertz.contact_radius_m();
        // A cap of p0 / 4 needs a punch wider than Hertz's contact (F = pi r^2 Y against
        // F = 2/3 pi a^2 p0: r = a sqrt(8 / 3)); a cap above p0 needs a narrower one.
        let low = hertz.peak_pressure_pa() / 4.0;
        let wide = sizing_radius_m(&hertz, low, true);
        assert!(
            (wide / a - (8.0f64 / 3.0).sqrt()).abs() < 1e-12,
            "{}",
            wide / a
        );
        assert_eq!(sizing_radius_m(&hertz, low, false).to_bits(), a.to_bits());
        let high = 2.0 * hertz.peak_pressure_pa();
        assert_eq!(sizing_radius_m(&hertz, high, true).to_bits(), a.to_bits());
    }

    #[test]
    fn lowest_yield_is_at_the_end_the_law_falls_towards() {
        let cap = |b_pa: f64| YieldCap::Hardness {
            law: HardnessLaw::Logarithmic { a_pa: 2.0e9, b_pa },
            yield_factor: 2.0,
        };
        assert_eq!(lowest_yield(&cap(1e8), 300).cycle, 1);
        let lowest = lowest_yield(&cap(-1e8), 300);
        assert_eq!(lowest.cycle, 300);
        assert!(!lowest.from_initial);
        // One division: exact to a rounding.
        assert!((lowest.yield_pa / (lowest.hardness_pa / 2.0) - 1.0).abs() < 1e-15);
        let hardening = YieldCap::StrainHardening {
            law: HardnessLaw::Logarithmic {
                a_pa: 2.0e9,
                b_pa: -1e8,
            },
            yield_factor: 2.0,
            initial_pa: 290e6,
        };
        let lowest = lowest_yield(&hardening, 300);
        assert_eq!((lowest.cycle, lowest.yield_pa), (1, 290e6));
        assert!(lowest.from_initial);
    }

    #[test]
    fn auto_grids_keep_the_cell_and_round_the_side_up() {
        let radius = 44.2e-6;
        let disc = (radius, CELLS_PER_CONTACT_RADIUS);
        let plan = plan_grid(&Numerics::default(), disc, None);
        // 3 radii in cells of radius / 44 is 133 cells, rounded up to 2^4 x 3^2 = 144.
        assert_eq!(plan.cells, 144);
        let cell = auto_cell_m(radius, CELLS_PER_CONTACT_RADIUS);
        assert!((plan.domain_m / (144.0 * cell) - 1.0).abs() < 1e-15);
        // The reciprocating rig's 16 per radius: 48 cells, 2^4 x 3.
        let stroke = plan_grid(
            &Numerics::default(),
            (radius, STROKE_CELLS_PER_CONTACT_RADIUS),
            None,
        );
        assert_eq!(stroke.cells, 48);
        let huge = Numerics {
            domain_um: crate::scene::DomainSize::Micrometres(100_000.0),
            ..Numerics::default()
        };
        assert_eq!(plan_grid(&huge, disc, None).cells, Grid::MAX_CELLS_PER_SIDE);
        // A surface asking for cells four times finer: 3 radii in cells of radius / 176 is
        // 528 cells, rounded up to 2^6 x 3^2 = 576.
        let rough = plan_grid(&Numerics::default(), disc, Some(cell / 4.0));
        assert_eq!(rough.cells, 576);
        assert!(rough.domain_m >= auto_domain_m(radius));
    }
}
