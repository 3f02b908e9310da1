//! Whether the simulation can run a scene: the limits of the contact it describes, which
//! depend on several fields at once (the materials, the load, the hardness law and the
//! numerics) and on the sizing rules of [`super::sizing`]. [`super::Plan`] judges every
//! scene by them once its fields passed their own checks.

use std::f64::consts::PI;

use super::sizing::{
    LowestYield, auto_cell_m, auto_domain_m, cells_per_contact_radius, punch_radius_m,
};
use crate::contact::{ElasticPair, Grid, Hertz};
use crate::scene::format::{num, sig};
use crate::scene::{DomainSize, FieldError, GridSize, Scene, Switch};

/// Largest `mu |beta|` accepted with the coupling term, beta being Dundurs' second parameter
/// `delta-nu / (2 (1 - nu*))`. Measured with `tribosim contact` on five pairs (|beta| 0.50 to
/// 0.75, auxetic ones among them) at grids 64 and 128: the coupled solve converged up to
/// 0.84-0.88 and failed (NotConverged, or the contact driven to the domain edge, however
/// large the domain) from 0.88-0.92 on; 20-cycle runs at 0.85 converged. Pairs with both
/// Poisson ratios >= 0 have |beta| <= 0.5, so every friction up to 1.6 passes.
const MAX_COUPLING: f64 = 0.8;
/// Fewest cells per contact radius. Measured on the paper's Hertz case at grid 64 over
/// 256 um, loads giving 0.5 to 15 cells per radius: from 1.43 cells the peak pressure errs
/// by 5.6% at most (the approach by 2%); at 1.27 cells by 15%, and more as the contact
/// shrinks, up to 87% at 0.5 cells.
const MIN_CELLS_PER_CONTACT_RADIUS: f64 = 1.5;

/// What the check derived from a scene whose fields each passed their own checks, and judges
/// it by.
pub(super) struct Derived<'a> {
    /// The scene's elastic pair.
    pub(super) pair: &'a ElasticPair,
    /// The lowest yield pressure of the run.
    pub(super) lowest: &'a LowestYield,
    /// Hertz's contact of the unworn ball.
    pub(super) hertz: &'a Hertz,
    /// Whether the cap may act (plasticity not "off").
    pub(super) capped: bool,
    /// The contact radius the grid is sized by.
    pub(super) sizing_m: f64,
}

/// The limits of the contact `scene` describes that it breaks, for a scene whose fields each
/// passed their own checks (a message here would otherwise really be about one of those
/// fields): the coupling and the capacity at the lowest cap. The resolution
/// ([`resolution`]) is judged only once these and plausibility hold, since a contact they
/// refuse is sized wrongly too.
pub(super) fn limits(scene: &Scene, derived: &Derived) -> Vec<FieldError> {
    let mut errors = Vec::new();
    check_coupling(&mut errors, scene, derived.pair);
    if derived.capped {
        check_capacity(&mut errors, scene, derived.lowest);
    }
    errors
}

/// Whether the grid resolves the unworn contact; see [`check_resolution`].
pub(super) fn resolution(scene: &Scene, derived: &Derived) -> Vec<FieldError> {
    let mut errors = Vec::new();
    let hertz_m = derived.hertz.contact_radius_m();
    check_resolution(&mut errors, scene, hertz_m, derived.sizing_m);
    errors
}

/// How the lowest yield pressure came about, for a message.
fn describe(lowest: &LowestYield, factor: f64) -> String {
    if lowest.from_initial {
        return format!(
            "cycle 1, where the yield pressure is lowest, the disc's initial yield strength Y \
             = {} MPa (disc.initial_yield_strength_mpa)",
            sig(lowest.yield_pa * 1e-6)
        );
    }
    format!(
        "cycle {}, where the yield pressure is lowest, Y = H / yield_factor = {} MPa / {} \
         = {} MPa",
        lowest.cycle,
        sig(lowest.hardness_pa * 1e-6),
        num(factor),
        sig(lowest.yield_pa * 1e-6)
    )
}

