//! The contact core against Hertz, the paper, brute force and the hard cases: a contact at
//! the domain edge, a load beyond the domain's capacity, the iteration limit, a rough
//! surface, a tiny contact (the friction coupling is `tests/contact_coupled.rs`).
//!
//! Grid convention: the domain is centred on the sphere apex, which lies on a cell corner
//! (even N), as in the public peer solvers of `docs/peers.md`.

mod common {
    pub mod physics;
}

use common::physics::{
    DOMAIN_M, LOAD_CHECK, LOAD_N, check_tolerance, paper_hertz as hertz, paper_pair, relative_error,
};
use tribosim::contact::{
    ContactError, ContactProblem, ContactSolution, DcFft, DenseOperator, ElasticConstant, Grid,
    Kernel, KnownStart, Material, Operator, SINGLE_PRECISION_MIN_TOLERANCE, SolverOptions,
    UPDATE_ROUNDOFF, WornRows, solve, solve_known, verify,
};

struct Solved {
    grid: Grid,
    separation: Vec<f64>,
    solution: ContactSolution,
}

fn solve_sphere(n: usize, domain_m: f64, load_n: f64, cap: f64) -> Result<Solved, ContactError> {
    solve_sphere_with(n, domain_m, load_n, cap, &SolverOptions::default())
}

/// [`solve_sphere`] at `options`.
fn solve_sphere_with(
    n: usize,
    domain_m: f64,
    load_n: f64,
    cap: f64,
    options: &SolverOptions,
) -> Result<Solved, ContactError> {
    let pair = paper_pair();
    let grid = Grid::square(n, domain_m)?;
    let separation = grid.sample(|x, y| hertz(&pair, load_n).separation_m(x, y));
    let mut op = DcFft::new(&Kernel::normal(&grid, &pair));
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n,
        yield_pressure_pa: cap,
        pass_wear_per_pa: 0.0,
    };
    let solution = solve(&mut op, &problem, options, None)?;
    let check = verify(&mut op, &problem, &solution);
    assert!(
        check.passes(check_tolerance(options), LOAD_CHECK),
        "independent check failed: {check:?}"
    );
    Ok(Solved {
        grid,
        separation,
        solution,
    })
}

struct HertzErrors {
    pmax: f64,
    area: f64,
    delta: f64,
}

fn hertz_errors(n: usize) -> HertzErrors {
    let pair = paper_pair();
    let reference = hertz(&pair, LOAD_N);
    let s = solve_sphere(n, DOMAIN_M, LOAD_N, f64::INFINITY).expect("converges");
    HertzErrors {
        pmax: s.solution.max_pressure_pa() / reference.peak_pressure_pa() - 1.0,
        area: s.solution.contact_area_m2(&s.grid) / reference.contact_area_m2() - 1.0,
        delta: s.solution.approach_m / reference.approach_m() - 1.0,
    }
}

#[test]
fn hertz_paper_case_errors_fall_with_the_grid_and_meet_issue_bounds_at_256() {
    let errors: Vec<HertzErrors> = [64, 128, 256].into_iter().map(hertz_errors).collect();
    for pair in errors.windows(2) {
        assert!(pair[1].pmax.abs() < pair[0].pmax.abs());
        assert!(pair[1].area.abs() < pair[0].area.abs());
        assert!(pair[1].delta.abs() < pair[0].delta.abs());
    }
    let at_256 = &errors[2];
    // Bounds about twice the public peers' errors on the same grid (docs/peers.md: -1.1e-4,
    // +6.3e-3, -2.3e-5 with the apex on a corner).
    assert!(at_256.pmax.abs() <= 2e-4, "p_max error {:e}", at_256.pmax);
    assert!(at_256.area.abs() <= 1e-2, "area error {:e}", at_256.area);
    assert!(at_256.delta.abs() <= 5e-5, "delta error {:e}", at_256.delta);
}

