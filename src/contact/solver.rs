//! The bounded contact solver: find pressures `0 <= p <= Y` carrying the load `W` such that
//! the gap `g = K p + h - delta` is zero where `0 < p < Y`, non-negative where `p = 0` and
//! non-positive where `p = Y` (the elastic-perfectly-plastic cap of eq. 12).
//!
//! # Algorithm
//! Polonsky & Keer's conjugate gradient (Wear 231, 1999) with load control, extended with the
//! upper bound. CG runs on the free cells `F = {0 < p < Y}`; `delta` is the mean of
//! `K p + h` over `F`. The search direction is projected to sum to zero over `F`, so a step
//! preserves the load exactly and needs no rescaling. Cells leaving `F` are truncated to the
//! bound they cross; cells on a bound whose gap says they should not be there (zero
//! pressure but penetrating, or at the cap but open) re-enter `F` by the Polonsky-Keer
//! rule and restart the conjugacy. When the free cells cannot move (at most one is free,
//! nearly every loaded cell at the cap), one projected steepest-descent step over the free
//! and the wrongly bounded cells takes the place of the CG step.
//!
//! # Preconditioning
//! When the operator offers one ([`Operator::preconditioner`]; [`super::DcFft`] does), the
//! direction is built from `z = M^-1 g` over the free cells instead of `g`, with the
//! Fletcher-Reeves ratio `(g.z) / (g.z)_old`: preconditioned CG on the free set. `M^-1` is
//! the inverse of the kernel wrapped onto the grid ([`super::FourierInverse`]), which
//! undoes the `1 / |k|` spread of the half-space's spectrum. Measured on the paper's Hertz
//! case (`tribosim bench contact`): 42 -> 21 iterations at N = 256, 72 -> 27 at N = 1024;
//! a warm-started wear cycle of the paper scene: about 37 -> 9.
//!
//! # Cost: one operator apply per iteration
//! The displacement `u = K p` is updated as `u - tau K t`, reusing the `K t` that the step
//! length needs, whenever the step changed no bound. Only iterations that moved a cell onto
//! or off a bound rescale to the load and recompute `u` (a second apply). Before success is
//! reported, `u` is always recomputed from `p`, so no drift from the updates survives.
//!
//! # Stopping test (relative, documented in `numerics.tolerance`)
//! `residual = max_i v_i / max_i |u_i|`, where `v_i = |g_i|` on free cells, `max(-g_i, 0)`
//! on zero cells and `max(g_i, 0)` on capped cells: the worst complementarity violation,
//! cell by cell, relative to the largest elastic displacement. The solve succeeds when
//! `residual <= tolerance` on a freshly computed `u` and the load is carried to 1e-12.

use super::{ContactError, Grid, Operator};

/// Relative load error accepted at convergence. Summing N^2 pressures in f64 errs by up to
/// N^2 * 1.1e-16 in the worst case (1.2e-10 at N = 1024), typically sqrt(N^2) times that;
/// 1e-11 is met after the final rescale and stays far inside issue 2's 1e-9.
const LOAD_TOLERANCE: f64 = 1e-11;

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Relative residual to reach (see the module documentation).
    pub tolerance: f64,
    /// Iterations allowed before [`ContactError::NotConverged`].
    pub max_iterations: usize,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-8,
            max_iterations: 2000,
        }
    }
}

/// One contact problem on a grid.
#[derive(Debug, Clone, Copy)]
pub struct ContactProblem<'a> {
    /// The grid the fields live on.
    pub grid: Grid,
    /// Separation `h` between the undeformed surfaces at zero approach, m, per cell.
    pub separation: &'a [f64],
    /// Normal load, N.
    pub load_n: f64,
    /// Pressure cap `Y`, Pa; `f64::INFINITY` for a purely elastic contact.
    pub yield_pressure_pa: f64,
}

