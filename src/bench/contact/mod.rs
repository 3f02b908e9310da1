//! The contact benchmark: the paper's case (R 3 mm, F 5 N, alumina on 316L, domain
//! 0.256 mm, apex on a cell corner, the default tolerance) in two cases:
//!
//! - `hertz`: elastic; errors against Hertz's analytic solution;
//! - `capped`: the same contact with the pressure cap `Y = 2551 MPa / 2.8` (the paper's
//!   first hardness over Johnson's factor), about 911 MPa against Hertz's 1221 MPa peak.
//!   It has no analytic answer: its errors are against our own solution of the same case
//!   on a [`CAPPED_REFERENCE_N`]-cell grid of the same domain. The grid error falls about
//!   as 1/N, so a row's error against that reference is about `1 - N / 2048` of its error
//!   against the continuum: half of it at N = 1024.
//!
//! [`grid_rows`] varies the grid at the default tolerance; [`tolerance_rows`] varies the
//! tolerance on one grid. `scripts/peers.py` reads the grid rows (`study`, `case`, `n` and
//! the fields of [`ContactRow`]) from `tribosim bench contact --json` and puts public
//! solvers beside them, so the JSON field names are kept stable.

use serde::Serialize;

use crate::contact::{
    ContactError, ContactProblem, ContactSolution, DcFft, ElasticPair, Grid, Hertz, Kernel,
    Material, SolverOptions, cold_start, solve,
};

mod table;

pub use table::{table, tolerance_table};

use super::fft_pair::FftPair;
use super::{median_time, median_times_alternating};

/// Side of the square domain, m.
pub const DOMAIN_M: f64 = 0.256e-3;

/// The cycle of the paper's first hardness measurement (Table 3: 10 s at 60 rpm).
pub const CAPPED_HARDNESS_CYCLES: u64 = 10;

/// The paper's hardness at [`CAPPED_HARDNESS_CYCLES`], Pa: the first the worn track shows,
/// and the lowest of the run, so the lowest cap a contact of the paper scene meets.
pub const CAPPED_HARDNESS_PA: f64 = 2551e6;

/// Johnson's factor between hardness and the yield pressure of a fully plastic contact.
pub const CAPPED_YIELD_FACTOR: f64 = 2.8;

/// The cap of the `capped` case, Pa.
pub const CAPPED_YIELD_PRESSURE_PA: f64 = CAPPED_HARDNESS_PA / CAPPED_YIELD_FACTOR;

/// Cells per side of the grid whose solution is the `capped` case's reference: twice the
/// largest benchmarked grid, and the largest [`Grid`] accepts.
pub const CAPPED_REFERENCE_N: usize = Grid::MAX_CELLS_PER_SIDE;

/// The tolerance of the solve that [`ToleranceRow::err_solve`] compares against: far below
/// every studied tolerance, so the difference is the error the studied tolerance leaves.
pub const TIGHT_TOLERANCE: f64 = 1e-12;

/// Cells per side of the grid study, up to the largest grid; the capped case stops at half
/// of it ([`ContactCase::studied_at`]).
pub const GRID_STUDY_SIZES: [usize; 6] = [64, 128, 256, 512, 1024, 2048];

/// The tolerance study: one grid, tolerances two decades apart around the default.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToleranceStudy {
    /// Cells per side.
    pub n: usize,
    /// The solver tolerances, loosest first.
    pub tolerances: &'static [f64],
}

/// The tolerance study as `bench contact` runs it.
pub const TOLERANCE_STUDY: ToleranceStudy = ToleranceStudy {
    n: 256,
    tolerances: &[1e-4, 1e-6, 1e-8, 1e-10],
};

/// Which study a contact row belongs to; the JSON `study` field that tells these rows from
/// the others of `bench --json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ContactStudy {
    /// [`ContactRow`]s: the grid varied at the default tolerance.
    #[serde(rename = "contact_grid")]
    Grid,
    /// [`ToleranceRow`]s: the tolerance varied on one grid.
    #[serde(rename = "contact_tolerance")]
    Tolerance,
}

/// Which contact is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactCase {
    /// Elastic: Hertz's problem, whose analytic solution is the reference.
    Hertz,
    /// With the pressure cap [`CAPPED_YIELD_PRESSURE_PA`]; our fine-grid solution is the
    /// reference.
    Capped,
}

impl ContactCase {
    /// Both cases, in table order.
    pub const ALL: [Self; 2] = [Self::Hertz, Self::Capped];

