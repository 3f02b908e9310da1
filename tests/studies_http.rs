//! Studies and calibrations over HTTP, against the real `tribosim serve` binary: a study's
//! summary equals `tribosim study`'s for the same file, cancelling a study cancels its
//! members, a study over the limits is refused whole, a study survives a restart (and a
//! damaged study file is quarantined without stopping it), and a calibration over HTTP gives
//! the numbers of `tribosim calibrate`.

mod common;

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use serde_json::{Value, json};

use common::process::{ServerProcess, serve_command};
use common::{PATIENCE, TempDir, get_json};

/// A 2 x 2 study of short runs (30 cycles on 32 cells: well under a second each).
fn two_by_two() -> Value {
    json!({
        "base": {
            "preset": "dalmau2018-316l",
            "overrides": {"test": {"cycles": 30}, "numerics": {"grid": 32}}
        },
        "axes": {"test.load_n": [2, 5], "test.speed_rpm": [30, 60]}
    })
}

/// A one-worker server with `flags` added.
fn server(data_dir: &Path, flags: &[&str]) -> ServerProcess {
    let mut command = serve_command(data_dir, 1);
    command.args(flags);
    ServerProcess::spawn(command)
}

async fn post(client: &reqwest::Client, url: &str, body: &Value) -> (u16, Value) {
    let response = client.post(url).json(body).send().await.expect("POST");
    let status = response.status().as_u16();
    (status, response.json().await.expect("JSON body"))
}

