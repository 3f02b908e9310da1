//! The depassivated area under a reciprocating stroke: each point of the track is stripped
//! while the contact covers it, twice a cycle, and repassivates in between, for a time
//! that varies along the stroke (`docs/corrosion.md`).
//!
//! The contact's footprint moves with the ball's centre X(t): a point at `x` on the row of
//! chord `[lo, hi]` (relative to the centre) is covered while `X` lies in `[x - hi, x - lo]`,
//! which the forward sweep crosses once and the return once; near an end the two merge, and
//! at the stroke's start they merge across the cycle. A covered point is bare; once
//! uncovered it passes the repassivation transient ([`Repassivation`]) from that moment
//! until it is covered again (a fresh strip replaces the old transient, as the disc's spots
//! do). Its bare-equivalent area is the row width times the point's spacing times the
//! current fraction, and the track's, over all points and rows, times the share of the
//! footprint that is stripped (the real contact over the solved one for the wake model).
//!
//! In the middle of a long stroke at constant speed `v`, with `tau` far below the half
//! period, this is the disc's wake: the footprint's area plus its width times `v tau`,
//! times the stripped share, A_r (1 + v tau / L).

use super::kinetics::Repassivation;
use crate::wear::Stroke;

/// The contact's footprint as it strips the film: per row across the track, the chord it
/// covers along the stroke relative to the ball's centre.
#[derive(Debug, Clone, PartialEq)]
pub struct Footprint {
    /// `(lo, hi)` along the stroke, m, one per row in contact.
    pub chords_m: Vec<(f64, f64)>,
    /// The width of a row, m.
    pub row_width_m: f64,
    /// The share of the footprint's area that is stripped (the real contact's share of
    /// the solved contact for the wake model; 1 when every covered cell is stripped).
    pub stripped_share: f64,
}

/// Each point of the track, a row's width by a spacing along it, and when it is covered in
/// a cycle.
#[derive(Debug, Clone)]
pub struct StrokeExposure {
    period_s: f64,
    /// The area a point stands for times the stripped share, m^2.
    point_area_m2: f64,
    /// Per point, how many rows' points it stands for and its covered intervals within a
    /// cycle, sorted (`end` may pass the period for the interval that runs over into the
    /// next cycle).
    covered: Vec<(f64, Vec<(f64, f64)>)>,
}

impl StrokeExposure {
    /// The exposure of the track `stroke` leaves under `footprint`, its points `spacing_m`
    /// apart along each row.
    pub fn new(stroke: &Stroke, footprint: &Footprint, spacing_m: f64) -> Self {
        let half = stroke.length_m / 2.0;
        let mut covered = Vec::new();
        for ((lo, hi), rows) in distinct(&footprint.chords_m) {
            // Points from the start's trailing edge to the far end's leading edge, centred
            // on that span so that a symmetric chord gives a mirror-symmetric track.
            let (first, last) = (-half + lo, half + hi);
            let count = ((last - first) / spacing_m).ceil().max(1.0) as usize;
            let centre = 0.5 * (first + last);
            for i in 0..count {
                let x = centre + (i as f64 + 0.5 - 0.5 * count as f64) * spacing_m;
                let intervals = intervals(stroke, x - hi, x - lo);
                if !intervals.is_empty() {
                    covered.push((rows, intervals));
                }
            }
        }
        Self {
            period_s: stroke.period_s(),
            point_area_m2: spacing_m * footprint.row_width_m * footprint.stripped_share,
            covered,
        }
    }

    /// The bare-equivalent area, m^2, at `t_s` into a cycle of the steady state.
    pub fn area_at_m2(&self, t_s: f64, kinetics: &Repassivation) -> f64 {
        let t = t_s.rem_euclid(self.period_s);
        let fraction: f64 = self
            .covered
            .iter()
            .map(|(rows, intervals)| rows * self.current_fraction(intervals, t, kinetics))
            .sum();
        fraction * self.point_area_m2
    }

