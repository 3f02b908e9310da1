//! An axis's ticks: round values 1, 2 or 5 times a power of ten apart, each labelled with
//! the same number of decimals, so an axis reads "0.5, 1.0, 1.5" and never "0.5000, 1,
//! 1.500" (what a per-value shortest form gives).

/// The ticks of one axis and how their labels are written.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    /// The tick values, increasing, all inside the axis's range.
    pub values: Vec<f64>,
    /// The distance between neighbouring ticks.
    step: f64,
}

/// Ticks at most this many: readable at the figures' 760 px width with 15 px labels.
const MOST: usize = 8;

/// Labels switch to powers of ten for steps below this, or values at or above
/// [`LARGEST_FIXED`]: past them a fixed-point label runs to seven or more digits.
const SMALLEST_FIXED_STEP: f64 = 1e-4;
const LARGEST_FIXED: f64 = 1e6;

impl Ticks {
    /// The ticks of `[low, high]`: the roundest step that gives at most [`MOST`] of them.
    pub fn of(low: f64, high: f64) -> Self {
        let span = (high - low).abs().max(f64::MIN_POSITIVE);
        let raw = span / MOST as f64;
        let power = 10f64.powf(raw.log10().floor());
        let count = |step: f64| (high / step).floor() - (low / step).ceil() + 1.0;
        let step = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * power)
            .find(|s| count(*s) <= MOST as f64)
            .unwrap_or(20.0 * power);
        let first = (low / step).ceil() as i64;
        let last = (high / step).floor() as i64;
        // k * step can land a rounding error outside the range at either end.
        let values = (first..=last)
            .map(|k| k as f64 * step)
            .filter(|v| (low..=high).contains(v))
            .collect();
        Self { values, step }
    }

    /// The label of `value`, one of the ticks: the step's decimals, or its powers of ten.
    pub fn label(&self, value: f64) -> String {
        // A tick at zero computed as k * step is exactly 0; -0.0 would print "-0.0".
        let value = if value.abs() < 1e-9 * self.step {
            0.0
        } else {
            value
        };
        let largest = self.values.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        let step_power = self.step.log10().floor();
        if self.step < SMALLEST_FIXED_STEP || largest >= LARGEST_FIXED {
            let digits = (largest.log10().floor() - step_power).max(0.0) as usize;
            format!("{value:.digits$e}")
        } else {
            let decimals = (-step_power).max(0.0) as usize;
            format!("{value:.decimals$}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Ticks;

    fn labels(low: f64, high: f64) -> Vec<String> {
        let ticks = Ticks::of(low, high);
        ticks.values.iter().map(|v| ticks.label(*v)).collect()
    }

    #[test]
    fn an_axis_labels_every_tick_with_the_same_decimals() {
        assert_eq!(
            labels(-0.2, 3.6),
            ["0.0", "0.5", "1.0", "1.5", "2.0", "2.5", "3.0", "3.5"]
        );
        assert_eq!(
            labels(-0.41, -0.09),
            [
                "-0.40", "-0.35", "-0.30", "-0.25", "-0.20", "-0.15", "-0.10"
            ]
        );
        assert_eq!(
            labels(-180.0, 3780.0),
            ["0", "500", "1000", "1500", "2000", "2500", "3000", "3500"]
        );
    }

    #[test]
    fn a_tick_at_zero_reads_zero_not_a_rounding_remainder() {
        let ticks = Ticks::of(-1.0, 1.0);
        assert!(ticks.values.contains(&0.0));
        assert_eq!(ticks.label(5.6e-17), "0.0");
        assert_eq!(ticks.label(-5.6e-17), "0.0");
    }

    #[test]
    fn tiny_and_huge_values_use_powers_of_ten_with_one_mantissa_width() {
        assert_eq!(
            labels(1e-7, 4.1e-7),
            [
                "1.0e-7", "1.5e-7", "2.0e-7", "2.5e-7", "3.0e-7", "3.5e-7", "4.0e-7"
            ]
        );
        assert_eq!(
            labels(1.0e6, 1.3e6),
            [
                "1.00e6", "1.05e6", "1.10e6", "1.15e6", "1.20e6", "1.25e6", "1.30e6"
            ]
        );
    }

    #[test]
    fn at_most_eight_ticks_and_all_inside_the_range() {
        for (low, high) in [(0.0, 1.0), (0.013, 0.0871), (-5.0, 1e3), (2.0, 2.0 + 1e-9)] {
            let ticks = Ticks::of(low, high);
            assert!(
                !ticks.values.is_empty() && ticks.values.len() <= 8,
                "{low}..{high}: {ticks:?}"
            );
            assert!(
                ticks.values.iter().all(|v| (low..=high).contains(v)),
                "{ticks:?}"
            );
        }
    }
}
