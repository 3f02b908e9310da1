use super::*;
use crate::contact::{
    CoupledSolver, DcFft, DenseOperator, ElasticPair, Hertz, Kernel, Material, NormalSolver, verify,
};

/// The paper's ball and disc.
fn paper_pair() -> ElasticPair {
    ElasticPair::new(
        Material::new(300e9, 0.21).expect("valid"),
        Material::new(205e9, 0.28).expect("valid"),
    )
}

/// The paper's pair, with the coupling term of its friction when `coupled`.
fn factory(coupled: bool) -> impl FnMut(&Grid) -> Box<dyn ContactSolver> {
    let pair = paper_pair();
    move |grid: &Grid| -> Box<dyn ContactSolver> {
        let normal = Kernel::normal(grid, &pair);
        if coupled {
            let coupling = Kernel::coupling(grid, &pair, 0.45);
            Box::new(CoupledSolver::new(&normal, &coupling))
        } else {
            Box::new(NormalSolver::new(DcFft::new(&normal)))
        }
    }
}

#[test]
fn the_least_recently_used_shape_is_dropped_beyond_those_kept() {
    let built = std::rc::Rc::new(std::cell::Cell::new(0));
    let counter = std::rc::Rc::clone(&built);
    let mut inner = factory(false);
    let grid = Grid::square(64, 64e-6).expect("valid");
    let mut solver = WindowedSolver::new(grid, move |g: &Grid| {
        counter.set(counter.get() + 1);
        inner(g)
    });
    let mut use_shape = |n: usize| {
        let window = Window::centred(&grid, (32, 32), n, n);
        solver.solver_of(&window).expect("valid");
    };
    // The whole grid's, then one per new shape until the kept shapes are full; the
    // first one again is kept.
    let sizes: Vec<usize> = (0..=KEPT_SHAPES).map(|k| 8 + 4 * k).collect();
    for &n in &sizes[..KEPT_SHAPES] {
        use_shape(n);
    }
    use_shape(sizes[0]);
    assert_eq!(built.get(), 1 + KEPT_SHAPES);
    // The first was used last, so one more shape drops the second, the least recent,
    // which is then built anew; the first is still kept.
    use_shape(sizes[KEPT_SHAPES]);
    use_shape(sizes[0]);
    assert_eq!(built.get(), 2 + KEPT_SHAPES);
    use_shape(sizes[1]);
    assert_eq!(built.get(), 3 + KEPT_SHAPES);
}

/// The paper's ball at 5 N over 96 cells across 300 um: the grid, Hertz's contact and
/// the separation.
fn paper_case() -> (Grid, Hertz, Vec<f64>) {
    let grid = Grid::square(96, 300e-6).expect("valid");
    let hertz = Hertz {
        radius_m: 3e-3,
        load_n: 5.0,
        reduced_modulus_pa: 130.17e9,
    };
    let separation = grid.sample(|x, y| hertz.separation_m(x, y));
    (grid, hertz, separation)
}

/// The paper's 5 N over `separation`, with no cap.
fn uncapped(grid: Grid, separation: &[f64]) -> ContactProblem<'_> {
    ContactProblem {
        grid,
        separation,
        load_n: 5.0,
        yield_pressure_pa: f64::INFINITY,
        pass_wear_per_pa: 0.0,
    }
}

/// The windowed solver of `grid` (with the coupling term when `coupled`), its first
/// solve focused on the loaded disc of `hertz`'s contact radius.
fn focused_on(
    hertz: &Hertz,
    grid: Grid,
    coupled: bool,
) -> WindowedSolver<impl FnMut(&Grid) -> Box<dyn ContactSolver>> {
    let a = hertz.contact_radius_m();
    let guess = grid.sample(|x, y| if x.hypot(y) < a { 1.0 } else { 0.0 });
    let mut solver = WindowedSolver::new(grid, factory(coupled));
    solver.focus_on(&guess);
    solver
}

/// Solves the paper's first cycle (cap 2455 MPa / 2.8) in a window around the contact
/// of `previous_load_n` and checks the answer on the whole grid with the full operator,
/// as the solver's own stopping test promises. Returns the window fraction of the two
/// solves.
fn check_window_from(previous_load_n: f64) -> f64 {
    let (grid, _, separation) = paper_case();
    let problem = |load_n| ContactProblem {
        grid,
        separation: &separation,
        load_n,
        yield_pressure_pa: 2455e6 / 2.8,
        pass_wear_per_pa: 0.0,
    };
    let options = SolverOptions::default();
    let mut solver = WindowedSolver::new(grid, factory(true));
    solver
        .solve(&problem(previous_load_n), &options, None)
        .expect("converges");
    let windowed = solver
        .solve(&problem(5.0), &options, None)
        .expect("converges");
    let check = verify(solver.operator(), &problem(5.0), &windowed);
    // The solver's tolerance plus the 1e-12 FFT round-off bound (tests/contact.rs).
    assert!(check.passes(options.tolerance + 1e-12, 1e-9), "{check:?}");
    solver.fractions().solved
}