    /// The bare-equivalent area averaged over a cycle, m^2: each point bare while covered
    /// and passing the transient's charge over each gap until the next strip.
    pub fn mean_area_m2(&self, kinetics: &Repassivation) -> f64 {
        let period = self.period_s;
        let seconds: f64 = self
            .covered
            .iter()
            .map(|(rows, intervals)| {
                let next_starts = intervals
                    .iter()
                    .skip(1)
                    .map(|i| i.0)
                    .chain(std::iter::once(intervals[0].0 + period));
                intervals
                    .iter()
                    .zip(next_starts)
                    .map(|(&(start, end), next)| end - start + kinetics.charge_s(next - end))
                    .sum::<f64>()
                    * rows
            })
            .sum();
        seconds / period * self.point_area_m2
    }

    /// The current fraction of a point covered over `intervals` at `t` in `0..period`.
    fn current_fraction(&self, intervals: &[(f64, f64)], t: f64, kinetics: &Repassivation) -> f64 {
        let period = self.period_s;
        let mut since = f64::INFINITY;
        for &(start, end) in intervals {
            // The interval in this cycle and the one before (an interval may run over).
            for shift in [0.0, -period] {
                let (start, end) = (start + shift, end + shift);
                if (start..=end).contains(&t) {
                    return 1.0;
                }
                if end < t {
                    since = since.min(t - end);
                }
            }
        }
        kinetics.current_fraction(since)
    }
}

/// The distinct chords of `chords_m`, each with how many rows have it. The chords of a
/// solved contact end on cell edges, so rows share them and their points are the same.
/// Merged, 1000 strokes of the default rig (`tribosim run` of `{"test": {"cycles": 1000,
/// "reciprocating": {}}}`) took 8.0 s of CPU against 9.8 s, with the same results to
/// 1e-14; the traces had taken 10% of its `perf` profile.
fn distinct(chords_m: &[(f64, f64)]) -> Vec<((f64, f64), f64)> {
    let mut merged: Vec<((f64, f64), f64)> = Vec::new();
    for &(lo, hi) in chords_m {
        let same = |c: &&mut ((f64, f64), f64)| {
            c.0.0.to_bits() == lo.to_bits() && c.0.1.to_bits() == hi.to_bits()
        };
        match merged.iter_mut().find(same) {
            Some(chord) => chord.1 += 1.0,
            None => merged.push(((lo, hi), 1.0)),
        }
    }
    merged
}

