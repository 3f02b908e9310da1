//! Range and consistency checks on a deserialised scene; every message names the allowed range.

use std::f64::consts::PI;

use super::{DomainSize, FieldError, GridSize, Scene, Switch};
use crate::contact::{ElasticPair, Grid, Hertz, Material};
use crate::simulation::{CELLS_PER_CONTACT_RADIUS, DOMAIN_PER_CONTACT_RADIUS};

/// Longest run accepted; a cap on run time and on the size of the result.
const MAX_CYCLES: u64 = 1_000_000;
/// Grid bounds. Below 8 cells a contact is not resolved at all; above 2048 the zero-padded
/// 2N x 2N spectra of the DC-FFT (a 4096 grid pads to 8192^2 complex values, 0.5 GiB each,
/// with several alive at once) need gigabytes.
const GRID_CELLS: std::ops::RangeInclusive<usize> = 8..=2048;
/// Largest domain side, um (10 cm, far beyond any ball-on-disc contact).
const MAX_DOMAIN_UM: f64 = 100_000.0;
/// Solver tolerance bounds. The relative residual has a round-off floor of about machine
/// epsilon times the approach over the largest elastic displacement, so it rises as a groove
/// deepens. Wear runs stalled with NotConverged at residuals of 1.2e-13 to 1.5e-13 (paper
/// scene, 3600 cycles), 6e-13 (H falling to 300 MPa over 3600 cycles) and 1.3e-12 (to
/// 100 MPa over 1000 cycles, grid 32); all of them ran at 1e-11. 1e-10 is also the tightest
/// reference `tribosim bench wear` uses: 1e-8 already agrees with it to 4e-11 in volume.
/// Above 1e-2 the pressures are too rough to wear with.
const TOLERANCE: (f64, f64) = (1e-10, 1e-2);
/// Cycle-step bound: above 0.1 a step skipped the end of the yielding phase (volume error
/// 1.6e-3 at 300 cycles); below 1e-4 no step is ever taken.
const CYCLE_STEP_BOUND: (f64, f64) = (1e-4, 0.1);

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

/// All problems with `scene`, empty when it is valid.
pub(super) fn check(scene: &Scene) -> Vec<FieldError> {
    let mut c = Checks::default();
    let ball = &scene.ball;
    c.positive("ball.radius_mm", ball.radius_mm, "mm");
    c.positive("ball.youngs_modulus_gpa", ball.youngs_modulus_gpa, "GPa");
    c.poisson("ball.poisson_ratio", ball.poisson_ratio);

    let disc = &scene.disc;
    c.positive("disc.youngs_modulus_gpa", disc.youngs_modulus_gpa, "GPa");
    c.poisson("disc.poisson_ratio", disc.poisson_ratio);
    c.positive("disc.hardness_mpa", disc.hardness_mpa, "MPa");
    c.positive("disc.yield_factor", disc.yield_factor, "");

    let test = &scene.test;
    c.positive("test.load_n", test.load_n, "N");
    c.positive("test.track_radius_mm", test.track_radius_mm, "mm");
    c.positive("test.speed_rpm", test.speed_rpm, "rpm");
    c.closed(
        "test.friction_coefficient",
        test.friction_coefficient,
        0.0,
        2.0,
        "",
    );
    if !(1..=MAX_CYCLES).contains(&test.cycles) {
        c.fail(
            "test.cycles",
            format!(
                "must be a whole number in 1..={MAX_CYCLES}, got {}",
                test.cycles
            ),
        );
    }

    check_hardness_table(&mut c, scene);
    check_wear(&mut c, scene);
    check_numerics(&mut c, scene);
    check_corrosion(&mut c, scene);
    check_contact(&mut c, scene);
    c.errors
}

