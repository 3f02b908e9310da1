use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

use super::*;
use crate::corrosion::real_contact_area_m2;
use crate::scene::{GridSize, RecordCycles, dalmau2018_316l};

/// The paper's scene (Table 2 cell, Table 3 hardness law) with the anode taken as the real
/// contact area F / H, the area Fig. 14 compares the depassivated one with.
fn paper_scene() -> Scene {
    let mut scene = dalmau2018_316l();
    if let Some(c) = scene.corrosion.as_mut() {
        c.anodic_area = AnodicArea::RealContact;
    }
    scene
}

/// Potentials during rubbing at 10 .. 3600 s made from the paper's numbers: eq. 18 with
/// A_a = `ratio` x F / H(t), plus normal noise of `noise_v` from `seed`.
fn fig14_curve(ratio: f64, noise_v: f64, seed: u64) -> Table {
    let scene = paper_scene();
    let cell = scene.corrosion.as_ref().expect("corrosion").model();
    let law = scene.hardness_law().expect("table fits");
    let mut rng = StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise_v).expect("finite spread");
    let times: Vec<f64> = (0..20)
        .map(|k| 10.0 * 360f64.powf(k as f64 / 19.0))
        .collect();
    let potentials: Vec<f64> = times
        .iter()
        .map(|&t| {
            let area = ratio * real_contact_area_m2(5.0, law.hardness_pa(scene.cycles_at(t)));
            cell.potential_v(area).expect("small anode") + normal.sample(&mut rng)
        })
        .collect();
    Table::from_columns(&[("time_s", &times), ("potential_v", &potentials)])
        .expect("equal-length finite columns")
}

#[test]
fn fig_14_ratio_of_fifty_comes_back_from_a_noise_free_curve() {
    let fit = fit_ocp(
        &fig14_curve(50.0, 0.0, 0),
        &paper_scene(),
        OcpOptions::default(),
    )
    .expect("fits");
    // eq. 18 inverted exactly (the corrosion module's round trip holds to 1e-12), and the
    // 1-D search stops within 1e-7 of the factor.
    assert!(
        (fit.anodic_to_real_contact - 50.0).abs() < 50.0 * 1e-9,
        "{fit:?}"
    );
    let factor = fit.anodic_area_factor.expect("the factor is fitted");
    assert!((factor.value - 50.0).abs() < 50.0 * 1e-6);
    assert_eq!(fit.repassivation_time_s, None);
    assert!(fit.rms_residual_v < 1e-6);
    let first = fit.points[0];
    let area = |a: Option<f64>| a.expect("a rubbing row has its areas");
    println!(
        "A_a = {:.4e} mm2, F/H = {:.4e} mm2, wear track {:.4e} mm2 at {} s; A_a/(F/H) = {:.3}, A_a/track = {:.4}, E = {:.4} V",
        area(first.anodic_area_mm2),
        area(first.real_contact_area_mm2),
        area(first.wear_track_area_mm2),
        first.time_s,
        fit.anodic_to_real_contact,
        fit.anodic_to_wear_track,
        first.potential_v
    );
}

#[test]
fn the_factor_comes_back_from_a_noisy_curve_within_three_standard_errors() {
    // 5 mV of noise, fixed seed.
    let fit = fit_ocp(
        &fig14_curve(50.0, 5e-3, 15),
        &paper_scene(),
        OcpOptions::default(),
    )
    .expect("fits");
    let f = fit.anodic_area_factor.expect("the factor is fitted");
    println!(
        "anodic_area_factor = {:.3} +- {:.3}, A_a/(F/H) = {:.3}, rms {:.4} V",
        f.value, f.standard_error, fit.anodic_to_real_contact, fit.rms_residual_v
    );
    assert!((f.value - 50.0).abs() < 3.0 * f.standard_error, "{f:?}");
    let scene_factor = fit.scene.corrosion.expect("kept").anodic_area_factor;
    assert!((scene_factor - f.value).abs() < f64::EPSILON * f.value);
}

