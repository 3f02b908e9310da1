//! What `"auto"` resolves to in `numerics` for the contact solves and the cycle steps, by
//! the rig and the disc a scene runs: one rule per setting, each choice's measurement in
//! its constant's documentation.

use super::Scene;
use super::auto_or::{CycleStep, StepBound, Tolerance};
use super::sections::{DEFAULT_TOLERANCE, Numerics, ROUGH_TOLERANCE, STEP_CHANGE_BOUND};

/// The relative residual `numerics.tolerance: "auto"` solves the reciprocating rig's
/// positions to. Measured by `scripts/stroke_step_bound.py` (`docs/rig-accuracy.md`, "The
/// reciprocating rig: step bound and tolerance over several scenes"): on each of its five
/// scenes, at bound 0.01, 1e-5 moved no error against every cycle solved at 1e-8 by more
/// than 1e-7 (volume, deepest point, WAC, both profiles) or 0.01 mV, for 0.83 to 0.93 of
/// the CPU time of 1e-6. A blended position already errs by 2.7e-3 of the deepest point
/// (`SOLVE_EVERY_POSITIONS`).
pub const STROKE_TOLERANCE: f64 = 1e-5;

/// The largest relative (L1) change of a cycle's pressure integral across one automatic
/// step on the reciprocating rig (`numerics.cycle_step_bound: "auto"`). Measured by
/// `scripts/stroke_step_bound.py` on five scenes (strokes of 2, 5 and 10 mm, 5 and 10 N,
/// 316L and Ti-6Al-4V), against every cycle solved at 1e-8: 0.02 at [`STROKE_TOLERANCE`]
/// took 0.44 to 0.66 of the CPU time of 0.01 at 1e-6, and every error stayed within
/// 3.5e-3 (0.01's: 2.4e-3), under the auto grid's own (5.2e-3 in the middle profile);
/// 0.03 saved little more (0.41 to 0.66) and erred by up to 4.5e-3 in volume under 10 N,
/// 0.05 by 7.0e-3.
pub const STROKE_STEP_CHANGE_BOUND: f64 = 0.02;

/// The runs the automatic numerics are chosen for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NumericsCase {
    /// The ball on a smooth rotating disc, as in the paper.
    SmoothDisc,
    /// The ball on a rough rotating disc (`disc.surface`).
    RoughDisc,
    /// The reciprocating rig on its smooth flat (`test.reciprocating`).
    Reciprocating,
}

impl Scene {
    /// The case this scene's automatic numerics are chosen for.
    pub fn numerics_case(&self) -> NumericsCase {
        if self.test.reciprocating.is_some() {
            NumericsCase::Reciprocating
        } else if self.disc.surface.is_some() {
            NumericsCase::RoughDisc
        } else {
            NumericsCase::SmoothDisc
        }
    }
}

impl Numerics {
    /// The contact solves' relative residual: the scene's, or on `auto` [`DEFAULT_TOLERANCE`]
    /// on a smooth disc, [`ROUGH_TOLERANCE`] on a rough one and [`STROKE_TOLERANCE`] on the
    /// reciprocating rig.
    pub fn solve_tolerance(&self, case: NumericsCase) -> f64 {
        match (self.tolerance, case) {
            (Tolerance::Relative(relative), _) => relative,
            (Tolerance::Auto, NumericsCase::SmoothDisc) => DEFAULT_TOLERANCE,
            (Tolerance::Auto, NumericsCase::RoughDisc) => ROUGH_TOLERANCE,
            (Tolerance::Auto, NumericsCase::Reciprocating) => STROKE_TOLERANCE,
        }
    }

    /// Which cycles a run solves: the scene's `cycle_step`, except that `auto` with an
    /// `auto` bound solves every cycle of a rough disc, where steps skip the yield cuts of
    /// their cycles and cost more accuracy than they save time ([`ROUGH_TOLERANCE`]). A
    /// rough scene that gives a bound steps under it.
    pub fn solve_cycle_step(&self, case: NumericsCase) -> CycleStep {
        match (self.cycle_step, self.cycle_step_bound, case) {
            (CycleStep::Auto, StepBound::Auto, NumericsCase::RoughDisc) => CycleStep::EveryCycle,
            (step, _, _) => step,
        }
    }

    /// The automatic step's bound: the scene's, or on `auto` [`STEP_CHANGE_BOUND`] on a disc
    /// and [`STROKE_STEP_CHANGE_BOUND`] on the reciprocating rig.
    pub fn step_bound(&self, case: NumericsCase) -> f64 {
        match (self.cycle_step_bound, case) {
            (StepBound::Share(share), _) => share,
            (StepBound::Auto, NumericsCase::Reciprocating) => STROKE_STEP_CHANGE_BOUND,
            (StepBound::Auto, _) => STEP_CHANGE_BOUND,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CASES: [NumericsCase; 3] = [
        NumericsCase::SmoothDisc,
        NumericsCase::RoughDisc,
        NumericsCase::Reciprocating,
    ];

    #[test]
    fn auto_resolves_by_the_case_and_a_given_value_is_kept_in_every_case() {
        let auto = Numerics::default();
        let bits = |value: f64| value.to_bits();
        let tolerances = CASES.map(|case| bits(auto.solve_tolerance(case)));
        assert_eq!(
            tolerances,
            [DEFAULT_TOLERANCE, ROUGH_TOLERANCE, STROKE_TOLERANCE].map(bits)
        );
        let bounds = CASES.map(|case| bits(auto.step_bound(case)));
        assert_eq!(
            bounds,
            [
                STEP_CHANGE_BOUND,
                STEP_CHANGE_BOUND,
                STROKE_STEP_CHANGE_BOUND
            ]
            .map(bits)
        );
        let steps = CASES.map(|case| auto.solve_cycle_step(case));
        assert_eq!(
            steps,
            [CycleStep::Auto, CycleStep::EveryCycle, CycleStep::Auto]
        );
        let given: Numerics =
            serde_json::from_str(r#"{"tolerance": 1e-7, "cycle_step_bound": 0.05}"#)
                .expect("given values");
        for case in CASES {
            assert_eq!(bits(given.solve_tolerance(case)), bits(1e-7));
            assert_eq!(bits(given.step_bound(case)), bits(0.05));
            assert_eq!(given.solve_cycle_step(case), CycleStep::Auto);
        }
        let every: Numerics = serde_json::from_str(r#"{"cycle_step": 1}"#).expect("every");
        for case in CASES {
            assert_eq!(every.solve_cycle_step(case), CycleStep::EveryCycle);
        }
    }

    #[test]
    fn the_case_is_the_rig_before_the_surface() {
        let mut scene = Scene::default();
        assert_eq!(scene.numerics_case(), NumericsCase::SmoothDisc);
        scene.disc.surface = serde_json::from_str(
            r#"{"kind": "synthetic", "rms_height_um": 0.1, "hurst": 0.8,
                "short_cutoff_um": 4, "long_cutoff_um": 50, "seed": 1}"#,
        )
        .expect("a surface");
        assert_eq!(scene.numerics_case(), NumericsCase::RoughDisc);
        scene.test.reciprocating = serde_json::from_str("{}").expect("a stroke");
        assert_eq!(scene.numerics_case(), NumericsCase::Reciprocating);
    }
}