/// The limits of the contact the scene describes. Each depends on several fields (the
/// materials, load, hardness law and numerics), so they are judged only when every field
/// passed on its own, or a message here would really be about one of those.
fn check_contact(c: &mut Checks, scene: &Scene) {
    if !c.errors.is_empty() {
        return;
    }
    let materials = (
        Material::new(scene.ball.youngs_modulus_pa(), scene.ball.poisson_ratio),
        Material::new(scene.disc.youngs_modulus_pa(), scene.disc.poisson_ratio),
    );
    let (Ok(ball), Ok(disc), Ok(law)) = (materials.0, materials.1, scene.hardness_law()) else {
        return;
    };
    let pair = ElasticPair::new(ball, disc);
    check_coupling(c, scene, &pair);

    // The lowest yield pressure of the run: A + B ln n is monotone, so at an end.
    let last = scene.test.cycles as f64;
    let (cycle, hardness_pa) = if law.hardness_pa(last) < law.hardness_pa(1.0) {
        (scene.test.cycles, law.hardness_pa(last))
    } else {
        (1, law.hardness_pa(1.0))
    };
    let capped = scene.wear.plasticity != Switch::Off;
    let lowest = LowestYield {
        cycle,
        hardness_pa,
        yield_pa: hardness_pa / scene.disc.yield_factor,
    };
    if capped {
        check_capacity(c, scene, &lowest);
    }
    if !c.errors.is_empty() {
        return;
    }
    let hertz = Hertz {
        radius_m: scene.ball_radius_m(),
        load_n: scene.load_n(),
        reduced_modulus_pa: pair.reduced_modulus_pa,
    };
    // The radius the simulation sizes its grid by: Hertz's, or the flat punch F = pi r^2 Y
    // at the lowest cap when that is larger (it is only when the cap can act).
    let punch = (scene.load_n() / (PI * lowest.yield_pa)).sqrt();
    let sizing = if capped {
        hertz.contact_radius_m().max(punch)
    } else {
        hertz.contact_radius_m()
    };
    check_resolution(c, scene, hertz.contact_radius_m(), sizing);
}

/// Where and how low the yield pressure falls during the run.
struct LowestYield {
    cycle: u64,
    hardness_pa: f64,
    yield_pa: f64,
}

impl LowestYield {
    fn describe(&self, factor: f64) -> String {
        format!(
            "cycle {}, where the yield pressure is lowest, Y = H / yield_factor = {} MPa / {} \
             = {} MPa",
            self.cycle,
            sig(self.hardness_pa * 1e-6),
            num(factor),
            sig(self.yield_pa * 1e-6)
        )
    }
}

/// The coupled solve's outer fixed point diverges when the friction coupling rivals the
/// normal compliance; see [`MAX_COUPLING`].
fn check_coupling(c: &mut Checks, scene: &Scene, pair: &ElasticPair) {
    let beta = pair.delta_nu / (2.0 * (1.0 - pair.nu_star));
    let mu = scene.test.friction_coefficient;
    if scene.numerics.coupling != Switch::Off && mu * beta.abs() > MAX_COUPLING {
        c.fail(
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
        );
    }
}

/// At the cap every loaded cell carries at most Y, so the load needs an area of at least
/// F / Y: on the ball (whose largest section is pi R^2) and inside a fixed domain.
fn check_capacity(c: &mut Checks, scene: &Scene, lowest: &LowestYield) {
    let load = scene.load_n();
    let radius = scene.ball_radius_m();
    let on_ball = PI * radius * radius * lowest.yield_pa;
    if load >= on_ball {
        c.fail(
            "test.load_n",
            format!(
                "must be < pi R^2 Y = {} N: at {}, the load needs a contact of radius \
                 sqrt(F / (pi Y)) = {} mm, wider than the ball ({} mm); got {} N",
                sig(on_ball),
                lowest.describe(scene.disc.yield_factor),
                sig((load / (PI * lowest.yield_pa)).sqrt() * 1e3),
                num(scene.ball.radius_mm),
                num(load)
            ),
        );
        return;
    }
    if let DomainSize::Micrometres(um) = scene.numerics.domain_um {
        let carried = lowest.yield_pa * (um * 1e-6).powi(2);
        if load >= carried {
            c.fail(
                "numerics.domain_um",
                format!(
                    "must be > sqrt(F / Y) = {} um (or \"auto\"): at {}, a {} um square \
                     carries at most {} N, less than the load {} N",
                    sig((load / lowest.yield_pa).sqrt() * 1e6),
                    lowest.describe(scene.disc.yield_factor),
                    num(um),
                    sig(carried),
                    num(load)
                ),
            );
        }
    }
}

