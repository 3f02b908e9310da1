//! `tribosim calibrate` end to end: the example tables of `docs/calibration/` through the
//! binary, the fit JSON it writes, and a bad table refused with the column named.

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