/// The times within a cycle at which the ball's centre lies in `[from, to]`: the forward
/// sweep's and the return's, merged where they touch at an end.
fn intervals(stroke: &Stroke, from: f64, to: f64) -> Vec<(f64, f64)> {
    let half = stroke.length_m / 2.0;
    let (from, to) = (from.max(-half), to.min(half));
    if from > to {
        return Vec::new();
    }
    let period = stroke.period_s();
    let (enter, leave) = (
        stroke.forward_pass_time_s(from),
        stroke.forward_pass_time_s(to),
    );
    let (back_enter, back_leave) = (period - leave, period - enter);
    match (from <= -half, to >= half) {
        (true, true) => vec![(0.0, period)],
        // Covered from the return's entry through the start into the next forward sweep.
        (true, false) => vec![(back_enter, period + leave)],
        (false, true) => vec![(enter, back_leave)],
        (false, false) => vec![(enter, leave), (back_enter, back_leave)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corrosion::depassivation::wake_area_m2;
    use crate::corrosion::kinetics::TransientForm;
    use crate::wear::VelocityLaw;

    fn exponential(tau_s: f64) -> Repassivation {
        Repassivation {
            form: TransientForm::Exponential,
            time_s: tau_s,
            exponent: 0.5,
        }
    }

    /// A circular footprint of radius `a` on rows `dy` wide.
    fn disc_footprint(a: f64, dy: f64, share: f64) -> Footprint {
        let rows = (a / dy).floor() as i64;
        let chords_m = (-rows..=rows)
            .map(|i| {
                let y = i as f64 * dy;
                let half = (a * a - y * y).max(0.0).sqrt();
                (-half, half)
            })
            .filter(|c| c.1 > c.0)
            .collect();
        Footprint {
            chords_m,
            row_width_m: dy,
            stripped_share: share,
        }
    }

    #[test]
    fn mid_stroke_at_constant_speed_is_the_disc_wake() {
        // 5 mm at 1 Hz, constant law: 10 mm/s. tau 10 ms: a 100 um wake behind a 60 um
        // contact, gone long before the return (0.5 s later: e^-50).
        let stroke = Stroke {
            length_m: 5e-3,
            frequency_hz: 1.0,
            law: VelocityLaw::Constant,
        };
        let footprint = disc_footprint(60e-6, 2e-6, 0.3);
        let area_s: f64 = footprint.chords_m.iter().map(|c| (c.1 - c.0) * 2e-6).sum();
        let width = footprint.chords_m.len() as f64 * 2e-6;
        let exposure = StrokeExposure::new(&stroke, &footprint, 0.5e-6);
        let kinetics = exponential(0.01);
        // A quarter period in: the ball at the middle, going forward.
        let got = exposure.area_at_m2(0.25, &kinetics);
        let real = 0.3 * area_s;
        let want = wake_area_m2(real, Some(area_s / width), 10e-3, 0.01);
        // Points 0.5 um apart sample chords of tens of um and a 100 um exponential: each
        // row's covered length is off by at most a spacing at each end (2 x 0.5 / 120 um
        // of the contact's share, about 1/3 of the total) and the wake's midpoint sum by
        // (0.5 / 100)^2 / 24: 3e-3 bounds both; measured 8.6e-5.
        assert!(((got - want) / want).abs() < 3e-3, "{got} against {want}");
    }

    #[test]
    fn the_mean_area_is_the_mean_of_the_trace_and_the_ends_dwell() {
        let stroke = Stroke {
            length_m: 1e-3,
            frequency_hz: 2.0,
            law: VelocityLaw::Sinusoidal,
        };
        let footprint = disc_footprint(50e-6, 5e-6, 1.0);
        let exposure = StrokeExposure::new(&stroke, &footprint, 2e-6);
        for kinetics in [
            exponential(0.05),
            Repassivation {
                form: TransientForm::PowerLaw,
                time_s: 0.01,
                exponent: 0.5,
            },
        ] {
            let samples = 4_000;
            let dt = stroke.period_s() / samples as f64;
            let sampled: f64 = (0..samples)
                .map(|i| exposure.area_at_m2((i as f64 + 0.5) * dt, &kinetics))
                .sum::<f64>()
                / samples as f64;
            let exact = exposure.mean_area_m2(&kinetics);
            // The midpoint rule over 4,000 samples of a trace that jumps where a point is
            // covered or uncovered: a point's bare time is off by at most a sample, one
            // 4000th of the period, so the mean by at most 1 / 4000 relative (the transient
            // between is smooth and sampled to far better); measured 2.1e-6 and 1.6e-6.
            assert!(
                ((sampled - exact) / exact).abs() < 2.5e-4,
                "{sampled} {exact}"
            );
        }
        // At the turning point the crank rests: the whole footprint is covered and bare,
        // and the track behind it repassivates.
        let kinetics = exponential(0.05);
        let at_end = exposure.area_at_m2(0.25, &kinetics);
        let at_middle = exposure.area_at_m2(0.125, &kinetics);
        assert!(at_middle > at_end, "{at_middle} {at_end}");
    }

    #[test]
    fn a_point_is_covered_twice_in_the_middle_and_once_at_the_ends() {
        let stroke = Stroke {
            length_m: 1e-3,
            frequency_hz: 1.0,
            law: VelocityLaw::Constant,
        };
        // The centre at x = 0 for a point contact: a quarter and three quarters in.
        let middle = intervals(&stroke, 0.0, 0.0);
        assert_eq!(middle.len(), 2);
        assert!((middle[0].0 - 0.25).abs() < 1e-15 && (middle[1].0 - 0.75).abs() < 1e-15);
        // Reaching the far end: one interval about the half period.
        let end = intervals(&stroke, 0.4e-3, 0.6e-3);
        assert_eq!(end.len(), 1);
        assert!((end[0].0 - 0.45).abs() < 1e-12 && (end[0].1 - 0.55).abs() < 1e-12);
        // Reaching the start: one interval running over into the next cycle.
        let start = intervals(&stroke, -0.6e-3, -0.4e-3);
        assert!((start[0].0 - 0.95).abs() < 1e-12 && (start[0].1 - 1.05).abs() < 1e-12);
        assert!(intervals(&stroke, 0.6e-3, 0.7e-3).is_empty());
    }
}