/// The unworn contact of radius `hertz_m` must span [`MIN_CELLS_PER_CONTACT_RADIUS`] cells
/// of the grid the simulation will use, which it sizes by `sizing_m` where the scene leaves
/// the grid or the domain to it.
fn check_resolution(c: &mut Checks, scene: &Scene, hertz_m: f64, sizing_m: f64) {
    let domain = scene.numerics.domain_m();
    let side = domain.unwrap_or(DOMAIN_PER_CONTACT_RADIUS * sizing_m);
    let auto_cell = sizing_m / CELLS_PER_CONTACT_RADIUS;
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
        c.fail(
            "numerics.domain_um",
            format!(
                "must be <= {} um, or \"auto\": {resolved}, and the grid is at most {} cells \
                 per side; got {} um",
                sig(Grid::MAX_CELLS_PER_SIDE as f64 * hertz_m / MIN_CELLS_PER_CONTACT_RADIUS * 1e6),
                Grid::MAX_CELLS_PER_SIDE,
                num(um)
            ),
        );
    } else {
        let beyond = if fewest > Grid::MAX_CELLS_PER_SIDE as f64 {
            format!(
                " (more than the {} allowed: make the domain smaller)",
                Grid::MAX_CELLS_PER_SIDE
            )
        } else {
            String::new()
        };
        c.fail(
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
        );
    }
}

fn check_hardness_table(c: &mut Checks, scene: &Scene) {
    let Some(table) = &scene.disc.hardness_table else {
        return;
    };
    let before = c.errors.len();
    if table.is_empty() {
        c.fail(
            "disc.hardness_table",
            "must hold at least one [cycles, hardness_mpa] pair; omit the field for a \
             constant hardness",
        );
    }
    let mut previous: Option<f64> = None;
    for (i, &(cycle, hardness)) in table.iter().enumerate() {
        let path = format!("disc.hardness_table[{i}][0]");
        if !(cycle.is_finite() && cycle >= 1.0) {
            c.fail(
                &path,
                format!("cycle counts must be >= 1 and finite, got {}", num(cycle)),
            );
        } else if let Some(prev) = previous.filter(|&prev| cycle <= prev) {
            c.fail(
                &path,
                format!(
                    "cycle counts must increase strictly, got {} after {}",
                    num(cycle),
                    num(prev)
                ),
            );
        }
        if cycle.is_finite() {
            previous = Some(cycle);
        }
        c.positive(&format!("disc.hardness_table[{i}][1]"), hardness, "MPa");
    }
    // Fit only well-formed data (the SVD of non-finite numbers need not terminate).
    if c.errors.len() > before || !(scene.disc.hardness_mpa.is_finite()) {
        return;
    }
    match scene.disc.hardness_law() {
        Err(e) => c.fail("disc.hardness_table", e.to_string()),
        Ok(law) => {
            // A + B ln n is monotone, so its minimum over the run is at an end.
            let last = scene.test.cycles as f64;
            let lowest = law.hardness_pa(1.0).min(law.hardness_pa(last));
            if lowest.is_nan() || lowest <= 0.0 {
                c.fail(
                    "disc.hardness_table",
                    format!(
                        "the fitted law H = A + B ln n falls to {} MPa by cycle {}; \
                         hardness must stay > 0 MPa over the run",
                        num(lowest * 1e-6),
                        scene.test.cycles
                    ),
                );
            }
        }
    }
}

