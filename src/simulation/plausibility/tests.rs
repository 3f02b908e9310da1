//! The plausibility rules, each against the slip it names.

use super::*;
use crate::scene::{SceneErrors, Switch};
use crate::simulation::Plan;

fn refusals(scene: &Scene) -> Vec<FieldError> {
    Plan::new(scene.clone())
        .err()
        .map(|SceneErrors(e)| e)
        .unwrap_or_default()
}

fn warnings(scene: &Scene) -> Vec<FieldWarning> {
    Plan::new(scene.clone())
        .map(|plan| plan.warnings().to_vec())
        .unwrap_or_else(|e| panic!("refused: {e}"))
}

/// The messages at `path` among `items` (paths and messages), one a line; "" for none.
fn at<'a>(items: impl IntoIterator<Item = (&'a str, &'a str)>, path: &str) -> String {
    items
        .into_iter()
        .filter(|(p, _)| *p == path)
        .map(|(_, m)| m)
        .collect::<Vec<_>>()
        .join("\n")
}

fn refused_at(scene: &Scene, path: &str) -> String {
    let found = refusals(scene);
    at(
        found.iter().map(|e| (e.path.as_str(), e.message.as_str())),
        path,
    )
}

fn warned_at(scene: &Scene, path: &str) -> String {
    let found = warnings(scene);
    at(
        found.iter().map(|w| (w.path.as_str(), w.message.as_str())),
        path,
    )
}

#[test]
fn the_paper_scene_and_the_presets_give_no_warning() {
    assert_eq!(warnings(&Scene::default()), []);
    for preset in crate::scene::presets() {
        assert_eq!(warnings(&preset.scene), [], "{}", preset.name);
    }
}

#[test]
fn a_load_in_mn_typed_as_n_is_refused_with_the_slip_named() {
    // The flat punch at the lowest cap (877 MPa at cycle 1): sqrt(5000 / (pi 877e6)) =
    // 1.347 mm, 45% of the 3 mm ball; at 5 N, 42.6 um.
    let mut scene = Scene::default();
    scene.test.load_n = 5000.0;
    let message = refused_at(&scene, "test.load_n");
    assert!(message.contains("1347 um, 45% of the ball's"), "{message}");
    assert!(
        message.contains("was the load in mN? 5000 mN = 5 N"),
        "{message}"
    );
}

#[test]
fn a_contact_wide_against_the_ball_is_warned_below_the_refusal() {
    // sqrt(1000 / (pi 877e6)) = 0.602 mm: 20% of the ball's radius.
    let mut scene = Scene::default();
    scene.test.load_n = 1000.0;
    let message = warned_at(&scene, "test.load_n");
    assert!(message.contains("20% of the ball's"), "{message}");
    assert!(message.contains("Hertz's a << R"), "{message}");
    // 2600 N: sqrt(2600 / (pi 877e6)) = 0.971 mm, 32%: refused.
    scene.test.load_n = 2600.0;
    assert!(refused_at(&scene, "test.load_n").contains("32% of the ball's"));
}

#[test]
fn a_modulus_or_a_radius_typed_in_another_unit_is_refused_with_the_slip_named() {
    // One modulus in MPa: E* stays near the ball's, p0 near the paper's; refused anyway.
    let mut scene = Scene::default();
    scene.disc.youngs_modulus_gpa = 205_000.0;
    let message = refused_at(&scene, "disc.youngs_modulus_gpa");
    assert!(message.contains("stiffer than diamond"), "{message}");
    assert!(
        message.contains("was it in MPa? 205000 MPa = 205 GPa"),
        "{message}"
    );
    // Both: p0 would be 122 GPa, named once, at the moduli.
    scene.ball.youngs_modulus_gpa = 300_000.0;
    let found = refusals(&scene);
    let paths: Vec<&str> = found.iter().map(|e| e.path.as_str()).collect();
    assert_eq!(
        paths,
        ["ball.youngs_modulus_gpa", "disc.youngs_modulus_gpa"]
    );
    // A 3 mm ball typed in m, without the cap (which refuses it as wider than the ball):
    // p0 = 1.2214 GPa x 1000^(2/3) = 122 GPa, beyond diamond's hardness.
    let mut scene = Scene::default();
    scene.ball.radius_mm = 0.003;
    scene.wear.plasticity = Switch::Off;
    let message = refused_at(&scene, "ball.radius_mm");
    assert!(message.contains("above diamond's hardness"), "{message}");
    assert!(
        message.contains("was the radius in m? 0.003 m = 3 mm"),
        "{message}"
    );
}

#[test]
fn a_peak_pressure_beyond_the_hardest_metals_is_warned() {
    // A 0.1 mm ball without the cap: p0 ~ R^(-2/3), 30^(2/3) = 9.655 times the paper's
    // 1.2214 GPa = 11.79 GPa.
    let mut scene = Scene::default();
    scene.ball.radius_mm = 0.1;
    scene.wear.plasticity = Switch::Off;
    let message = warned_at(&scene, "test.load_n");
    assert!(
        message.contains("11.79 GPa") && message.contains("hardest metals"),
        "{message}"
    );
}

