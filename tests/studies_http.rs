//! Studies over HTTP, against the real `tribosim serve` binary: a study's summary equals
//! `tribosim study`'s for the same file, cancelling a study cancels its members, a study over
//! the limits is refused whole, and a study survives a restart (and a damaged study file is
//! quarantined without stopping it). Calibrations over HTTP: `calibrations_http.rs`.

mod common;

use std::ffi::OsStr;
use std::path::Path;

use serde_json::{Value, json};

use common::process::{ServerProcess, cli_json, serve_command};
use common::{TempDir, get_json, post, refused, wait_for};

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
    let study_args = [
        OsStr::new("study"),
        "--workers".as_ref(),
        "1".as_ref(),
        study_file.as_ref(),
    ];
    let cli = cli_json(study_args, &dir.path().join("cli.json"));

    let server = ServerProcess::spawn(serve_command(&dir.path().join("data"), 2));
    let client = reqwest::Client::new();
    let (code, study) = post(&client, &server.url("/api/v1/studies"), &two_by_two()).await;
    assert_eq!(code, 201, "{study}");
    assert_eq!(study["members"].as_array().map(Vec::len), Some(4));
    // Named after its preset and its axes: the preset's own name states 5 N and 60 rpm.
    assert_eq!(
        study["name"], "dalmau2018-316l varied in test.load_n, test.speed_rpm",
        "{study}"
    );
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
    let error = refused(&client, &url, &three).await;
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
    let error = refused(&client, &url, &unknown).await;
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
    let error = refused(&client, &url, &two_by_two()).await;
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

/// A study of `members` loads from 1 to 6 N on short runs.
fn load_range(members: u64) -> Value {
    json!({
        "base": {
            "preset": "dalmau2018-316l",
            "overrides": {"test": {"cycles": 3}, "numerics": {"grid": 16}, "corrosion": null}
        },
        "axes": {"test.load_n": {"from": 1, "to": 6, "steps": members - 1}}
    })
}

/// How many jobs and studies the server lists.
async fn counts(client: &reqwest::Client, server: &ServerProcess) -> (usize, usize) {
    let jobs = get_json(client, &server.url("/api/v1/jobs?limit=1000")).await;
    let studies = get_json(client, &server.url("/api/v1/studies?limit=1000")).await;
    let len = |v: &Value| v.as_array().map_or(0, Vec::len);
    (len(&jobs), len(&studies))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_crash_while_a_study_is_accepted_leaves_the_whole_study_or_nothing() {
    let dir = TempDir::new("study-crash");
    let client = reqwest::Client::new();
    let study = load_range(60);
    // How long an acceptance takes here, to spread the kills across it.
    let first = server(dir.path(), &["--queue-capacity", "1000"]);
    let started = std::time::Instant::now();
    let (code, _) = post(&client, &first.url("/api/v1/studies"), &study).await;
    assert_eq!(code, 201);
    let took = started.elapsed();
    drop(first);
    let tries = 8;
    for attempt in 0..tries {
        let mut victim = server(dir.path(), &["--queue-capacity", "1000"]);
        let before = counts(&client, &victim).await;
        let url = victim.url("/api/v1/studies");
        let (sender, body) = (client.clone(), study.clone());
        let posting = tokio::spawn(async move { sender.post(url).json(&body).send().await });
        tokio::time::sleep(took * (2 * attempt + 1) / (2 * tries)).await;
        victim.kill_9();
        let _ = posting.await;
        let after_restart = server(dir.path(), &["--queue-capacity", "1000"]);
        let (jobs, studies) = counts(&client, &after_restart).await;
        let added = (jobs - before.0, studies - before.1);
        assert!(
            added == (0, 0) || added == (60, 1),
            "try {attempt}: {added:?} (jobs, studies) after the crash"
        );
    }

    // The crash between the last member and the study file, laid out by hand: the members
    // written, the study's file not yet.
    let server_3 = server(dir.path(), &["--queue-capacity", "1000"]);
    let before = counts(&client, &server_3).await;
    let (code, accepted) = post(&client, &server_3.url("/api/v1/studies"), &study).await;
    assert_eq!(code, 201, "{accepted}");
    drop(server_3);
    let id = accepted["id"].as_str().expect("id");
    let studies = dir.path().join("studies");
    let members: Vec<&str> = accepted["members"]
        .as_array()
        .expect("members")
        .iter()
        .filter_map(|m| m["job_id"].as_str())
        .collect();
    assert_eq!(members.len(), 60);
    std::fs::remove_file(studies.join(format!("{id}.json"))).expect("remove the study file");
    std::fs::write(
        studies.join(format!("{id}.pending")),
        json!({"job_ids": members}).to_string(),
    )
    .expect("write the mark");
    let restarted = server(dir.path(), &[]);
    assert_eq!(counts(&client, &restarted).await, before);
    assert!(!studies.join(format!("{id}.pending")).exists());
}