fn check_wear(c: &mut Checks, scene: &Scene) {
    let wear = &scene.wear;
    if let Some(k) = wear.archard_k {
        if !(0.0..=1.0).contains(&k) {
            c.fail(
                "wear.archard_k",
                format!(
                    "must be in [0, 1] (0 is a run without wear), got {}",
                    num(k)
                ),
            );
        }
    }
    let Some(calibration) = &wear.archard_calibration else {
        return;
    };
    if wear.archard_k.is_some() {
        c.fail(
            "wear",
            "give either `archard_k` or `archard_calibration`, not both (over a preset, set \
             `archard_k` to null in the overrides)",
        );
    }
    c.positive("wear.archard_calibration.time_s", calibration.time_s, "s");
    c.closed(
        "wear.archard_calibration.wear_volume_mm3",
        calibration.wear_volume_mm3,
        0.0,
        f64::INFINITY,
        " mm^3",
    );
    // The derived k depends on the load, speed and hardness law; judge it only when all of
    // those passed, or a message about k would really be about them.
    if !c.errors.is_empty() {
        return;
    }
    let mut derived = scene.clone();
    derived.wear.archard_k = None;
    if let Ok(k) = derived.archard_k() {
        if !(0.0..=1.0).contains(&k) {
            c.fail(
                "wear.archard_calibration",
                format!(
                    "gives k = {}, outside [0, 1]; check the units (s, mm^3)",
                    num(k)
                ),
            );
        }
    }
}

fn check_numerics(c: &mut Checks, scene: &Scene) {
    let numerics = &scene.numerics;
    if let GridSize::Cells(cells) = numerics.grid {
        if !GRID_CELLS.contains(&cells) {
            c.fail(
                "numerics.grid",
                format!(
                    "must be \"auto\" or a whole number of cells per side in 8..=2048 \
                     (larger grids' padded 2N x 2N spectra need gigabytes), got {cells}"
                ),
            );
        }
    }
    if let DomainSize::Micrometres(um) = numerics.domain_um {
        if !(um > 0.0 && um <= MAX_DOMAIN_UM) {
            c.fail(
                "numerics.domain_um",
                format!(
                    "must be \"auto\" or a side > 0 um and <= {MAX_DOMAIN_UM} um, got {}",
                    num(um)
                ),
            );
        }
    }
    c.closed(
        "numerics.tolerance",
        numerics.tolerance,
        TOLERANCE.0,
        TOLERANCE.1,
        "",
    );
    c.closed(
        "numerics.cycle_step_bound",
        numerics.cycle_step_bound,
        CYCLE_STEP_BOUND.0,
        CYCLE_STEP_BOUND.1,
        "",
    );
}

fn check_corrosion(c: &mut Checks, scene: &Scene) {
    let Some(corrosion) = &scene.corrosion else {
        return;
    };
    c.finite(
        "corrosion.corrosion_potential_v",
        corrosion.corrosion_potential_v,
    );
    c.finite("corrosion.tafel_a_c_v", corrosion.tafel_a_c_v);
    c.positive(
        "corrosion.tafel_b_c_v_per_decade",
        corrosion.tafel_b_c_v_per_decade,
        "V/decade",
    );
    c.positive(
        "corrosion.anodic_current_density_a_cm2",
        corrosion.anodic_current_density_a_cm2,
        "A/cm^2",
    );
    c.positive(
        "corrosion.exposed_area_cm2",
        corrosion.exposed_area_cm2,
        "cm^2",
    );
    c.positive(
        "corrosion.anodic_area_factor",
        corrosion.anodic_area_factor,
        "",
    );
    c.positive(
        "corrosion.molar_mass_g_mol",
        corrosion.molar_mass_g_mol,
        "g/mol",
    );
    c.positive("corrosion.valence", corrosion.valence, "");
    c.positive("corrosion.density_g_cm3", corrosion.density_g_cm3, "g/cm^3");
}

