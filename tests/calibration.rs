//! `tribosim calibrate` end to end: the example tables of `docs/calibration/` through the
//! binary, the fit JSON it writes, a change of regime fitted back, and bad tables and change
//! cycles refused with the column or the cycle named.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn calibrate(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .arg("calibrate")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary starts")
}

fn scratch(name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join(name)
}

#[test]
fn hardness_of_table_3_through_the_command_line() {
    let out = scratch("hardness_fit.json");
    let output = calibrate(&[
        "hardness",
        "docs/calibration/table3_hardness.csv",
        "-o",
        out.to_str().expect("utf-8 path"),
    ]);
    assert!(output.status.success(), "{output:?}");
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("written")).expect("JSON");
    // A = 2454.986623 MPa and its standard error 26.977757 MPa, from the closed-form normal
    // equations evaluated independently (Python); 1e-9 relative allows round-off only.
    let a = fit["a_mpa"]["value"].as_f64().expect("A");
    let se = fit["a_mpa"]["standard_error"].as_f64().expect("se");
    assert!((a - 2454.986623221253).abs() < 1e-9 * a, "{a}");
    assert!((se - 26.977756781226276).abs() < 1e-9 * se, "{se}");
    assert_eq!(fit["residuals"].as_array().map(Vec::len), Some(6));
    assert_eq!(fit["scene"]["disc"]["hardness_table"][4][0], 3600.0);
}

#[test]
fn a_lab_export_gives_the_fit_of_the_documented_table_and_says_how_it_was_read() {
    // Table 3's hardness as a tab-separated export with decimal commas, in GPa, the headers
    // `Cycles` and `Hardness [GPa]`: the same points as docs/calibration/table3_hardness.csv.
    let (documented, exported) = (
        scratch("hardness_documented.json"),
        scratch("hardness_tab.json"),
    );
    for (table, out) in [
        ("docs/calibration/table3_hardness.csv", &documented),
        ("tests/fixtures/lab/hardness_tab.txt", &exported),
    ] {
        let output = calibrate(&["hardness", table, "-o", out.to_str().expect("utf-8 path")]);
        assert!(output.status.success(), "{output:?}");
        if table.ends_with(".txt") {
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(
                stderr.contains("read the column `Hardness [GPa]` as `hardness_mpa`"),
                "{stderr}"
            );
        }
    }
    let a = |path: &PathBuf| -> f64 {
        let fit: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path).expect("written")).expect("JSON");
        fit["a_mpa"]["value"].as_f64().expect("A")
    };
    // 2.551 GPa times 1e3 is 2551 MPa to the last bit or two: the fits agree to round-off.
    assert!((a(&exported) / a(&documented) - 1.0).abs() < 1e-12);
}