/// A converged contact.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSolution {
    /// Pressure per cell, Pa.
    pub pressure: Vec<f64>,
    /// Elastic displacement `K p` per cell (both bodies together), m.
    pub displacement: Vec<f64>,
    /// Rigid-body approach `delta`, m.
    pub approach_m: f64,
    /// CG iterations.
    pub iterations: usize,
    /// Operator applications (each one padded FFT round trip for [`super::DcFft`]).
    pub operator_applies: usize,
    /// The relative residual reached.
    pub residual: f64,
}

impl ContactSolution {
    /// The load carried, N.
    pub fn load_n(&self, grid: &Grid) -> f64 {
        self.pressure.iter().sum::<f64>() * grid.cell_area()
    }

    /// Largest pressure, Pa.
    pub fn max_pressure_pa(&self) -> f64 {
        self.pressure.iter().fold(0.0, |m, &p| m.max(p))
    }

    /// Area of the cells in contact (p > 0), m^2.
    pub fn contact_area_m2(&self, grid: &Grid) -> f64 {
        self.pressure.iter().filter(|&&p| p > 0.0).count() as f64 * grid.cell_area()
    }

    /// Area of the cells at the cap (p = Y), m^2.
    pub fn plastic_area_m2(&self, grid: &Grid, yield_pressure_pa: f64) -> f64 {
        let capped = self
            .pressure
            .iter()
            .filter(|&&p| p >= yield_pressure_pa)
            .count();
        capped as f64 * grid.cell_area()
    }
}