/// Polls `url` until `done` holds for its JSON.
async fn wait_for(client: &reqwest::Client, url: &str, done: impl Fn(&Value) -> bool) -> Value {
    let poll = async {
        loop {
            let value = get_json(client, url).await;
            if done(&value) {
                return value;
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    };
    tokio::time::timeout(PATIENCE, poll)
        .await
        .expect("state reached")
}

fn ended(study: &Value) -> bool {
    !matches!(study["status"].as_str(), Some("queued" | "running"))
}

/// The summary's member rows with each run's wall time (the only field that differs between
/// two runs of a deterministic simulation) removed.
fn rows_without_wall_time(summary: &Value) -> Vec<Value> {
    let mut rows = summary["members"].as_array().expect("members").clone();
    for row in &mut rows {
        row["summary"]
            .as_object_mut()
            .expect("a summary")
            .remove("wall_s");
    }
    rows
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_study_over_http_summarises_as_tribosim_study_does() {
    let dir = TempDir::new("study-http");
    let study_file = dir.path().join("study.json");
    std::fs::write(&study_file, two_by_two().to_string()).expect("write the study");
    let cli_summary = dir.path().join("cli.json");
    let status = Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(["study", "--workers", "1", "-o"])
        .arg(&cli_summary)
        .arg(&study_file)
        .status()
        .expect("run tribosim study");
    assert!(status.success());
    let cli: Value =
        serde_json::from_slice(&std::fs::read(&cli_summary).expect("read")).expect("JSON");

    let server = ServerProcess::spawn(serve_command(&dir.path().join("data"), 2));
    let client = reqwest::Client::new();
    let (code, study) = post(&client, &server.url("/api/v1/studies"), &two_by_two()).await;
    assert_eq!(code, 201, "{study}");
    assert_eq!(study["members"].as_array().map(Vec::len), Some(4));
    // Named after its base (the preset's name), not its first member.
    assert_eq!(study["name"], "316L vs alumina, 5 N, 60 rpm", "{study}");
    let id = study["id"].as_str().expect("id");
    let study = wait_for(
        &client,
        &server.url(&format!("/api/v1/studies/{id}")),
        ended,
    )
    .await;
    assert_eq!(study["status"], "succeeded", "{study}");
    assert_eq!(study["counts"]["succeeded"], 4, "{study}");
    // Each member is an ordinary job.
    let jobs = get_json(&client, &server.url("/api/v1/jobs")).await;
    for member in study["members"].as_array().expect("members") {
        let job_id = member["job_id"].as_str().expect("job id");
        let job = jobs
            .as_array()
            .and_then(|jobs| jobs.iter().find(|job| job["id"] == job_id))
            .expect("the member's job is listed");
        assert_eq!(job["status"], "succeeded", "{job}");
    }

    let summary = get_json(
        &client,
        &server.url(&format!("/api/v1/studies/{id}/summary")),
    )
    .await;
    assert_eq!(summary["axes"], cli["axes"]);
    assert_eq!(
        rows_without_wall_time(&summary),
        rows_without_wall_time(&cli)
    );
    let csv = client
        .get(server.url(&format!("/api/v1/studies/{id}/summary.csv")))
        .send()
        .await
        .expect("GET csv")
        .text()
        .await
        .expect("text");
    assert_eq!(csv.lines().count(), 5, "{csv}");
    assert!(
        csv.starts_with("member,test.load_n,test.speed_rpm,cycles,"),
        "{csv}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cancelling_a_study_cancels_its_members_and_a_second_delete_removes_it() {
    let dir = TempDir::new("study-cancel");
    let server = server(dir.path(), &[]);
    let client = reqwest::Client::new();
    // Every cycle solved on a fine grid: the first member is still running when the DELETE
    // comes, and the others wait for the one worker.
    let slow = json!({
        "base": {
            "preset": "dalmau2018-316l",
            "overrides": {
                "test": {"cycles": 3000},
                "numerics": {"grid": 128, "domain_um": 256, "cycle_step": 1}
            }
        },
        "axes": {"test.load_n": [2, 5, 10]}
    });
    let (code, study) = post(&client, &server.url("/api/v1/studies"), &slow).await;
    assert_eq!(code, 201, "{study}");
    let id = study["id"].as_str().expect("id").to_owned();
    let first_job = study["members"][0]["job_id"]
        .as_str()
        .expect("job")
        .to_owned();
    wait_for(
        &client,
        &server.url(&format!("/api/v1/jobs/{first_job}")),
        |job| job["cycles_done"].as_u64() >= Some(1),
    )
    .await;
    let study_url = server.url(&format!("/api/v1/studies/{id}"));
    let response = client.delete(&study_url).send().await.expect("DELETE");
    assert_eq!(
        response.status(),
        202,
        "the running member stops within a cycle"
    );
    let study = wait_for(&client, &study_url, ended).await;
    assert_eq!(study["status"], "cancelled", "{study}");
    assert_eq!(study["counts"]["cancelled"], 3, "{study}");
    for member in study["members"].as_array().expect("members") {
        let job_id = member["job_id"].as_str().expect("job id");
        let job = get_json(&client, &server.url(&format!("/api/v1/jobs/{job_id}"))).await;
        assert_eq!(job["status"], "cancelled", "{job}");
    }
    let summary = get_json(
        &client,
        &server.url(&format!("/api/v1/studies/{id}/summary")),
    )
    .await;
    assert!(
        summary["members"]
            .as_array()
            .expect("members")
            .iter()
            .all(|row| row["error"] == "cancelled"),
        "{summary}"
    );

    let response = client.delete(&study_url).send().await.expect("DELETE");
    assert_eq!(response.status(), 204);
    let response = client.get(&study_url).send().await.expect("GET");
    assert_eq!(response.status(), 404);
    let response = client
        .get(server.url(&format!("/api/v1/jobs/{first_job}")))
        .send()
        .await
        .expect("GET");
    assert_eq!(response.status(), 404, "the members' jobs are removed too");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_study_over_the_member_limit_or_the_queue_is_refused_whole() {
    let dir = TempDir::new("study-limit");
    // The queue's 2 is the limit that applies, not the 3 members allowed a study.
    let server = server(
        dir.path(),
        &["--max-study-members", "3", "--queue-capacity", "2"],
    );
    let client = reqwest::Client::new();
    let url = server.url("/api/v1/studies");
    let mut three = two_by_two();
    three["axes"] = json!({"test.load_n": [2, 5, 10]});
    let (code, error) = post(&client, &url, &three).await;
    assert_eq!(code, 422, "{error}");
    let message = error["error"].as_str().expect("message");
    assert!(
        message.contains("3 members") && message.contains("limit of 2"),
        "{message}"
    );
    assert!(message.contains("--queue-capacity"), "{message}");
    assert_eq!(error["fields"][0]["path"], "axes", "{error}");

    // A study sent as another type is told it is the study that must be JSON.
    let response = client
        .post(&url)
        .header("content-type", "text/plain")
        .body(two_by_two().to_string())
        .send()
        .await
        .expect("POST");
    assert_eq!(response.status().as_u16(), 415);
    let error: Value = response.json().await.expect("JSON body");
    let message = error["error"].as_str().expect("message");
    assert!(message.starts_with("the study must be sent"), "{message}");

    let mut unknown = two_by_two();
    unknown["axes"] = json!({"test.lod_n": [2, 5]});
    let (code, error) = post(&client, &url, &unknown).await;
    assert_eq!(code, 422, "{error}");
    assert_eq!(
        error["fields"][0]["path"], "base.overrides.test.lod_n",
        "{error}"
    );

    let jobs = get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(jobs, json!([]), "a refused study leaves no job behind");
    drop(server);

    // With room in the queue, the study limit applies and is named.
    let server = self::server(
        &dir.path().join("roomy"),
        &["--max-study-members", "3", "--queue-capacity", "8"],
    );
    let url = server.url("/api/v1/studies");
    let (code, error) = post(&client, &url, &two_by_two()).await;
    assert_eq!(code, 422, "{error}");
    let message = error["error"].as_str().expect("message");
    assert!(
        message.contains("4 members") && message.contains("limit of 3"),
        "{message}"
    );
    assert!(message.contains("--max-study-members"), "{message}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_study_survives_a_restart_and_a_damaged_study_file_is_quarantined() {
    let dir = TempDir::new("study-restart");
    let client = reqwest::Client::new();
    let mut first = server(dir.path(), &[]);
    let (code, study) = post(&client, &first.url("/api/v1/studies"), &two_by_two()).await;
    assert_eq!(code, 201, "{study}");
    let id = study["id"].as_str().expect("id").to_owned();
    let path = format!("/api/v1/studies/{id}");
    let before = wait_for(&client, &first.url(&path), ended).await;
    let summary_before = get_json(&client, &first.url(&format!("{path}/summary"))).await;
    first.kill_9();
    let damaged = dir
        .path()
        .join("studies")
        .join(format!("{}.json", uuid::Uuid::new_v4()));
    std::fs::write(&damaged, "{\"id\": ").expect("write a damaged study");

    let second = server(dir.path(), &[]);
    assert_eq!(get_json(&client, &second.url(&path)).await, before);
    let summary_after = get_json(&client, &second.url(&format!("{path}/summary"))).await;
    assert_eq!(
        rows_without_wall_time(&summary_after),
        rows_without_wall_time(&summary_before)
    );
    let studies = get_json(&client, &second.url("/api/v1/studies")).await;
    assert_eq!(studies.as_array().map(Vec::len), Some(1), "{studies}");
    assert!(!damaged.exists(), "the damaged study file is moved aside");
    let quarantined = std::fs::read_dir(dir.path().join("quarantine"))
        .expect("a quarantine directory")
        .count();
    assert_eq!(quarantined, 1);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hardness_calibration_over_http_gives_the_numbers_of_tribosim_calibrate() {
    let dir = TempDir::new("calibration-http");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let table_path = root.join("docs/calibration/table3_hardness.csv");
    let cli_output = dir.path().join("fit.json");
    let status = Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(["calibrate", "hardness"])
        .arg(&table_path)
        .arg("-o")
        .arg(&cli_output)
        .status()
        .expect("run tribosim calibrate");
    assert!(status.success());
    let cli: Value =
        serde_json::from_slice(&std::fs::read(&cli_output).expect("read")).expect("JSON");

    let server = server(&dir.path().join("data"), &[]);
    let client = reqwest::Client::new();
    let url = server.url("/api/v1/calibrations");
    let table = std::fs::read_to_string(&table_path).expect("read the table");
    let (code, started) = post(&client, &url, &json!({"kind": "hardness", "table": table})).await;
    assert_eq!(code, 202, "{started}");
    let id = started["id"].as_str().expect("id");
    let fit = wait_for(
        &client,
        &server.url(&format!("/api/v1/calibrations/{id}")),
        |c| c["status"] != "running",
    )
    .await;
    assert_eq!(fit["status"], "succeeded", "{fit}");
    assert_eq!(fit["result"], cli, "the same fit, to the last digit");

    let bad = json!({"kind": "hardness", "table": "cycles,hardness_mpa\n10,2551\n60,abc\n"});
    let (code, error) = post(&client, &url, &bad).await;
    assert_eq!(code, 422, "{error}");
    let message = error["error"].as_str().expect("message");
    assert!(
        message.contains("`hardness_mpa`") && message.contains("row 2"),
        "{message}"
    );
    let backwards =
        json!({"kind": "archard", "table": {"time_s": [60, 10], "volume_mm3": [1e-3, 2e-3]}});
    let (code, error) = post(&client, &url, &backwards).await;
    assert_eq!(code, 422, "{error}");
    let message = error["error"].as_str().expect("message");
    assert!(
        message.contains("`time_s`") && message.contains("row 2"),
        "{message}"
    );

    // A change of regime is refused before any run: on another fit, as no cycle, and at a
    // cycle outside Table 3's 10 to 3600 cycles.
    let wear = std::fs::read_to_string(root.join("docs/calibration/table3_wear.csv"))
        .expect("read the wear table");
    for (kind, table, change) in [
        ("hardness", &table, json!(300)),
        ("archard", &wear, json!("soon")),
        ("archard", &wear, json!(5000)),
    ] {
        let request = json!({"kind": kind, "table": table, "options": {"regime_change": change}});
        let (code, error) = post(&client, &url, &request).await;
        assert_eq!(code, 422, "{kind} {change}: {error}");
        let field = &error["fields"][0]["path"];
        assert!(
            field == "options.regime_change" || field == "table",
            "{kind} {change}: {error}"
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_ocp_trace_over_http_fits_the_repassivation_time_as_tribosim_calibrate() {
    let dir = TempDir::new("calibration-ocp-http");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let table_path = root.join("docs/calibration/paper_ocp_trace.csv");
    let cli_output = dir.path().join("fit.json");
    let status = Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(["calibrate", "ocp"])
        .arg(&table_path)
        .args(["--rubbing-start", "3600", "--rubbing-stop", "7200", "-o"])
        .arg(&cli_output)
        .status()
        .expect("run tribosim calibrate");
    assert!(status.success());
    let cli: Value =
        serde_json::from_slice(&std::fs::read(&cli_output).expect("read")).expect("JSON");

    let server = server(&dir.path().join("data"), &[]);
    let client = reqwest::Client::new();
    let url = server.url("/api/v1/calibrations");
    let table = std::fs::read_to_string(&table_path).expect("read the table");
    let options = json!({"rubbing_start_s": 3600, "rubbing_stop_s": 7200});
    let request = json!({"kind": "ocp", "table": table, "options": options});
    let (code, started) = post(&client, &url, &request).await;
    assert_eq!(code, 202, "{started}");
    let id = started["id"].as_str().expect("id");
    let fit = wait_for(
        &client,
        &server.url(&format!("/api/v1/calibrations/{id}")),
        |c| c["status"] != "running",
    )
    .await;
    assert_eq!(fit["status"], "succeeded", "{fit}");
    assert_eq!(fit["result"], cli, "the same fit, to the last digit");
    assert_eq!(fit["result"]["parameter"], "repassivation_time_s");

    // Refused before any run: a rubbing time on another fit (the option named), a stop
    // without its start (the table's field).
    let (code, error) = post(
        &client,
        &url,
        &json!({"kind": "tafel", "table": table, "options": {"rubbing_start_s": 3600}}),
    )
    .await;
    assert_eq!(code, 422, "{error}");
    assert_eq!(
        error["fields"][0]["path"], "options.rubbing_start_s",
        "{error}"
    );
    let (code, error) = post(
        &client,
        &url,
        &json!({"kind": "ocp", "table": table, "options": {"rubbing_stop_s": 7200}}),
    )
    .await;
    assert_eq!(code, 422, "{error}");
    assert!(
        error["error"]
            .as_str()
            .is_some_and(|m| m.contains("rubbing start")),
        "{error}"
    );
}
