//! The warm start of each contact solve. Between solves the surface changes smoothly (Archard
//! wear nearly constant per cycle), so a linear extrapolation in the cycle number of the last
//! two solves starts much closer than the last pressure alone; right after a regrid, with no
//! earlier solve on the new grid, the last pressure is used as it is.
//!
//! What is extrapolated is not the pressure but `q = p - c g` (gap `g = u + h - delta`, `c`
//! a contact stiffness): `q = p` in contact (the gap vanishes there), `-c g < 0` out of it,
//! `Y - c g >= Y` under the cap; the guess is `q` clipped to `[0, Y]`. A pressure
//! extrapolation keeps every cell unloaded in both solves unloaded, so the cells the
//! widening groove brings into contact at the rim can only enter during the solve, a few
//! per iteration; a closing gap extrapolates past zero and enters them in the guess.
//! Paper scene `{}` (`tribosim run`, `summary.iterations / summary.solves`, with the
//! preconditioner of the whole grid, [`crate::contact::Preconditioning::WholeGrid`]): 6.3 iterations
//! a solve instead of 7.0 with the pressure extrapolated (`c = 0`). The iterations barely
//! depend on `c` between 0.03 and 0.2 `E* / dx` (6.3 to 6.5), and rise again beyond (7.3 at
//! 1, 7.9 at 3: large guessed pressures at the rim leave contact again).
//!
//! On a rough disc the start is the last pressure itself, clipped to the cap: from cycle to
//! cycle the asperities' pressures move by steps that do not continue (the per-pass
//! profile's changes are uncorrelated from one cycle to the next, `docs/accuracy.md`,
//! "Rough wear: speed levers"), so a line through the last two solves adds a change that
//! does not come. The 4 um cut-off disc of that section (rms 0.1 um, seed 1), with a build
//! that switched the extrapolation on for rough discs against the same build without: every
//! cycle solved over 150 cycles, 10.5 iterations a solve extrapolated against 10.3 from the
//! last `q`; over 600 cycles at the default step bound, 5559 against 5117. Nor is the gap
//! term of `q` kept there: on the same disc over 600 cycles with the default numerics
//! (`tribosim run`, `summary.iterations`), 3465 iterations from the last `q` clipped
//! against 3004 from the last pressure, the results within 2e-4 of each other. The exact
//! last pressure is also what lets the windowed solver reuse the displacement its check
//! computed for it (`crate::contact::WindowedSolver`). On the smooth discs the
//! extrapolation keeps its lead: the paper scene `{}` takes 4.7 iterations a solve
//! extrapolated and 6.2 from the last pressure, and the same over 600 cycles 4.4 against
//! 6.9.

/// The contact stiffness `c` of `q = p - c g`, as a fraction of `E* / dx` (the pressure per
/// gap of one cell pressed alone is about `E* / dx`; within a contact its neighbours'
/// load makes it softer). Measured above: the middle of the plateau.
const STIFFNESS_PER_CELL: f64 = 0.1;

/// The last two solves (`q` as above) and their cycles, and the last pressure.
#[derive(Debug)]
pub(super) struct WarmStart {
    /// `c` of `q = p - c g`, Pa/m.
    stiffness: f64,
    last: Option<(u64, Vec<f64>)>,
    before: Option<(u64, Vec<f64>)>,
    pressure: Vec<f64>,
    /// Whether the guess extrapolates (a smooth disc) or is the last pressure (a rough one).
    extrapolates: bool,
}

impl WarmStart {
    /// No solve yet, on grids of cells `cell_m` across between bodies of reduced modulus
    /// `reduced_modulus_pa`; the guesses extrapolate when the disc is smooth (`rough`
    /// false).
    pub(super) fn new(reduced_modulus_pa: f64, cell_m: f64, rough: bool) -> Self {
        Self {
            stiffness: STIFFNESS_PER_CELL * reduced_modulus_pa / cell_m,
            last: None,
            before: None,
            pressure: Vec::new(),
            extrapolates: !rough,
        }
    }

    /// Forgets every solve (the grid changed under a failed one).
    pub(super) fn forget(&mut self) {
        self.last = None;
        self.before = None;
        self.pressure.clear();
    }

    /// Whether [`Self::push`] needs the solve's gap: only an extrapolating start keeps `q`.
    pub(super) fn needs_gap(&self) -> bool {
        self.extrapolates
    }