/// Dot product with four independent accumulators: a single running sum is a serial chain
/// of additions (and was kept on the stack), which profiling showed as a third of the
/// solver's own time at N = 256.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in a4.zip(b4) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// Sum with four independent accumulators, as [`dot`].
fn sum(a: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let chunks = a.chunks_exact(4);
    let tail: f64 = chunks.remainder().iter().sum();
    for x in chunks {
        for k in 0..4 {
            acc[k] += x[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// `delta = mean of u + h` over the free cells, or over all loaded cells when every loaded
/// cell sits at the cap.
pub(crate) fn approach(
    pressure: &[f64],
    displacement: &[f64],
    separation: &[f64],
    cap: f64,
) -> f64 {
    let mut free = (0.0, 0usize);
    let mut loaded = (0.0, 0usize);
    for ((&p, &u), &h) in pressure.iter().zip(displacement).zip(separation) {
        if p > 0.0 {
            loaded = (loaded.0 + u + h, loaded.1 + 1);
            if p < cap {
                free = (free.0 + u + h, free.1 + 1);
            }
        }
    }
    if free.1 > 0 {
        free.0 / free.1 as f64
    } else {
        loaded.0 / loaded.1.max(1) as f64
    }
}

/// Scales the cells below the cap so the total is `target`; cells pushed over the cap are
/// clipped to it and the rest rescaled again (each pass caps at least one more cell, so
/// this ends). If the capped cells alone exceed the target, every cell is scaled down. If
/// every loaded cell is capped and the load is still short, the contact must grow: the
/// deficit goes to unloaded cells in order of increasing `u + h`, the order in which a
/// larger approach would bring them into contact. Without that, a contact that is almost
/// entirely at the cap has an empty free set and the iteration stalls.
fn rescale_to_load(pressure: &mut [f64], cap: f64, target: f64, raw_gap: &[f64]) {
    loop {
        let (mut capped, mut free) = (0.0, 0.0);
        for &p in pressure.iter() {
            if p >= cap {
                capped += cap;
            } else {
                free += p;
            }
        }
        if capped >= target {
            let scale = target / (capped + free);
            pressure.iter_mut().for_each(|p| *p *= scale);
            return;
        }
        if free <= 0.0 {
            grow_contact(pressure, cap, target - capped, raw_gap);
            return;
        }
        let scale = (target - capped) / free;
        let mut clipped = false;
        for p in pressure.iter_mut().filter(|p| **p < cap) {
            *p *= scale;
            if *p >= cap {
                *p = cap;
                clipped = true;
            }
        }
        if !clipped {
            return;
        }
    }
}

fn grow_contact(pressure: &mut [f64], cap: f64, mut deficit: f64, raw_gap: &[f64]) {
    let mut unloaded: Vec<usize> = (0..pressure.len())
        .filter(|&i| pressure[i] <= 0.0)
        .collect();
    unloaded.sort_unstable_by(|&i, &j| raw_gap[i].total_cmp(&raw_gap[j]));
    for i in unloaded {
        if deficit <= 0.0 {
            break;
        }
        pressure[i] = deficit.min(cap);
        deficit -= pressure[i];
    }
}

fn validate(problem: &ContactProblem, options: &SolverOptions) -> Result<(), ContactError> {
    let invalid = |m: String| Err(ContactError::InvalidProblem(m));
    if problem.separation.len() != problem.grid.len() {
        return invalid(format!(
            "separation has {} values for {} cells",
            problem.separation.len(),
            problem.grid.len()
        ));
    }
    if let Some(i) = problem.separation.iter().position(|h| !h.is_finite()) {
        return invalid(format!("separation[{i}] is not finite"));
    }
    if !(problem.load_n.is_finite() && problem.load_n > 0.0) {
        return invalid(format!("load {} N: must be finite and > 0", problem.load_n));
    }
    if problem.yield_pressure_pa.is_nan() || problem.yield_pressure_pa <= 0.0 {
        return invalid(format!(
            "yield pressure {} Pa: must be > 0 (infinite for no cap)",
            problem.yield_pressure_pa
        ));
    }
    if !(options.tolerance > 0.0 && options.tolerance.is_finite()) {
        return invalid(format!("tolerance {}: must be > 0", options.tolerance));
    }
    Ok(())
}

/// Solves one contact problem on `operator`, optionally warm-started from `warm_start`
/// (e.g. the previous wear cycle's pressure). Fails with a named [`ContactError`], never
/// silently: an impossible load, a contact reaching the domain edge, or no convergence.
pub fn solve(
    operator: &mut dyn Operator,
    problem: &ContactProblem,
    options: &SolverOptions,
    warm_start: Option<&[f64]>,
) -> Result<ContactSolution, ContactError> {
    validate(problem, options)?;
    let grid = problem.grid;
    let (n, h, cap) = (grid.len(), problem.separation, problem.yield_pressure_pa);
    let target = problem.load_n / grid.cell_area();
    if target >= cap * n as f64 {
        return Err(ContactError::LoadExceedsCapacity {
            load_n: problem.load_n,
            capacity_n: cap * grid.area(),
        });
    }

    let mut p = match warm_start {
        Some(w) if w.len() == n && w.iter().any(|&v| v > 0.0) => {
            w.iter().map(|&v| v.clamp(0.0, cap)).collect()
        }
        _ => vec![target / n as f64; n],
    };
    // Before the first apply the displacement is unknown: order by the separation alone.
    rescale_to_load(&mut p, cap, target, h);
    let mut u = vec![0.0; n];
    operator.apply(&p, &mut u);
    let mut applies = 1;
    let mut fresh = true;

    let (mut t, mut r, mut g) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    // 1 on the free cells, 0 elsewhere: the sums over the free set become dot products,
    // with no branch and no accumulator chained through memory.
    let mut free = vec![0.0; n];
    let preconditioned = operator.preconditioner().is_some();
    let mut z = if preconditioned {
        vec![0.0; n]
    } else {
        Vec::new()
    };
    // Pressure per unit of gap given to a re-entering cell (Polonsky-Keer: the last step
    // length, for a direction made of gaps).
    let mut entry_rate = 0.0;
    let mut rho_old = 0.0;
    let mut restart = true;
    let mut tau_last = 0.0;
    let mut residual = f64::INFINITY;
    let is_free = |v: f64| v > 0.0 && v < cap;

    for iteration in 1..=options.max_iterations {
        let delta = approach(&p, &u, h, cap);
        // The gap, the free mask, the gap on the free cells (into r, free until the apply
        // below) and the worst complementarity violation.
        let (mut worst, mut u_max, mut load) = (0.0f64, 0.0f64, 0.0);
        for i in 0..n {
            let (pi, gi) = (p[i], u[i] + h[i] - delta);
            g[i] = gi;
            u_max = u_max.max(u[i].abs());
            load += pi;
            let violation = if pi <= 0.0 {
                (-gi).max(0.0)
            } else if pi >= cap {
                gi.max(0.0)
            } else {
                gi.abs()
            };
            worst = worst.max(violation);
            free[i] = if is_free(pi) { 1.0 } else { 0.0 };
            r[i] = free[i] * gi;
        }
        residual = worst / u_max;
        if residual <= options.tolerance {
            if (load - target).abs() > LOAD_TOLERANCE * target {
                // Round-off in many small steps moved the load: restore it exactly.
                rescale_to_load(&mut p, cap, target, &g);
                operator.apply(&p, &mut u);
                applies += 1;
                fresh = true;
                continue;
            }
            if fresh {
                check_edges(&grid, &p, target)?;
                return Ok(ContactSolution {
                    pressure: p,
                    displacement: u,
                    approach_m: delta,
                    iterations: iteration - 1,
                    operator_applies: applies,
                    residual,
                });
            }
            // Converged on the updated displacement: confirm on a fresh one.
            operator.apply(&p, &mut u);
            applies += 1;
            fresh = true;
            continue;
        }

        // The preconditioned gap z = M^-1 g over the free cells (z = g without one), then
        // the conjugate direction over the free cells, projected to sum to zero there, so
        // a step keeps the load. (g sums to zero by the choice of delta, up to round-off.)
        let n_free = sum(&free);
        let t_old_sum = dot(&free, &t);
        let (rho, z_sum) = match operator.preconditioner() {
            Some(inverse) => {
                inverse.apply(&r, &mut z);
                (dot(&r, &z), dot(&free, &z))
            }
            None => (dot(&r, &r), sum(&r)),
        };
        let beta = if restart || rho_old == 0.0 {
            0.0
        } else {
            rho / rho_old
        };
        rho_old = rho;
        let t_mean = if n_free > 0.0 {
            (z_sum + beta * t_old_sum) / n_free
        } else {
            0.0
        };
        let source = if preconditioned { &z } else { &g };
        for ((ti, &si), &fi) in t.iter_mut().zip(source).zip(&free) {
            *ti = fi * (si + beta * *ti - t_mean);
        }
        let num = dot(&g, &t);
        if num <= 0.0 {
            // The free cells cannot move: at most one is free (a load-preserving step over
            // one cell is zero), nearly every loaded cell at the cap. The re-entry rule alone
            // then stalls (no step length yet) or cycles (the rescale to the load sends the
            // re-entered cells back to the cap), as a softening disc's warm starts showed.
            // Step instead along the gap over the free and the wrongly bounded cells; if
            // there is no such direction, start again from the uniform pressure.
            if !violator_step(operator, &mut p, &g, &mut t, &mut r, cap, &mut applies) {
                p.fill(target / n as f64);
            }
            rescale_to_load(&mut p, cap, target, &g);
            operator.apply(&p, &mut u);
            applies += 1;
            fresh = true;
            restart = true;
            continue;
        }

        operator.apply(&t, &mut r);
        applies += 1;
        let den = dot(&t, &r);
        let tau = if den > 0.0 { num / den } else { tau_last };
        if tau > 0.0 {
            tau_last = tau;
        }
        // A preconditioned direction is not made of gaps, so its step length is no
        // pressure per gap; the direction's own compliance t.t / t.Kt is, and matches
        // Polonsky-Keer's rate when t is the gap.
        // A direction without a positive t.Kt (only the non-symmetric coupled operator can
        // give one; no direction at all took the steepest-descent branch above) keeps the
        // last rate: a preconditioned step length has other units and would stall re-entry.
        let rate = if !preconditioned {
            tau
        } else if den > 0.0 {
            dot(&t, &t) / den
        } else {
            entry_rate
        };
        if rate > 0.0 {
            entry_rate = rate;
        }

        // Step, truncation at the bounds, re-entry of wrongly bounded cells; u follows the
        // step and is recomputed below if any bound changed.
        let (mut bounds_hit, mut entered) = (false, false);
        for i in 0..n {
            let pi = &mut p[i];
            if is_free(*pi) {
                *pi -= tau * t[i];
                if *pi <= 0.0 {
                    *pi = 0.0;
                    bounds_hit = true;
                } else if *pi >= cap {
                    *pi = cap;
                    bounds_hit = true;
                }
            } else if *pi <= 0.0 && g[i] < 0.0 {
                *pi = (-entry_rate * g[i]).min(cap);
                entered = true;
            } else if *pi >= cap && g[i] > 0.0 {
                *pi = (cap - entry_rate * g[i]).max(0.0);
                entered = true;
            }
            u[i] -= tau * r[i];
        }
        if bounds_hit || entered {
            rescale_to_load(&mut p, cap, target, &g);
            operator.apply(&p, &mut u);
            applies += 1;
        }
        fresh = bounds_hit || entered;
        restart = entered;
    }
    Err(ContactError::NotConverged {
        iterations: options.max_iterations,
        residual,
        tolerance: options.tolerance,
    })
}

/// Projected steepest descent over the cells that may move: the free ones and those on a
/// bound whose gap says they should leave it (zero pressure but penetrating, at the cap but
/// open). The direction is the gap there, less its mean so the load is kept; the step is the
/// exact line search `g.t / t.Kt`, then cut at the bounds. False (and `p` unchanged) when
/// there is no descent direction: at most one such cell, or their gaps all equal.
fn violator_step(
    operator: &mut dyn Operator,
    p: &mut [f64],
    g: &[f64],
    t: &mut [f64],
    kt: &mut [f64],
    cap: f64,
    applies: &mut usize,
) -> bool {
    let movable = |pi: f64, gi: f64| {
        (pi > 0.0 && pi < cap) || (pi <= 0.0 && gi < 0.0) || (pi >= cap && gi > 0.0)
    };
    let (mut sum, mut count) = (0.0, 0usize);
    for (&pi, &gi) in p.iter().zip(g) {
        if movable(pi, gi) {
            sum += gi;
            count += 1;
        }
    }
    let mean = sum / count.max(1) as f64;
    for ((ti, &pi), &gi) in t.iter_mut().zip(p.iter()).zip(g) {
        *ti = if movable(pi, gi) { gi - mean } else { 0.0 };
    }
    let num = dot(g, t);
    if num <= 0.0 {
        return false;
    }
    operator.apply(t, kt);
    *applies += 1;
    let den = dot(t, kt);
    if den <= 0.0 {
        return false;
    }
    let tau = num / den;
    for (pi, &ti) in p.iter_mut().zip(t.iter()) {
        *pi = (*pi - tau * ti).clamp(0.0, cap);
    }
    true
}

/// Success is refused when the outermost ring of cells carries load: the half-space outside
/// the domain would have carried some too, so the answer is not that of the real contact.
fn check_edges(grid: &Grid, pressure: &[f64], target: f64) -> Result<(), ContactError> {
    let (mut cells, mut sum) = (0usize, 0.0);
    for (i, &p) in pressure.iter().enumerate() {
        if p > 0.0 && grid.is_edge(i) {
            cells += 1;
            sum += p;
        }
    }
    if cells > 0 {
        return Err(ContactError::ContactAtEdge {
            edge_cells: cells,
            edge_load_fraction: sum / target,
        });
    }
    Ok(())
}
