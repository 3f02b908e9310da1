use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

use super::*;

/// Table 2: E_corr = -0.10 V, a_c = -3.31 V, b_c = 0.56 V/decade.
const E_CORR: f64 = -0.10;
const A_C: f64 = -3.31;
const B_C: f64 = 0.56;
/// Anodic Tafel slope of the synthetic curve, V/decade: a typical 0.12 for the passive
/// current's rise; it only shapes the bend near E_corr.
const B_A: f64 = 0.12;

/// The paper's scan: from E_corr down to -1.1 V at 1 mV per point (1 mV/s, Section 2.2).
fn potentials() -> Vec<f64> {
    scan(1, 1000)
}

/// Potentials `first` to `last` mV below E_corr, 1 mV apart (negative `first`: above it).
fn scan(first: i32, last: i32) -> Vec<f64> {
    (first..=last)
        .map(|k| E_CORR - 1e-3 * f64::from(k))
        .collect()
}

/// Net current density (A/cm^2, negative: cathodic) of a cell whose cathodic branch is the
/// Table 2 line and whose anodic branch meets it at E_corr, with log-normal noise of
/// `noise_decades` from `seed`.
fn synthetic_curve(noise_decades: f64, seed: u64, anodic: bool) -> Table {
    curve_over(&potentials(), noise_decades, seed, anodic)
}

/// [`synthetic_curve`] at the potentials `potential`.
fn curve_over(potential: &[f64], noise_decades: f64, seed: u64, anodic: bool) -> Table {
    let mut rng = StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise_decades).expect("finite spread");
    let i_corr = 10f64.powf(A_C / B_C);
    let potential = potential.to_vec();
    let current: Vec<f64> = potential
        .iter()
        .map(|&e| {
            let eta = e - E_CORR;
            let cathodic = 10f64.powf((A_C - eta) / B_C);
            let anodic = if anodic {
                i_corr * 10f64.powf(eta / B_A)
            } else {
                0.0
            };
            -(cathodic - anodic) * 10f64.powf(normal.sample(&mut rng))
        })
        .collect();
    Table::from_columns(&[
        ("potential_v", &potential),
        ("current_density_a_cm2", &current),
    ])
    .expect("equal-length finite columns")
}

fn given_e_corr() -> TafelOptions {
    TafelOptions {
        corrosion_potential_v: Some(E_CORR),
        ..TafelOptions::default()
    }
}

#[test]
fn noise_free_tafel_line_comes_back_exactly() {
    let fit = fit_tafel(
        &synthetic_curve(0.0, 0, false),
        &Scene::default(),
        given_e_corr(),
    )
    .expect("a straight curve");
    // Exact data on a line: the centred least squares loses a few ulps times the 1000
    // points' sums, far inside 1e-9 relative.
    assert!(
        ((fit.tafel_a_c_v.value - A_C) / A_C).abs() < 1e-9,
        "{fit:?}"
    );
    assert!(((fit.tafel_b_c_v_per_decade.value - B_C) / B_C).abs() < 1e-9);
    assert_eq!(fit.domain.points, 1000);
    let corrosion = fit.scene.corrosion.expect("filled in");
    assert!((corrosion.tafel_b_c_v_per_decade - B_C).abs() < 1e-9);
}

#[test]
fn table_2_values_come_back_from_a_noisy_curve_within_three_standard_errors() {
    // 0.02 decades (4.7%) of noise on each current, fixed seed.
    let fit = fit_tafel(
        &synthetic_curve(0.02, 15, true),
        &Scene::default(),
        given_e_corr(),
    )
    .expect("a Tafel domain");
    let (a, b) = (fit.tafel_a_c_v, fit.tafel_b_c_v_per_decade);
    println!(
        "a_c = {:.4} +- {:.4} V, b_c = {:.5} +- {:.5} V/dec, i_corr = {:.3e} A/cm2, domain {:.3} .. {:.3} V ({} points), rms {:.4} dec",
        a.value,
        a.standard_error,
        b.value,
        b.standard_error,
        fit.corrosion_current_density_a_cm2,
        fit.domain.lower_v,
        fit.domain.upper_v,
        fit.domain.points,
        fit.rms_residual_decades
    );
    assert!((a.value - A_C).abs() < 3.0 * a.standard_error, "{a:?}");
    assert!((b.value - B_C).abs() < 3.0 * b.standard_error, "{b:?}");
    // The anodic branch bends the curve near E_corr: the domain must stop short of it, at
    // least where the anodic current is 10% of the cathodic (eta = -1 / (1/b_a + 1/b_c)
    // = -0.099 V, a bend of 0.046 decades, twice the noise).
    let bend_v = E_CORR - 1.0 / (1.0 / B_A + 1.0 / B_C);
    assert!(fit.domain.upper_v < bend_v, "{:?}", fit.domain);
    // The residuals' spread is the noise put in: within 10% for ~900 points (the relative
    // error of a standard deviation from n points is 1 / sqrt(2n) = 2.4%).
    assert!((fit.rms_residual_decades - 0.02).abs() < 0.002);
}