/// Collects failures.
#[derive(Default)]
struct Checks {
    errors: Vec<FieldError>,
}

impl Checks {
    fn fail(&mut self, path: &str, message: impl Into<String>) {
        self.errors.push(FieldError::new(path, message));
    }

    /// `value` > 0 and finite; `unit` is printed after the bound ("" for none).
    fn positive(&mut self, path: &str, value: f64, unit: &str) {
        if !(value > 0.0 && value.is_finite()) {
            let unit = if unit.is_empty() {
                String::new()
            } else {
                format!(" {unit}")
            };
            self.fail(
                path,
                format!("must be > 0{unit} and finite, got {}", num(value)),
            );
        }
    }

    /// `lo` <= `value` <= `hi`, and not NaN; `unit` is appended to the interval.
    fn closed(&mut self, path: &str, value: f64, lo: f64, hi: f64, unit: &str) {
        if !(lo..=hi).contains(&value) || !value.is_finite() {
            let range = if hi.is_infinite() {
                format!(">= {}{unit} and finite", num(lo))
            } else {
                format!("in [{}, {}]{unit}", num(lo), num(hi))
            };
            self.fail(path, format!("must be {range}, got {}", num(value)));
        }
    }

    fn poisson(&mut self, path: &str, value: f64) {
        if !(value > -1.0 && value < 0.5) {
            self.fail(
                path,
                format!(
                    "must be in the open interval (-1, 0.5) (the bounds of an isotropic \
                     elastic solid), got {}",
                    num(value)
                ),
            );
        }
    }

    fn finite(&mut self, path: &str, value: f64) {
        if !value.is_finite() {
            self.fail(path, format!("must be a finite number, got {}", num(value)));
        }
    }
}

/// `value` to four significant digits, printed as [`num`] does.
fn sig(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || !(1e-4..1e9).contains(&magnitude) {
        return format!("{value:.3e}");
    }
    // Scale by an exact power of ten (multiply or divide by 10^k, k >= 0) so the rounding
    // leaves no binary residue such as 24969.999999999996.
    let shift = 3 - magnitude.log10().floor() as i32;
    let scale = 10f64.powi(shift.abs());
    let rounded = if shift >= 0 {
        (value * scale).round() / scale
    } else {
        (value / scale).round() * scale
    };
    format!("{rounded}")
}