/// The coupled solve's outer fixed point diverges when the friction coupling rivals the
/// normal compliance; see [`MAX_COUPLING`].
fn check_coupling(errors: &mut Vec<FieldError>, scene: &Scene, pair: &ElasticPair) {
    let beta = pair.delta_nu / (2.0 * (1.0 - pair.nu_star));
    let mu = scene.test.friction_coefficient;
    if scene.numerics.coupling != Switch::Off && mu * beta.abs() > MAX_COUPLING {
        errors.push(FieldError::new(
            "test.friction_coefficient",
            format!(
                "with the friction coupling term, mu |beta| must be <= {MAX_COUPLING} (beta = \
                 delta-nu / (2 (1 - nu*)) = {} for these materials), so mu <= {}, got {}: \
                 above about 0.88 the coupled contact solve diverges. Set numerics.coupling to \
                 \"off\" to leave the term out",
                sig(beta),
                sig(MAX_COUPLING / beta.abs()),
                num(mu)
            ),
        ));
    }
}

/// At the cap every loaded cell carries at most Y, so the load needs an area of at least
/// F / Y: on the ball (whose largest section is pi R^2) and inside a fixed domain.
fn check_capacity(errors: &mut Vec<FieldError>, scene: &Scene, lowest: &LowestYield) {
    let load = scene.load_n();
    let radius = scene.ball_radius_m();
    let on_ball = PI * radius * radius * lowest.yield_pa;
    if load >= on_ball {
        errors.push(FieldError::new(
            "test.load_n",
            format!(
                "must be < pi R^2 Y = {} N: at {}, the load needs a contact of radius \
                 sqrt(F / (pi Y)) = {} mm, wider than the ball ({} mm); got {} N (was it \
                 in mN? {} mN = {} N)",
                sig(on_ball),
                describe(lowest, scene.disc.yield_factor),
                sig(punch_radius_m(load, lowest.yield_pa) * 1e3),
                num(scene.ball.radius_mm),
                num(load),
                num(load),
                sig(load * 1e-3)
            ),
        ));
        return;
    }
    if let DomainSize::Micrometres(um) = scene.numerics.domain_um {
        let carried = lowest.yield_pa * (um * 1e-6).powi(2);
        if load >= carried {
            errors.push(FieldError::new(
                "numerics.domain_um",
                format!(
                    "must be > sqrt(F / Y) = {} um (or \"auto\"): at {}, a {} um square \
                     carries at most {} N, less than the load {} N",
                    sig((load / lowest.yield_pa).sqrt() * 1e6),
                    describe(lowest, scene.disc.yield_factor),
                    num(um),
                    sig(carried),
                    num(load)
                ),
            ));
        }
    }
}

