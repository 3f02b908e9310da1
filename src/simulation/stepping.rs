//! Cycle stepping: when the surface changes slowly, one contact solve stands for several
//! cycles. The wear of the skipped cycles uses the pressure of the last solve, which is
//! forward Euler on the groove with step `m` (on a rough disc the solve includes the wear
//! of the last step's passes, which makes it stable, [`crate::contact::worn_rows`]); its
//! error is about half the change of the per-pass wear profile across the step. The controller measures that change between
//! consecutive solves in the L1 norm relative to the profile (the share of the wear that
//! moves), and keeps it below a bound per step: the scene's `numerics.cycle_step_bound`,
//! by default [`crate::scene::STEP_CHANGE_BOUND`], whose documentation gives what each
//! bound costs and buys.
//!
//! The wear volume does not depend on the step in the Archard phase (each pass removes
//! `k F L / H` whatever the pressure shape); stepping moves wear across the track. A
//! max-norm measure stalls at steps of 1: the row entering contact at the rim of the
//! widening groove changes by 2.5% of the peak every cycle, however slowly the rest moves.

use crate::scene::{CycleStep, Scene};

/// The longest step, cycles: keeps a record at least this often.
pub const MAX_STEP: u64 = 50;

/// The cycle a step from `cycle` may not pass, of a run of `total`: the next record cycle
/// (which must be solved), or the first cycle of a new wear rate (`rate_change`, whose rate
/// the step was not chosen for), else the last.
pub fn step_stop(cycle: u64, total: u64, record_cycles: &[u64], rate_change: Option<u64>) -> u64 {
    record_cycles
        .iter()
        .copied()
        .chain(rate_change)
        .filter(|&r| r > cycle)
        .min()
        .unwrap_or(total)
}

/// Chooses how many cycles the next solve stands for.
#[derive(Debug, Clone)]
pub struct Stepper {
    mode: CycleStep,
    bound: f64,
    previous: Option<(u64, Vec<f64>)>,
    step: u64,
}

impl Stepper {
    /// A controller for `mode` keeping each step's relative profile change within `bound`.
    pub fn new(mode: CycleStep, bound: f64) -> Self {
        Self {
            mode,
            bound,
            previous: None,
            step: 1,
        }
    }

    /// The controller of `scene`'s numerics, resolved for its rig and disc
    /// ([`crate::scene::Numerics::solve_cycle_step`], [`crate::scene::Numerics::step_bound`]).
    pub fn of(scene: &Scene) -> Self {
        let (numerics, case) = (&scene.numerics, scene.numerics_case());
        Self::new(numerics.solve_cycle_step(case), numerics.step_bound(case))
    }

    /// The cycles the last solve stood for (1 before the first): the next step is at most
    /// twice as long.
    pub fn last_step(&self) -> u64 {
        self.step
    }

    /// Re-expresses the last solved profile on a new layout (`relayout`, e.g. a map
    /// embedded in a grown grid's), so that the controller keeps its step and measures the
    /// next change against it.
    pub fn carry(&mut self, relayout: impl FnOnce(&[f64]) -> Vec<f64>) {
        if let Some((_, profile)) = &mut self.previous {
            *profile = relayout(profile);
        }
    }

    /// Cycles the solve at `cycle` stands for (itself included), given its per-pass wear
    /// profile and whether yielding reshaped the groove (`plastic`: a cut larger than the
    /// step bound's share of it). Never steps past `total`, so the last cycle is always
    /// solved.
    pub fn next(&mut self, cycle: u64, total: u64, plastic: bool, profile: &[f64]) -> u64 {
        let wanted = match self.mode {
            CycleStep::EveryCycle => 1,
            // Yielding reshapes the groove within a cycle or two: solve every one.
            CycleStep::Auto if plastic => 1,
            CycleStep::Auto => match &self.previous {
                None => 1,
                Some((before, old)) => {
                    let total: f64 = profile.iter().map(|v| v.abs()).sum();
                    let change = profile
                        .iter()
                        .zip(old)
                        .map(|(a, b)| (a - b).abs())
                        .sum::<f64>()
                        / total;
                    let per_cycle = change / (cycle - before) as f64;
                    let allowed = if per_cycle > 0.0 {
                        (self.bound / per_cycle).floor() as u64
                    } else {
                        MAX_STEP
                    };
                    allowed.clamp(1, (2 * self.step).min(MAX_STEP))
                }
            },
        };
        // A plastic cycle is no reference: the groove it cut changes the next profile.
        self.previous =
            (self.mode == CycleStep::Auto && !plastic).then(|| (cycle, profile.to_vec()));
        let remaining = total - cycle;
        self.step = if remaining == 0 {
            1
        } else {
            wanted.min(remaining)
        };
        self.step
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::STEP_CHANGE_BOUND;

    #[test]
    fn every_cycle_mode_steps_by_one() {
        let mut s = Stepper::new(CycleStep::EveryCycle, STEP_CHANGE_BOUND);
        assert_eq!(s.next(1, 100, false, &[1.0]), 1);
        assert_eq!(s.next(2, 100, false, &[1.0]), 1);
    }

    #[test]
    fn auto_grows_by_doubling_while_the_profile_is_steady_and_lands_on_the_last_cycle() {
        let mut s = Stepper::new(CycleStep::Auto, STEP_CHANGE_BOUND);
        let mut cycle = 1;
        let mut steps = Vec::new();
        while cycle <= 100 {
            let step = s.next(cycle, 100, false, &[1.0, 2.0]);
            steps.push(step);
            cycle += step;
        }
        assert_eq!(&steps[..5], &[1, 2, 4, 8, 16]);
        assert_eq!(
            steps.iter().sum::<u64>(),
            100,
            "ends exactly at the last cycle"
        );
    }

    #[test]
    fn auto_solves_every_cycle_while_plastic_and_limits_fast_change() {
        let mut s = Stepper::new(CycleStep::Auto, STEP_CHANGE_BOUND);
        assert_eq!(s.next(1, 100, true, &[1.0]), 1);
        assert_eq!(s.next(2, 100, false, &[1.0]), 1);
        // 0.5% change in one cycle: at most 2 cycles for a 1% bound.
        assert_eq!(s.next(3, 100, false, &[1.005]), 2);
        // The same change under a 0.4% bound: no step beyond the solved cycle.
        let mut tight = Stepper::new(CycleStep::Auto, 0.004);
        tight.next(2, 100, false, &[1.0]);
        assert_eq!(tight.next(3, 100, false, &[1.005]), 1);
        // L1-relative: a change confined to a small part of the profile counts for its share.
        let mut s = Stepper::new(CycleStep::Auto, STEP_CHANGE_BOUND);
        let flat = vec![1.0; 100];
        s.next(1, 1000, false, &flat);
        let mut rim = flat.clone();
        rim[99] = 1.1;
        assert_eq!(
            s.next(2, 1000, false, &rim),
            2,
            "1e-3 of the wear moved: doubling"
        );
    }

    #[test]
    fn a_carried_profile_keeps_the_step_and_compares_on_the_new_layout() {
        let mut s = Stepper::new(CycleStep::Auto, STEP_CHANGE_BOUND);
        s.next(1, 1000, false, &[1.0, 2.0]);
        assert_eq!(s.next(2, 1000, false, &[1.0, 2.0]), 2);
        // The same values with a zero either side: no change, so the step doubles on.
        s.carry(|old| [&[0.0][..], old, &[0.0]].concat());
        assert_eq!(s.next(4, 1000, false, &[0.0, 1.0, 2.0, 0.0]), 4);
    }
}