    /// The name used in the JSON and the tables: `hertz` or `capped`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Hertz => "hertz",
            Self::Capped => "capped",
        }
    }

    /// Whether the grid study solves this case on `n` cells: `capped` only up to half of
    /// [`CAPPED_REFERENCE_N`], so that its reference stays at least twice as fine as every
    /// row; `hertz`, whose reference is analytic, on every grid.
    pub fn studied_at(self, n: usize) -> bool {
        match self {
            Self::Hertz => true,
            Self::Capped => 2 * n <= CAPPED_REFERENCE_N,
        }
    }

    /// The pressure cap, Pa (infinite for `hertz`).
    pub fn yield_pressure_pa(self) -> f64 {
        match self {
            Self::Hertz => f64::INFINITY,
            Self::Capped => CAPPED_YIELD_PRESSURE_PA,
        }
    }
}

/// The quantities the errors are taken on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Measures {
    /// Largest pressure, Pa.
    pub pmax_pa: f64,
    /// Contact area (cells with p > 0), m^2.
    pub area_m2: f64,
    /// Rigid-body approach, m.
    pub approach_m: f64,
    /// Plastic area (cells at the cap), m^2; 0 for `hertz`.
    pub plastic_area_m2: f64,
}

impl Measures {
    fn of(solution: &ContactSolution, grid: &Grid, cap: f64) -> Self {
        Self {
            pmax_pa: solution.max_pressure_pa(),
            area_m2: solution.contact_area_m2(grid),
            approach_m: solution.approach_m,
            plastic_area_m2: solution.plastic_area_m2(grid, cap),
        }
    }
}

/// What a case's errors are measured against.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Reference {
    /// Cells per side of the reference solution; `None` for Hertz's analytic solution.
    pub n: Option<usize>,
    /// The reference values. For `capped`, `pmax_pa` is the cap `Y`.
    #[serde(flatten)]
    pub measures: Measures,
}

impl Reference {
    /// Hertz's analytic solution for the paper's case.
    pub fn hertz() -> Self {
        let (_, hertz) = paper_hertz();
        Self {
            n: None,
            measures: Measures {
                pmax_pa: hertz.peak_pressure_pa(),
                area_m2: hertz.contact_area_m2(),
                approach_m: hertz.approach_m(),
                plastic_area_m2: 0.0,
            },
        }
    }

    /// Our solution of the capped case on an `n`-cell grid at [`TIGHT_TOLERANCE`]; at
    /// `n` = 2048 one solve of about 30 s on the 2-core development machine.
    pub fn capped(n: usize) -> Result<Self, ContactError> {
        let case = ContactCase::Capped;
        let setup = Setup::new(case, n)?;
        let mut operator = setup.operator();
        let options = SolverOptions {
            tolerance: TIGHT_TOLERANCE,
            ..SolverOptions::default()
        };
        let solution = solve(&mut operator, &setup.problem(), &options, None)?;
        let mut measures = Measures::of(&solution, &setup.grid, case.yield_pressure_pa());
        // The cap itself, not the solution's largest pressure, which equals it exactly.
        measures.pmax_pa = case.yield_pressure_pa();
        Ok(Self {
            n: Some(n),
            measures,
        })
    }
}

/// Relative errors of measured values against a reference.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Errors {
    pmax: f64,
    area: f64,
    delta: f64,
    plastic_area: Option<f64>,
}

impl Errors {
    fn of(measured: &Measures, reference: &Reference) -> Self {
        let r = &reference.measures;
        Self {
            pmax: measured.pmax_pa / r.pmax_pa - 1.0,
            area: measured.area_m2 / r.area_m2 - 1.0,
            delta: measured.approach_m / r.approach_m - 1.0,
            plastic_area: (r.plastic_area_m2 > 0.0)
                .then(|| measured.plastic_area_m2 / r.plastic_area_m2 - 1.0),
        }
    }
}

