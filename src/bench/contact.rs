//! The Hertz benchmark of issue 2: the paper's case (R 3 mm, F 5 N, alumina on 316L, domain
//! 0.256 mm, apex on a cell corner, tolerance 1e-8) at several grid sizes.

use serde::Serialize;

use crate::contact::{
    ContactError, ContactProblem, DcFft, ElasticPair, Grid, Hertz, Kernel, Material, SolverOptions,
    solve,
};

use super::{FftPair, median_time};

/// One grid size of the contact benchmark.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactRow {
    /// Cells per side.
    pub n: usize,
    /// Kernel and operator construction plus solve, s (median).
    pub wall_s: f64,
    /// Kernel and operator construction, s (median).
    pub build_s: f64,
    /// Solve alone, s (median).
    pub solve_s: f64,
    /// CG iterations.
    pub iterations: usize,
    /// Operator applications.
    pub applies: usize,
    /// One padded 2N x 2N forward + inverse real FFT, s (median, same run).
    pub fft_pair_s: f64,
    /// Time per iteration in FFT pairs: `solve_s / iterations / fft_pair_s`.
    pub iteration_per_fft_pair: f64,
    /// `p_max / p0 - 1`.
    pub err_pmax: f64,
    /// `area / (pi a^2) - 1`.
    pub err_area: f64,
    /// `delta / (a^2 / R) - 1`.
    pub err_delta: f64,
}

/// The paper's elastic pair and Hertz solution.
pub fn paper_hertz() -> (ElasticPair, Hertz) {
    let pair = ElasticPair::new(
        Material {
            youngs_modulus_pa: 300e9,
            poisson_ratio: 0.21,
        },
        Material {
            youngs_modulus_pa: 205e9,
            poisson_ratio: 0.28,
        },
    );
    let hertz = Hertz {
        radius_m: 3e-3,
        load_n: 5.0,
        reduced_modulus_pa: pair.reduced_modulus_pa,
    };
    (pair, hertz)
}

/// Measures each grid size in `sizes`.
pub fn contact_rows(sizes: &[usize]) -> Result<Vec<ContactRow>, ContactError> {
    let (pair, hertz) = paper_hertz();
    let options = SolverOptions::default();
    sizes
        .iter()
        .map(|&n| {
            let grid = Grid::square(n, 0.256e-3)?;
            let separation = grid.sample(|x, y| hertz.separation_m(x, y));
            let problem = ContactProblem {
                grid,
                separation: &separation,
                load_n: hertz.load_n,
                yield_pressure_pa: f64::INFINITY,
            };
            // Fewer repetitions where one run takes seconds.
            let reps = if n >= 1024 {
                3
            } else if n >= 512 {
                5
            } else {
                9
            };
            let build_s = median_time(reps, || {
                std::hint::black_box(DcFft::new(&Kernel::normal(&grid, &pair)));
            });
            let mut operator = DcFft::new(&Kernel::normal(&grid, &pair));
            let solution = solve(&mut operator, &problem, &options, None)?;
            let solve_s = median_time(reps, || {
                std::hint::black_box(solve(&mut operator, &problem, &options, None).ok());
            });
            let mut pair_fft = FftPair::new(n);
            let fft_pair_s = median_time(4 * reps, || pair_fft.round_trip());
            Ok(ContactRow {
                n,
                wall_s: build_s + solve_s,
                build_s,
                solve_s,
                iterations: solution.iterations,
                applies: solution.operator_applies,
                fft_pair_s,
                iteration_per_fft_pair: solve_s / solution.iterations as f64 / fft_pair_s,
                err_pmax: solution.max_pressure_pa() / hertz.peak_pressure_pa() - 1.0,
                err_area: solution.contact_area_m2(&grid) / hertz.contact_area_m2() - 1.0,
                err_delta: solution.approach_m / hertz.approach_m() - 1.0,
            })
        })
        .collect()
}

/// The rows as a fixed-width table.
pub fn table(rows: &[ContactRow]) -> String {
    let mut out = String::from(
        "Hertz, paper case (R 3 mm, F 5 N, E* 130.17 GPa, domain 0.256 mm, apex on a cell corner, tolerance 1e-8)\n\
         \x20    N   wall s  build s  solve s  iters  applies  FFT pair ms  iter/pair   err p_max    err area   err delta\n",
    );
    for r in rows {
        out += &format!(
            "{:>6} {:>8.4} {:>8.4} {:>8.4} {:>6} {:>8} {:>12.3} {:>10.2} {:>+11.3e} {:>+11.3e} {:>+11.3e}\n",
            r.n,
            r.wall_s,
            r.build_s,
            r.solve_s,
            r.iterations,
            r.applies,
            r.fft_pair_s * 1e3,
            r.iteration_per_fft_pair,
            r.err_pmax,
            r.err_area,
            r.err_delta
        );
    }
    out
}
