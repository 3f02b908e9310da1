//! Archard's k with a change of regime (the paper's Section 5.2 reads Table 3 as a low-wear
//! period before about 300 cycles and Archard wear after it): k before and after a cycle the
//! user gives or the fit finds, fitted over whole simulated runs as [`fit_archard`](super::fit_archard) fits one
//! k, and compared with that one-k fit.
//!
//! At a given cycle the two k's are fitted by Gauss-Newton ([`gauss_newton`]), started from
//! the one-k fit's k for both. With `auto` the cycle is searched among the whole
//! cycles between the table's points that leave each regime [`MIN_POINTS_PER_REGIME`]: a
//! golden-section search on ln n inside each interval between two points (the residuals
//! bend at the points), down to single cycles, each candidate started from the nearest one
//! already fitted.
//!
//! Which model fits better is decided by Akaike's criterion, AIC = m ln(RSS / m) + 2 p for m
//! points and p fitted parameters, a fitted change cycle counted as one. An F-test would
//! need the two-k model's extra parameters to be regular: a change cycle chosen by the fit is
//! not (its statistic has no F distribution), and AIC ranks all three fits on one scale. The
//! small-sample correction AICc is left out: with Table 3's five points and a fitted cycle
//! (four parameters with the scatter) its denominator m - p - 2 is zero.

use std::collections::BTreeMap;
use std::str::FromStr;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use serde::Serialize;
use thiserror::Error;

use super::archard::{Problem, fitted_scene, problem};
use super::minimise::{PairFit, gauss_newton, standard_errors, sum_of_squares};
use super::{ArchardFit, ArchardOptions, CalibrationError, Estimate, Table, fit_archard_until};
use crate::scene::{ArchardRegimeChange, Scene};

/// Points each regime needs: two fit its own k with one degree of freedom to spare, so a
/// table of four points leaves the two-k fit with a fitted cycle one degree of freedom.
pub const MIN_POINTS_PER_REGIME: usize = 2;

/// Step in ln k of the standard errors' central differences, as [`fit_archard`](super::fit_archard)'s: 1% is
/// far above the cycle stepping's 1e-4 noise on the volume, and the volume is linear in k
/// across it.
const ERROR_STEP: f64 = 0.01;

/// Where the regime changes: the last cycle of the first regime, or `auto` to fit it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChangeCycle {
    /// At this cycle.
    At(u64),
    /// The cycle that fits best.
    Auto,
}

/// A change cycle that is neither a whole number nor `auto`.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("expected a cycle (a whole number >= 1) or `auto`, got `{0}`")]
pub struct ChangeCycleError(String);

impl FromStr for ChangeCycle {
    type Err = ChangeCycleError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        if text == "auto" {
            return Ok(Self::Auto);
        }
        match text.parse::<u64>() {
            Ok(cycle) if cycle >= 1 => Ok(Self::At(cycle)),
            _ => Err(ChangeCycleError(text.to_owned())),
        }
    }
}

/// Settings of the two-regime fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegimeOptions {
    /// Where the regime changes.
    pub change: ChangeCycle,
    /// The one-k fit's settings; its `span` bounds both k's around its k, its `tolerance`
    /// stops the Gauss-Newton steps (relative, in k).
    pub archard: ArchardOptions,
}

/// The two-regime fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TwoRegimeFit {
    /// The last cycle of the first regime.
    pub change_cycle: u64,
    /// Whether the fit chose it (`auto`) or it was given.
    pub change_cycle_fitted: bool,
    /// Whether the fitted cycle is the first or the last one the search could try: the sum
    /// of squares still fell towards that end, where the next cycle would leave a regime
    /// fewer than [`MIN_POINTS_PER_REGIME`] points, so the table cannot place the change.
    pub change_cycle_at_search_edge: bool,
    /// k up to and including the change cycle.
    pub archard_k_before: Estimate,
    /// k after it.
    pub archard_k_after: Estimate,
    /// Residual sum of squares (weighted when the one-k fit is).
    pub rss: f64,
    /// Root-mean-square residual, mm^3.
    pub rms_residual_mm3: f64,
    /// The scene with `wear.archard_k` and `wear.archard_regime_change` filled in.
    pub scene: Scene,
}