#[test]
fn e_corr_is_where_the_current_changes_sign() {
    // The scan from 50 mV above E_corr: the net current is anodic there and cathodic below.
    let curve = curve_over(&scan(-50, 1000), 0.02, 15, true);
    let fit = fit_tafel(&curve, &Scene::default(), TafelOptions::default()).expect("fits");
    // Log-normal noise keeps each current's sign, so the one change lies between the two
    // points 1 mV apart either side of E_corr.
    let shift = (fit.corrosion_potential_v - E_CORR).abs();
    assert!(shift < 1e-3, "E_corr {}", fit.corrosion_potential_v);
    assert_eq!(
        fit.corrosion_potential_source,
        CorrosionPotentialSource::SignChange
    );
    assert!(!fit.corrosion_potential_given);
    assert!(
        fit.warnings[0].contains("changes sign"),
        "{:?}",
        fit.warnings
    );
    let a = fit.tafel_a_c_v;
    assert!(
        (a.value - A_C).abs() < 3.0 * a.standard_error + shift,
        "{a:?}"
    );
}

#[test]
fn a_cathodic_only_scan_needs_e_corr_from_the_option_or_the_labs_scene() {
    // The curve: Table 2's line from -0.15 to -0.50 V, no noise. Taking its top as
    // E_corr once gave a_c 1.5% and i_corr 23% off.
    let curve = curve_over(&scan(50, 400), 0.0, 0, false);
    let err = fit_tafel(&curve, &Scene::default(), TafelOptions::default()).expect_err("no E_corr");
    assert!(matches!(err, CalibrationError::CorrosionPotentialUnknown));
    assert!(err.to_string().contains("--e-corr"), "{err}");
    let scene_given = TafelOptions {
        scene_corrosion_potential: true,
        ..TafelOptions::default()
    };
    let fit = fit_tafel(&curve, &Scene::default(), scene_given).expect("E_corr from the scene");
    assert_eq!(
        fit.corrosion_potential_source,
        CorrosionPotentialSource::Scene
    );
    assert!(
        fit.warnings[0].contains("from the scene"),
        "{:?}",
        fit.warnings
    );
    // Noise-free on the line: as exact as the 1000-point fit.
    assert!(
        ((fit.tafel_a_c_v.value - A_C) / A_C).abs() < 1e-9,
        "{fit:?}"
    );
    let corrosion = fit.scene.corrosion.expect("filled in");
    assert!((corrosion.tafel_overpotential_max_v - -0.05).abs() < 1e-12);
    assert!((corrosion.tafel_overpotential_min_v - -0.40).abs() < 1e-12);
}

#[test]
fn a_domain_too_narrow_for_a_tafel_line_is_refused_with_the_reason() {
    let scene = Scene::default();
    // 41 points over 40 mV.
    let narrow = curve_over(&scan(60, 100), 0.0, 0, false);
    let err = fit_tafel(&narrow, &scene, given_e_corr()).expect_err("40 mV");
    assert!(
        matches!(err, CalibrationError::NarrowTafelDomain(_)),
        "{err}"
    );
    assert!(err.to_string().contains("50 mV"), "{err}");
    // 8 points over 700 mV.
    let sparse: Vec<f64> = (0..8).map(|k| E_CORR - 0.2 - 0.1 * f64::from(k)).collect();
    let err = fit_tafel(&curve_over(&sparse, 0.0, 0, false), &scene, given_e_corr())
        .expect_err("8 points");
    assert!(err.to_string().contains("at least 10"), "{err}");
    // A given upper end that leaves 4 mV, the window a noisy curve was once fitted on.
    let options = TafelOptions {
        overpotential_max_v: Some(-0.996),
        ..given_e_corr()
    };
    let err = fit_tafel(&synthetic_curve(0.02, 15, true), &scene, options).expect_err("4 mV");
    assert!(
        matches!(err, CalibrationError::NarrowTafelDomain(_)),
        "{err}"
    );
}

