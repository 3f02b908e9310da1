//! `tribosim report` against the built binary: a run's report, a comparison and a study's,
//! each one self-contained HTML file (nothing fetched, nothing run) holding its figures,
//! tables, methods and provenance; and the same reports over HTTP.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use serde_json::{Value, json};

use common::{
    Server, TempDir, args, expect_client_error, is_final, small_scene, submit, wait_for_job,
};

/// A run with corrosion on a small grid: a dozen cycles in well under a second.
const SCENE: &str = r#"{"preset": "dalmau2018-316l", "overrides": {
    "name": "report run", "test": {"cycles": 12}, "numerics": {"grid": 32}}}"#;

/// An id no job has.
const UNKNOWN_JOB: &str = "00000000-0000-4000-8000-000000000000";

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
        "spread_mm3": [1e-5, 1e-5]}, "profile": null, "ocp": null}"#;
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

    // The same points as a lab's CSV, read as the service reads a PUT of it: the same
    // report, up to the time it was made (the last table, after "This report").
    let csv = "cycles,volume_mm3,spread_mm3\n5,1e-4,1e-5\n10,2e-4,1e-5\n";
    std::fs::write(dir.path().join("wear.csv"), csv).expect("CSV");
    let args = [
        "report",
        "result.json",
        "--wear-volume",
        "wear.csv",
        "-o",
        "csv.html",
    ];
    tribosim(dir.path(), &args);
    let from_csv = read(dir.path(), "csv.html");
    let before_its_time = |html: &str| html.split("This report").next().map(str::to_owned);
    assert_eq!(before_its_time(&from_csv), before_its_time(&html));

    // A CSV where the JSON belongs is sent to the option that reads it; a refused table
    // names its option, its file and its column.
    for (args, expected) in [
        (
            ["report", "result.json", "--measurements", "wear.csv"],
            "a lab's table (CSV or JSON, units in the column names) goes in with --wear-volume",
        ),
        (
            ["report", "result.json", "--ocp", "wear.csv"],
            "--ocp wear.csv: unknown column `cycles`",
        ),
    ] {
        let output = Command::new(env!("CARGO_BIN_EXE_tribosim"))
            .args(args)
            .current_dir(dir.path())
            .output()
            .expect("start tribosim");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && stderr.contains(expected),
            "{stderr}"
        );
    }
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
    // The total, mechanical and corrosion volumes, the depth and the potential against each
    // of the two axes.
    assert_eq!(html.matches("<svg").count(), 10);
    assert!(html.contains("total volume lost against speed (rpm)"));
    assert!(html.contains("wear-accelerated corrosion volume against load (N)"));
    // The members table names its axes in words too.
    assert!(html.contains("<th>load (N)</th><th>speed (rpm)</th>"));
}

/// GET `path` and expect 200 with an HTML download saved as `filename`; the body.
async fn get_report(
    client: &reqwest::Client,
    server: &Server,
    path: &str,
    filename: &str,
) -> String {
    let response = client.get(server.url(path)).send().await.expect("GET");
    assert_eq!(response.status(), 200, "GET {path}");
    let headers = response.headers();
    assert_eq!(headers["content-type"], "text/html; charset=utf-8");
    let disposition = headers["content-disposition"].to_str().expect("ascii");
    assert_eq!(disposition, format!("attachment; filename=\"{filename}\""));
    response.text().await.expect("the report's text")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_service_serves_a_job_report_with_its_measurements_a_comparison_and_a_study() {
    let dir = TempDir::new("report-http");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let mut ids = Vec::new();
    for cycles in [6, 9] {
        let job = submit(&client, &server.base, &small_scene(cycles)).await;
        let id = job["id"].as_str().expect("id").to_owned();
        let done = wait_for_job(&client, &server.base, &id, is_final).await;
        assert_eq!(done["status"], "succeeded", "{done}");
        ids.push(id);
    }
    let put = client
        .put(server.url(&format!("/api/v1/jobs/{}/measurements/potential", ids[0])))
        .header("content-type", "text/csv")
        .body("time_s,potential_v\n1,-0.3\n3,-0.35\n")
        .send()
        .await
        .expect("PUT");
    assert_eq!(put.status(), 200);

    let html = get_report(
        &client,
        &server,
        &format!("/api/v1/jobs/{}/report", ids[0]),
        "small-6-cycles.report.html",
    )
    .await;
    assert_self_contained(&html);
    assert_eq!(html.matches("<svg").count(), 6);
    assert!(html.contains("Potential against the model&#39;s, on the record&#39;s clock"));

    let both = format!("/api/v1/report?jobs={},{}", ids[0], ids[1]);
    let html = get_report(&client, &server, &both, "comparison.report.html").await;
    assert_self_contained(&html);
    assert!(html.contains("small, 6 cycles") && html.contains("small, 9 cycles"));
    for refused in [
        format!("/api/v1/report?jobs={}", ids[0]),
        format!("/api/v1/report?jobs={0},{0}", ids[0]),
        "/api/v1/report?jobs=nope,also-not".to_owned(),
        "/api/v1/report".to_owned(),
    ] {
        let response = client.get(server.url(&refused)).send().await.expect("GET");
        expect_client_error(response, 400).await;
    }
    let unknown = format!("/api/v1/jobs/{UNKNOWN_JOB}/report");
    let response = client.get(server.url(&unknown)).send().await.expect("GET");
    expect_client_error(response, 404).await;

    let study = json!({"base": small_scene(2), "axes": {"test.load_n": [2, 5]}});
    let response = client
        .post(server.url("/api/v1/studies"))
        .json(&study)
        .send()
        .await
        .expect("POST");
    assert_eq!(response.status(), 201);
    let record: Value = response.json().await.expect("JSON");
    let id = record["id"].as_str().expect("id");
    for member in record["members"].as_array().expect("members") {
        let job = member["job_id"].as_str().expect("job id");
        wait_for_job(&client, &server.base, job, is_final).await;
    }
    let html = get_report(
        &client,
        &server,
        &format!("/api/v1/studies/{id}/report"),
        "small-2-cycles.report.html",
    )
    .await;
    assert_self_contained(&html);
    assert!(html.contains("total volume lost against load (N)"));
    server.stop().await;
}
