//! `tribosim report` against the built binary: a run's report, a comparison and a study's,
//! each one self-contained HTML file (nothing fetched, nothing run) holding its figures,
//! tables, methods and provenance.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use common::TempDir;

/// A run with corrosion on a small grid: a dozen cycles in well under a second.
const SCENE: &str = r#"{"preset": "dalmau2018-316l", "overrides": {
    "name": "report run", "test": {"cycles": 12}, "numerics": {"grid": 32}}}"#;

fn tribosim(dir: &Path, args: &[&str]) -> Output {
    let output = Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("start tribosim");
    assert!(
        output.status.success(),
        "tribosim {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

fn read(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).expect("the report is written")
}

/// What every report is: one HTML document with its CSS inline, its print rules, and no
/// script, stylesheet link, image or frame that would fetch or run anything.
fn assert_self_contained(html: &str) {
    assert!(html.starts_with("<!DOCTYPE html>"), "{}", &html[..80]);
    assert!(html.contains("@page"), "print rules");
    for forbidden in [
        "<script", "<link", "<img", "<iframe", "src=", "@import", "url(",
    ] {
        assert!(!html.contains(forbidden), "the report holds `{forbidden}`");
    }
}

#[test]
fn a_run_report_holds_every_figure_its_tables_the_methods_and_the_provenance() {
    let dir = TempDir::new("report-run");
    std::fs::write(dir.path().join("scene.json"), SCENE).expect("scene");
    tribosim(dir.path(), &["run", "scene.json", "-o", "result.json"]);
    let measured = r#"{"wear_volume": {"cycles": [5, 10], "volume_mm3": [1e-4, 2e-4],
        "spread_mm3": [1e-5, 1e-5]}, "profile": null, "potential": null}"#;
    std::fs::write(dir.path().join("m.json"), measured).expect("measurements");
    tribosim(
        dir.path(),
        &[
            "report",
            "result.json",
            "--measurements",
            "m.json",
            "-o",
            "r.html",
        ],
    );
    let html = read(dir.path(), "r.html");
    assert_self_contained(&html);
    // Volume, depth, potential, WAC, profiles and pressure maps, as on the page.
    assert_eq!(html.matches("<figure>").count(), 6, "every figure drawn");
    assert_eq!(html.matches("<svg").count(), 6);
    // Summary, the scene's differences from its preset and its fields, models, residuals,
    // the run's provenance and the report's.
    assert_eq!(html.matches("<table>").count(), 7);
    assert!(html.contains("<td>test.cycles</td><td>3600</td><td>12</td>"));
    assert!(html.contains("Wear 394-395 (2018) 166-175"));
    let result: serde_json::Value =
        serde_json::from_str(&read(dir.path(), "result.json")).expect("JSON");
    let hash = result["provenance"]["scene_sha256"].as_str().expect("hash");
    assert!(html.contains(hash), "the scene's SHA-256 is in the report");
    assert!(html.contains("attached measurement"));
    assert!(html.contains("residual"));
}

#[test]
fn a_comparison_and_a_study_have_their_own_reports() {
    let dir = TempDir::new("report-compare");
    std::fs::write(dir.path().join("a.json"), SCENE).expect("scene");
    let heavier = SCENE.replace(r#""cycles": 12}"#, r#""cycles": 12, "load_n": 8}"#);
    std::fs::write(dir.path().join("b.json"), heavier).expect("scene");
    tribosim(dir.path(), &["run", "a.json", "-o", "ra.json"]);
    tribosim(dir.path(), &["run", "b.json", "-o", "rb.json"]);
    tribosim(
        dir.path(),
        &["report", "ra.json", "rb.json", "-o", "cmp.html"],
    );
    let html = read(dir.path(), "cmp.html");
    assert_self_contained(&html);
    assert_eq!(
        html.matches("<svg").count(),
        5,
        "volume, depth, potential, WAC, profiles"
    );
    assert!(
        html.contains("<td>test.load_n</td><td>5.0</td><td>8.0</td>"),
        "the scenes' difference"
    );
    assert!(html.contains("<th>ra.json</th><th>rb.json</th>"));

    let study = r#"{"base": {"name": "tiny", "test": {"cycles": 2}, "numerics": {"grid": 32}},
                    "axes": {"test.load_n": [2, 5], "test.speed_rpm": [30, 60]}}"#;
    std::fs::write(dir.path().join("s.json"), study).expect("study");
    tribosim(dir.path(), &["study", "s.json", "-o", "summary.json"]);
    tribosim(dir.path(), &["report", "summary.json", "-o", "study.html"]);
    let html = read(dir.path(), "study.html");
    assert_self_contained(&html);
    // Wear volume, depth, total volume and potential against each of the two axes.
    assert_eq!(html.matches("<svg").count(), 8);
    assert!(html.contains("wear volume against test.speed_rpm"));
    assert!(html.contains("<th>test.load_n</th><th>test.speed_rpm</th>"));
}
