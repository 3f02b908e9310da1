//! The depassivated area of a sliding contact: the metal the contact strips of its passive
//! film, bare until the film grows back (`docs/corrosion.md`).
//!
//! Landolt, Mischler and Stemp (Electrochim. Acta 46 (2001) 3913) write the wear-accelerated
//! corrosion current as the charge needed to repassivate a unit of bare area, Q_p, times the
//! area stripped per unit time; with the bare metal dissolving at i_a until it repassivates
//! after a time tau, Q_p = i_a tau. Bowden and Tabor's real contact carries the load on
//! A_r = F / H. Each spot of it is stripped as it enters the contact, stays bare while it
//! crosses the contact (L / v, L its chord along the sliding direction) and for tau after it
//! leaves, so in steady state the bare area is the stripping rate times the mean bare time:
//!
//! A_a = (A_r v / L) (L / v + tau) = A_r (1 + v tau / L).
//!
//! On the solved contact the mean chord is its area A_s over the width it sweeps, W_c (each
//! row's separate chords counted, so a rough contact's islands each leave a wake):
//! A_a = A_r (1 + v tau W_c / A_s). The band form strips a band of fixed width W instead,
//! A_a = A_r + W v tau.

use super::spots::SpotRows;

/// The solved contact as the wake sees it: its area and the width it sweeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// Area in contact, A_s, m^2.
    pub area_m2: f64,
    /// The sum over the rows across the track of the row's separate contact chords times
    /// the row's width, W_c, m: the contact's width for a smooth contact.
    pub swept_width_m: f64,
}

impl ContactGeometry {
    /// The geometry of the cells `in_contact`, rows of `nx` cells along the sliding
    /// direction, each `dx` long and `dy` wide: the chords [`SpotRows`] finds in them.
    pub fn of(in_contact: &[bool], nx: usize, dx: f64, dy: f64) -> Self {
        let rows = SpotRows::of(in_contact, nx, dx, dy, 0.0);
        Self {
            area_m2: rows.area_m2(),
            swept_width_m: rows.chords() as f64 * dy,
        }
    }

    /// The mean chord along the sliding direction, A_s / W_c, m; `None` without contact.
    pub fn mean_chord_m(&self) -> Option<f64> {
        (self.swept_width_m > 0.0).then(|| self.area_m2 / self.swept_width_m)
    }
}

/// What one cycle offers the anodic area models, in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaInputs {
    /// The real contact F / H, m^2.
    pub real_contact_m2: f64,
    /// The solved contact's area, m^2.
    pub contact_area_m2: f64,
    /// The solved contact's mean chord along the sliding, m; `None` without contact.
    pub mean_chord_m: Option<f64>,
    /// The wear track, worn width times track length, m^2.
    pub wear_track_m2: f64,
    /// The band of the band model, m.
    pub band_width_m: f64,
    /// The sliding speed, m/s.
    pub sliding_speed_m_s: f64,
    /// The spot models' bare-equivalent area over the cycle (`spots`), m^2; 0 for the
    /// others.
    pub spot_area_m2: f64,
}

/// The depassivated area of the wake model, A_r (1 + v tau / L) with L the solved contact's
/// mean chord `mean_chord_m`, m^2: the real contact `real_contact_m2` alone without a
/// solved contact.
pub fn wake_area_m2(
    real_contact_m2: f64,
    mean_chord_m: Option<f64>,
    sliding_speed_m_s: f64,
    repassivation_time_s: f64,
) -> f64 {
    match mean_chord_m {
        Some(chord) => real_contact_m2 * (1.0 + sliding_speed_m_s * repassivation_time_s / chord),
        None => real_contact_m2,
    }
}

/// The depassivated area of the band model, A_r + W v tau, m^2.
pub fn band_area_m2(
    real_contact_m2: f64,
    band_width_m: f64,
    sliding_speed_m_s: f64,
    repassivation_time_s: f64,
) -> f64 {
    real_contact_m2 + band_width_m * sliding_speed_m_s * repassivation_time_s
}

/// The bare area `since_stop_s` after the sliding stopped, when it was `area_at_stop_m2`:
/// nothing strips the film any more, and each bare spot repassivates with the first-order
/// kinetics whose time constant is tau (the current of a spot decays as exp(-t / tau), and
/// its integral i_a tau is the Q_p of the sliding), m^2.
pub fn recovering_area_m2(
    area_at_stop_m2: f64,
    since_stop_s: f64,
    repassivation_time_s: f64,
) -> f64 {
    if repassivation_time_s > 0.0 {
        area_at_stop_m2 * (-since_stop_s / repassivation_time_s).exp()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_smooth_contact_sweeps_its_width_and_islands_each_count() {
        // A 3 x 3 block of cells in a 5 x 5 grid of 2 x 1 um cells: 3 rows of one chord.
        let mut cells = vec![false; 25];
        for iy in 1..4 {
            for ix in 1..4 {
                cells[iy * 5 + ix] = true;
            }
        }
        let block = ContactGeometry::of(&cells, 5, 2e-6, 1e-6);
        // Counts times cell sizes: exact up to one rounding of the products.
        assert!((block.area_m2 - 18e-12).abs() < 1e-25);
        assert!((block.swept_width_m - 3e-6).abs() < 1e-20);
        let chord = block.mean_chord_m().expect("in contact");
        assert!((chord - 6e-6).abs() < 1e-20, "{chord}");
        // Split each row in two islands: the same width carries twice the chords.
        for iy in 1..4 {
            cells[iy * 5 + 2] = false;
        }
        let split = ContactGeometry::of(&cells, 5, 2e-6, 1e-6);
        assert!((split.swept_width_m - 6e-6).abs() < 1e-20);
        assert!((split.mean_chord_m().expect("in contact") - 2e-6).abs() < 1e-20);
        let none = ContactGeometry::of(&[false; 25], 5, 2e-6, 1e-6);
        assert_eq!(none.mean_chord_m(), None);
    }

    #[test]
    fn the_wake_is_the_stripping_rate_times_the_bare_time() {
        // A_r = 2e-9 m^2, chord 50 um, 20 mm/s: a spot crosses in 2.5 ms; bare for 0.1 s
        // more, the area grows by 1 + 0.1 / 2.5e-3 = 41.
        let contact = ContactGeometry {
            area_m2: 5e-9,
            swept_width_m: 1e-4,
        };
        let chord = contact.mean_chord_m();
        let area = wake_area_m2(2e-9, chord, 0.02, 0.1);
        assert!((area / 2e-9 - 41.0).abs() < 1e-12, "{area}");
        assert!((wake_area_m2(2e-9, chord, 0.02, 0.0) - 2e-9).abs() < 1e-24);
        assert!((wake_area_m2(2e-9, None, 0.02, 0.1) - 2e-9).abs() < 1e-24);
        // The band of the same width strips W v tau beside the contact.
        let band = band_area_m2(2e-9, 1e-4, 0.02, 0.1);
        assert!((band - 2.02e-7).abs() < 1e-20, "{band}");
    }

    #[test]
    fn after_the_stop_the_bare_area_decays_with_tau() {
        let at_stop = 8e-8;
        assert!((recovering_area_m2(at_stop, 0.0, 0.15) - at_stop).abs() < 1e-22);
        let after_tau = recovering_area_m2(at_stop, 0.15, 0.15);
        assert!((after_tau / at_stop - (-1.0f64).exp()).abs() < 1e-15);
        assert!(recovering_area_m2(at_stop, 1.0, 0.0).abs() < f64::MIN_POSITIVE);
    }
}