#[test]
fn a_potential_above_e_corr_is_refused_naming_the_row() {
    let table = Table::from_columns(&[
        ("time_s", &[10.0, 20.0, 30.0]),
        ("potential_v", &[-0.3, -0.05, -0.3]),
    ])
    .expect("equal-length finite columns");
    let err = fit_ocp(&table, &paper_scene(), OcpOptions::default()).expect_err("above E_corr");
    assert!(
        matches!(
            err,
            CalibrationError::AboveCorrosionPotential { row: 2, .. }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("`potential_v`"));
    let no_cell = Scene {
        corrosion: None,
        ..Scene::default()
    };
    let ok = fig14_curve(50.0, 0.0, 0);
    assert!(matches!(
        fit_ocp(&ok, &no_cell, OcpOptions::default()),
        Err(CalibrationError::MissingSection("corrosion"))
    ));
    let backwards = Table::from_columns(&[
        ("time_s", &[10.0, 5.0, 30.0]),
        ("potential_v", &[-0.3, -0.3, -0.3]),
    ])
    .expect("equal-length finite columns");
    let err =
        fit_ocp(&backwards, &paper_scene(), OcpOptions::default()).expect_err("not increasing");
    assert!(err.to_string().contains("`time_s`"), "{err}");
}

/// The paper's scene for 300 cycles on 32 cells, solved exactly at `RECORDED` (the wake's
/// own model, tau as given).
fn small_wake_scene(tau: f64) -> Scene {
    let mut scene = dalmau2018_316l();
    scene.test.cycles = 300;
    scene.numerics.grid = GridSize::Cells(32);
    scene.numerics.record_cycles = RecordCycles::Cycles(RECORDED.to_vec());
    if let Some(c) = scene.corrosion.as_mut() {
        c.repassivation_time_s = tau;
    }
    scene
}

const RECORDED: [u64; 6] = [10, 30, 60, 100, 200, 300];

/// The potentials of the run of `scene` at `RECORDED`.
fn wake_potentials(scene: &Scene) -> Vec<f64> {
    let result = crate::simulation::run(
        &crate::simulation::Plan::new(scene.clone()).expect("a valid scene"),
        &mut |_| {},
        &std::sync::atomic::AtomicBool::new(false),
    )
    .expect("runs");
    RECORDED
        .iter()
        .map(|&n| {
            let record = result
                .cycles
                .iter()
                .find(|r| r.cycle == n)
                .expect("recorded");
            record.potential_v.expect("corrosion")
        })
        .collect()
}

#[test]
fn the_repassivation_time_comes_back_from_a_trace_the_wake_model_made() {
    let truth = small_wake_scene(0.1);
    let potentials = wake_potentials(&truth);
    // The lab's clock: 600 s at open circuit first, the ball stopped after 300 s, two rows
    // at E_corr before and two after (the model's recovery is over within a second).
    let start = 600.0;
    let mut times = vec![0.0, 300.0];
    times.extend(RECORDED.iter().map(|&n| start + n as f64));
    times.extend([start + 310.0, start + 600.0]);
    let mut measured = vec![-0.1, -0.1];
    measured.extend(&potentials);
    measured.extend([-0.1, -0.1]);
    let table = Table::from_columns(&[("time_s", &times), ("potential_v", &measured)])
        .expect("equal-length finite columns");
    let options = OcpOptions {
        rubbing_start_s: Some(start),
        rubbing_stop_s: Some(start + 300.0),
    };
    // Fitted from a scene whose tau is elsewhere: the run's areas do not depend on it.
    let fit = fit_ocp(&table, &small_wake_scene(0.3), options).expect("fits");
    let tau = fit.repassivation_time_s.expect("tau is fitted");
    // The fit's run is the truth's own run (same scene but tau), so only the 1-D search's
    // 1e-7 in ln tau and eq. 18's round trip stand between them.
    assert!((tau.value - 0.1).abs() < 1e-6, "{tau:?}");
    assert_eq!(fit.parameter, OcpParameter::RepassivationTimeS);
    let q_p = fit.repassivation_charge_mc_cm2.expect("with tau");
    assert!((q_p.value - 1.0).abs() < 1e-5, "{q_p:?}");
    assert!(fit.rms_residual_v < 1e-6, "{}", fit.rms_residual_v);
    let phases: Vec<OcpPhase> = fit.points.iter().map(|p| p.phase).collect();
    assert_eq!(phases[..2], [OcpPhase::Before, OcpPhase::Before]);
    assert_eq!(phases[8..], [OcpPhase::After, OcpPhase::After]);
    assert!(
        fit.points
            .iter()
            .all(|p| p.fitted == (p.phase == OcpPhase::Rubbing))
    );
    // After the stop the model is back at E_corr, as the rows are: no residual there.
    assert!(fit.points[9].residual_v.abs() < 1e-12);
    // The scene is the lab's test: 600 s before, 300 cycles, 300 s after.
    let scene = fit.scene;
    assert_eq!(scene.test.cycles, 300);
    assert!((scene.test.ocp_before_s - 600.0).abs() < 1e-12);
    assert!((scene.test.ocp_after_s - 300.0).abs() < 1e-12);
    let corrosion = scene.corrosion.expect("kept");
    assert!((corrosion.repassivation_time_s - tau.value).abs() < 1e-15);
    // The rows after the stop are reported, not fitted, and said so.
    assert!(fit.warnings.iter().any(|w| w.contains("not fitted")));
}

#[test]
fn a_stop_needs_its_start_and_must_follow_it() {
    let table = fig14_curve(50.0, 0.0, 0);
    let stop_alone = OcpOptions {
        rubbing_start_s: None,
        rubbing_stop_s: Some(100.0),
    };
    let err = fit_ocp(&table, &paper_scene(), stop_alone).expect_err("no start");
    assert!(matches!(err, CalibrationError::StopWithoutStart), "{err}");
    let backwards = OcpOptions {
        rubbing_start_s: Some(100.0),
        rubbing_stop_s: Some(50.0),
    };
    let err = fit_ocp(&table, &paper_scene(), backwards).expect_err("stop before start");
    assert!(
        matches!(err, CalibrationError::StopBeforeStart { .. }),
        "{err}"
    );
}