#[test]
fn a_curve_without_a_tafel_domain_is_refused() {
    let scene = Scene::default();
    // Nothing below E_corr.
    let anodic = Table::from_columns(&[
        ("potential_v", &[0.0, 0.1, 0.2, 0.3, 0.4, 0.5]),
        (
            "current_density_a_cm2",
            &[1e-6, 2e-6, 3e-6, 4e-6, 5e-6, 6e-6],
        ),
    ])
    .expect("equal-length finite columns");
    let err = fit_tafel(&anodic, &scene, given_e_corr()).expect_err("no cathodic branch");
    assert!(err.to_string().contains("`potential_v`"), "{err}");
    // log10 |i| a parabola in E everywhere: no straight stretch.
    let potential = potentials();
    let bent: Vec<f64> = potential
        .iter()
        .map(|e| -10f64.powf(-6.0 - 8.0 * (e - E_CORR).powi(2)))
        .collect();
    let curved = Table::from_columns(&[
        ("potential_v", &potential),
        ("current_density_a_cm2", &bent),
    ])
    .expect("equal-length finite columns");
    // At the current's resolution (1e-3 decades) the bottom 29 mV of the parabola bend too
    // little to tell from a line: that stretch is refused as too narrow rather than none.
    let err = fit_tafel(&curved, &scene, given_e_corr()).expect_err("curved");
    assert!(
        matches!(
            err,
            CalibrationError::NoTafelDomain(_) | CalibrationError::NarrowTafelDomain(_)
        ),
        "{err}"
    );
    // Current in A/m^2 is read too; a missing current column is named.
    let missing =
        Table::from_columns(&[("potential_v", &potential)]).expect("equal-length finite columns");
    let err = fit_tafel(&missing, &scene, given_e_corr()).expect_err("no current");
    assert!(err.to_string().contains("current_density_a_cm2"), "{err}");
}

#[test]
fn current_in_a_per_m2_gives_the_same_fit() {
    let curve = synthetic_curve(0.0, 0, false);
    let potential = curve.column("potential_v").expect("present").to_vec();
    let a_m2: Vec<f64> = curve
        .column("current_density_a_cm2")
        .expect("present")
        .iter()
        .map(|i| i * 1e4)
        .collect();
    let si = Table::from_columns(&[("potential_v", &potential), ("current_density_a_m2", &a_m2)])
        .expect("equal-length finite columns");
    let fit = fit_tafel(&si, &Scene::default(), given_e_corr()).expect("straight");
    // One more multiplication per point: 1e-9 as in the A/cm^2 test.
    assert!(((fit.tafel_b_c_v_per_decade.value - B_C) / B_C).abs() < 1e-9);
}

#[test]
fn the_domain_leaves_no_bias_beyond_the_statistical_error() {
    // Over 30 seeds the errors in standard errors, z, of an unbiased fit average to 0 with a
    // standard deviation of 1 / sqrt(30) = 0.18: a bias above 3 x 0.18 = 0.55 fails.
    // Measured: +0.22 for a_c, -0.24 for b_c, the largest |z| 2.1.
    let (mut z_a, mut z_b) = (0.0, 0.0);
    let seeds = 30;
    for seed in 0..seeds {
        let fit = fit_tafel(
            &synthetic_curve(0.02, seed, true),
            &Scene::default(),
            given_e_corr(),
        )
        .expect("a Tafel domain");
        z_a += (fit.tafel_a_c_v.value - A_C) / fit.tafel_a_c_v.standard_error;
        z_b += (fit.tafel_b_c_v_per_decade.value - B_C) / fit.tafel_b_c_v_per_decade.standard_error;
    }
    let (mean_a, mean_b) = (z_a / seeds as f64, z_b / seeds as f64);
    println!("mean z: a_c {mean_a:+.2}, b_c {mean_b:+.2}");
    let limit = 3.0 / (seeds as f64).sqrt();
    assert!(
        mean_a.abs() < limit && mean_b.abs() < limit,
        "{mean_a} {mean_b}"
    );
}

