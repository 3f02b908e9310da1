//! The depassivated area from the stripped spots of the solved contact, island by island,
//! each row of the track carrying its own age since stripping (`docs/corrosion.md`).
//!
//! The contact's patch is the same at every point of the track (the wear state is uniform
//! along it), so a material point of the track at lateral position y meets, once a
//! revolution, the spots of the grid row at y: it is stripped as it enters each spot's chord
//! and bare while it crosses it (l / v), then repassivates until it meets the next spot of
//! its row, g / v later, or the first spot again a revolution later (the closing gap,
//! L_track minus the spots' span). With Q(t) the charge a stripped unit area passes in t,
//! over i_a (the [`Repassivation`]), a row of width dy passes the current
//!
//! I_row = i_a dy Σ_spots (l + v Q(g / v)),
//!
//! and the bare-equivalent area that carries it at i_a, the A_a of eq. 18, is the sum of the
//! brackets over the rows. Spots of one row closer than the repassivation distance share
//! their wake (Q saturates) instead of each adding a full one; at high speed, where even the
//! closing gap is crossed before the film regrows, the area tends to the stripped rows times
//! the track length: the repassivation is incomplete, and the area is bounded by the track.
//!
//! A row without a spot this cycle keeps repassivating from its last stripping: its points,
//! stripped at instants spread over that revolution, pass v dy (Q(s + 3T/2) - Q(s + T/2))
//! per i_a over the cycle, s after the end of the cycle that last stripped it (the midpoint
//! rule over the spread of their ages).

use std::collections::BTreeMap;

use super::kinetics::Repassivation;

/// One cycle's spots: for each row, its lateral key and its chords along the sliding.
#[derive(Debug, Clone, PartialEq)]
pub struct SpotRows {
    /// Rows with at least one spot: the row's key (twice y over dy, rounded: the same row
    /// keeps it while the grid grows around it) and its chords' (entry, exit) along the
    /// sliding, m.
    rows: Vec<(i64, Vec<(f64, f64)>)>,
    /// The width of a row, m.
    dy_m: f64,
}

impl SpotRows {
    /// The spots `mask` marks on rows of `nx` cells, `dx` long and `dy` wide, row 0 at
    /// lateral position `y0_m` (its centre).
    pub fn of(mask: &[bool], nx: usize, dx: f64, dy: f64, y0_m: f64) -> Self {
        let mut rows = Vec::new();
        for (iy, row) in mask.chunks_exact(nx).enumerate() {
            let mut chords: Vec<(f64, f64)> = Vec::new();
            let mut entry = None;
            for (ix, &spot) in row.iter().chain(std::iter::once(&false)).enumerate() {
                match (spot, entry) {
                    (true, None) => entry = Some(ix),
                    (false, Some(start)) => {
                        chords.push((start as f64 * dx, ix as f64 * dx));
                        entry = None;
                    }
                    _ => {}
                }
            }
            if !chords.is_empty() {
                let y = y0_m + iy as f64 * dy;
                rows.push(((2.0 * y / dy).round() as i64, chords));
            }
        }
        Self { rows, dy_m: dy }
    }

    /// The spots' area, m^2.
    pub fn area_m2(&self) -> f64 {
        let length: f64 = self
            .rows
            .iter()
            .flat_map(|(_, chords)| chords.iter().map(|(a, b)| b - a))
            .sum();
        length * self.dy_m
    }

    /// The width of the rows with a spot, m: the width the cycle strips.
    pub fn stripped_width_m(&self) -> f64 {
        self.rows.len() as f64 * self.dy_m
    }

    /// The number of spots: chords, one per island per row.
    pub fn chords(&self) -> usize {
        self.rows.iter().map(|(_, chords)| chords.len()).sum()
    }
}

/// The track's rows and how long ago each was last stripped: the state the kinetics carry
/// from cycle to cycle.
#[derive(Debug, Clone, Default)]
pub struct TrackAges {
    /// Since the end of the cycle that last stripped the row, s, by row key.
    since_s: BTreeMap<i64, f64>,
    /// The width of a row, m (the first cycle's; a grid that changes its cell width starts
    /// the ages afresh).
    dy_m: f64,
}

/// The sliding as the kinetics see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sliding {
    /// Sliding speed, m/s.
    pub speed_m_s: f64,
    /// The track's length, one revolution, m.
    pub track_length_m: f64,
}

impl Sliding {
    /// One revolution, s.
    pub fn period_s(&self) -> f64 {
        self.track_length_m / self.speed_m_s
    }
}

