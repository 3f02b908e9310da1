//! From JSON to a [`Scene`] whose fields are each within range, with every problem located
//! by path: presets resolved, the document deserialised field by field where it fails
//! ([`super::located`]), defaults filled, the ranges checked ([`super::validate`]) and any
//! further checks of the caller run.

use serde_json::Value;

use crate::json::JsonError;

use super::located::deserialize_located;
use super::validate;
use super::{FieldError, PAPER_ARCHARD_CALIBRATION, Scene, SceneErrors, preset};

/// Parses scene JSON text; malformed JSON is a single error with an empty path whose message
/// carries serde_json's line and column, and a key given twice is a single error at its path.
/// See [`parse_scene`].
pub fn parse_scene_str(text: &str) -> Result<Scene, SceneErrors> {
    parse_scene_str_with(text, Ok)
}

/// [`parse_scene_str`] with the caller's further step, as [`parse_scene_with`].
pub fn parse_scene_str_with<T>(
    text: &str,
    further: impl FnOnce(Scene) -> Result<T, Vec<FieldError>>,
) -> Result<T, SceneErrors> {
    let json = crate::json::from_str(text).map_err(|e| {
        let error = match e {
            JsonError::Syntax(_) => FieldError::new("", e.to_string()),
            JsonError::DuplicateKey { ref path, .. } => {
                FieldError::new(path.clone(), e.to_string())
            }
        };
        SceneErrors(vec![error])
    })?;
    parse_scene_with(&json, further)
}

/// Parses a scene: resolves `{"preset": ..., "overrides": ...}`, fills every default and
/// checks each field against its own range, returning all problems at once. With a preset,
/// paths start with `overrides.`, which is where the user's text is. Whether the simulation
/// can run the scene is not judged here: `simulation::parse_scene` adds that.
pub fn parse_scene(json: &Value) -> Result<Scene, SceneErrors> {
    parse_scene_with(json, Ok)
}

/// [`parse_scene`] followed by the caller's `further` step, which turns a scene whose fields
/// are each within their own range into a `T` (it may combine fields freely) or refuses it
/// with errors located in the document like the others.
pub fn parse_scene_with<T>(
    json: &Value,
    further: impl FnOnce(Scene) -> Result<T, Vec<FieldError>>,
) -> Result<T, SceneErrors> {
    let preset::Resolved {
        document,
        prefix,
        mut errors,
    } = preset::resolve(json)?;
    if let Some(mut scene) = deserialize_located(&document, &mut errors) {
        if scene.wear.archard_k.is_none() && scene.wear.archard_calibration.is_none() {
            scene.wear.archard_calibration = Some(PAPER_ARCHARD_CALIBRATION);
        }
        let own = validate::check(&scene);
        if !own.is_empty() {
            errors.extend(own);
        } else {
            match further(scene) {
                Ok(value) if errors.is_empty() => return Ok(value),
                Ok(_) => {}
                Err(more) => errors.extend(more),
            }
        }
    }
    if !prefix.is_empty() {
        for error in &mut errors {
            error.path = if error.path.is_empty() {
                prefix.to_owned()
            } else {
                format!("{prefix}.{}", error.path)
            };
        }
    }
    Err(SceneErrors(errors))
}

#[cfg(test)]
mod tests {
    use super::super::located::SECTIONS;
    use super::super::{
        AnodicArea, ArchardCalibration, CycleStep, DomainSize, GridSize, MAX_LISTED_PROBLEMS,
        Switch, presets,
    };
    use super::*;
    use serde_json::json;