/// `curve`'s current column with row `k` (from 0) multiplied by `factor(k)`.
fn rescaled(curve: &Table, factor: impl Fn(usize) -> f64) -> Table {
    let potential = curve.column("potential_v").expect("present").to_vec();
    let current: Vec<f64> = curve
        .column("current_density_a_cm2")
        .expect("present")
        .iter()
        .enumerate()
        .map(|(k, i)| i * factor(k))
        .collect();
    Table::from_columns(&[
        ("potential_v", &potential),
        ("current_density_a_cm2", &current),
    ])
    .expect("equal-length finite columns")
}

#[test]
fn a_clean_curve_is_fitted_on_its_tafel_region_never_past_the_scans_end() {
    // Table 2's cell scanned 300 mV below E_corr without noise: 203 points lie below the
    // anodic branch's 10% bend (-0.199 V). Its straight stretch ends where the bend reaches
    // the current's resolution, and twice that lies past the scan's end; this curve was
    // once refused as too narrow.
    let curve = curve_over(&scan(1, 300), 0.0, 0, true);
    let fit = fit_tafel(&curve, &Scene::default(), given_e_corr()).expect("a Tafel region");
    println!(
        "{:?}, b_c {:?}, warnings {:?}",
        fit.domain, fit.tafel_b_c_v_per_decade, fit.warnings
    );
    assert!(
        fit.domain.lower_v >= E_CORR - 0.300 - 1e-12,
        "{:?}",
        fit.domain
    );
    assert!(fit.domain.points >= MIN_TAFEL_POINTS, "{:?}", fit.domain);
    assert!(!fit.domain.given);
    // The anodic branch is the only error: at the domain's top it is 10^(eta (1/b_a + 1/b_c))
    // of the cathodic current, bending log10 |i| by -log10(1 - that); spread over the domain
    // it tilts the slope 1/b_c by at most that bend over the span. Measured: domain -0.3 to
    // -0.2 V from E_corr, b_c 0.5494 (-1.9%) against that bound's 2.3%.
    let (top, span) = (
        fit.domain.overpotential_max_v,
        fit.domain.overpotential_max_v - fit.domain.overpotential_min_v,
    );
    let share = 10f64.powf(top * (1.0 / B_A + 1.0 / B_C));
    let tilt_relative = -(1.0 - share).log10() / span * B_C;
    let b = fit.tafel_b_c_v_per_decade.value;
    assert!(
        ((b - B_C) / B_C).abs() <= tilt_relative,
        "{b} against {tilt_relative}"
    );
    assert!(fit.outliers.is_empty(), "{:?}", fit.outliers);
}

#[test]
fn the_domains_bounds_are_options_refused_out_of_range_with_the_slip() {
    let curve = synthetic_curve(0.02, 15, true);
    let bounded = TafelOptions {
        overpotential_max_v: Some(-0.2),
        overpotential_min_v: Some(-0.8),
        ..given_e_corr()
    };
    let fit = fit_tafel(&curve, &Scene::default(), bounded).expect("inside the scan");
    // Potentials 1 mV apart from 200 to 800 mV below E_corr, both ends included.
    assert_eq!(fit.domain.points, 601, "{:?}", fit.domain);
    assert!(fit.domain.given);
    assert!((fit.domain.overpotential_max_v - -0.2).abs() < 1e-9);
    assert!((fit.domain.overpotential_min_v - -0.8).abs() < 1e-9);
    let refused = |max: Option<f64>, min: Option<f64>| {
        let options = TafelOptions {
            overpotential_max_v: max,
            overpotential_min_v: min,
            ..given_e_corr()
        };
        fit_tafel(&curve, &Scene::default(), options).expect_err("out of range")
    };
    let err = refused(Some(-150.0), None);
    assert!(
        matches!(err, CalibrationError::DomainOption { .. }),
        "{err}"
    );
    assert!(
        err.to_string().contains("was it in mV? -150 mV = -0.15 V"),
        "{err}"
    );
    assert!(
        err.to_string().contains("tafel_overpotential_max_v"),
        "{err}"
    );
    let err = refused(Some(0.15), None);
    assert!(
        err.to_string().contains("E rather than E - E_corr"),
        "{err}"
    );
    let err = refused(Some(-0.8), Some(-0.2));
    assert!(err.to_string().contains("must lie above"), "{err}");
}

