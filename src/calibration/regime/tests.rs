use super::*;
use crate::calibration::calibration_scene;
use crate::scene::{CycleStep, GridSize, dalmau2018_316l};

/// The paper's scene on a small grid with every cycle solved: each run is then the same
/// smooth function of the k's, with no step choices moving with them.
fn small_scene() -> Scene {
    let mut scene = dalmau2018_316l();
    scene.numerics.grid = GridSize::Cells(16);
    scene.numerics.cycle_step = CycleStep::EveryCycle;
    scene
}

/// The change the synthetic table is made with: a low-wear first regime, as Section 5.2
/// describes, then the paper's k.
const TRUE_CHANGE: ArchardRegimeChange = ArchardRegimeChange {
    cycle: 85,
    archard_k_before: 2e-5,
};
const TRUE_K_AFTER: f64 = 1e-4;
const CYCLES: [f64; 6] = [10.0, 40.0, 70.0, 100.0, 140.0, 200.0];

/// The volumes of a run with [`TRUE_CHANGE`], as a table.
fn synthetic_table() -> Table {
    let (scene, grid_cells) = calibration_scene(&small_scene(), CYCLES[5]);
    let mut maker = Problem::maker(&CYCLES, scene, grid_cells);
    let volumes = maker
        .volumes_with(TRUE_K_AFTER, Some(TRUE_CHANGE))
        .expect("runs");
    Table::from_columns(&[("cycles", &CYCLES), ("volume_mm3", &volumes)])
        .expect("equal-length finite columns")
}

/// Gauss-Newton stops at a step shorter than this in ln k.
const TOLERANCE: f64 = 1e-6;

fn options(change: ChangeCycle) -> RegimeOptions {
    RegimeOptions {
        change,
        archard: ArchardOptions {
            tolerance: TOLERANCE,
            ..ArchardOptions::default()
        },
    }
}

fn relative_error(got: f64, want: f64) -> f64 {
    ((got - want) / want).abs()
}

#[test]
fn both_k_and_the_change_cycle_come_back_from_a_two_regime_run() {
    let table = synthetic_table();
    let fit =
        fit_archard_regimes(&table, &small_scene(), options(ChangeCycle::Auto)).expect("fits");
    let two = &fit.two_regimes;
    println!(
        "change {} (true {}), k before {:?}, k after {:?}; one k {:?}; AIC {:?}; {} runs in {:.1} s",
        two.change_cycle,
        TRUE_CHANGE.cycle,
        two.archard_k_before,
        two.archard_k_after,
        fit.one_regime.archard_k,
        fit.comparison,
        fit.runs,
        fit.wall_s
    );
    // The table is the model's own run, so the residuals vanish at the true values alone:
    // the search tries every cycle near its minimum, so it meets the true one exactly.
    assert_eq!(two.change_cycle, TRUE_CHANGE.cycle);
    assert!(two.change_cycle_fitted && !two.change_cycle_at_search_edge);
    // Gauss-Newton stops once a step moves neither k by TOLERANCE of itself; on a volume
    // nearly linear in k each step removes all but a small fraction of the error, so what
    // is left after the last step is below that step (measured: 5e-7 before, 2e-8 after).
    let before = relative_error(two.archard_k_before.value, TRUE_CHANGE.archard_k_before);
    let after = relative_error(two.archard_k_after.value, TRUE_K_AFTER);
    assert!(
        before < TOLERANCE && after < TOLERANCE,
        "{before:e}, {after:e}"
    );
    // One k cannot follow the change: the two-regime fit is better by AIC, by far.
    assert_eq!(fit.comparison.better, Regimes::TwoRegimes);
    assert!(fit.comparison.two_regimes.rss < 1e-6 * fit.comparison.one_regime.rss);
    assert_eq!(fit.comparison.two_regimes.parameters, 3);
    assert_eq!(
        fit.scene.wear.archard_regime_change,
        two.scene.wear.archard_regime_change
    );
    assert!(fit.candidates.len() > 4);
}

#[test]
fn a_given_change_cycle_fits_both_k_with_their_errors() {
    let table = synthetic_table();
    let cycle = ChangeCycle::At(TRUE_CHANGE.cycle);
    let fit = fit_archard_regimes(&table, &small_scene(), options(cycle)).expect("fits");
    let two = &fit.two_regimes;
    // As above: within the Gauss-Newton tolerance.
    assert!(relative_error(two.archard_k_before.value, TRUE_CHANGE.archard_k_before) < TOLERANCE);
    assert!(relative_error(two.archard_k_after.value, TRUE_K_AFTER) < TOLERANCE);
    assert!(!two.change_cycle_fitted);
    assert_eq!(fit.comparison.two_regimes.parameters, 2);
    assert_eq!(fit.candidates.len(), 1);
    // An exact table leaves almost no scatter: the errors are tiny but positive.
    assert!(two.archard_k_after.standard_error > 0.0);
    assert!(two.archard_k_after.standard_error < 1e-3 * TRUE_K_AFTER);
    for point in &fit.points {
        assert!(point.two_regime_residual_mm3.abs() < 1e-6 * point.volume_mm3);
    }
    // The same table off by a cycle: a fit, but a worse one.
    let off =
        fit_archard_regimes(&table, &small_scene(), options(ChangeCycle::At(95))).expect("fits");
    assert!(off.two_regimes.rss > 1e3 * two.rss);
}

#[test]
fn change_cycles_outside_the_table_or_starving_a_regime_are_refused() {
    let table = Table::from_columns(&[
        ("cycles", &CYCLES),
        (
            "volume_mm3",
            &[1e-3, 1.1e-3, 1.2e-3, 1.3e-3, 1.5e-3, 1.8e-3],
        ),
    ])
    .expect("valid");
    let scene = small_scene();
    let refuse = |cycle: u64| {
        fit_archard_regimes(&table, &scene, options(ChangeCycle::At(cycle)))
            .expect_err("refused before any run")
    };
    assert!(matches!(
        refuse(5),
        CalibrationError::ChangeOutsideTable { cycle: 5, .. }
    ));
    assert!(matches!(
        refuse(200),
        CalibrationError::ChangeOutsideTable { .. }
    ));
    let err = refuse(10);
    assert!(
        matches!(
            err,
            CalibrationError::TooFewInRegime {
                regime: "up to it",
                got: 1,
                ..
            }
        ),
        "{err}"
    );
    let err = refuse(140);
    assert!(err.to_string().contains("1 point(s) after it"), "{err}");
    let three = Table::from_columns(&[("cycles", &CYCLES[..3]), ("volume_mm3", &[1e-3; 3])])
        .expect("valid");
    let err =
        fit_archard_regimes(&three, &scene, options(ChangeCycle::Auto)).expect_err("three points");
    assert!(
        matches!(
            err,
            CalibrationError::TooFewPoints {
                needed: 4,
                got: 3,
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn change_cycles_parse_from_the_command_line() {
    assert_eq!("auto".parse(), Ok(ChangeCycle::Auto));
    assert_eq!("300".parse(), Ok(ChangeCycle::At(300)));
    assert!("0".parse::<ChangeCycle>().is_err());
    assert!("3e2".parse::<ChangeCycle>().is_err());
}
