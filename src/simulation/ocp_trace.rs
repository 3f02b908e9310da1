//! The open-circuit potential as the lab's potentiostat records it (the paper's Fig. 6):
//! E_corr while the passive film stands, the drop when the ball starts, the potential of each
//! solved cycle during the rubbing, and the recovery after the ball stops while the bare
//! metal repassivates.
//!
//! Sampling: two points before the rubbing (the film is passive throughout, so the potential
//! is E_corr); during the rubbing, one point per solved cycle, which the cycle stepping
//! already spaces by how fast the state changes (464 points for the 3600 cycles of `{}`)
//! and which are the run's own states, not interpolations; after the stop, at tau / 8,
//! tau / 4, tau / 2, tau, 2 tau, ... until eq. 18 reaches E_corr, at that instant and at the
//! end. The model's recovery takes a few tau (a fraction of a second), after which it stays
//! at E_corr, so geometric steps in tau resolve all of it in a dozen points. The spot models
//! carry each row's age to the stop and let every row repassivate by its transient; a power
//! law recovers over the whole hold, so they are sampled geometrically in revolutions to the
//! end ([`spot_recovery_times`]).

use crate::corrosion::recovering_area_m2;
use crate::scene::Scene;

use super::electrochemistry::Cell;
use super::result::{CycleRecord, OcpPhase, OcpSample};

/// The first sample after the stop, in repassivation times.
const FIRST_RECOVERY_SAMPLE: f64 = 0.125;

/// The trace of a run of `scene` that recorded `records` with `cell`.
pub(super) fn ocp_trace(scene: &Scene, cell: &Cell, records: &[CycleRecord]) -> Vec<OcpSample> {
    if cell.settings().held_v().is_some() {
        // A potentiostat holds the potential: there is no open-circuit trace.
        return Vec::new();
    }
    let model = cell.model();
    let e_corr = model.corrosion_potential_v;
    let start = scene.test.ocp_before_s;
    let sample = |time_s, potential_v, phase| OcpSample {
        time_s,
        potential_v,
        phase,
    };
    let mut trace = Vec::new();
    if start > 0.0 {
        trace.push(sample(0.0, e_corr, OcpPhase::Before));
    }
    trace.push(sample(start, e_corr, OcpPhase::Before));
    for record in records {
        if let Some(potential) = record.potential_v {
            trace.push(sample(start + record.time_s, potential, OcpPhase::Rubbing));
        }
    }
    let after = scene.test.ocp_after_s;
    let Some(area_at_stop) = records
        .last()
        .and_then(|r| r.anodic_area_mm2)
        .map(|a| a * 1e-6)
    else {
        return trace;
    };
    if after <= 0.0 {
        return trace;
    }
    let stop = start + scene.test.cycles as f64 * scene.cycle_period_s();
    if let Some(spots_at_stop) = cell.spot_area_after_stop_m2(0.0) {
        for since in spot_recovery_times(scene.cycle_period_s(), after) {
            let area = cell.spot_area_after_stop_m2(since).unwrap_or(spots_at_stop);
            let potential = cell.couple(area).map_or(e_corr, |(e, _)| e);
            trace.push(sample(stop + since, potential, OcpPhase::After));
        }
        return trace;
    }
    let tau = cell.settings().repassivation_time_s;
    for since in recovery_times(area_at_stop, model.capping_area_m2(), tau, after) {
        let area = recovering_area_m2(area_at_stop, since, tau);
        // The area only shrinks from one eq. 18 already took: it stays a valid anode.
        let potential = cell.couple(area).map_or(e_corr, |(e, _)| e);
        trace.push(sample(stop + since, potential, OcpPhase::After));
    }
    trace
}

/// The times after the stop to sample for the spot models, up to `after_s`: from an eighth
/// of a revolution `period_s`, doubling, and the end. The rows' ages at the stop spread over
/// a revolution, and a power-law transient decays over the whole hold, so geometric steps
/// resolve it in a dozen or so points (14 for a 1 s cycle and the paper's 1200 s).
fn spot_recovery_times(period_s: f64, after_s: f64) -> Vec<f64> {
    let mut times = Vec::new();
    let mut t = FIRST_RECOVERY_SAMPLE * period_s;
    while t < after_s {
        times.push(t);
        t *= 2.0;
    }
    times.push(after_s);
    times
}

/// The times after the stop to sample, up to `after_s`: geometric in `tau` until the bare
/// area `area_at_stop_m2` decays to `capping_m2` (where eq. 18 reaches E_corr), that
/// instant, and the end.
fn recovery_times(area_at_stop_m2: f64, capping_m2: f64, tau: f64, after_s: f64) -> Vec<f64> {
    let capped_at = if tau > 0.0 && area_at_stop_m2 > capping_m2 {
        tau * (area_at_stop_m2 / capping_m2).ln()
    } else {
        0.0
    };
    let mut times = Vec::new();
    let mut t = FIRST_RECOVERY_SAMPLE * tau;
    while tau > 0.0 && t < capped_at.min(after_s) {
        times.push(t);
        t *= 2.0;
    }
    if capped_at > 0.0 && capped_at < after_s {
        times.push(capped_at);
    }
    times.push(after_s);
    times
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovery_is_sampled_geometrically_to_the_cap_then_once_at_the_end() {
        // 0.15 s, from 50 times the capping area: E_corr after 0.15 ln 50 = 0.587 s.
        let times = recovery_times(50.0, 1.0, 0.15, 1200.0);
        // Doublings of 0.15 / 8 and the end given: exact in binary, so compared as bits.
        let bits = |times: &[f64]| times.iter().map(|t| t.to_bits()).collect::<Vec<_>>();
        let capped = 0.15 * 50f64.ln();
        let expected = [0.01875, 0.0375, 0.075, 0.15, 0.3, capped, 1200.0];
        assert_eq!(bits(&times), bits(&expected), "{times:?}");
        // A record shorter than the recovery ends inside it.
        let short = recovery_times(50.0, 1.0, 0.15, 0.1);
        assert_eq!(bits(&short), bits(&[0.01875, 0.0375, 0.075, 0.1]));
        // Already at E_corr (or no repassivation time): the end alone.
        assert_eq!(bits(&recovery_times(0.5, 1.0, 0.15, 60.0)), bits(&[60.0]));
        assert_eq!(bits(&recovery_times(50.0, 1.0, 0.0, 60.0)), bits(&[60.0]));
    }

    #[test]
    fn the_spots_recovery_is_sampled_from_an_eighth_of_a_revolution_to_the_end() {
        let times = spot_recovery_times(1.0, 1200.0);
        assert_eq!(times.len(), 15, "{times:?}");
        assert!((times[0] - 0.125).abs() < f64::EPSILON);
        assert!((times[13] - 1024.0).abs() < f64::EPSILON);
        assert!((times[14] - 1200.0).abs() < f64::EPSILON);
    }
}