/// One measured volume against both fitted runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RegimePoint {
    /// Cycle count.
    pub cycles: f64,
    /// Measured volume, mm^3.
    pub volume_mm3: f64,
    /// The one-k run's volume, mm^3.
    pub one_regime_model_mm3: f64,
    /// Measured minus the one-k run, mm^3.
    pub one_regime_residual_mm3: f64,
    /// The two-k run's volume, mm^3.
    pub two_regime_model_mm3: f64,
    /// Measured minus the two-k run, mm^3.
    pub two_regime_residual_mm3: f64,
}

/// A change cycle the search tried, and the best two k's there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Candidate {
    /// The last cycle of the first regime.
    pub cycle: u64,
    /// k before, or absent when the fit at this cycle did not converge.
    pub archard_k_before: Option<f64>,
    /// k after, or absent when the fit did not converge.
    pub archard_k_after: Option<f64>,
    /// Residual sum of squares, or absent when the fit did not converge.
    pub rss: Option<f64>,
}

/// A fit's score.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModelScore {
    /// Fitted parameters: the k's, and the change cycle when fitted.
    pub parameters: usize,
    /// Residual sum of squares.
    pub rss: f64,
    /// m ln(RSS / m) + 2 p.
    pub aic: f64,
}

/// One model or the other.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Regimes {
    /// One k throughout.
    OneRegime,
    /// A k before the change cycle and another after it.
    TwoRegimes,
}

/// Which fit is better, by Akaike's criterion (the module's documentation says why).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Comparison {
    /// The criterion, as computed.
    pub criterion: &'static str,
    /// The one-k fit.
    pub one_regime: ModelScore,
    /// The two-k fit.
    pub two_regimes: ModelScore,
    /// The lower AIC.
    pub better: Regimes,
    /// The worse AIC minus the better, >= 0.
    pub aic_difference: f64,
    /// exp(-difference / 2): how likely the worse model is against the better one.
    pub relative_likelihood: f64,
}

/// One k against a change of regime, side by side.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegimeFit {
    /// The one-k fit ([`fit_archard`](super::fit_archard)).
    pub one_regime: ArchardFit,
    /// The two-k fit.
    pub two_regimes: TwoRegimeFit,
    /// Each point against both.
    pub points: Vec<RegimePoint>,
    /// Which fits better and by how much.
    pub comparison: Comparison,
    /// The change cycles tried, by cycle (the given one alone when not `auto`).
    pub candidates: Vec<Candidate>,
    /// Simulated runs made, the one-k fit's included.
    pub runs: usize,
    /// Wall time of the calibration, s.
    pub wall_s: f64,
    /// The better model's scene.
    pub scene: Scene,
}

/// Fits Archard's k with a change of regime to a wear-volume table over whole simulated runs
/// of `scene`, with the one-k fit beside it.
pub fn fit_archard_regimes(
    table: &Table,
    scene: &Scene,
    options: RegimeOptions,
) -> Result<RegimeFit, CalibrationError> {
    fit_archard_regimes_until(table, scene, options, &Arc::default())
}