/// One case and grid size of the contact benchmark at the default tolerance.
///
/// Errors are relative, `value / reference - 1`, against [`ContactRow::reference`]: Hertz's
/// analytic solution for `hertz`, our [`CAPPED_REFERENCE_N`]-cell solution for `capped`.
/// For `capped`, `err_pmax` is `p_max / Y - 1`: 0 when the cap is reached and held, so it
/// checks the bound rather than measuring a discretisation error; the discretisation shows
/// in `err_area`, `err_delta` and `err_plastic_area`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactRow {
    /// Always [`ContactStudy::Grid`].
    pub study: ContactStudy,
    /// `hertz` or `capped`.
    pub case: ContactCase,
    /// Cells per side.
    pub n: usize,
    /// Kernel and operator construction plus the cold solve, s (median).
    pub wall_s: f64,
    /// Runs behind each median.
    pub runs: usize,
    /// Kernel and operator construction, s (median).
    pub build_s: f64,
    /// The cold solve alone, s (median): the coarse-to-fine start
    /// ([`crate::contact::cold_start`], coarse operators and solves included) and the
    /// solve on this grid.
    pub solve_s: f64,
    /// CG iterations on this grid (the coarse levels' not counted).
    pub iterations: usize,
    /// Operator applications on this grid.
    pub applies: usize,
    /// The same solve from the uniform pressure, s (median, run alternately with the cold
    /// solve).
    pub uniform_solve_s: f64,
    /// CG iterations from the uniform pressure.
    pub uniform_iterations: usize,
    /// The residual reached (the relative residual of [`crate::contact::solver`]).
    pub residual: f64,
    /// One padded 2N x 2N forward + inverse real FFT, s (median, same run).
    pub fft_pair_s: f64,
    /// Time per iteration in FFT pairs, from the uniform start (every iteration on this
    /// grid): `uniform_solve_s / uniform_iterations / fft_pair_s`.
    pub iteration_per_fft_pair: f64,
    /// `p_max / p0 - 1` (`hertz`) or `p_max / Y - 1` (`capped`).
    pub err_pmax: f64,
    /// Contact area error.
    pub err_area: f64,
    /// Approach error.
    pub err_delta: f64,
    /// Plastic area error (`capped`; `None`, JSON `null`, for `hertz`).
    pub err_plastic_area: Option<f64>,
    /// The values measured.
    #[serde(flatten)]
    pub measures: Measures,
    /// What the errors are against.
    pub reference: Reference,
}

/// One tolerance of the tolerance study, on one grid, cold-started.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToleranceRow {
    /// Always [`ContactStudy::Tolerance`].
    pub study: ContactStudy,
    /// `hertz` or `capped`.
    pub case: ContactCase,
    /// Cells per side.
    pub n: usize,
    /// The solver tolerance (the relative residual of [`crate::contact::solver`]).
    pub tolerance: f64,
    /// Solve alone, s (median); construction does not depend on the tolerance and is in
    /// [`ContactRow::build_s`].
    pub solve_s: f64,
    /// CG iterations.
    pub iterations: usize,
    /// Operator applications.
    pub applies: usize,
    /// The residual reached.
    pub residual: f64,
    /// Errors against the case's reference, as in [`ContactRow`]: at these grids they are
    /// mostly the grid's own error once the tolerance is tight enough.
    pub err_pmax: f64,
    /// Contact area error against the case's reference.
    pub err_area: f64,
    /// Approach error against the case's reference.
    pub err_delta: f64,
    /// Plastic area error against the case's reference (`capped` only).
    pub err_plastic_area: Option<f64>,
    /// The error the tolerance alone leaves: `max |p - p*| / max p*`, with `p*` the
    /// solution on the same grid at [`TIGHT_TOLERANCE`].
    pub err_solve: f64,
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

/// One case on one grid: the problem's data.
struct Setup {
    case: ContactCase,
    pair: ElasticPair,
    load_n: f64,
    grid: Grid,
    separation: Vec<f64>,
}

impl Setup {
    fn new(case: ContactCase, n: usize) -> Result<Self, ContactError> {
        let (pair, hertz) = paper_hertz();
        let grid = Grid::square(n, DOMAIN_M)?;
        Ok(Self {
            case,
            pair,
            load_n: hertz.load_n,
            grid,
            separation: grid.sample(|x, y| hertz.separation_m(x, y)),
        })
    }

    fn operator(&self) -> DcFft {
        DcFft::new(&Kernel::normal(&self.grid, &self.pair))
    }

    fn problem(&self) -> ContactProblem<'_> {
        ContactProblem {
            grid: self.grid,
            separation: &self.separation,
            load_n: self.load_n,
            yield_pressure_pa: self.case.yield_pressure_pa(),
            pass_wear_per_pa: 0.0,
        }
    }

    fn reference(&self, capped: &Reference) -> Reference {
        match self.case {
            ContactCase::Hertz => Reference::hertz(),
            ContactCase::Capped => *capped,
        }
    }
}

