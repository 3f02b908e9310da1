//! The warm start of each contact solve. Between solves the surface changes smoothly (Archard
//! wear nearly constant per cycle), so a linear extrapolation of the last two pressures in
//! the cycle number starts much closer than the last pressure alone (clipped to `[0, Y]`);
//! right after a regrid, with no earlier pressure on the new grid, the last one is used as
//! it is.

/// The last two solved pressures and their cycles.
#[derive(Debug, Default)]
pub(super) struct WarmStart {
    last: Option<(u64, Vec<f64>)>,
    before: Option<(u64, Vec<f64>)>,
}

impl WarmStart {
    /// Records the pressure of `cycle`; a pressure from before a regrid (another size)
    /// cannot be extrapolated from and is forgotten.
    pub(super) fn push(&mut self, cycle: u64, pressure: Vec<f64>) {
        let size = pressure.len();
        self.before = self
            .last
            .replace((cycle, pressure))
            .filter(|(_, p)| p.len() == size);
    }

    /// The last solved pressure, on the grid as it is now.
    pub(super) fn last(&self) -> Option<&[f64]> {
        self.last.as_ref().map(|(_, p)| p.as_slice())
    }

    /// The guess for `cycle` under the cap `cap`, or `None` before the first solve.
    pub(super) fn guess(&self, cycle: u64, cap: f64) -> Option<Vec<f64>> {
        let (c1, p1) = self.last.as_ref()?;
        let Some((c0, p0)) = self.before.as_ref() else {
            return Some(p1.clone());
        };
        let ratio = (cycle - c1) as f64 / (c1 - c0) as f64;
        Some(
            p1.iter()
                .zip(p0)
                .map(|(&a, &b)| (a + ratio * (a - b)).clamp(0.0, cap))
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extrapolates_in_the_cycle_number_and_forgets_across_a_regrid() {
        let mut warm = WarmStart::default();
        assert!(warm.guess(1, 10.0).is_none());
        warm.push(1, vec![1.0, 4.0]);
        assert_eq!(warm.guess(2, 10.0), Some(vec![1.0, 4.0]));
        warm.push(3, vec![2.0, 2.0]);
        // Two cycles on from cycle 3 at the slope of cycles 1 to 3, clipped to [0, 10].
        assert_eq!(warm.guess(5, 10.0), Some(vec![3.0, 0.0]));
        warm.push(5, vec![1.0, 1.0, 1.0]);
        assert_eq!(warm.guess(6, 10.0), Some(vec![1.0, 1.0, 1.0]));
    }
}
