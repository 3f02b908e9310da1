//! The materials library as a scene sees it: a named material fills the fields the scene
//! does not give, a given value wins, and what the library lacks is refused at its field.

use serde_json::{Value, json};
use tribosim::corrosion::FaradayBasis;
use tribosim::scene::materials::{DISCS, DiscMaterialName};
use tribosim::scene::{FieldError, Scene, SceneErrors, parse_scene};

fn errors_of(json: &Value) -> Vec<FieldError> {
    match parse_scene(json) {
        Ok(scene) => panic!("expected errors, parsed {scene:?}"),
        Err(SceneErrors(errors)) => errors,
    }
}

/// A value copied from a literal: bit for bit.
fn assert_exact(got: f64, want: f64) {
    assert_eq!(got.to_bits(), want.to_bits(), "{got} against {want}");
}

fn paths(errors: &[FieldError]) -> Vec<&str> {
    errors.iter().map(|e| e.path.as_str()).collect()
}

/// A Ti-6Al-4V disc for wear alone, with its own k.
fn titanium_wear() -> Value {
    json!({"disc": {"material": "ti6al4v"}, "corrosion": null, "wear": {"archard_k": 1e-4}})
}

#[test]
fn a_named_disc_fills_its_sourced_values_and_a_constant_hardness() {
    let scene = parse_scene(&titanium_wear()).expect("wear alone needs no electrochemistry");
    assert_eq!(scene.disc.material, Some(DiscMaterialName::Ti6Al4V));
    // The library's literals, copied once (`src/scene/materials/discs.rs`): exact.
    assert_exact(scene.disc.youngs_modulus_gpa, 114.0);
    assert_exact(scene.disc.poisson_ratio, 0.33);
    assert_exact(scene.disc.initial_yield_strength_mpa, 830.0);
    // HV1 349 x 9.80665: one rounding.
    assert!((scene.disc.hardness_mpa - 3_422.520_85).abs() < 1e-9);
    assert_eq!(
        scene.disc.hardness_table, None,
        "no published law: constant"
    );
    // The rest is the default's (the paper's): the library names no other field.
    assert_eq!(scene.ball, Scene::default().ball);
    assert_eq!(scene.test, Scene::default().test);
}

#[test]
fn a_given_value_wins_over_the_librarys() {
    let mut json = titanium_wear();
    json["disc"]["youngs_modulus_gpa"] = json!(108.0);
    json["disc"]["hardness_table"] = json!([[10, 3500], [100, 3700]]);
    let scene = parse_scene(&json).expect("valid");
    assert_exact(scene.disc.youngs_modulus_gpa, 108.0);
    assert_eq!(
        scene.disc.hardness_table,
        Some(vec![(10.0, 3500.0), (100.0, 3700.0)])
    );
    assert_exact(scene.disc.poisson_ratio, 0.33);
}

#[test]
fn a_disc_without_electrochemistry_needs_its_constants_and_its_own_k() {
    let errors = errors_of(&json!({"disc": {"material": "ti6al4v"}}));
    assert_eq!(
        paths(&errors),
        [
            "corrosion.corrosion_potential_v",
            "corrosion.tafel_a_c_v",
            "corrosion.tafel_b_c_v_per_decade",
            "corrosion.anodic_current_density_a_cm2",
            "corrosion.repassivation_time_s",
            "wear.archard_k",
        ]
    );
    let first = &errors[0].message;
    assert!(
        first.contains("Ti-6Al-4V") && first.contains("null"),
        "{first}"
    );
    assert!(
        errors[5].message.contains("archard_calibration"),
        "{}",
        errors[5].message
    );
    // Given, the constants are the user's and the metal is the disc's.
    let scene = parse_scene(&json!({
        "disc": {"material": "ti6al4v"}, "wear": {"archard_k": 1e-4},
        "corrosion": {"corrosion_potential_v": -0.3, "tafel_a_c_v": -3.0,
                      "tafel_b_c_v_per_decade": 0.2, "anodic_current_density_a_cm2": 0.01,
                      "repassivation_time_s": 0.05}
    }))
    .expect("every constant given");
    let corrosion = scene.corrosion.expect("on");
    assert_eq!(corrosion.faraday, FaradayBasis::Ti6Al4VG102);
    assert_exact(corrosion.corrosion_potential_v, -0.3);
}

#[test]
fn a_missing_mechanical_value_is_refused_at_its_field_with_a_hint() {
    let errors = errors_of(&json!({
        "preset": "dalmau2018-316l",
        "overrides": {"disc": {"material": "cocrmo"}, "ball": {"material": "si3n4"},
                      "corrosion": null, "wear": {"archard_k": 1e-4}}
    }));
    assert_eq!(
        paths(&errors),
        [
            "overrides.disc.hardness_mpa",
            "overrides.ball.poisson_ratio"
        ]
    );
    assert!(
        errors[1].message.contains("0.24-0.27"),
        "{}",
        errors[1].message
    );
    let scene = parse_scene(&json!({
        "preset": "dalmau2018-316l",
        "overrides": {"disc": {"material": "cocrmo", "hardness_mpa": 3900},
                      "ball": {"material": "si3n4", "poisson_ratio": 0.27},
                      "corrosion": null, "wear": {"archard_k": 1e-4}}
    }))
    .expect("given");
    assert_exact(scene.ball.youngs_modulus_gpa, 306.0);
    assert_eq!(
        scene.disc.hardness_table, None,
        "the preset's 316L table is not CoCrMo's"
    );
}

#[test]
fn the_papers_pair_keeps_the_papers_k_and_316l_is_the_papers_disc() {
    let scene =
        parse_scene(&json!({"disc": {"material": "aisi_316l"}, "ball": {"material": "alumina"}}))
            .expect("the paper's pair needs nothing more");
    let mut paper = Scene::default();
    paper.disc.material = Some(DiscMaterialName::Aisi316l);
    // The library's alumina is NIST's sintered >= 99.5% (416 GPa), not the paper's printed
    // 300: the ball differs, the disc and the electrochemistry do not.
    assert_exact(scene.ball.youngs_modulus_gpa, 416.0);
    paper.ball = scene.ball.clone();
    assert_eq!(scene, paper);
}

#[test]
fn e_corr_follows_the_reference_electrode_the_scene_names() {
    let scene = parse_scene(&json!({
        "disc": {"material": "aisi_316l"}, "corrosion": {"reference_electrode": "sce"}
    }))
    .expect("valid");
    let e = scene.corrosion.expect("on").corrosion_potential_v;
    // -0.10 V vs Ag/AgCl (3 M KCl, +0.205) is -0.136 V vs SCE (+0.241).
    assert!((e - -0.136).abs() < 1e-15, "{e}");
}

#[test]
fn a_resolved_scene_parses_back_to_itself() {
    for disc in DISCS {
        let name = serde_json::to_value(disc.name).expect("a name");
        let json = json!({
            "disc": {"material": name, "hardness_mpa": 3000}, "corrosion": null,
            "ball": {"material": "zirconia"}, "wear": {"archard_k": 1e-4}
        });
        let scene = parse_scene(&json).expect("valid");
        let again = parse_scene(&serde_json::to_value(&scene).expect("serialises"))
            .expect("a resolved scene is valid");
        assert_eq!(again, scene);
    }
}

#[test]
fn an_unknown_material_is_named_with_the_known_ones() {
    let errors = errors_of(&json!({"disc": {"material": "ti64"}}));
    assert_eq!(paths(&errors), ["disc.material"]);
    assert!(
        errors[0].message.contains("ti6al4v"),
        "{}",
        errors[0].message
    );
}