/// Fewer repetitions where one run takes seconds.
fn repetitions(n: usize) -> usize {
    if n >= 1024 {
        3
    } else if n >= 512 {
        5
    } else {
        9
    }
}

/// Measures both cases at each grid size in `sizes` where the case is studied
/// ([`ContactCase::studied_at`]), the capped case against `capped`. Hertz rows come first.
pub fn grid_rows(sizes: &[usize], capped: &Reference) -> Result<Vec<ContactRow>, ContactError> {
    let mut rows = Vec::with_capacity(2 * sizes.len());
    for case in ContactCase::ALL {
        for &n in sizes.iter().filter(|&&n| case.studied_at(n)) {
            rows.push(grid_row(&Setup::new(case, n)?, capped)?);
        }
    }
    Ok(rows)
}

/// One grid of a case: the cold solve as the simulation's first cycle and `tribosim
/// contact` make it (from the coarse-to-fine start), timed alternately with the solve from
/// the uniform pressure.
fn grid_row(setup: &Setup, capped: &Reference) -> Result<ContactRow, ContactError> {
    let (n, reps) = (setup.grid.nx, repetitions(setup.grid.nx));
    let problem = setup.problem();
    let options = SolverOptions::default();
    let build_s = median_time(reps, || {
        std::hint::black_box(setup.operator());
    });
    let (mut operator, mut uniform_operator) = (setup.operator(), setup.operator());
    let cold = |operator: &mut DcFft| {
        let start = cold_start(&problem, &setup.pair, &options);
        solve(operator, &problem, &options, start.as_deref())
    };
    let solution = cold(&mut operator)?;
    let uniform = solve(&mut uniform_operator, &problem, &options, None)?;
    let (solve_s, uniform_solve_s) = median_times_alternating(
        reps,
        || {
            std::hint::black_box(cold(&mut operator).ok());
        },
        || {
            std::hint::black_box(solve(&mut uniform_operator, &problem, &options, None).ok());
        },
    );
    let mut pair_fft = FftPair::new(n);
    let fft_pair_s = median_time(4 * reps, || pair_fft.round_trip());
    let measures = Measures::of(&solution, &setup.grid, setup.case.yield_pressure_pa());
    let reference = setup.reference(capped);
    let errors = Errors::of(&measures, &reference);
    Ok(ContactRow {
        study: ContactStudy::Grid,
        case: setup.case,
        n,
        wall_s: build_s + solve_s,
        runs: reps,
        build_s,
        solve_s,
        iterations: solution.iterations,
        applies: solution.operator_applies,
        uniform_solve_s,
        uniform_iterations: uniform.iterations,
        residual: solution.residual,
        fft_pair_s,
        iteration_per_fft_pair: uniform_solve_s / uniform.iterations as f64 / fft_pair_s,
        err_pmax: errors.pmax,
        err_area: errors.area,
        err_delta: errors.delta,
        err_plastic_area: errors.plastic_area,
        measures,
        reference,
    })
}

/// The tolerance study: both cases on the study's grid at each of its tolerances.
pub fn tolerance_rows(
    study: &ToleranceStudy,
    capped: &Reference,
) -> Result<Vec<ToleranceRow>, ContactError> {
    let n = study.n;
    let mut rows = Vec::with_capacity(2 * study.tolerances.len());
    for case in ContactCase::ALL {
        let setup = Setup::new(case, n)?;
        let problem = setup.problem();
        let reference = setup.reference(capped);
        let mut operator = setup.operator();
        let tight = SolverOptions {
            tolerance: TIGHT_TOLERANCE,
            ..SolverOptions::default()
        };
        let exact = solve(&mut operator, &problem, &tight, None)?;
        let exact_max = exact.max_pressure_pa();
        for &tolerance in study.tolerances {
            let options = SolverOptions {
                tolerance,
                ..SolverOptions::default()
            };
            let solution = solve(&mut operator, &problem, &options, None)?;
            let solve_s = median_time(repetitions(n), || {
                std::hint::black_box(solve(&mut operator, &problem, &options, None).ok());
            });
            let measures = Measures::of(&solution, &setup.grid, case.yield_pressure_pa());
            let errors = Errors::of(&measures, &reference);
            let worst = solution
                .pressure
                .iter()
                .zip(&exact.pressure)
                .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
            rows.push(ToleranceRow {
                study: ContactStudy::Tolerance,
                case,
                n,
                tolerance,
                solve_s,
                iterations: solution.iterations,
                applies: solution.operator_applies,
                residual: solution.residual,
                err_pmax: errors.pmax,
                err_area: errors.area,
                err_delta: errors.delta,
                err_plastic_area: errors.plastic_area,
                err_solve: worst / exact_max,
            });
        }
    }
    Ok(rows)
}