#[test]
fn hertz_pressure_profile_matches_the_analytic_one() {
    // Away from the contact edge (where a cell straddles the sqrt singularity of dp/dr)
    // the cell pressures follow p0 sqrt(1 - r^2/a^2). The 1% bound is above the measured
    // worst cell inside r < 0.8 a at N = 128 and well below the 20%+ a wrong E* would cause.
    let pair = paper_pair();
    let reference = hertz(&pair, LOAD_N);
    let s = solve_sphere(128, DOMAIN_M, LOAD_N, f64::INFINITY).expect("converges");
    let a = reference.contact_radius_m();
    let mut worst = 0.0f64;
    for iy in 0..s.grid.ny {
        for ix in 0..s.grid.nx {
            let r = s.grid.x(ix).hypot(s.grid.y(iy));
            if r < 0.8 * a {
                let p = s.solution.pressure[iy * s.grid.nx + ix];
                worst = worst.max(relative_error(p, reference.pressure_pa(r)));
            }
        }
    }
    assert!(
        worst < 1e-2,
        "worst relative pressure error inside 0.8 a: {worst:e}"
    );
}

#[test]
fn solutions_pass_the_check_by_direct_summation() {
    // On a small grid the check recomputes u by the O(N^4) direct sum, sharing nothing
    // with the FFT path the solver used.
    let pair = paper_pair();
    let grid = Grid::square(32, 0.128e-3).expect("valid");
    let separation = grid.sample(|x, y| hertz(&pair, 2.0).separation_m(x, y));
    let kernel = Kernel::normal(&grid, &pair);
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: 2.0,
        yield_pressure_pa: 700e6,
        pass_wear_per_pa: 0.0,
    };
    let options = SolverOptions::default();
    let solution = solve(&mut DcFft::new(&kernel), &problem, &options, None).expect("converges");
    let check = verify(&mut DenseOperator::new(kernel), &problem, &solution);
    assert!(
        check.passes(check_tolerance(&options), LOAD_CHECK),
        "{check:?}"
    );
    assert!(
        solution.plastic_area_m2(&grid, 700e6) > 0.0,
        "the cap is active"
    );
}

#[test]
fn capped_paper_case() {
    // The paper's first measured hardness over Johnson's factor: Y = H(10 cycles) / 2.8 =
    // 2551 / 2.8 MPa (Table 3).
    let cap = 2551e6 / 2.8;
    let s = solve_sphere(256, DOMAIN_M, LOAD_N, cap).expect("converges");
    let sol = &s.solution;
    assert!(sol.max_pressure_pa() <= cap);
    assert!(sol.plastic_area_m2(&s.grid, cap) > 0.0);
    assert!(sol.contact_area_m2(&s.grid) >= LOAD_N / cap);
    assert!(relative_error(sol.load_n(&s.grid), LOAD_N) <= LOAD_CHECK);
}

#[test]
fn more_than_95_percent_of_the_contact_at_the_cap() {
    // With Y = 0.12 p0 the contact is nearly a flat punch of area ~ F / Y.
    let pair = paper_pair();
    let cap = 0.12 * hertz(&pair, LOAD_N).peak_pressure_pa();
    let s = solve_sphere(128, 0.5e-3, LOAD_N, cap).expect("converges");
    let fraction = s.solution.plastic_area_m2(&s.grid, cap) / s.solution.contact_area_m2(&s.grid);
    assert!(fraction > 0.95, "fraction at the cap: {fraction}");
}

#[test]
fn contact_reaching_the_domain_edge_is_refused() {
    // A 60 um domain cannot hold the 88 um wide Hertz contact.
    match solve_sphere(64, 60e-6, LOAD_N, f64::INFINITY) {
        Err(ContactError::ContactAtEdge {
            edge_cells,
            edge_load_fraction,
        }) => {
            assert!(edge_cells > 0);
            assert!(edge_load_fraction > 0.0 && edge_load_fraction < 1.0);
        }
        other => panic!(
            "expected ContactAtEdge, got {:?}",
            other.map(|s| s.solution.iterations)
        ),
    }
}