#[test]
fn a_bad_table_is_refused_naming_the_column() {
    let table = scratch("negative_volume.csv");
    std::fs::write(&table, "time_s,volume_mm3\n10,1e-3\n60,-2e-3\n").expect("written");
    let output = calibrate(&["archard", table.to_str().expect("utf-8 path")]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("`volume_mm3`: row 2"), "{stderr}");
    let output = calibrate(&["tafel", "docs/calibration/table3_hardness.csv"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("`potential_v`"), "{stderr}");
}

/// A table made by a two-regime run of the library, fitted back through the command line.
#[test]
fn a_change_of_regime_through_the_command_line() {
    use std::sync::atomic::AtomicBool;
    use tribosim::simulation::{Plan, parse_scene_str, run};

    let small = r#"{"preset": "dalmau2018-316l", "overrides": {
        "test": {"cycles": 200}, "numerics": {"grid": 16, "cycle_step": 1}}}"#;
    let scene_path = scratch("regime_scene.json");
    std::fs::write(&scene_path, small).expect("written");
    let mut scene = parse_scene_str(small).expect("valid").into_scene();
    scene.wear.archard_k = Some(1e-4);
    scene.wear.archard_calibration = None;
    // The fit compares totals, wear plus WAC, so its k is the mechanical loss's.
    scene.wear.archard_k_basis = tribosim::wear::VolumeBasis::Mechanical;
    scene.wear.archard_regime_change = Some(tribosim::scene::ArchardRegimeChange {
        cycle: 85,
        archard_k_before: 2e-5,
    });
    let plan = Plan::new(scene).expect("valid");
    let result = run(&plan, &mut |_| {}, &AtomicBool::new(false)).expect("runs");
    let mut csv = "cycles,volume_mm3\n".to_owned();
    for record in result
        .cycles
        .iter()
        .filter(|r| [10, 40, 70, 100, 140, 200].contains(&r.cycle))
    {
        // What a profilometer measures, and what the fit compares with when the scene has
        // corrosion: the total, wear plus WAC.
        let total = record.total_volume_mm3.expect("the preset has corrosion");
        csv.push_str(&format!("{},{:e}\n", record.cycle, total));
    }
    let table = scratch("regime_table.csv");
    std::fs::write(&table, csv).expect("written");
    let out = scratch("regime_fit.json");
    let path = |p: &PathBuf| p.to_str().expect("utf-8 path").to_owned();
    let output = calibrate(&[
        "archard",
        &path(&table),
        "--scene",
        &path(&scene_path),
        "--regime-change",
        "85",
        "-o",
        &path(&out),
    ]);
    assert!(output.status.success(), "{output:?}");
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("written")).expect("JSON");
    // The default tolerance stops Gauss-Newton at a step below 1e-3 of each k, and what is
    // left after that step is smaller than it (see calibration::regime's tests).
    let k = |name: &str| fit["two_regimes"][name]["value"].as_f64().expect(name);
    assert!((k("archard_k_before") / 2e-5 - 1.0).abs() < 1e-3, "{fit}");
    assert!((k("archard_k_after") / 1e-4 - 1.0).abs() < 1e-3, "{fit}");
    assert_eq!(fit["comparison"]["better"], "two_regimes");
    assert_eq!(fit["scene"]["wear"]["archard_regime_change"]["cycle"], 85);
    assert_eq!(fit["points"].as_array().map(Vec::len), Some(6));
}

#[test]
fn bad_change_cycles_are_refused_by_the_command_line() {
    let table = "docs/calibration/table3_wear.csv";
    let refused = |args: &[&str]| {
        let output = calibrate(args);
        assert!(!output.status.success());
        String::from_utf8_lossy(&output.stderr).into_owned()
    };
    let stderr = refused(&["archard", table, "--regime-change", "5000"]);
    assert!(stderr.contains("outside the table's cycles"), "{stderr}");
    let stderr = refused(&["archard", table, "--regime-change", "30"]);
    assert!(stderr.contains("1 point(s) up to it"), "{stderr}");
    let stderr = refused(&["archard", table, "--regime-change", "soon"]);
    assert!(stderr.contains("`auto`"), "{stderr}");
    let hardness = "docs/calibration/table3_hardness.csv";
    let stderr = refused(&["hardness", hardness, "--regime-change", "300"]);
    assert!(stderr.contains("`calibrate archard` only"), "{stderr}");
}

#[test]
fn the_papers_ocp_trace_through_the_command_line() {
    // docs/calibration/paper_ocp_trace.csv: an hour at E_corr, then the potentials of
    // A_a = 50 F / H for 3600 s of rubbing (the default run: a few seconds).
    let out = scratch("ocp_trace_fit.json");
    let output = calibrate(&[
        "ocp",
        "docs/calibration/paper_ocp_trace.csv",
        "--rubbing-start",
        "3600",
        "--rubbing-stop",
        "7200",
        "-o",
        out.to_str().expect("utf-8 path"),
    ]);
    assert!(output.status.success(), "{output:?}");
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("written")).expect("JSON");
    assert_eq!(fit["parameter"], "repassivation_time_s");
    let tau = fit["repassivation_time_s"]["value"].as_f64().expect("tau");
    assert!((tau - 0.148).abs() <= 0.5e-3, "{fit}");
    let phases: Vec<&str> = fit["points"]
        .as_array()
        .expect("points")
        .iter()
        .map(|p| p["phase"].as_str().expect("a phase"))
        .collect();
    assert_eq!(phases[..3], ["before"; 3]);
    assert_eq!(phases[3..], ["rubbing"; 5]);
    assert_eq!(fit["scene"]["test"]["ocp_before_s"], 3600.0);
    // An option of another fit is refused by name.
    let output = calibrate(&[
        "tafel",
        "docs/calibration/paper_ocp.csv",
        "--rubbing-start",
        "3600",
    ]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("--rubbing-start applies to `calibrate ocp` only"),
        "{stderr}"
    );
}