    /// The preset written out in full with the names of `docs/scene.md`, which users and
    /// scripts rely on: a renamed or dropped field fails here.
    const CONTRACT_EXAMPLE: &str = r#"{
      "name": "316L vs alumina, 5 N, 60 rpm",
      "ball": { "radius_mm": 3.0, "youngs_modulus_gpa": 300.0, "poisson_ratio": 0.21 },
      "disc": {
        "youngs_modulus_gpa": 205.0, "poisson_ratio": 0.28,
        "hardness_mpa": 2473.0,
        "hardness_table": [[10, 2551], [60, 2727], [300, 2854], [1800, 2933], [3600, 2953]],
        "yield_factor": 2.8
      },
      "test": {
        "load_n": 5.0, "track_radius_mm": 2.992, "speed_rpm": 60.0,
        "friction_coefficient": 0.45, "cycles": 300, "ocp_before_s": 0, "ocp_after_s": 0
      },
      "wear": { "archard_k": 1.19e-4, "plasticity": "auto" },
      "corrosion": {
        "corrosion_potential_v": -0.10, "reference_electrode": "ag_agcl_3m_kcl",
        "tafel_a_c_v": -3.31, "tafel_b_c_v_per_decade": 0.56,
        "tafel_overpotential_min_v": -1.0, "tafel_overpotential_max_v": -0.05,
        "anodic_current_density_a_cm2": 0.01, "exposed_area_cm2": 2.56,
        "anodic_area": "depassivated_wake", "repassivation_time_s": 0.148,
        "anodic_area_factor": 1.0, "repassivation_kinetics": "exponential",
        "repassivation_exponent": 0.5, "galvanic_cell": "eq18",
        "bare_corrosion_potential_v": null, "ohmic_resistance_ohm": 0.0,
        "control": "open_circuit", "applied_potential_v": null,
        "faraday": "316l_g102",
        "molar_mass_g_mol": 55.85, "valence": 2.0, "density_g_cm3": 7.9
      },
      "numerics": { "grid": "auto", "domain_um": "auto", "tolerance": "auto",
                    "cycle_step": "auto", "coupling": "auto" }
    }"#;

    /// The Archard k of `scene`'s wear law.
    fn k_of(scene: &Scene) -> f64 {
        scene
            .wear_law()
            .expect("the table fits")
            .summary()
            .archard_k
    }

    fn errors_of(json: &Value) -> Vec<FieldError> {
        match parse_scene(json) {
            Ok(scene) => panic!("expected errors, parsed {scene:?}"),
            Err(SceneErrors(errors)) => errors,
        }
    }

    fn paths(errors: &[FieldError]) -> Vec<&str> {
        errors.iter().map(|e| e.path.as_str()).collect()
    }

    fn message_at<'a>(errors: &'a [FieldError], path: &str) -> &'a str {
        errors.iter().find(|e| e.path == path).map_or_else(
            || panic!("no error at {path}: {errors:?}"),
            |e| e.message.as_str(),
        )
    }

    #[test]
    fn contract_example_is_the_preset_stopped_at_300_cycles_with_its_k() {
        let parsed = parse_scene_str(CONTRACT_EXAMPLE).expect("the full example is valid");
        let mut preset = presets()
            .into_iter()
            .find(|p| p.name == "dalmau2018-316l")
            .expect("the paper's preset exists")
            .scene;
        preset.test.cycles = 300;
        preset.wear.archard_k = Some(1.19e-4);
        preset.wear.archard_calibration = None;
        assert_eq!(parsed, preset);
    }

    #[test]
    fn empty_scene_is_the_papers_whole_test() {
        let scene = parse_scene(&json!({})).expect("all fields are optional");
        assert_eq!(scene.wear.archard_k, None);
        assert_eq!(
            scene.wear.archard_calibration,
            Some(PAPER_ARCHARD_CALIBRATION)
        );
        assert!(scene.corrosion.is_some());
        assert_eq!(
            scene.disc.hardness_table.as_deref(),
            Some(&super::super::PAPER_HARDNESS_TABLE[..])
        );
        assert_eq!(scene.test.cycles, 3600);
        // Same literals as the defaults, so equality is exact.
        assert_eq!(scene, Scene::default());
        // Eq. 14 by hand: 11.72e-12 m^3 x 2953e6 Pa / (5 N x 3600 s x 2 pi 2.992 mm/s)
        // = 1.02285e-4; the inputs carry 4 digits.
        let k = k_of(&scene);
        assert!(((k - 1.02285e-4) / 1.02285e-4).abs() < 1e-4, "k = {k}");
        // The point carries its test's conditions: another load keeps the paper's k.
        let heavier = parse_scene(&json!({"test": {"load_n": 10}})).expect("valid");
        assert_eq!(k_of(&heavier).to_bits(), k.to_bits());
    }

    #[test]
    fn a_k_in_the_overrides_replaces_the_presets_calibration_and_back() {
        let scene = parse_scene(&json!({
            "preset": "dalmau2018-316l", "overrides": {"wear": {"archard_k": 1e-4}}
        }))
        .expect("a number replaces the calibration point");
        assert_eq!(scene.wear.archard_k, Some(1e-4));
        assert_eq!(scene.wear.archard_calibration, None);
        let point = json!({"time_s": 300, "wear_volume_mm3": 1.18e-3, "hardness_mpa": 2854});
        let scene = parse_scene(&json!({
            "preset": "dalmau2018-316l",
            "overrides": {"wear": {"archard_calibration": point}}
        }))
        .expect("a point replaces the point");
        // Table 3's 300 s point: 1.18e-12 x 2854e6 / (5 x 300 x 18.80 mm/s) = 1.194e-4.
        let k = k_of(&scene);
        assert!(((k - 1.1944e-4) / 1.1944e-4).abs() < 1e-3, "k = {k}");
    }

    #[test]
    fn echo_fills_every_default_and_parses_back_to_the_same_scene() {
        let scene =
            parse_scene(&json!({"test": {"load_n": 10}, "corrosion": {}})).expect("valid scene");
        let echo = serde_json::to_value(&scene).expect("scenes serialise");
        assert_eq!(echo["wear"]["archard_calibration"]["time_s"], json!(3600.0));
        assert_eq!(echo["numerics"]["grid"], json!("auto"));
        assert_eq!(echo["numerics"]["cycle_step"], json!("auto"));
        assert_eq!(echo["corrosion"]["anodic_area"], json!("depassivated_wake"));
        assert_eq!(echo["test"]["load_n"], json!(10.0));
        assert_eq!(parse_scene(&echo), Ok(scene));
    }

    #[test]
    fn top_level_keys_match_the_sections() {
        let full = presets().remove(0).scene;
        let echo = serde_json::to_value(&full).expect("scenes serialise");
        let keys: Vec<&str> = echo
            .as_object()
            .expect("a scene serialises to an object")
            .keys()
            .map(String::as_str)
            .collect();
        let mut sections = SECTIONS.to_vec();
        sections.sort_unstable();
        let mut keys = keys;
        keys.sort_unstable();
        assert_eq!(keys, sections);
    }

    #[test]
    fn auto_or_number_settings_round_trip() {
        let scene = parse_scene(&json!({"numerics": {
            "grid": 256, "domain_um": 256.0, "cycle_step": 1, "coupling": "off"
        }}))
        .expect("valid numerics");
        assert_eq!(scene.numerics.grid, GridSize::Cells(256));
        assert_eq!(scene.numerics.domain_um, DomainSize::Micrometres(256.0));
        assert_eq!(scene.numerics.cycle_step, CycleStep::EveryCycle);
        assert_eq!(scene.numerics.coupling, Switch::Off);
        let echo = serde_json::to_value(&scene.numerics).expect("numerics serialise");
        assert_eq!(echo["grid"], json!(256));
        assert_eq!(echo["domain_um"], json!(256.0));
        assert_eq!(echo["cycle_step"], json!(1));
    }

    #[test]
    fn typo_is_named_with_the_valid_names() {
        let errors = errors_of(&json!({"test": {"lod_n": 5}, "wears": {}}));
        assert_eq!(paths(&errors), ["test.lod_n", "wears"]);
        assert!(message_at(&errors, "test.lod_n").contains("`load_n`"));
        assert!(message_at(&errors, "wears").contains("`wear`"));
    }

    #[test]
    fn every_problem_is_reported_at_once() {
        let errors = errors_of(&json!({
            "ball": {"poisson_ratio": 0.5},
            "test": {"load_n": -5, "speed_rpm": "fast", "cycles": 0},
            "numerics": {"grid": 4096, "cycle_step": 2, "tolerance": 0.1},
            "corrosion": {"valence": 0}
        }));
        let mut got = paths(&errors);
        got.sort_unstable();
        assert_eq!(
            got,
            [
                "ball.poisson_ratio",
                "corrosion.valence",
                "numerics.cycle_step",
                "numerics.grid",
                "numerics.tolerance",
                "test.cycles",
                "test.load_n",
                "test.speed_rpm",
            ]
        );
        assert_eq!(
            message_at(&errors, "test.load_n"),
            "must be > 0 N and finite, got -5"
        );
        assert!(message_at(&errors, "test.speed_rpm").contains("expected f64"));
        assert!(message_at(&errors, "numerics.grid").contains("8..=2048"));
        assert!(message_at(&errors, "numerics.cycle_step").contains("fixed strides"));
        assert!(message_at(&errors, "ball.poisson_ratio").contains("(-1, 0.5)"));
    }

    #[test]
    fn integer_fields_name_their_range_on_type_errors() {
        let errors = errors_of(&json!({"test": {"cycles": 2.5}, "numerics": {"grid": "big"}}));
        assert!(message_at(&errors, "test.cycles").contains("1..=1000000"));
        assert!(message_at(&errors, "numerics.grid").contains("\"auto\""));
    }

    #[test]
    fn hardness_table_problems_carry_indices() {
        let errors = errors_of(&json!({"disc": {
            "hardness_table": [[10, 2551], [5, 2600], [20, -1], [0.5, 2700]]
        }}));
        assert_eq!(
            paths(&errors),
            [
                "disc.hardness_table[1][0]",
                "disc.hardness_table[2][1]",
                "disc.hardness_table[3][0]",
            ]
        );
        let errors = errors_of(&json!({"disc": {"hardness_table": [["a", 1], [2, 3, 4]]}}));
        assert_eq!(
            paths(&errors),
            ["disc.hardness_table[0][0]", "disc.hardness_table[1]"]
        );
    }

    #[test]
    fn hardness_table_must_determine_the_fit() {
        let errors = errors_of(&json!({"disc": {"hardness_table": []}}));
        assert_eq!(paths(&errors), ["disc.hardness_table"]);
        let errors = errors_of(&json!({"disc": {"hardness_table": [[1, 2500]]}}));
        assert!(message_at(&errors, "disc.hardness_table").contains("two cycle counts"));
        let errors = errors_of(&json!({"disc": {
            "hardness_table": [[10, 2500]], "hardness_fit_includes_bulk": false
        }}));
        assert!(message_at(&errors, "disc.hardness_table").contains("two cycle counts"));
    }

    #[test]
    fn softening_law_must_stay_positive_over_the_run() {
        // H = 2473 - 600 ln n passes zero at n = e^(2473/600), about 61.6 cycles.
        let table = json!([[10, 2473.0 - 600.0 * 10f64.ln()]]);
        let short = json!({"disc": {"hardness_table": table}, "test": {"cycles": 60}});
        assert!(parse_scene(&short).is_ok());
        let long = json!({"disc": {"hardness_table": table}, "test": {"cycles": 62}});
        assert_eq!(paths(&errors_of(&long)), ["disc.hardness_table"]);
    }

    #[test]
    fn archard_k_and_calibration_are_exclusive() {
        let calibration = json!({"time_s": 3600, "wear_volume_mm3": 11.72e-3});
        let errors = errors_of(&json!({"wear": {
            "archard_k": 1e-4, "archard_calibration": calibration
        }}));
        let message = message_at(&errors, "wear");
        assert!(message.contains("archard_k") && message.contains("archard_calibration"));
        // Alone, a calibration is fine: a missing `archard_k` is "not given", not the default.
        let scene = parse_scene(&json!({"wear": {"archard_calibration": calibration}}))
            .expect("a calibration without k is valid");
        assert_eq!(scene.wear.archard_k, None);
    }

    #[test]
    fn calibration_derives_k_from_the_3600_s_point() {
        let scene = parse_scene(&json!({
            "preset": "dalmau2018-316l",
            "overrides": {"wear": {
                "archard_k": null,
                "archard_calibration": {"time_s": 3600, "wear_volume_mm3": 11.72e-3}
            }}
        }))
        .expect("a calibration replaces k");
        assert_eq!(
            scene.wear.archard_calibration,
            Some(ArchardCalibration {
                time_s: 3600.0,
                wear_volume_mm3: 11.72e-3,
                hardness_mpa: None,
                load_n: None,
                speed_rpm: None,
                track_radius_mm: None,
            })
        );
        let k = k_of(&scene);
        // By hand: H(3600) = 2454.99 + 63.383 ln 3600 = 2974.0 MPa (fit of the paper table),
        // s = 3600 s x 2 pi x 2.992 mm/s = 67.677 m, k = 11.72e-12 x 2974.0e6 / (5 x 67.677)
        // = 1.0300e-4. Carried to 5 digits: 1e-4 relative.
        assert!(((k - 1.0300e-4) / 1.0300e-4).abs() < 1e-4, "k = {k}");
    }

    #[test]
    fn zero_k_is_a_run_without_wear_but_k_above_one_is_refused() {
        let scene = parse_scene(&json!({"wear": {"archard_k": 0.0}})).expect("k = 0 is valid");
        assert_eq!(scene.wear.archard_k, Some(0.0));
        let errors = errors_of(&json!({"wear": {"archard_k": 1.5}}));
        assert!(message_at(&errors, "wear.archard_k").contains("[0, 1]"));
    }

    #[test]
    fn a_regime_change_is_a_cycle_of_the_run_and_a_k_in_range() {
        let change = json!({"cycle": 300, "archard_k_before": 2e-5});
        let scene =
            parse_scene(&json!({"wear": {"archard_regime_change": change}})).expect("valid");
        let parsed = scene.wear.archard_regime_change.expect("kept");
        assert_eq!((parsed.cycle, parsed.archard_k_before), (300, 2e-5));
        // The k after it still comes from the paper's calibration point.
        assert!(scene.wear.archard_calibration.is_some());
        let errors = errors_of(&json!({"test": {"cycles": 300}, "wear": {
            "archard_regime_change": {"cycle": 300, "archard_k_before": 1.5}
        }}));
        assert_eq!(
            paths(&errors),
            [
                "wear.archard_regime_change.archard_k_before",
                "wear.archard_regime_change.cycle"
            ]
        );
        let message = message_at(&errors, "wear.archard_regime_change.cycle");
        assert!(
            message.contains("below `test.cycles`") && message.contains("1..=299"),
            "{message}"
        );
        let errors = errors_of(&json!({"wear": {"archard_regime_change": [300, 2e-5]}}));
        assert_eq!(paths(&errors), ["wear.archard_regime_change"]);
        let errors = errors_of(&json!({"wear": {"archard_regime_change": {"cycle": 300}}}));
        assert!(message_at(&errors, "wear.archard_regime_change").contains("archard_k_before"));
    }

    #[test]
    fn preset_overrides_merge_and_null_removes_a_section() {
        let scene = parse_scene(&json!({
            "preset": "dalmau2018-316l",
            "overrides": {"test": {"load_n": 10}, "corrosion": null}
        }))
        .expect("valid overrides");
        assert_eq!(scene.test.load_n.to_bits(), 10f64.to_bits());
        assert_eq!(scene.test.speed_rpm.to_bits(), 60f64.to_bits());
        assert_eq!(scene.corrosion, None);
        assert!(scene.disc.hardness_table.is_some());

        let kept = parse_scene(&json!({
            "preset": "dalmau2018-316l",
            "overrides": {"corrosion": {"anodic_area": "real_contact"}}
        }))
        .expect("valid overrides");
        let corrosion = kept.corrosion.expect("the preset has corrosion");
        assert_eq!(corrosion.anodic_area, AnodicArea::RealContact);
        assert_eq!(corrosion.exposed_area_cm2.to_bits(), 2.56f64.to_bits());
    }

    #[test]
    fn preset_errors_point_into_the_overrides() {
        let errors = errors_of(&json!({
            "preset": "dalmau2018-316l",
            "overrides": {"test": {"load_n": 0}}
        }));
        assert_eq!(paths(&errors), ["overrides.test.load_n"]);

        let errors = errors_of(&json!({"preset": "dalmau2019", "ball": {}}));
        assert_eq!(paths(&errors), ["ball", "preset"]);
        assert!(message_at(&errors, "preset").contains("`dalmau2018-316l`"));
    }

    #[test]
    fn sections_must_be_objects_not_field_arrays() {
        let errors = errors_of(&json!({
            "ball": [3.0],
            "corrosion": [1],
            "name": 5,
            "wear": {"archard_calibration": [3600, 0.01], "archard_k": null}
        }));
        assert_eq!(
            paths(&errors),
            ["ball", "corrosion", "wear.archard_calibration", "name"]
        );
        assert!(parse_scene(&json!({"corrosion": null})).is_ok());
    }

    #[test]
    fn a_key_given_twice_is_refused_at_its_path() {
        let Err(SceneErrors(errors)) = parse_scene_str(r#"{"test": {"load_n": 5, "load_n": 50}}"#)
        else {
            panic!("a duplicate key parsed");
        };
        assert_eq!(paths(&errors), ["test.load_n"]);
        assert!(errors[0].message.contains("more than once"), "{errors:?}");
    }

    #[test]
    fn malformed_json_and_non_objects_are_single_errors() {
        let Err(SceneErrors(errors)) = parse_scene_str("{\"test\": ") else {
            panic!("truncated JSON parsed");
        };
        assert_eq!(paths(&errors), [""]);
        assert!(errors[0].message.contains("line 1"));
        assert_eq!(paths(&errors_of(&json!([1, 2]))), [""]);
    }

    #[test]
    fn overflowing_numbers_are_rejected_by_the_json_parser() {
        // serde_json refuses 1e400 rather than producing infinity, so no inf reaches a scene
        // from text; the finiteness checks guard scenes built in Rust.
        let Err(SceneErrors(errors)) = parse_scene_str(r#"{"test": {"load_n": 1e400}}"#) else {
            panic!("1e400 parsed");
        };
        assert!(errors[0].message.contains("out of range"), "{errors:?}");
    }

    #[test]
    fn display_lists_every_problem() {
        let errors = SceneErrors(vec![
            FieldError::new("test.load_n", "must be > 0 N and finite, got -5"),
            FieldError::new("", "a scene must be a JSON object, got 3"),
        ]);
        assert_eq!(
            errors.to_string(),
            "invalid scene, 2 problems:\n  test.load_n: must be > 0 N and finite, got -5\n  \
             a scene must be a JSON object, got 3"
        );
        let json = serde_json::to_value(&errors).expect("errors serialise");
        assert_eq!(json[0]["path"], json!("test.load_n"));
    }

    #[test]
    fn e_corr_keeps_its_meaning_in_another_reference_unless_given() {
        let e_corr = |json: Value| {
            parse_scene(&json)
                .expect("valid")
                .corrosion
                .expect("corrosion")
                .corrosion_potential_v
        };
        // The paper's -0.10 V vs Ag/AgCl (3 M KCl, +0.205 V vs SHE) is -0.136 V vs SCE
        // (+0.241 V vs SHE): two roundings of numbers near 0.2.
        let sce = e_corr(json!({"corrosion": {"reference_electrode": "sce"}}));
        assert!((sce - -0.136).abs() < 1e-15, "{sce}");
        let preset = e_corr(json!({"preset": "dalmau2018-316l",
            "overrides": {"corrosion": {"reference_electrode": "she"}}}));
        assert!((preset - 0.105).abs() < 1e-15, "{preset}");
        let given = e_corr(json!({"corrosion": {"reference_electrode": "sce",
            "corrosion_potential_v": -0.2}}));
        assert_eq!(given.to_bits(), (-0.2f64).to_bits());
        // The scene as run names its E_corr, so it parses back to itself.
        let scene =
            parse_scene(&json!({"corrosion": {"reference_electrode": "sce"}})).expect("valid");
        let echo = serde_json::to_value(&scene).expect("scenes serialise");
        assert_eq!(parse_scene(&echo), Ok(scene));
    }

    #[test]
    fn a_megabyte_of_unknown_keys_is_refused_with_the_first_problems_and_a_count() {
        // The hostile scene of the service's load test: 110,000 unknown keys in one
        // section, and as many at the top.
        let keys = 110_000;
        let disc: serde_json::Map<String, Value> =
            (0..keys).map(|i| (format!("k{i}"), json!(1))).collect();
        // "disc" comes first in insertion order and in key order alike.
        let mut top = serde_json::Map::new();
        top.insert("disc".to_owned(), Value::Object(disc));
        for i in 0..keys {
            top.insert(format!("t{i}"), json!(1));
        }
        let SceneErrors(errors) = parse_scene(&Value::Object(top)).expect_err("refused");
        assert_eq!(errors.len(), MAX_LISTED_PROBLEMS + 1, "{errors:?}");
        let last = errors.last().map(|e| e.message.clone()).unwrap_or_default();
        // The 20 listed are disc's first keys; the rest of disc's and every top-level key
        // after "disc" are counted.
        let unchecked = 2 * keys - MAX_LISTED_PROBLEMS;
        assert!(
            last.starts_with(&format!("{unchecked} more fields were not checked")),
            "{last}"
        );
        // A scene with a few problems still lists each of them.
        let SceneErrors(few) =
            parse_scene(&json!({"test": {"lod_n": 5, "cycles": -1}, "colour": 1}))
                .expect_err("refused");
        assert_eq!(few.len(), 3, "{few:?}");
    }
}