#[test]
fn load_above_the_yield_capacity_of_the_domain_is_refused() {
    let cap = 100e6;
    let domain_m: f64 = 0.1e-3;
    let load_n = 1.5 * cap * domain_m * domain_m;
    match solve_sphere(32, domain_m, load_n, cap) {
        Err(ContactError::LoadExceedsCapacity { capacity_n, .. }) => {
            assert!((capacity_n - cap * domain_m * domain_m).abs() < 1e-9 * capacity_n);
        }
        other => panic!("expected LoadExceedsCapacity, got {:?}", other.is_ok()),
    }
}

#[test]
fn iteration_limit_reports_the_residual_reached() {
    let pair = paper_pair();
    let grid = Grid::square(64, DOMAIN_M).expect("valid");
    let separation = grid.sample(|x, y| hertz(&pair, LOAD_N).separation_m(x, y));
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: LOAD_N,
        yield_pressure_pa: f64::INFINITY,
        pass_wear_per_pa: 0.0,
    };
    let options = SolverOptions {
        tolerance: 1e-8,
        max_iterations: 5,
        ..SolverOptions::default()
    };
    let mut op = DcFft::new(&Kernel::normal(&grid, &pair));
    match solve(&mut op, &problem, &options, None) {
        Err(ContactError::NotConverged {
            iterations,
            residual,
            tolerance,
        }) => {
            assert_eq!(iterations, 5);
            assert!(residual > tolerance && residual.is_finite());
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

#[test]
fn invalid_inputs_are_named_errors() {
    assert!(matches!(
        Material::new(205e9, 0.7),
        Err(ContactError::InvalidMaterial {
            constant: ElasticConstant::PoissonRatio,
            ..
        })
    ));
    let grid = Grid::square(8, 1e-4).expect("valid");
    let separation = vec![0.0; 10];
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: 1.0,
        yield_pressure_pa: f64::INFINITY,
        pass_wear_per_pa: 0.0,
    };
    let mut op = DcFft::new(&Kernel::normal(&grid, &paper_pair()));
    let result = solve(&mut op, &problem, &SolverOptions::default(), None);
    assert!(matches!(result, Err(ContactError::InvalidProblem(_))));
}

#[test]
fn tiny_load_with_four_cells_or_fewer_in_contact() {
    // F = 1 mN: a = 2.6 um against 4 um cells, so the contact covers the 4 cells around
    // the apex corner. Its load is carried and its check passes (in solve_sphere).
    let s = solve_sphere(64, DOMAIN_M, 1e-3, f64::INFINITY).expect("converges");
    let cells = s.solution.pressure.iter().filter(|&&p| p > 0.0).count();
    assert!((1..=4).contains(&cells), "{cells} cells in contact");
}

#[test]
fn warm_start_from_the_answer_needs_no_iterations() {
    let s = solve_sphere(128, DOMAIN_M, LOAD_N, 900e6).expect("converges");
    let pair = paper_pair();
    let mut op = DcFft::new(&Kernel::normal(&s.grid, &pair));
    let problem = ContactProblem {
        grid: s.grid,
        separation: &s.separation,
        load_n: LOAD_N,
        yield_pressure_pa: 900e6,
        pass_wear_per_pa: 0.0,
    };
    let again = solve(
        &mut op,
        &problem,
        &SolverOptions::default(),
        Some(&s.solution.pressure),
    )
    .expect("converges");
    assert_eq!(again.iterations, 0);
    assert!(s.solution.iterations > 10);
}

#[test]
fn grid_of_1024_cells_per_side() {
    let pair = paper_pair();
    let reference = hertz(&pair, LOAD_N);
    let s = solve_sphere(1024, DOMAIN_M, LOAD_N, f64::INFINITY).expect("converges");
    // Finer than N = 256, whose bounds it must beat.
    let peak = relative_error(s.solution.max_pressure_pa(), reference.peak_pressure_pa());
    assert!(peak < 2e-4, "{peak}");
    let approach = relative_error(s.solution.approach_m, reference.approach_m());
    assert!(approach < 5e-5, "{approach}");
}

#[test]
fn rough_sphere() {
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    // Heights with rms equal to the Hertz approach, correlated over ~3 cells (three box
    // filters of white noise), on the sphere.
    let pair = paper_pair();
    let reference = hertz(&pair, LOAD_N);
    let grid = Grid::square(256, 0.384e-3).expect("valid");
    let mut rng = rand::rngs::StdRng::seed_from_u64(2018);
    let normal = Normal::new(0.0, 1.0).expect("valid");
    let mut noise: Vec<f64> = (0..grid.len()).map(|_| normal.sample(&mut rng)).collect();
    for _ in 0..3 {
        noise = box_filter(&noise, grid.nx);
    }
    let rms = (noise.iter().map(|v| v * v).sum::<f64>() / noise.len() as f64).sqrt();
    let scale = reference.approach_m() / rms;
    let sphere = grid.sample(|x, y| reference.separation_m(x, y));
    let separation: Vec<f64> = sphere
        .iter()
        .zip(&noise)
        .map(|(s, z)| s + scale * z)
        .collect();
    let mut op = DcFft::new(&Kernel::normal(&grid, &pair));
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: LOAD_N,
        yield_pressure_pa: f64::INFINITY,
        pass_wear_per_pa: 0.0,
    };
    let options = SolverOptions::default();
    let solution = solve(&mut op, &problem, &options, None).expect("converges");
    assert!(verify(&mut op, &problem, &solution).passes(check_tolerance(&options), LOAD_CHECK));
    // Roughness concentrates the load: higher peaks and a smaller real area than Hertz.
    assert!(solution.max_pressure_pa() > reference.peak_pressure_pa());
    assert!(solution.contact_area_m2(&grid) < reference.contact_area_m2());
}

