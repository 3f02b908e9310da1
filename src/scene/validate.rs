//! Each field of a deserialised scene against its own range, and the fields' consistency with
//! each other (the hardness table's fit, k against its calibration); every message names
//! the allowed range. Whether the contact such a scene describes can be simulated is
//! judged by the simulation (`simulation::Plan::new`).

use super::field::{Field, Range};
use super::fields::{
    ANODIC_AREA_FACTOR, ANODIC_CURRENT, APPLIED_POTENTIAL, ARCHARD_K, BALL_MODULUS, BALL_POISSON,
    BALL_RADIUS, BARE_CORROSION_POTENTIAL, CALIBRATION_HARDNESS, CALIBRATION_LOAD,
    CALIBRATION_SPEED, CALIBRATION_TIME, CALIBRATION_TRACK_RADIUS, CALIBRATION_VOLUME,
    CORROSION_POTENTIAL, CYCLE_STEP_BOUND, CYCLES, DENSITY, DISC_HARDNESS, DISC_MODULUS,
    DISC_POISSON, DOMAIN, EXPOSED_AREA, FRICTION, GRID, INITIAL_YIELD, LOAD, MOLAR_MASS, NAME,
    OCP_AFTER, OCP_BEFORE, OHMIC_RESISTANCE, REGIME_CHANGE_CYCLE, REGIME_CHANGE_K_BEFORE,
    REPASSIVATION_EXPONENT, REPASSIVATION_TIME, SPEED, SURFACE_HURST, SURFACE_ID,
    SURFACE_LONG_CUTOFF, SURFACE_RMS_HEIGHT, SURFACE_RMS_SLOPE, SURFACE_SEED, SURFACE_SHORT_CUTOFF,
    TAFEL_A, TAFEL_B, TAFEL_ETA_MAX, TAFEL_ETA_MIN, THREADS, TOLERANCE, TRACK_RADIUS, VALENCE,
    YIELD_FACTOR,
};
use super::format::num;
use super::surface::SurfaceKind;
use super::{
    Control, Corrosion, DomainSize, FieldError, GridSize, MAX_RECORD_CYCLES, RecordCycles, Scene,
    SolverThreads, StepBound, Tolerance,
};
use crate::text::TextError;

/// All problems with `scene`'s own fields, empty when each is valid.
pub(super) fn check(scene: &Scene) -> Vec<FieldError> {
    let mut c = Checks::default();
    c.text(&NAME, &scene.name);
    let ball = &scene.ball;
    c.number(&BALL_RADIUS, ball.radius_mm);
    c.number(&BALL_MODULUS, ball.youngs_modulus_gpa);
    c.number(&BALL_POISSON, ball.poisson_ratio);

    let disc = &scene.disc;
    c.number(&DISC_MODULUS, disc.youngs_modulus_gpa);
    c.number(&DISC_POISSON, disc.poisson_ratio);
    c.number(&DISC_HARDNESS, disc.hardness_mpa);
    c.number(&YIELD_FACTOR, disc.yield_factor);
    c.number(&INITIAL_YIELD, disc.initial_yield_strength_mpa);

    let test = &scene.test;
    c.number(&LOAD, test.load_n);
    c.number(&TRACK_RADIUS, test.track_radius_mm);
    c.number(&SPEED, test.speed_rpm);
    c.number(&FRICTION, test.friction_coefficient);
    c.whole(&CYCLES, test.cycles);
    c.number(&OCP_BEFORE, test.ocp_before_s);
    c.number(&OCP_AFTER, test.ocp_after_s);

    check_hardness_table(&mut c, scene);
    check_surface(&mut c, scene);
    check_wear(&mut c, scene);
    check_numerics(&mut c, scene);
    check_corrosion(&mut c, scene);
    c.errors.extend(super::reciprocating::check(scene));
    c.errors
}

/// Each hardness typed in another unit (one whose own range held) refused with the slip
/// named.
fn refuse_hardness_slips(c: &mut Checks, scene: &Scene) {
    let slips = super::hardness_slips(scene);
    for slip in slips.into_iter().filter(|s| s.refused) {
        if !c.errors.iter().any(|e| e.path == slip.path) {
            c.fail(&slip.path, slip.message);
        }
    }
}