/// [`fit_archard_regimes`], stopped (failing with the run's `Cancelled`) once `cancel` is
/// set.
pub fn fit_archard_regimes_until(
    table: &Table,
    scene: &Scene,
    options: RegimeOptions,
    cancel: &Arc<AtomicBool>,
) -> Result<RegimeFit, CalibrationError> {
    let started = Instant::now();
    let mut problem = checked(table, scene, options.change)?;
    problem.cancel = Arc::clone(cancel);
    let cycles = problem.cycles.clone();
    let points = cycles.len();
    let one = fit_archard_until(table, scene, options.archard, cancel)?;
    let k = one.archard_k.value;
    let mut search = Search {
        problem,
        bounds: (k / options.archard.span, k * options.archard.span),
        tolerance: options.archard.tolerance,
        start: [k, k],
        fits: BTreeMap::new(),
        range: None,
    };
    let (cycle, fitted) = match options.change {
        ChangeCycle::At(cycle) => {
            search.fit_at(cycle)?;
            (cycle, false)
        }
        ChangeCycle::Auto => (search.auto(&cycles)?, true),
    };
    let best = search.best_at(cycle)?;
    let parameters = 2 + usize::from(fitted);
    let (two, model) = search.summarise(scene, cycle, &best, fitted, points - parameters)?;
    let points_side_by_side = one
        .residuals
        .iter()
        .zip(&model)
        .map(|(r, &m)| RegimePoint {
            cycles: r.cycles,
            volume_mm3: r.volume_mm3,
            one_regime_model_mm3: r.model_volume_mm3,
            one_regime_residual_mm3: r.residual_mm3,
            two_regime_model_mm3: m,
            two_regime_residual_mm3: r.volume_mm3 - m,
        })
        .collect();
    let comparison = compare(points, (one.rss, 1), (two.rss, parameters));
    let scene_out = match comparison.better {
        Regimes::OneRegime => one.scene.clone(),
        Regimes::TwoRegimes => two.scene.clone(),
    };
    Ok(RegimeFit {
        runs: one.runs + search.problem.runs,
        candidates: search.candidates(),
        one_regime: one,
        two_regimes: two,
        points: points_side_by_side,
        comparison,
        wall_s: started.elapsed().as_secs_f64(),
        scene: scene_out,
    })
}

/// Refuses what [`fit_archard_regimes`] would refuse about the table, the scene and the
/// change cycle, without any simulated run.
pub(super) fn check(
    table: &Table,
    scene: &Scene,
    change: ChangeCycle,
) -> Result<(), CalibrationError> {
    checked(table, scene, change).map(drop)
}

/// The runs' setup, once the table has enough points for two regimes and a given change
/// cycle lies inside it.
fn checked(table: &Table, scene: &Scene, change: ChangeCycle) -> Result<Problem, CalibrationError> {
    let problem = problem(table, scene)?;
    let points = problem.cycles.len();
    if points < 2 * MIN_POINTS_PER_REGIME {
        return Err(CalibrationError::TooFewPoints {
            column: "volume_mm3",
            needed: 2 * MIN_POINTS_PER_REGIME,
            got: points,
        });
    }
    if let ChangeCycle::At(cycle) = change {
        check_change(&problem.cycles, cycle)?;
    }
    Ok(problem)
}

/// Refuses a change cycle outside the table's cycles or one that leaves a regime fewer than
/// [`MIN_POINTS_PER_REGIME`] points.
fn check_change(cycles: &[f64], cycle: u64) -> Result<(), CalibrationError> {
    let (first, last) = (cycles[0], cycles[cycles.len() - 1]);
    let n = cycle as f64;
    if n < first || n >= last {
        return Err(CalibrationError::ChangeOutsideTable { cycle, first, last });
    }
    let before = cycles.partition_point(|&c| c <= n);
    let regimes = [("up to it", before), ("after it", cycles.len() - before)];
    match regimes
        .into_iter()
        .find(|&(_, got)| got < MIN_POINTS_PER_REGIME)
    {
        Some((regime, got)) => Err(CalibrationError::TooFewInRegime {
            cycle,
            regime,
            needed: MIN_POINTS_PER_REGIME,
            got,
        }),
        None => Ok(()),
    }
}