impl TrackAges {
    /// The bare-equivalent area over a cycle that strips `spots`, m^2: the stripped rows by
    /// their chords and gaps, the others by their age.
    pub fn cycle_area_m2(
        &mut self,
        spots: &SpotRows,
        sliding: Sliding,
        kinetics: &Repassivation,
    ) -> f64 {
        if (self.dy_m - spots.dy_m).abs() > 1e-12 * spots.dy_m {
            self.since_s.clear();
            self.dy_m = spots.dy_m;
        }
        let mut length = 0.0;
        for (key, chords) in &spots.rows {
            length += stripped_row_length_m(chords, sliding, kinetics);
            self.since_s.remove(key);
        }
        length += self.resting_length_m(sliding, kinetics);
        for (key, _) in &spots.rows {
            self.since_s.insert(*key, 0.0);
        }
        length * spots.dy_m
    }

    /// What the rows that rest pass over the coming cycle, as a length of bare-equivalent
    /// track (times dy for an area), m.
    fn resting_length_m(&self, sliding: Sliding, kinetics: &Repassivation) -> f64 {
        let period = sliding.period_s();
        self.since_s
            .values()
            .map(|&s| {
                sliding.speed_m_s * kinetics.charge_between_s(s + 0.5 * period, s + 1.5 * period)
            })
            .sum()
    }

    /// `cycles` cycles pass after the solved one, repeating its spots: the rows it stripped
    /// stay freshly stripped, the others age.
    pub fn repeat(&mut self, spots: &SpotRows, cycles: u64, sliding: Sliding) {
        let elapsed = cycles as f64 * sliding.period_s();
        for (key, since) in &mut self.since_s {
            if !spots.rows.iter().any(|(k, _)| k == key) {
                *since += elapsed;
            }
        }
    }

    /// The bare-equivalent area `after_s` after the sliding stopped, m^2: no spot strips any
    /// more, and every row repassivates from its last stripping (at the stop, for the rows
    /// of the last cycle: their points' ages are spread over the last revolution).
    pub fn area_after_stop_m2(
        &self,
        after_s: f64,
        sliding: Sliding,
        kinetics: &Repassivation,
    ) -> f64 {
        let period = sliding.period_s();
        // A row's points have ages spread evenly over a revolution, so its bare-equivalent
        // length is L_track / T times the charge over that spread: v (Q(t + T) - Q(t)).
        let length: f64 = self
            .since_s
            .values()
            .map(|&s| {
                let start = s + after_s;
                sliding.speed_m_s * kinetics.charge_between_s(start, start + period)
            })
            .sum();
        length * self.dy_m
    }
}