fn box_filter(field: &[f64], n: usize) -> Vec<f64> {
    let at = |i: isize, j: isize| {
        field[(j.rem_euclid(n as isize) as usize) * n + i.rem_euclid(n as isize) as usize]
    };
    let mut out = vec![0.0; field.len()];
    for j in 0..n as isize {
        for i in 0..n as isize {
            let mut sum = 0.0;
            for dj in -1..=1 {
                for di in -1..=1 {
                    sum += at(i + di, j + dj);
                }
            }
            out[j as usize * n + i as usize] = sum / 9.0;
        }
    }
    out
}

/// The FFT operator with its preconditioner hidden: plain conjugate gradients.
struct Unpreconditioned(DcFft);

impl Operator for Unpreconditioned {
    fn shape(&self) -> (usize, usize) {
        self.0.shape()
    }

    fn apply(&mut self, input: &[f64], output: &mut [f64]) {
        self.0.apply(input, output);
    }
}

/// The preconditioner must only change how the solver gets there.
#[test]
fn preconditioning_changes_the_path_not_the_answer() {
    let pair = paper_pair();
    let grid = Grid::square(128, DOMAIN_M).expect("valid");
    let separation = grid.sample(|x, y| hertz(&pair, LOAD_N).separation_m(x, y));
    let kernel = Kernel::normal(&grid, &pair);
    let cap = 2551e6 / 2.8;
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: LOAD_N,
        yield_pressure_pa: cap,
        pass_wear_per_pa: 0.0,
    };
    let options = SolverOptions {
        tolerance: 1e-10,
        ..SolverOptions::default()
    };
    let with = solve(&mut DcFft::new(&kernel), &problem, &options, None).expect("converges");
    let plain = solve(
        &mut Unpreconditioned(DcFft::new(&kernel)),
        &problem,
        &options,
        None,
    )
    .expect("converges");
    let worst = with
        .pressure
        .iter()
        .zip(&plain.pressure)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    // Each solution may leave a gap error of `tolerance * max|u|` per cell; through a
    // cell's own compliance K(0,0) that is a pressure error of about that over K(0,0), so
    // the two differ by at most about twice it (7.4e-9 Y here; measured: 2.0e-9 Y).
    let u_max = with.displacement.iter().fold(0.0f64, |m, u| m.max(u.abs()));
    let bound = 2.0 * options.tolerance * u_max / kernel.value(0, 0);
    assert!(worst <= bound, "worst {worst:e} Pa, bound {bound:e} Pa");
    // Measured: 22 preconditioned iterations against 27 plain ones.
    assert!(with.iterations < plain.iterations);
}