/// The unworn contact of radius `hertz_m` must span [`MIN_CELLS_PER_CONTACT_RADIUS`] cells
/// of the grid the simulation will use, which it sizes by `sizing_m` where the scene leaves
/// the grid or the domain to it.
fn check_resolution(errors: &mut Vec<FieldError>, scene: &Scene, hertz_m: f64, sizing_m: f64) {
    let domain = scene.numerics.domain_m();
    let side = domain.unwrap_or(auto_domain_m(sizing_m));
    let auto_cell = auto_cell_m(sizing_m, cells_per_contact_radius(scene));
    let cell = match (scene.numerics.grid, domain) {
        (GridSize::Cells(n), _) => side / n as f64,
        // Auto cells over a fixed domain: as fine as the auto density, unless that needs
        // more than the largest grid.
        (GridSize::Auto, Some(side)) => (side / Grid::MAX_CELLS_PER_SIDE as f64).max(auto_cell),
        (GridSize::Auto, None) => auto_cell,
    };
    let per_radius = hertz_m / cell;
    if per_radius >= MIN_CELLS_PER_CONTACT_RADIUS {
        return;
    }
    let resolved = format!(
        "cells of {} um give the unworn contact (Hertz radius a = {} um) {} cells per \
         radius, and at least {MIN_CELLS_PER_CONTACT_RADIUS} are needed (at 1.27 the peak \
         pressure errs by 15%, at 0.5 by 87%)",
        sig(cell * 1e6),
        sig(hertz_m * 1e6),
        sig(per_radius)
    );
    let fewest = (MIN_CELLS_PER_CONTACT_RADIUS * side / hertz_m).ceil();
    if let (GridSize::Auto, DomainSize::Micrometres(um)) =
        (scene.numerics.grid, scene.numerics.domain_um)
    {
        errors.push(FieldError::new(
            "numerics.domain_um",
            format!(
                "must be <= {} um, or \"auto\": {resolved}, and the grid is at most {} cells \
                 per side; got {} um",
                sig(Grid::MAX_CELLS_PER_SIDE as f64 * hertz_m / MIN_CELLS_PER_CONTACT_RADIUS * 1e6),
                Grid::MAX_CELLS_PER_SIDE,
                num(um)
            ),
        ));
    } else {
        let beyond = if fewest > Grid::MAX_CELLS_PER_SIDE as f64 {
            format!(
                " (more than the {} allowed: make the domain smaller)",
                Grid::MAX_CELLS_PER_SIDE
            )
        } else {
            String::new()
        };
        errors.push(FieldError::new(
            "numerics.grid",
            format!(
                "must be at least {fewest} cells over this {} um domain{beyond}: {resolved}; \
                 got {}",
                sig(side * 1e6),
                match scene.numerics.grid {
                    GridSize::Cells(n) => n.to_string(),
                    GridSize::Auto => "\"auto\"".to_owned(),
                }
            ),
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Material;
    use crate::scene::{self, SceneErrors};
    use crate::simulation::Plan;

    /// Whether `scene` passes the whole check: its fields, then these limits.
    fn check(scene: &Scene) -> Result<(), SceneErrors> {
        Plan::new(scene.clone()).map(drop)
    }

    fn errors(scene: &Scene) -> Vec<FieldError> {
        check(scene).err().map(|e| e.0).unwrap_or_default()
    }

    fn paths(scene: &Scene) -> Vec<String> {
        errors(scene).into_iter().map(|e| e.path).collect()
    }

    fn message(scene: &Scene, path: &str) -> String {
        errors(scene)
            .into_iter()
            .find(|e| e.path == path)
            .map(|e| e.message)
            .unwrap_or_default()
    }

    #[test]
    fn defaults_and_presets_can_run() {
        assert_eq!(check(&Scene::default()), Ok(()));
        for preset in scene::presets() {
            assert_eq!(check(&preset.scene), Ok(()), "{}", preset.name);
        }
    }

    #[test]
    fn the_largest_grid_over_the_largest_domain_can_run_a_wide_enough_contact() {
        // 2048 cells over 10 cm are 48.8 um cells; a 50 N contact's Hertz radius spans 1.7.
        let mut scene = Scene::default();
        scene.numerics.grid = GridSize::Cells(Grid::MAX_CELLS_PER_SIDE);
        scene.numerics.domain_um = DomainSize::Micrometres(100_000.0);
        scene.test.load_n = 50.0;
        assert_eq!(check(&scene), Ok(()));
    }

    #[test]
    fn strong_friction_coupling_is_refused_unless_the_term_is_off() {
        // A 1 GPa, nu 0 ball on a 300 GPa, nu 0.3 disc: G1 = 0.5, G2 = 115.38 GPa, so
        // beta = (1/G1 - 0.4/G2) / (2 (1/G1 + 0.7/G2)) = 0.497624 by hand, mu <= 1.60764.
        let mut scene = Scene::default();
        scene.ball.youngs_modulus_gpa = 1.0;
        scene.ball.poisson_ratio = 0.0;
        scene.disc.poisson_ratio = 0.3;
        scene.disc.youngs_modulus_gpa = 300.0;
        scene.test.friction_coefficient = 1.607;
        assert_eq!(check(&scene), Ok(()));
        scene.test.friction_coefficient = 1.608;
        assert_eq!(paths(&scene), ["test.friction_coefficient"]);
        assert!(message(&scene, "test.friction_coefficient").contains("mu <= 1.608"));
        scene.numerics.coupling = Switch::Off;
        assert_eq!(check(&scene), Ok(()));
    }

    #[test]
    fn load_beyond_what_the_ball_carries_at_the_cap_is_refused() {
        // pi R^2 Y = pi (3 mm)^2 2473 / 2.8 MPa = 24972.3 N, at a constant hardness.
        let mut scene = Scene::default();
        scene.disc.hardness_table = None;
        // Below the capacity the contact is still nearly the ball's width, which
        // plausibility refuses on its own (its tests hold that rule).
        scene.test.load_n = 24_900.0;
        assert!(!message(&scene, "test.load_n").contains("24970 N"));
        scene.test.load_n = 25_000.0;
        assert_eq!(paths(&scene), ["test.load_n"]);
        assert!(message(&scene, "test.load_n").contains("24970 N"));
        assert!(message(&scene, "test.load_n").contains("was it in mN? 25000 mN = 25 N"));
        // Without the cap the load spreads elastically; nothing to refuse here.
        scene.wear.plasticity = Switch::Off;
        assert_eq!(check(&scene), Ok(()));
    }

    #[test]
    fn fixed_domain_must_carry_the_load_at_the_lowest_cap() {
        // sqrt(F / Y) = sqrt(5 N / (2473 / 2.8 MPa)) = 75.24 um, at a constant hardness.
        let mut scene = Scene::default();
        scene.disc.hardness_table = None;
        scene.numerics.domain_um = DomainSize::Micrometres(75.3);
        assert_eq!(check(&scene), Ok(()));
        scene.numerics.domain_um = DomainSize::Micrometres(75.2);
        assert_eq!(paths(&scene), ["numerics.domain_um"]);
        // A softening law lowers the cap by the last cycle: H(60) = 2473 - 600 ln 60 MPa.
        scene.numerics.domain_um = DomainSize::Micrometres(256.0);
        scene.disc.hardness_table = Some(vec![(10.0, 2473.0 - 600.0 * 10f64.ln())]);
        scene.test.cycles = 60;
        assert!(message(&scene, "numerics.domain_um").contains("at cycle 60"));
    }

    #[test]
    fn contact_narrower_than_one_and_a_half_cells_is_refused() {
        // Cells of 4 um (64 over 256 um): the load whose Hertz radius is 6 um, by
        // a^3 = 3 F R / (4 E*), is the boundary.
        let pair = ElasticPair::new(
            Material::new(300e9, 0.21).expect("valid"),
            Material::new(205e9, 0.28).expect("valid"),
        );
        let load = |a: f64| 4.0 * pair.reduced_modulus_pa * a.powi(3) / (3.0 * 3e-3);
        let mut scene = Scene::default();
        scene.numerics.grid = GridSize::Cells(64);
        scene.numerics.domain_um = DomainSize::Micrometres(256.0);
        scene.test.load_n = load(6.0e-6 * (1.0 + 1e-9));
        assert_eq!(check(&scene), Ok(()));
        scene.test.load_n = load(6.0e-6 * (1.0 - 1e-9));
        assert_eq!(paths(&scene), ["numerics.grid"]);
        assert!(message(&scene, "numerics.grid").contains("at least 65 cells"));
        // Left to choose its cells over a huge domain, the grid stops at 2048.
        scene.numerics.grid = GridSize::Auto;
        scene.numerics.domain_um = DomainSize::Micrometres(10_000.0);
        assert_eq!(paths(&scene), ["numerics.domain_um"]);
    }
}