/// The paper's case in words, from the values the rows are solved with.
pub fn paper_case() -> String {
    let (_, hertz) = paper_hertz();
    format!(
        "(R {} mm, F {} N, E* {:.2} GPa, domain {} mm, apex on a cell corner, tolerance {:.0e})",
        hertz.radius_m * 1e3,
        hertz.load_n,
        hertz.reduced_modulus_pa / 1e9,
        DOMAIN_M * 1e3,
        SolverOptions::default().tolerance
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capped_errors_are_against_the_fine_grid_and_the_cap() {
        let reference = Reference::capped(128).expect("reference solves");
        assert_eq!(reference.n, Some(128));
        let rows = grid_rows(&[64], &reference).expect("rows solve");
        let (hertz, capped) = (&rows[0], &rows[1]);
        assert_eq!(
            (hertz.case, capped.case),
            (ContactCase::Hertz, ContactCase::Capped)
        );
        assert!(hertz.err_plastic_area.is_none() && hertz.reference.n.is_none());
        assert!(hertz.err_pmax.abs() < 1e-2 && hertz.err_area.abs() < 5e-2);
        // The cap is reached and held exactly.
        assert!(capped.err_pmax.abs() < 1e-12);
        assert!(capped.measures.plastic_area_m2 > 0.0);
        let plastic = capped.err_plastic_area.expect("capped has a plastic area");
        assert!(plastic.abs() < 0.2 && capped.err_area.abs() < 0.05);
        assert!(capped.err_delta.abs() < 1e-2);
        let json = serde_json::to_value(capped).expect("serialises");
        assert_eq!(json["case"], "capped");
        assert_eq!(json["reference"]["n"], 128);
    }

    #[test]
    fn the_capped_case_stops_at_half_its_reference() {
        let largest = *GRID_STUDY_SIZES.last().expect("sizes");
        assert!(ContactCase::Hertz.studied_at(largest));
        assert!(!ContactCase::Capped.studied_at(CAPPED_REFERENCE_N));
        assert!(ContactCase::Capped.studied_at(CAPPED_REFERENCE_N / 2));
    }

    #[test]
    fn a_looser_tolerance_leaves_a_larger_solve_error() {
        let reference = Reference::capped(128).expect("reference solves");
        let study = ToleranceStudy {
            n: 64,
            tolerances: &[1e-4, 1e-10],
        };
        let rows = tolerance_rows(&study, &reference).expect("rows solve");
        assert_eq!(rows.len(), 4);
        for pair in rows.chunks(2) {
            assert!(pair[0].iterations <= pair[1].iterations);
            assert!(pair[1].err_solve < 1e-6, "{pair:?}");
            assert!(pair[0].residual <= 1e-4 && pair[1].residual <= 1e-10);
        }
    }

    /// The capped case's constants are the paper scene's first hardness and yield factor.
    #[test]
    fn the_cap_is_the_paper_scenes_first_yield_pressure() {
        let scene = super::super::wear::paper_scene();
        let table = scene
            .disc
            .hardness_table
            .expect("the preset has Table 3's hardness");
        let (cycles, hardness_mpa) = table[0];
        assert_eq!(cycles.to_bits(), (CAPPED_HARDNESS_CYCLES as f64).to_bits());
        assert_eq!((hardness_mpa * 1e6).to_bits(), CAPPED_HARDNESS_PA.to_bits());
        let factor = scene.disc.yield_factor;
        assert_eq!(factor.to_bits(), CAPPED_YIELD_FACTOR.to_bits());
    }

    #[test]
    fn study_and_case_names_are_their_json() {
        let study = |s: ContactStudy| serde_json::to_value(s).expect("serialises");
        assert_eq!(study(ContactStudy::Grid), "contact_grid");
        assert_eq!(study(ContactStudy::Tolerance), "contact_tolerance");
        for case in ContactCase::ALL {
            let json = serde_json::to_value(case).expect("serialises");
            assert_eq!(json, case.name());
        }
    }
}