/// AIC of both fits on `points` points, each as (RSS, parameters).
fn compare(points: usize, one: (f64, usize), two: (f64, usize)) -> Comparison {
    let m = points as f64;
    let score = |(rss, parameters): (f64, usize)| ModelScore {
        parameters,
        rss,
        aic: m * (rss / m).ln() + 2.0 * parameters as f64,
    };
    let (one, two) = (score(one), score(two));
    let better = if two.aic < one.aic {
        Regimes::TwoRegimes
    } else {
        Regimes::OneRegime
    };
    let difference = (one.aic - two.aic).abs();
    Comparison {
        criterion: "AIC = m ln(RSS / m) + 2 p",
        one_regime: one,
        two_regimes: two,
        better,
        aic_difference: difference,
        relative_likelihood: (-difference / 2.0).exp(),
    }
}

/// The two-k fits made so far, by change cycle.
struct Search {
    problem: Problem,
    /// Both k's stay within these.
    bounds: (f64, f64),
    tolerance: f64,
    /// The one-k fit's k, for both, where no fit is near.
    start: [f64; 2],
    /// `None` where the fit did not converge.
    fits: BTreeMap<u64, Option<PairFit>>,
    /// The first and last cycle an `auto` search may try.
    range: Option<(u64, u64)>,
}

impl Search {
    /// The volumes at the measured cycles with k's `before` and `after` a change at `cycle`.
    fn volumes(
        &mut self,
        cycle: u64,
        before: f64,
        after: f64,
    ) -> Result<Vec<f64>, CalibrationError> {
        let change = ArchardRegimeChange {
            cycle,
            archard_k_before: before,
        };
        self.problem.volumes_with(after, Some(change))
    }

    /// Weighted residuals for `[before, after]` at `cycle`.
    fn residuals(&mut self, cycle: u64, k: [f64; 2]) -> Result<Vec<f64>, CalibrationError> {
        let model = self.volumes(cycle, k[0], k[1])?;
        Ok(self.problem.weighted_residuals(&model))
    }

    /// The residual sum of squares of the best two k's at `cycle` (fitted once, then
    /// remembered), `None` when the fit there did not converge.
    fn fit_at(&mut self, cycle: u64) -> Result<Option<f64>, CalibrationError> {
        if let Some(fit) = self.fits.get(&cycle) {
            return Ok(fit.as_ref().map(|f| f.rss));
        }
        match self.fit_or_not_converged(cycle) {
            Ok(fit) => {
                let rss = fit.rss;
                self.fits.insert(cycle, Some(fit));
                Ok(Some(rss))
            }
            Err(CalibrationError::NotConverged { .. }) => {
                self.fits.insert(cycle, None);
                Ok(None)
            }
            Err(other) => Err(other),
        }
    }

    /// The fit at `cycle`: the one remembered, or made now (so that a fit that does not
    /// converge says so, with what it tried).
    fn best_at(&mut self, cycle: u64) -> Result<PairFit, CalibrationError> {
        match self.fits.get(&cycle) {
            Some(Some(fit)) => Ok(fit.clone()),
            _ => self.fit_or_not_converged(cycle),
        }
    }

    /// Gauss-Newton at `cycle`, started from the nearest cycle fitted (or the one-k fit).
    fn fit_or_not_converged(&mut self, cycle: u64) -> Result<PairFit, CalibrationError> {
        let start = self
            .fits
            .iter()
            .filter_map(|(&c, fit)| fit.as_ref().map(|f| (c.abs_diff(cycle), f.values)))
            .min_by_key(|&(distance, _)| distance)
            .map_or(self.start, |(_, values)| values);
        let (bounds, tolerance) = ([self.bounds; 2], self.tolerance);
        gauss_newton(
            ["archard_k_before", "archard_k_after"],
            start,
            bounds,
            tolerance,
            &mut |k| self.residuals(cycle, k),
        )
    }

