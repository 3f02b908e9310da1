//! Each field of a deserialised scene against its own range, and the fields' consistency with
//! each other (the hardness table's fit, k against its calibration); every message names
//! the allowed range. Whether the contact such a scene describes can be simulated is
//! judged by the simulation (`simulation::check`).

use std::ops::RangeInclusive;

use super::format::num;
use super::{DomainSize, FieldError, GridSize, MAX_RECORD_CYCLES, RecordCycles, Scene};
use crate::contact::Grid;

/// Longest run accepted; a cap on run time and on the size of the result.
pub(super) const MAX_CYCLES: u64 = 1_000_000;
/// Cells per side of a requested grid: below 8 a contact is not resolved at all; the upper
/// bound is the largest grid the contact core accepts.
pub(super) const GRID_CELLS: RangeInclusive<usize> = 8..=Grid::MAX_CELLS_PER_SIDE;
/// Friction coefficient bounds: 2 is beyond any lubricated or dry metal-ceramic pair.
const FRICTION: (f64, f64) = (0.0, 2.0);
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

/// All problems with `scene`'s own fields, empty when each is valid.
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
        FRICTION.0,
        FRICTION.1,
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
    c.errors
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
    let conditions = [
        ("hardness_mpa", calibration.hardness_mpa, "MPa"),
        ("load_n", calibration.load_n, "N"),
        ("speed_rpm", calibration.speed_rpm, "rpm"),
        ("track_radius_mm", calibration.track_radius_mm, "mm"),
    ];
    for (field, value, unit) in conditions {
        if let Some(value) = value {
            c.positive(&format!("wear.archard_calibration.{field}"), value, unit);
        }
    }
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
                    "must be \"auto\" or a whole number of cells per side in {}..={} \
                     (larger grids' padded 2N x 2N spectra need gigabytes), got {cells}",
                    GRID_CELLS.start(),
                    GRID_CELLS.end()
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
    check_record_cycles(c, scene);
}

fn check_record_cycles(c: &mut Checks, scene: &Scene) {
    let RecordCycles::Cycles(cycles) = &scene.numerics.record_cycles else {
        return;
    };
    if cycles.len() > MAX_RECORD_CYCLES {
        c.fail(
            "numerics.record_cycles",
            format!(
                "names {} cycles; at most {MAX_RECORD_CYCLES} (each is a solve and a kept \
                 profile)",
                cycles.len()
            ),
        );
    }
    let total = scene.test.cycles;
    for (i, &cycle) in cycles.iter().enumerate() {
        if !(1..=total).contains(&cycle) {
            c.fail(
                &format!("numerics.record_cycles[{i}]"),
                format!("must be a cycle of the run, in 1..={total}, got {cycle}"),
            );
        }
    }
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
        scene.test.friction_coefficient = FRICTION.1;
        scene.test.cycles = MAX_CYCLES;
        scene.numerics.grid = GridSize::Cells(*GRID_CELLS.end());
        scene.numerics.tolerance = TOLERANCE.0;
        scene.numerics.cycle_step_bound = CYCLE_STEP_BOUND.1;
        scene.numerics.domain_um = DomainSize::Micrometres(MAX_DOMAIN_UM);
        scene.ball.poisson_ratio = -0.99;
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));

        scene.test.friction_coefficient = 2.01;
        scene.test.cycles = MAX_CYCLES + 1;
        scene.numerics.grid = GridSize::Cells(GRID_CELLS.start() - 1);
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
}