#[test]
fn a_hardness_in_gpa_typed_as_mpa_is_refused_and_a_soft_one_warned() {
    let mut scene = Scene::default();
    scene.disc.hardness_mpa = 2.473;
    let message = refused_at(&scene, "disc.hardness_mpa");
    assert!(
        message.contains("was it in GPa? 2.473 GPa = 2473 MPa"),
        "{message}"
    );
    // A lead-like disc: warned, and not taken for a slip (50 GPa is no metal's).
    scene.disc.hardness_table = None;
    scene.disc.hardness_mpa = 50.0;
    let message = warned_at(&scene, "disc.hardness_mpa");
    assert!(
        message.contains("softer than annealed pure aluminium"),
        "{message}"
    );
    assert!(message.contains("check that it is in MPa"), "{message}");
    // A table point is judged too, at its own path.
    scene.disc.hardness_mpa = 2473.0;
    scene.disc.hardness_table = Some(vec![(10.0, 2551.0), (60.0, 2.5)]);
    scene.disc.hardness_fit_includes_bulk = false;
    scene.test.cycles = 60;
    let message = refused_at(&scene, "disc.hardness_table[1][1]");
    assert!(!message.is_empty(), "{:?}", refusals(&scene));
    // The punch of 5 N at 2.5 / 2.8 MPa is 1.3 mm wide: the hardness's slip, not the
    // load's, and not the grid's resolution of it.
    assert_eq!(refusals(&scene).len(), 1, "{:?}", refusals(&scene));
    assert!(
        message.contains("was it in GPa? 2.5 GPa = 2500 MPa"),
        "{message}"
    );
    assert_eq!(refused_at(&scene, "disc.hardness_mpa"), "");
}

#[test]
fn a_hardness_in_pa_a_table_in_gpa_and_a_modulus_in_pa_are_refused_with_their_slip() {
    let mut scene = Scene::default();
    scene.disc.hardness_mpa = 2.473e9;
    let message = refused_at(&scene, "disc.hardness_mpa");
    assert!(
        message.contains("was it in Pa? 2.473e9 Pa = 2473 MPa"),
        "{message}"
    );
    // The paper's table typed in GPa: the slip at each point, not the law's fit.
    let mut scene = Scene::default();
    let table = scene
        .disc
        .hardness_table
        .as_mut()
        .expect("the paper's table");
    table.iter_mut().for_each(|(_, mpa)| *mpa *= 1e-3);
    let found = refusals(&scene);
    assert!(
        !found.is_empty()
            && found
                .iter()
                .all(|e| e.path.starts_with("disc.hardness_table[")),
        "{found:?}"
    );
    assert!(found[0].message.contains("was it in GPa?"), "{found:?}");
    let mut scene = Scene::default();
    scene.disc.youngs_modulus_gpa = 205e9;
    let message = refused_at(&scene, "disc.youngs_modulus_gpa");
    assert!(
        message.contains("was it in Pa? 2.05e11 Pa = 205 GPa"),
        "{message}"
    );
}

#[test]
fn a_long_run_is_warned_with_its_time_and_size() {
    let mut scene = Scene::default();
    scene.test.cycles = 1_000_000;
    let message = warned_at(&scene, "test.cycles");
    assert!(
        message.contains("1000000 cycles will take about"),
        "{message}"
    );
    assert!(
        message.contains(" min") || message.contains(" h"),
        "{message}"
    );
    assert!(message.contains(" MB"), "{message}");
    // Ten times the paper's test is no warning (59 s measured).
    scene.test.cycles = 36_000;
    assert_eq!(warned_at(&scene, "test.cycles"), "");
}

#[test]
fn a_height_map_in_um_read_as_m_is_refused() {
    // A checkerboard of +-0.1 read as m: rms 0.1 m = 1e5 um.
    let heights: Vec<f64> = (0..64)
        .map(|i| if (i + i / 8) % 2 == 0 { 0.1 } else { -0.1 })
        .collect();
    let map = HeightMap::new(8, 8, 1e-6, 1e-6, heights.clone()).expect("a valid map");
    let error = check_map("disc.gsf", &map).expect_err("refused");
    assert_eq!(error.path, "disc.surface.id");
    assert!(
        error.message.contains("in um rather than m"),
        "{}",
        error.message
    );
    assert!(error.message.contains("1.000e5 um") || error.message.contains("100000 um"));
    let scaled: Vec<f64> = heights.iter().map(|h| h * 1e-6).collect();
    let map = HeightMap::new(8, 8, 1e-6, 1e-6, scaled).expect("a valid map");
    assert_eq!(check_map("disc.gsf", &map), Ok(()));
}

#[test]
fn the_hardening_caps_initial_yield_strength_names_its_slip() {
    let hardening = |mpa: f64| {
        let mut scene = Scene::default();
        scene.disc.yield_cap = YieldCapLaw::StrainHardening;
        scene.disc.initial_yield_strength_mpa = mpa;
        scene
    };
    assert_eq!(warnings(&hardening(290.0)), []);
    let path = "disc.initial_yield_strength_mpa";
    let message = refused_at(&hardening(0.29), path);
    assert!(
        message.contains("was it in GPa? 0.29 GPa = 290 MPa"),
        "{message}"
    );
    let message = refused_at(&hardening(290e6), path);
    assert!(
        message.contains("was it in Pa? 290000000 Pa = 290 MPa"),
        "{message}"
    );
    // At or above H(1) / 2.8 = 876.8 MPa the cap never hardens: the paper's throughout.
    let message = warned_at(&hardening(900.0), path);
    assert!(
        message.contains("H(1) / yield_factor = 876.8 MPa"),
        "{message}"
    );
    // The paper's cap never reads the strength.
    let mut paper = hardening(0.29);
    paper.disc.yield_cap = YieldCapLaw::Hardness;
    assert_eq!(refused_at(&paper, path), "");
}
