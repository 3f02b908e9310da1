use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

use super::*;
use crate::scene::dalmau2018_316l;

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
    let fit = fit_ocp(&fig14_curve(50.0, 0.0, 0), &paper_scene()).expect("fits");
    // eq. 18 inverted exactly (the corrosion module's round trip holds to 1e-12), and the
    // 1-D search stops within 1e-7 of the factor.
    assert!(
        (fit.anodic_to_real_contact - 50.0).abs() < 50.0 * 1e-9,
        "{fit:?}"
    );
    assert!((fit.anodic_area_factor.value - 50.0).abs() < 50.0 * 1e-6);
    assert!(fit.rms_residual_v < 1e-6);
    let first = fit.points[0];
    println!(
        "A_a = {:.4e} mm2, F/H = {:.4e} mm2, wear track {:.4e} mm2 at {} s; A_a/(F/H) = {:.3}, A_a/track = {:.4}, E = {:.4} V",
        first.anodic_area_mm2,
        first.real_contact_area_mm2,
        first.wear_track_area_mm2,
        first.time_s,
        fit.anodic_to_real_contact,
        fit.anodic_to_wear_track,
        first.potential_v
    );
}

#[test]
fn the_factor_comes_back_from_a_noisy_curve_within_three_standard_errors() {
    // 5 mV of noise, fixed seed.
    let fit = fit_ocp(&fig14_curve(50.0, 5e-3, 15), &paper_scene()).expect("fits");
    let f = fit.anodic_area_factor;
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
    let err = fit_ocp(&table, &paper_scene()).expect_err("above E_corr");
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
        fit_ocp(&ok, &no_cell),
        Err(CalibrationError::MissingSection("corrosion"))
    ));
    let backwards = Table::from_columns(&[
        ("time_s", &[10.0, 5.0, 30.0]),
        ("potential_v", &[-0.3, -0.3, -0.3]),
    ])
    .expect("equal-length finite columns");
    let err = fit_ocp(&backwards, &paper_scene()).expect_err("not increasing");
    assert!(err.to_string().contains("`time_s`"), "{err}");
}