/// The solve time of the paper's Hertz case at N = 256 from the uniform pressure (the
/// uniform-start column of `tribosim bench contact`'s first table), median of 21 solves on one
/// operator, for comparing two builds of the solver. Speed
/// is printed, never asserted: `cargo test --release --test contact -- --ignored --nocapture
/// hertz_256_solve_time`.
#[test]
#[ignore = "a timing, not a test"]
fn hertz_256_solve_time() {
    let pair = paper_pair();
    let grid = Grid::square(256, DOMAIN_M).expect("valid");
    let separation = grid.sample(|x, y| hertz(&pair, LOAD_N).separation_m(x, y));
    let mut op = DcFft::new(&Kernel::normal(&grid, &pair));
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: LOAD_N,
        yield_pressure_pa: f64::INFINITY,
        pass_wear_per_pa: 0.0,
    };
    let mut times: Vec<f64> = (0..21)
        .map(|_| {
            let started = std::time::Instant::now();
            let solution =
                solve(&mut op, &problem, &SolverOptions::default(), None).expect("converges");
            let elapsed = started.elapsed().as_secs_f64();
            println!(
                "{} iterations, {} applies",
                solution.iterations, solution.operator_applies
            );
            elapsed
        })
        .collect();
    times.sort_by(f64::total_cmp);
    println!("Hertz N = 256: median {:.4} s", times[10]);
}

/// The largest difference between `solution`'s displacement and `op` applied to its
/// pressure afresh, relative to the largest fresh displacement.
fn drift_from_fresh(op: &mut dyn Operator, solution: &ContactSolution) -> f64 {
    let mut fresh = vec![0.0; solution.pressure.len()];
    op.apply(&solution.pressure, &mut fresh);
    let scale = fresh.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let largest = solution
        .displacement
        .iter()
        .zip(&fresh)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    largest / scale
}

#[test]
fn an_updated_displacement_drifts_from_a_fresh_one_by_round_off_only() {
    // Success is declared on the displacement the steps updated unless its drift could
    // take a share of the tolerance; the solver bounds that drift by `UPDATE_ROUNDOFF` per
    // update. Measured here: at most 6.3e-17 of the largest displacement per iteration
    // (1.6e-15 after 26 iterations at N = 512), so the bound per iteration holds with a
    // factor of about 160 to spare, with the cap and without, and across the sparse
    // updates of the truncated and re-entering cells.
    let pair = paper_pair();
    // The tightest tolerance a scene may ask for still leaves room for the drift.
    let options = SolverOptions {
        tolerance: 1e-10,
        ..SolverOptions::default()
    };
    for n in [64, 256] {
        for cap in [f64::INFINITY, 900e6] {
            let Solved { grid, solution, .. } =
                solve_sphere_with(n, DOMAIN_M, LOAD_N, cap, &options).expect("converges");
            let mut op = DcFft::new(&Kernel::normal(&grid, &pair));
            let drift = drift_from_fresh(&mut op, &solution);
            assert!(
                drift <= UPDATE_ROUNDOFF * solution.iterations as f64,
                "N = {n}, cap {cap:e}: drift {drift:e} after {} iterations",
                solution.iterations
            );
        }
    }
}