    /// Records the pressure of `cycle` and, when the start extrapolates, its gap (`None`
    /// otherwise: a rough disc's start uses neither the gap nor `q`); a solve from before a
    /// regrid (another size) cannot be extrapolated from and is forgotten.
    pub(super) fn push(&mut self, cycle: u64, pressure: Vec<f64>, gap: Option<&[f64]>) {
        let size = pressure.len();
        let c = self.stiffness;
        let signed = match gap {
            Some(gap) => pressure.iter().zip(gap).map(|(&p, &g)| p - c * g).collect(),
            None => {
                assert!(!self.extrapolates, "an extrapolating start needs the gap");
                Vec::new()
            }
        };
        self.pressure = pressure;
        self.before = self
            .last
            .replace((cycle, signed))
            .filter(|(_, q)| q.len() == size);
    }

    /// The last solved pressure, on the grid as it is now.
    pub(super) fn last(&self) -> Option<&[f64]> {
        self.last.as_ref().map(|_| self.pressure.as_slice())
    }

    /// The guess for `cycle` under the cap `cap`, or `None` before the first solve.
    pub(super) fn guess(&self, cycle: u64, cap: f64) -> Option<Vec<f64>> {
        let (c1, q1) = self.last.as_ref()?;
        if !self.extrapolates {
            return Some(self.pressure.iter().map(|&p| p.clamp(0.0, cap)).collect());
        }
        let ratio = match self.before.as_ref() {
            Some((c0, _)) => (cycle - c1) as f64 / (c1 - c0) as f64,
            None => 0.0,
        };
        let q0 = self.before.as_ref().map_or(q1, |(_, q)| q);
        Some(
            q1.iter()
                .zip(q0)
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
        // c = 0.1 * 10 / 1 = 1 Pa/m: q = p - g.
        let mut warm = WarmStart::new(10.0, 1.0, false);
        assert!(warm.guess(1, 10.0).is_none());
        warm.push(1, vec![1.0, 4.0], Some(&[0.0, 0.0]));
        assert_eq!(warm.guess(2, 10.0), Some(vec![1.0, 4.0]));
        warm.push(3, vec![2.0, 2.0], Some(&[0.0, 0.0]));
        // Two cycles on from cycle 3 at the slope of cycles 1 to 3, clipped to [0, 10].
        assert_eq!(warm.guess(5, 10.0), Some(vec![3.0, 0.0]));
        warm.push(5, vec![1.0, 1.0, 1.0], Some(&[0.0; 3]));
        assert_eq!(warm.guess(6, 10.0), Some(vec![1.0, 1.0, 1.0]));
        warm.forget();
        assert!(warm.guess(7, 10.0).is_none());
    }

    #[test]
    fn a_rough_disc_starts_from_the_last_pressure() {
        let mut warm = WarmStart::new(10.0, 1.0, true);
        warm.push(1, vec![1.0, 4.0], Some(&[0.0, 0.0]));
        warm.push(3, vec![2.0, 12.0], Some(&[0.5, -0.5]));
        // Extrapolated, cycle 5 would start from [2, 10] (q = p - g: [1.5, 12.5] at cycle
        // 3); rough, from the last pressure under the cap, the gaps left out.
        assert_eq!(warm.guess(5, 10.0), Some(vec![2.0, 10.0]));
        assert_eq!(warm.guess(5, 20.0), Some(vec![2.0, 12.0]));
    }

    #[test]
    fn only_an_extrapolating_start_needs_the_gap() {
        let mut rough = WarmStart::new(10.0, 1.0, true);
        assert!(!rough.needs_gap());
        rough.push(1, vec![1.0, 4.0], None);
        assert_eq!(rough.guess(2, 10.0), Some(vec![1.0, 4.0]));
        assert_eq!(rough.last(), Some(&[1.0, 4.0][..]));
        assert!(WarmStart::new(10.0, 1.0, false).needs_gap());
    }

    #[test]
    fn a_closing_gap_enters_the_guess_and_an_opening_one_stays_out() {
        let mut warm = WarmStart::new(10.0, 1.0, false);
        // Both cells unloaded; the first one's gap closes by 2 per cycle, the second's opens.
        warm.push(1, vec![0.0, 0.0], Some(&[3.0, 1.0]));
        warm.push(2, vec![0.0, 0.0], Some(&[1.0, 2.0]));
        // Cycle 3 extrapolates the first gap to -1: pressure c * 1 = 1.
        assert_eq!(warm.guess(3, 10.0), Some(vec![1.0, 0.0]));
        assert_eq!(warm.last(), Some(&[0.0, 0.0][..]));
    }
}