/// What a stripped row passes over a cycle, as a length of bare-equivalent track, m: each
/// chord, and the charge of the gap that follows it (the last one closing the revolution).
fn stripped_row_length_m(chords: &[(f64, f64)], sliding: Sliding, kinetics: &Repassivation) -> f64 {
    let v = sliding.speed_m_s;
    let span = chords.last().map_or(0.0, |c| c.1) - chords.first().map_or(0.0, |c| c.0);
    let closing = (sliding.track_length_m - span).max(0.0);
    let gaps = chords
        .windows(2)
        .map(|pair| pair[1].0 - pair[0].1)
        .chain(std::iter::once(closing));
    chords
        .iter()
        .zip(gaps)
        .map(|(&(entry, exit), gap)| (exit - entry) + v * kinetics.charge_s(gap / v))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corrosion::kinetics::TransientForm;

    const EXPONENTIAL: Repassivation = Repassivation {
        form: TransientForm::Exponential,
        time_s: 0.01,
        exponent: 1.0,
    };
    const PARABOLIC: Repassivation = Repassivation {
        form: TransientForm::PowerLaw,
        time_s: 1e-3,
        exponent: 0.5,
    };

    /// One row of `cells` cells of 1 um, spots where `pattern` says so.
    fn row(pattern: &[bool]) -> SpotRows {
        SpotRows::of(pattern, pattern.len(), 1e-6, 1e-6, 0.0)
    }

    /// The mean bare-equivalent length of one row over a revolution in steady state, by
    /// brute force: `points` material points around the ring, stepped `steps` times a
    /// revolution through the spots, each passing i(age) / i_a since its last stripping.
    fn brute_length(spots: &[(f64, f64)], sliding: Sliding, kinetics: &Repassivation) -> f64 {
        let (points, steps) = (4000, 4000);
        let ring = sliding.track_length_m;
        let period = sliding.period_s();
        let dt = period / steps as f64;
        let mut stripped_at = vec![f64::NEG_INFINITY; points];
        let mut sum = 0.0;
        // Two revolutions: the first strips every point once, the second is steady.
        for step in 0..2 * steps {
            let t = step as f64 * dt;
            let mut bare = 0.0;
            for (k, last) in stripped_at.iter_mut().enumerate() {
                let x = (k as f64 / points as f64 * ring + sliding.speed_m_s * t) % ring;
                if spots.iter().any(|&(a, b)| (a..b).contains(&x)) {
                    *last = t;
                }
                bare += kinetics.current_fraction(t - *last);
            }
            if step >= steps {
                sum += bare * ring / points as f64;
            }
        }
        sum / steps as f64
    }

    #[test]
    fn a_row_passes_what_its_points_pass_one_by_one() {
        // A short ring (300 um at 20 mm/s: 15 ms) so that the gaps and the closing gap all
        // matter, with three spots of 5, 10 and 5 um.
        let pattern: Vec<bool> = (0..40)
            .map(|i| (2..7).contains(&i) || (12..22).contains(&i) || (30..35).contains(&i))
            .collect();
        let spots = row(&pattern);
        let sliding = Sliding {
            speed_m_s: 0.02,
            track_length_m: 300e-6,
        };
        let chords = spots.rows[0].1.clone();
        assert_eq!(chords.len(), 3);
        for kinetics in [EXPONENTIAL, PARABOLIC] {
            let exact = stripped_row_length_m(&chords, sliding, &kinetics);
            let brute = brute_length(&chords, sliding, &kinetics);
            // 4000 points and steps a revolution: a point's stripping is late by one step
            // (75 nm of travel) at most, against chords of 5 um and more: 1.5e-2 of a chord
            // at worst, less over the whole row. Measured: -1.75e-4 relative.
            assert!(
                ((brute - exact) / exact).abs() < 1e-3,
                "{kinetics:?}: brute {brute} against {exact}"
            );
        }
    }

    #[test]
    fn a_lone_spot_leaves_its_wake_and_close_spots_share_one() {
        let sliding = Sliding {
            speed_m_s: 0.0188,
            track_length_m: 0.0188,
        };
        let mut pattern = vec![false; 100];
        pattern[10..14].fill(true);
        let mut ages = TrackAges::default();
        let lone = ages.cycle_area_m2(&row(&pattern), sliding, &EXPONENTIAL);
        // l + v tau = 4 um + 188 um, one row 1 um wide, exp(-100) of the wake cut off.
        assert!((lone - 192e-12).abs() < 1e-20, "{lone}");
        // A second spot 20 um behind, well within v tau: the wake is shared, not doubled.
        pattern[34..38].fill(true);
        let pair = TrackAges::default().cycle_area_m2(&row(&pattern), sliding, &EXPONENTIAL);
        let shared = 8e-12 + 188e-12 * (1.0 - (-20.0f64 / 188.0).exp()) + 188e-12;
        assert!((pair - shared).abs() < 1e-20, "{pair} against {shared}");
        assert!(pair < 2.0 * lone);
    }

    #[test]
    fn fast_sliding_leaves_the_track_bare_but_no_barer() {
        let mut pattern = vec![false; 100];
        pattern[40..60].fill(true);
        let spots = row(&pattern);
        for speed in [0.02, 2.0, 200.0] {
            let sliding = Sliding {
                speed_m_s: speed,
                track_length_m: 0.0188,
            };
            let area = TrackAges::default().cycle_area_m2(&spots, sliding, &PARABOLIC);
            let track = spots.stripped_width_m() * sliding.track_length_m;
            assert!(
                area <= track * (1.0 + 1e-12),
                "{speed} m/s: {area} > {track}"
            );
            if speed > 100.0 {
                // A revolution of 94 us is within t0 (1 ms): never repassivated.
                assert!((area / track - 1.0).abs() < 1e-12, "{area} against {track}");
            }
        }
    }

    #[test]
    fn rows_left_alone_keep_repassivating() {
        let sliding = Sliding {
            speed_m_s: 0.0188,
            track_length_m: 0.0188,
        };
        let mut pattern = vec![false; 200];
        pattern[50..60].fill(true);
        pattern[150..160].fill(true);
        let both = SpotRows::of(&pattern, 100, 1e-6, 1e-6, 0.0);
        assert_eq!((both.chords(), both.rows.len()), (2, 2));
        assert!((both.area_m2() - 20e-12).abs() < 1e-24);
        let mut ages = TrackAges::default();
        let first = ages.cycle_area_m2(&both, sliding, &PARABOLIC);
        // The next cycle strips only the first row: the second passes its tail.
        pattern[150..160].fill(false);
        let one = SpotRows::of(&pattern, 100, 1e-6, 1e-6, 0.0);
        let alone = TrackAges::default().cycle_area_m2(&one, sliding, &PARABOLIC);
        let next = ages.cycle_area_m2(&one, sliding, &PARABOLIC);
        let tail = 0.0188 * PARABOLIC.charge_between_s(0.5, 1.5) * 1e-6;
        assert!((next - alone - tail).abs() < 1e-22, "{next} {alone} {tail}");
        assert!(next < first);
        ages.repeat(&one, 10, sliding);
        let later = ages.cycle_area_m2(&one, sliding, &PARABOLIC);
        assert!(later < next && later > alone);
        // After the stop the bare area falls off as the power law, over minutes.
        let stop = [0.0, 1.0, 10.0, 100.0, 1000.0]
            .map(|t| ages.area_after_stop_m2(t, sliding, &PARABOLIC));
        assert!(stop.windows(2).all(|w| w[1] < w[0]), "{stop:?}");
        assert!(stop[4] > 0.0);
    }
}