fn check_hardness_table(c: &mut Checks, scene: &Scene) {
    let Some(table) = &scene.disc.hardness_table else {
        refuse_hardness_slips(c, scene);
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
        let cell = format!("disc.hardness_table[{i}][1]");
        c.number_at(&cell, &DISC_HARDNESS, hardness);
    }
    // Fit only well-formed data (the SVD of non-finite numbers need not terminate), in MPa:
    // points in GPa would only be said to fit a law that falls below 0.
    refuse_hardness_slips(c, scene);
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

fn check_surface(c: &mut Checks, scene: &Scene) {
    let Some(surface) = &scene.disc.surface else {
        return;
    };
    let foreign = surface.foreign_keys();
    if !foreign.is_empty() {
        c.fail(
            "disc.surface",
            format!(
                "{} not used by a {:?} surface",
                foreign.join(", "),
                surface.kind
            )
            .to_lowercase(),
        );
    }
    match surface.kind {
        SurfaceKind::Measured => match surface.id.as_deref() {
            None | Some("") => c.fail("disc.surface.id", "a measured surface needs the map's id"),
            Some(id) => c.text(&SURFACE_ID, id),
        },
        SurfaceKind::Synthetic => check_synthetic(c, surface),
    }
}

fn check_synthetic(c: &mut Checks, surface: &super::SurfaceSpec) {
    match (surface.rms_height_um, surface.rms_slope) {
        (Some(h), None) => c.number(&SURFACE_RMS_HEIGHT, h),
        (None, Some(s)) => c.number(&SURFACE_RMS_SLOPE, s),
        _ => c.fail(
            "disc.surface",
            "a synthetic surface needs exactly one of `rms_height_um` and `rms_slope`",
        ),
    }
    if let Some(h) = surface.hurst {
        c.number(&SURFACE_HURST, h);
    }
    if let Some(seed) = surface.seed {
        c.whole(&SURFACE_SEED, seed);
    }
    let cutoffs = [
        (&SURFACE_SHORT_CUTOFF, surface.short_cutoff_um),
        (&SURFACE_LONG_CUTOFF, surface.long_cutoff_um),
    ];
    for (field, value) in cutoffs {
        match value {
            Some(v) => c.number(field, v),
            None => c.fail(field.path, "a synthetic surface needs both cut-offs"),
        }
    }
    if let (Some(short), Some(long)) = (surface.short_cutoff_um, surface.long_cutoff_um) {
        if short >= long {
            c.fail(
                "disc.surface.short_cutoff_um",
                format!(
                    "must be below `long_cutoff_um` ({}), got {}",
                    num(long),
                    num(short)
                ),
            );
        }
    }
}

fn check_wear(c: &mut Checks, scene: &Scene) {
    let wear = &scene.wear;
    if let Some(k) = wear.archard_k {
        c.number(&ARCHARD_K, k);
    }
    check_regime_change(c, scene);
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
    c.number(&CALIBRATION_TIME, calibration.time_s);
    c.number(&CALIBRATION_VOLUME, calibration.wear_volume_mm3);
    let conditions = [
        (&CALIBRATION_HARDNESS, calibration.hardness_mpa),
        (&CALIBRATION_LOAD, calibration.load_n),
        (&CALIBRATION_SPEED, calibration.speed_rpm),
        (&CALIBRATION_TRACK_RADIUS, calibration.track_radius_mm),
    ];
    for (field, value) in conditions {
        if let Some(value) = value {
            c.number(field, value);
        }
    }
    // The derived k depends on the load, speed and hardness law; judge it only when all of
    // those passed, or a message about k would really be about them.
    if !c.errors.is_empty() {
        return;
    }
    if let Ok(hardness) = scene.hardness_law() {
        let k = wear.calibration_point(&scene.test, &hardness).k();
        if !ARCHARD_K.range.admits(k) {
            c.fail(
                "wear.archard_calibration",
                format!(
                    "gives k = {}, which is not {}; check the units (s, mm^3)",
                    num(k),
                    ARCHARD_K.range.describe(ARCHARD_K.unit)
                ),
            );
        }
    }
}

fn check_regime_change(c: &mut Checks, scene: &Scene) {
    let Some(change) = &scene.wear.archard_regime_change else {
        return;
    };
    c.number(&REGIME_CHANGE_K_BEFORE, change.archard_k_before);
    if !(REGIME_CHANGE_CYCLE.range.admits_whole(change.cycle) && change.cycle < scene.test.cycles) {
        c.fail(
            REGIME_CHANGE_CYCLE.path,
            format!(
                "{} (this run: 1..={})",
                REGIME_CHANGE_CYCLE.message(&change.cycle.to_string()),
                scene.test.cycles.saturating_sub(1)
            ),
        );
    }
}

fn check_numerics(c: &mut Checks, scene: &Scene) {
    let numerics = &scene.numerics;
    if let GridSize::Cells(cells) = numerics.grid {
        c.whole(&GRID, cells as u64);
    }
    if let DomainSize::Micrometres(um) = numerics.domain_um {
        c.number(&DOMAIN, um);
    }
    if let Tolerance::Relative(relative) = numerics.tolerance {
        c.number(&TOLERANCE, relative);
    }
    if let StepBound::Share(share) = numerics.cycle_step_bound {
        c.number(&CYCLE_STEP_BOUND, share);
    }
    if let SolverThreads::Count(threads) = numerics.threads {
        c.whole(&THREADS, threads as u64);
    }
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
    c.number(&CORROSION_POTENTIAL, corrosion.corrosion_potential_v);
    c.number(&TAFEL_A, corrosion.tafel_a_c_v);
    c.number(&TAFEL_B, corrosion.tafel_b_c_v_per_decade);
    c.number(&TAFEL_ETA_MIN, corrosion.tafel_overpotential_min_v);
    c.number(&TAFEL_ETA_MAX, corrosion.tafel_overpotential_max_v);
    if corrosion.tafel_overpotential_max_v <= corrosion.tafel_overpotential_min_v {
        c.fail(
            TAFEL_ETA_MAX.path,
            format!(
                "must be above `corrosion.tafel_overpotential_min_v` ({} V), got {} V",
                num(corrosion.tafel_overpotential_min_v),
                num(corrosion.tafel_overpotential_max_v)
            ),
        );
    }
    c.number(&ANODIC_CURRENT, corrosion.anodic_current_density_a_cm2);
    c.number(&EXPOSED_AREA, corrosion.exposed_area_cm2);
    c.number(&REPASSIVATION_TIME, corrosion.repassivation_time_s);
    // The wake picture has each stripped spot repassivate before the ball comes round
    // again; a wake as long as the track leaves the whole track bare (`wear_track`).
    let wake_m = scene.sliding_speed_m_s() * corrosion.repassivation_time_s;
    // On the reciprocating rig a point is stripped again at each pass, whatever the wake
    // (`corrosion::stroke`), and its frequency is warned of instead.
    let rotating = scene.test.reciprocating.is_none();
    if corrosion.depassivates() && rotating && wake_m >= scene.track_length_m() {
        c.fail(
            REPASSIVATION_TIME.path,
            format!(
                "the wake v tau = {} mm would reach round the {} mm track: tau must be below \
                 one cycle, {} s; a track that never repassivates is `anodic_area: \
                 \"wear_track\"`",
                num(wake_m * 1e3),
                num(scene.track_length_m() * 1e3),
                num(scene.cycle_period_s())
            ),
        );
    }
    c.number(&ANODIC_AREA_FACTOR, corrosion.anodic_area_factor);
    c.number(&REPASSIVATION_EXPONENT, corrosion.repassivation_exponent);
    c.number(&OHMIC_RESISTANCE, corrosion.ohmic_resistance_ohm);
    if let Some(floor) = corrosion.bare_corrosion_potential_v {
        c.number(&BARE_CORROSION_POTENTIAL, floor);
        if floor >= corrosion.corrosion_potential_v {
            c.fail(
                BARE_CORROSION_POTENTIAL.path,
                format!(
                    "must be below `corrosion.corrosion_potential_v` ({} V): bare metal is \
                     more active than the passive surface; got {} V (was it against another \
                     reference electrode?)",
                    num(corrosion.corrosion_potential_v),
                    num(floor)
                ),
            );
        }
    }
    check_control(c, corrosion);
    c.number(&MOLAR_MASS, corrosion.molar_mass_g_mol);
    c.number(&VALENCE, corrosion.valence);
    c.number(&DENSITY, corrosion.density_g_cm3);
}

/// Potentiostatic control needs its potential, within what an aqueous cell holds, and the
/// bare metal's corrosion potential that says whether the bare spots dissolve there.
fn check_control(c: &mut Checks, corrosion: &Corrosion) {
    if corrosion.control != Control::Potentiostatic {
        return;
    }
    let e_corr = corrosion.corrosion_potential_v;
    match corrosion.applied_potential_v {
        None => c.fail(
            APPLIED_POTENTIAL.path,
            "`control: \"potentiostatic\"` needs the potential to hold, V against \
             `reference_electrode`"
                .to_owned(),
        ),
        Some(v) if !(e_corr - 3.0..=e_corr + 1.0).contains(&v) => c.fail(
            APPLIED_POTENTIAL.path,
            format!(
                "must lie within 3 V below and 1 V above E_corr ({} to {} V), got {} V (was it \
                 in mV?)",
                num(e_corr - 3.0),
                num(e_corr + 1.0),
                num(v)
            ),
        ),
        Some(_) => {}
    }
    if corrosion.bare_corrosion_potential_v.is_none() {
        c.fail(
            BARE_CORROSION_POTENTIAL.path,
            "`control: \"potentiostatic\"` needs the bare metal's corrosion potential: below \
             it the bare spots do not dissolve, and without it they would dissolve at i_a at \
             any potential, cathodic protection included"
                .to_owned(),
        );
    }
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

    /// `value` within `field`'s range, else a failure at its path.
    fn number(&mut self, field: &Field, value: f64) {
        self.number_at(field.path, field, value);
    }

    /// `value` within `field`'s range, else a failure at `path` (an element of the field).
    fn number_at(&mut self, path: &str, field: &Field, value: f64) {
        if !field.range.admits(value) {
            self.fail(path, field.number_message(value));
        }
    }

    /// The text `value` within `field`'s bound and the text rule ([`crate::text`]), else a
    /// failure at its path naming the bound or the character refused.
    fn text(&mut self, field: &Field, value: &str) {
        let Range::Text(most) = field.range else {
            return;
        };
        match crate::text::check(value, most, crate::text::Lines::One) {
            Ok(()) => {}
            Err(TextError::TooLong { chars, .. }) => {
                self.fail(field.path, field.message(&format!("{chars} characters")));
            }
            Err(forbidden) => self.fail(field.path, forbidden.to_string()),
        }
    }

    /// The whole number `value` within `field`'s range, else a failure at its path.
    fn whole(&mut self, field: &Field, value: u64) {
        if !field.range.admits_whole(value) {
            self.fail(field.path, field.message(&value.to_string()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Corrosion;
    use super::super::fields::MAX_CYCLES;
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
        scene.numerics.tolerance = Tolerance::Relative(f64::NEG_INFINITY);
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
        scene.numerics.tolerance = Tolerance::Relative(1e-10);
        scene.numerics.cycle_step_bound = StepBound::Share(0.1);
        scene.numerics.domain_um = DomainSize::Micrometres(100_000.0);
        scene.numerics.threads = SolverThreads::Count(64);
        scene.ball.poisson_ratio = -0.99;
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));

        scene.test.friction_coefficient = 2.01;
        scene.test.cycles = MAX_CYCLES + 1;
        scene.numerics.grid = GridSize::Cells(7);
        scene.numerics.tolerance = Tolerance::Relative(0.99e-10);
        scene.numerics.cycle_step_bound = StepBound::Share(0.11);
        scene.numerics.domain_um = DomainSize::Micrometres(0.0);
        scene.numerics.threads = SolverThreads::Count(0);
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
                "numerics.threads",
            ]
        );
    }

    #[test]
    fn the_tafel_domain_is_ordered_and_the_wake_shorter_than_the_track() {
        let mut scene = Scene {
            corrosion: Some(Corrosion {
                tafel_overpotential_min_v: -0.2,
                tafel_overpotential_max_v: -0.3,
                // 18.8 mm/s for 1 s is the whole 18.8 mm track.
                repassivation_time_s: 1.0,
                ..Corrosion::default()
            }),
            ..Scene::default()
        };
        assert_eq!(
            paths(&scene),
            [
                "corrosion.tafel_overpotential_max_v",
                "corrosion.repassivation_time_s"
            ]
        );
        // A track that never repassivates is the wear track's model, not an error.
        if let Some(c) = scene.corrosion.as_mut() {
            c.anodic_area = super::super::AnodicArea::WearTrack;
            c.tafel_overpotential_max_v = -0.05;
        }
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));
    }
    /// A name of a million characters was accepted and copied into every record and list
    /// page; names are bounded and hold no hidden characters, on the command line and the
    /// service alike (both validate here).
    #[test]
    fn the_name_is_bounded_and_holds_no_hidden_characters() {
        let mut scene = Scene {
            name: "é".repeat(crate::text::NAME_MAX_CHARS),
            ..Scene::default()
        };
        assert!(check(&scene).is_empty(), "{:?}", check(&scene));
        scene.name = "x".repeat(1_000_000);
        let errors = check(&scene);
        assert_eq!(errors.len(), 1);
        assert_eq!(errors[0].path, "name");
        assert!(
            errors[0]
                .message
                .starts_with("must be a string of at most 200 characters")
                && errors[0].message.ends_with("got 1000000 characters"),
            "{}",
            errors[0].message
        );
        scene.name = "run\u{202e}3 N".to_owned();
        let errors = check(&scene);
        assert_eq!(errors[0].path, "name");
        assert!(
            errors[0]
                .message
                .starts_with("holds U+202E (a bidirectional control) at character 4"),
            "{}",
            errors[0].message
        );
    }
}