#[test]
fn a_curve_in_ma_typed_as_a_is_named() {
    // The Table 2 curve in mA/cm^2 under an A/cm^2 name: i_corr 1000 times Table 2's.
    let curve = rescaled(&synthetic_curve(0.02, 15, true), |_| 1e3);
    let fit = fit_tafel(&curve, &Scene::default(), given_e_corr()).expect("a line");
    assert!(
        fit.warnings
            .iter()
            .any(|w| w.contains("mA/cm^2 typed as A/cm^2")),
        "{:?}",
        fit.warnings
    );
    // The same curve in A/cm^2 says nothing of units.
    let fit = fit_tafel(
        &synthetic_curve(0.02, 15, true),
        &Scene::default(),
        given_e_corr(),
    )
    .expect("a line");
    assert!(
        !fit.warnings.iter().any(|w| w.contains("typed as")),
        "{:?}",
        fit.warnings
    );
}

#[test]
fn rows_mixing_ma_and_a_are_refused_with_the_rows() {
    // Rows 301 to 600 of the scan in mA/cm^2, the rest in A/cm^2: a three-decade step.
    let curve = rescaled(&synthetic_curve(0.02, 15, true), |k| {
        if (300..600).contains(&k) { 1e3 } else { 1.0 }
    });
    let err = fit_tafel(&curve, &Scene::default(), given_e_corr()).expect_err("mixed");
    assert!(matches!(err, CalibrationError::MixedUnits { .. }), "{err}");
    let words = err.to_string();
    assert!(
        words.contains("rows 300 and 301") || words.contains("rows 600 and 601"),
        "{words}"
    );
    assert!(words.contains("mix units"), "{words}");
}

#[test]
fn outliers_are_flagged_and_reported() {
    // Three rows deep in the domain read ten times high: one decade off against 0.02 of
    // noise, 50 robust standard deviations; fewer than the 2 decades of a change of units.
    let curve = rescaled(&synthetic_curve(0.02, 15, true), |k| {
        if [500, 600, 700].contains(&k) {
            10.0
        } else {
            1.0
        }
    });
    let fit = fit_tafel(&curve, &Scene::default(), given_e_corr()).expect("a line");
    let flagged: Vec<f64> = fit.outliers.iter().map(|r| r.potential_v).collect();
    // Row k (from 0) is E_corr - (k + 1) mV.
    for k in [500, 600, 700] {
        let e = E_CORR - 1e-3 * f64::from(k + 1);
        assert!(
            flagged.iter().any(|f| (f - e).abs() < 1e-9),
            "{k}: {flagged:?}"
        );
    }
    // Normal noise passes 3.5 robust deviations with probability 4.7e-4: of ~900 points,
    // a few at most beside the three.
    assert!(fit.outliers.len() <= 3 + 3, "{flagged:?}");
    assert!(
        fit.warnings.iter().any(|w| w.contains("outliers")),
        "{:?}",
        fit.warnings
    );
}

#[test]
fn implausible_fitted_values_are_refused_with_the_slip() {
    // Potentials and E_corr in mV under V names.
    let curve = synthetic_curve(0.02, 15, true);
    let millivolts: Vec<f64> = curve
        .column("potential_v")
        .expect("present")
        .iter()
        .map(|e| e * 1e3)
        .collect();
    let current = curve
        .column("current_density_a_cm2")
        .expect("present")
        .to_vec();
    let table = Table::from_columns(&[
        ("potential_v", &millivolts),
        ("current_density_a_cm2", &current),
    ])
    .expect("equal-length finite columns");
    let options = TafelOptions {
        corrosion_potential_v: Some(E_CORR * 1e3),
        ..TafelOptions::default()
    };
    let err = fit_tafel(&table, &Scene::default(), options).expect_err("mV as V");
    assert!(matches!(err, CalibrationError::Implausible { .. }), "{err}");
    assert!(
        err.to_string().contains("was it in mV? -100 mV = -0.1 V"),
        "{err}"
    );
    // E_corr of 1e300 V.
    let options = TafelOptions {
        corrosion_potential_v: Some(1e300),
        ..TafelOptions::default()
    };
    let err = fit_tafel(&curve, &Scene::default(), options).expect_err("1e300 V");
    assert!(matches!(err, CalibrationError::Implausible { .. }), "{err}");
    // The potentials in mV with E_corr in V: b_c = 560 V/decade.
    let options = TafelOptions {
        corrosion_potential_v: Some(0.0),
        ..TafelOptions::default()
    };
    let err = fit_tafel(&table, &Scene::default(), options).expect_err("560 V/decade");
    assert!(err.to_string().contains("mV/decade"), "{err}");
}