/// Plain decimals for ordinary magnitudes, exponent form for tiny or huge ones
/// (Rust's `{}` would print 1e-15 as 0.000000000000001).
fn num(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-4..1e9).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::super::Corrosion;
    use super::*;

    fn paths(scene: &Scene) -> Vec<String> {
        check(scene).into_iter().map(|e| e.path).collect()
    }

    #[test]
    fn defaults_and_preset_are_valid() {
        assert!(check(&Scene::default()).is_empty());
        for preset in super::super::presets() {
            assert!(check(&preset.scene).is_empty(), "{}", preset.name);
        }
    }

    #[test]
    fn non_finite_numbers_are_rejected() {
        // JSON cannot carry NaN or infinity, but a scene built in Rust can.
        let mut scene = Scene::default();
        scene.test.load_n = f64::INFINITY;
        scene.ball.poisson_ratio = f64::NAN;
        scene.test.friction_coefficient = f64::NAN;
        scene.numerics.tolerance = f64::NEG_INFINITY;
        scene.corrosion = Some(Corrosion {
            tafel_a_c_v: f64::NAN,
            ..Corrosion::default()
        });
        scene.disc.hardness_table = Some(vec![(f64::INFINITY, 2500.0)]);
        assert_eq!(
            paths(&scene),
            [
                "ball.poisson_ratio",
                "test.load_n",
                "test.friction_coefficient",
                "disc.hardness_table[0][0]",
                "numerics.tolerance",
                "corrosion.tafel_a_c_v",
            ]
        );
    }

    #[test]
    fn bounds_are_inclusive_or_exclusive_as_documented() {
        let mut scene = Scene::default();
        scene.test.friction_coefficient = 2.0;
        scene.test.cycles = MAX_CYCLES;
        scene.numerics.grid = GridSize::Cells(2048);
        scene.numerics.tolerance = 1e-10;
        scene.numerics.cycle_step_bound = CYCLE_STEP_BOUND.1;
        scene.numerics.domain_um = DomainSize::Micrometres(MAX_DOMAIN_UM);
        scene.ball.poisson_ratio = -0.99;
        // A contact wide enough for 2048 cells over 10 cm: 1.7 cells per Hertz radius.
        scene.test.load_n = 50.0;
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));

        scene.test.friction_coefficient = 2.01;
        scene.test.cycles = MAX_CYCLES + 1;
        scene.numerics.grid = GridSize::Cells(7);
        scene.numerics.tolerance = 0.99e-10;
        scene.numerics.cycle_step_bound = 0.11;
        scene.numerics.domain_um = DomainSize::Micrometres(0.0);
        scene.ball.poisson_ratio = -1.0;
        assert_eq!(
            paths(&scene),
            [
                "ball.poisson_ratio",
                "test.friction_coefficient",
                "test.cycles",
                "numerics.grid",
                "numerics.domain_um",
                "numerics.tolerance",
                "numerics.cycle_step_bound",
            ]
        );
    }

    fn message(scene: &Scene, path: &str) -> String {
        check(scene)
            .into_iter()
            .find(|e| e.path == path)
            .map(|e| e.message)
            .unwrap_or_default()
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
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));
        scene.test.friction_coefficient = 1.608;
        assert_eq!(paths(&scene), ["test.friction_coefficient"]);
        assert!(message(&scene, "test.friction_coefficient").contains("mu <= 1.608"));
        scene.numerics.coupling = Switch::Off;
        assert!(check(&scene).is_empty());
    }

    #[test]
    fn load_beyond_what_the_ball_carries_at_the_cap_is_refused() {
        // pi R^2 Y = pi (3 mm)^2 2473 / 2.8 MPa = 24972.3 N.
        let mut scene = Scene::default();
        scene.test.load_n = 24_900.0;
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));
        scene.test.load_n = 25_000.0;
        assert_eq!(paths(&scene), ["test.load_n"]);
        assert!(message(&scene, "test.load_n").contains("24970 N"));
        // Without the cap the load spreads elastically; nothing to refuse here.
        scene.wear.plasticity = Switch::Off;
        assert!(check(&scene).is_empty());
    }

    #[test]
    fn fixed_domain_must_carry_the_load_at_the_lowest_cap() {
        // sqrt(F / Y) = sqrt(5 N / (2473 / 2.8 MPa)) = 75.24 um.
        let mut scene = Scene::default();
        scene.numerics.domain_um = DomainSize::Micrometres(75.3);
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));
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
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));
        scene.test.load_n = load(6.0e-6 * (1.0 - 1e-9));
        assert_eq!(paths(&scene), ["numerics.grid"]);
        assert!(message(&scene, "numerics.grid").contains("at least 65 cells"));
        // Left to choose its cells over a huge domain, the grid stops at 2048.
        scene.numerics.grid = GridSize::Auto;
        scene.numerics.domain_um = DomainSize::Micrometres(10_000.0);
        assert_eq!(paths(&scene), ["numerics.domain_um"]);
    }

    #[test]
    fn four_significant_digits() {
        assert_eq!(sig(24_972.295), "24970");
        assert_eq!(sig(0.024_73), "0.02473");
        assert_eq!(sig(75.240_55), "75.24");
        assert_eq!(sig(6.992e-296), "6.992e-296");
    }

    #[test]
    fn small_and_large_numbers_print_in_exponent_form() {
        assert_eq!(num(1e-15), "1e-15");
        assert_eq!(num(-5.0), "-5");
        assert_eq!(num(0.45), "0.45");
        assert_eq!(num(2e12), "2e12");
    }
}