    /// The best change cycle between the table's points: each interval between two points
    /// that leaves both regimes enough points, searched by golden section on ln n.
    fn auto(&mut self, cycles: &[f64]) -> Result<u64, CalibrationError> {
        let m = cycles.len();
        for i in MIN_POINTS_PER_REGIME - 1..m - MIN_POINTS_PER_REGIME {
            let low = cycles[i].ceil() as u64;
            let high = (cycles[i + 1].ceil() as u64).saturating_sub(1);
            if low <= high {
                self.range = Some(self.range.map_or((low, high), |(first, _)| (first, high)));
                self.golden(low, high)?;
            }
        }
        let best = self
            .fits
            .iter()
            .filter_map(|(&c, fit)| fit.as_ref().map(|f| (c, f.rss)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(c, _)| c);
        // When every candidate failed, the first one's fit says why.
        best.or_else(|| self.fits.keys().next().copied())
            .ok_or(CalibrationError::TooFewPoints {
                column: "cycles",
                needed: 2 * MIN_POINTS_PER_REGIME,
                got: m,
            })
    }

    /// Golden section over the whole cycles `low..=high` on ln n, down to four cycles, then
    /// each of those.
    fn golden(&mut self, mut low: u64, mut high: u64) -> Result<(), CalibrationError> {
        const INVERSE_PHI: f64 = 0.618_033_988_749_894_8;
        let rss = |fit: Option<f64>| fit.unwrap_or(f64::INFINITY);
        while high - low > 3 {
            let (a, b) = ((low as f64).ln(), (high as f64).ln());
            let c = ((b - INVERSE_PHI * (b - a)).exp().round() as u64).clamp(low + 1, high - 2);
            let d = ((a + INVERSE_PHI * (b - a)).exp().round() as u64).clamp(c + 1, high - 1);
            if rss(self.fit_at(c)?) < rss(self.fit_at(d)?) {
                high = d;
            } else {
                low = c;
            }
        }
        for cycle in low..=high {
            self.fit_at(cycle)?;
        }
        Ok(())
    }

    /// The `fit` at `cycle` with its standard errors (`freedom` degrees of freedom) and
    /// scene; with the model's volumes at the measured cycles.
    fn summarise(
        &mut self,
        scene: &Scene,
        cycle: u64,
        fit: &PairFit,
        fitted: bool,
        freedom: usize,
    ) -> Result<(TwoRegimeFit, Vec<f64>), CalibrationError> {
        let se = standard_errors(fit.values, &fit.residuals, ERROR_STEP, freedom, &mut |k| {
            self.residuals(cycle, k)
        })?;
        let model = self.volumes(cycle, fit.values[0], fit.values[1])?;
        let mut filled = fitted_scene(
            scene,
            fit.values[1],
            Some(ArchardRegimeChange {
                cycle,
                archard_k_before: fit.values[0],
            }),
        );
        // The scene must run past the change for its second regime to apply.
        if filled.test.cycles <= cycle {
            filled.test.cycles = self.problem.scene.test.cycles;
        }
        let rms_residual_mm3 = self.problem.rms(&model);
        let two = TwoRegimeFit {
            change_cycle: cycle,
            change_cycle_fitted: fitted,
            change_cycle_at_search_edge: self
                .range
                .is_some_and(|(first, last)| cycle == first || cycle == last),
            archard_k_before: Estimate {
                value: fit.values[0],
                standard_error: se[0],
            },
            archard_k_after: Estimate {
                value: fit.values[1],
                standard_error: se[1],
            },
            rss: sum_of_squares(&fit.residuals),
            rms_residual_mm3,
            scene: filled,
        };
        Ok((two, model))
    }

    /// Every cycle tried, in order.
    fn candidates(&self) -> Vec<Candidate> {
        self.fits
            .iter()
            .map(|(&cycle, fit)| Candidate {
                cycle,
                archard_k_before: fit.as_ref().map(|f| f.values[0]),
                archard_k_after: fit.as_ref().map(|f| f.values[1]),
                rss: fit.as_ref().map(|f| f.rss),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests;