#[test]
fn a_single_precision_solve_drifts_by_the_transforms_round_off_only() {
    // In single precision the updates err by the f32 transforms' round-off, and a step
    // under the cap takes `K` of its moves from the kept transform of its direction
    // instead of an apply of the new pressure, so `u` is never recomputed within the
    // solve (`src/contact/solver.rs`, "Stopping test"). The solver promises the drift stays
    // under a hundredth of the tolerance (1e-6 here); measured: 2.5e-7 of the largest
    // displacement against an f64 apply, after 3 iterations whose steps truncated cells at
    // the cap as the wear term moved the answer.
    let s = solve_sphere(128, DOMAIN_M, LOAD_N, 900e6).expect("converges");
    let kernel = Kernel::normal(&s.grid, &paper_pair());
    let problem = worn_problem(&s, 5e-14);
    let options = SolverOptions {
        tolerance: SINGLE_PRECISION_MIN_TOLERANCE,
        ..SolverOptions::default()
    };
    let mut single = DcFft::<f32>::of(&kernel);
    let start = Some(&s.solution.pressure[..]);
    let solution = solve(&mut single, &problem, &options, start).expect("converges");
    assert!(solution.iterations > 2, "the wear moved the answer");
    let mut double = DcFft::new(&kernel);
    let mut worn = WornRows::new(&mut double, problem.pass_wear_per_pa, s.grid.dx);
    let drift = drift_from_fresh(&mut worn, &solution);
    println!(
        "f32 drift {drift:e} after {} iterations",
        solution.iterations
    );
    assert!(drift <= 0.01 * options.tolerance, "drift {drift:e}");
}

/// The paper's sphere on 128 cells at 5 N under a 900 MPa cap, with a pass's wear of
/// `pass_wear_per_pa` on every row (about 0.3 um on the most loaded row at 5e-14 m/Pa,
/// against 0.6 um of approach: the term moves the answer).
fn worn_problem(s: &Solved, pass_wear_per_pa: f64) -> ContactProblem<'_> {
    ContactProblem {
        grid: s.grid,
        separation: &s.separation,
        load_n: LOAD_N,
        yield_pressure_pa: 900e6,
        pass_wear_per_pa,
    }
}

#[test]
fn a_start_of_known_displacement_skips_the_start_apply_only() {
    let s = solve_sphere(128, DOMAIN_M, LOAD_N, 900e6).expect("converges");
    let mut op = DcFft::new(&Kernel::normal(&s.grid, &paper_pair()));
    let problem = worn_problem(&s, 5e-14);
    let options = SolverOptions::default();
    let start = &s.solution.pressure;
    let from_pressure = solve(&mut op, &problem, &options, Some(start)).expect("converges");
    let mut displacement = vec![0.0; start.len()];
    op.apply(start, &mut displacement);
    let known = KnownStart {
        pressure: start,
        displacement: &displacement,
    };
    let from_known = solve_known(&mut op, &problem, &options, known).expect("converges");
    assert!(from_known.iterations > 2, "the wear moved the answer");
    // The same path: only the start's apply is left out.
    assert_eq!(from_known.iterations, from_pressure.iterations);
    assert_eq!(
        from_known.operator_applies + 1,
        from_pressure.operator_applies
    );
    let mut worn = WornRows::new(&mut op, problem.pass_wear_per_pa, s.grid.dx);
    let check = verify(&mut worn, &problem, &from_known);
    assert!(
        check.passes(check_tolerance(&options), LOAD_CHECK),
        "{check:?}"
    );
}

#[test]
fn a_known_start_off_the_load_or_the_cap_is_applied_afresh() {
    let s = solve_sphere(128, DOMAIN_M, LOAD_N, 900e6).expect("converges");
    let mut op = DcFft::new(&Kernel::normal(&s.grid, &paper_pair()));
    let options = SolverOptions::default();
    let displacement = vec![0.0; s.grid.len()];
    // A wrong displacement: were it used, the solve would end elsewhere or fail the check.
    let known = KnownStart {
        pressure: &s.solution.pressure,
        displacement: &displacement,
    };
    let lower_cap = ContactProblem {
        yield_pressure_pa: 850e6,
        ..worn_problem(&s, 0.0)
    };
    let more_load = ContactProblem {
        load_n: 1.01 * LOAD_N,
        ..worn_problem(&s, 0.0)
    };
    for problem in [lower_cap, more_load] {
        let solution = solve_known(&mut op, &problem, &options, known).expect("converges");
        let check = verify(&mut op, &problem, &solution);
        assert!(
            check.passes(check_tolerance(&options), LOAD_CHECK),
            "{check:?}"
        );
    }
}