#[test]
fn windowed_solution_is_a_solution_on_the_whole_grid() {
    // First solve on the whole grid (fraction 1), the second on a window.
    let fraction = check_window_from(5.0);
    assert!(fraction < 1.6, "the second solve used a window: {fraction}");
}

#[test]
fn the_check_computes_the_displacement_where_a_gap_could_close() {
    let (grid, _, separation) = paper_case();
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: 5.0,
        yield_pressure_pa: 2455e6 / 2.8,
        pass_wear_per_pa: 0.0,
    };
    let options = SolverOptions::default();
    let mut solver = WindowedSolver::new(grid, factory(true));
    solver.solve(&problem, &options, None).expect("converges");
    let windowed = solver.solve(&problem, &options, None).expect("converges");
    let checked = solver.fractions().checked - 1.0;
    assert!(
        checked < 0.5,
        "the check's box is a part of the grid: {checked}"
    );
    let mut full = vec![0.0; grid.len()];
    solver.operator().apply(&windowed.pressure, &mut full);
    let scale = full.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut computed = 0;
    for (i, (&u, &exact)) in windowed.displacement.iter().zip(&full).enumerate() {
        if u == 0.0 {
            // Left out: the separation alone keeps the gap open.
            let open = separation[i] - windowed.approach_m;
            assert!(open >= -options.tolerance * scale, "cell {i}: {open:e}");
        } else {
            // Two DC-FFT applies of the same field: the FFT's round-off bound.
            assert!(
                (u - exact).abs() < 1e-12 * scale,
                "cell {i}: {u:e} vs {exact:e}"
            );
            computed += 1;
        }
    }
    assert!(computed as f64 <= checked * grid.len() as f64);
}

#[test]
fn a_penetration_outside_the_window_enlarges_it() {
    // An asperity 2 um high, 37 cells from the contact's centre: far outside the window
    // around the Hertz contact that the first solve starts in.
    let (grid, hertz, mut separation) = paper_case();
    let asperity = 85 * grid.nx + 48;
    separation[asperity] -= 2e-6;
    let problem = uncapped(grid, &separation);
    let options = SolverOptions::default();
    let mut solver = focused_on(&hertz, grid, true);
    let solution = solver.solve(&problem, &options, None).expect("converges");
    assert!(
        solution.pressure[asperity] > 0.0,
        "the asperity carries load"
    );
    let check = verify(solver.operator(), &problem, &solution);
    // As in `check_window_from`.
    assert!(check.passes(options.tolerance + 1e-12, 1e-9), "{check:?}");
}

#[test]
fn without_a_nonnegative_kernel_the_check_covers_the_grid() {
    // The dense operator does not say its kernel is nonnegative. 48 cells of 5 um: the
    // Hertz contact's window is 32 cells across.
    let grid = Grid::square(48, 240e-6).expect("valid");
    let (_, hertz, _) = paper_case();
    let separation = grid.sample(|x, y| hertz.separation_m(x, y));
    let pair = paper_pair();
    let dense = move |grid: &Grid| -> Box<dyn ContactSolver> {
        Box::new(NormalSolver::new(DenseOperator::new(Kernel::normal(
            grid, &pair,
        ))))
    };
    let problem = uncapped(grid, &separation);
    let mut solver = WindowedSolver::new(grid, dense);
    let options = SolverOptions::default();
    solver.solve(&problem, &options, None).expect("converges");
    let windowed = solver.solve(&problem, &options, None).expect("converges");
    let fractions = solver.fractions();
    assert!(fractions.solved < 1.5, "solved on a window: {fractions:?}");
    // Two whole grids, summed exactly.
    assert!(
        (fractions.checked - 2.0).abs() < f64::EPSILON,
        "{fractions:?}"
    );
    assert!(windowed.displacement.iter().all(|&u| u > 0.0));
}

#[test]
fn a_window_too_small_for_the_contact_is_enlarged() {
    // Around a 0.05 N contact the window cannot hold the 5 N one: it must grow.
    check_window_from(0.05);
}

#[test]
fn a_focus_starts_the_first_solve_in_a_window() {
    let (grid, hertz, separation) = paper_case();
    let problem = uncapped(grid, &separation);
    let mut solver = focused_on(&hertz, grid, false);
    solver
        .solve(&problem, &SolverOptions::default(), None)
        .expect("converges");
    let fraction = solver.fractions().solved;
    assert!(fraction < 1.0, "solved on a window: {fraction}");
}
