//! User strings over HTTP, against the service in this process: every name has a
//! bound and refuses hidden characters (as `tribosim run` does, `tests/cli.rs`), a hundred
//! thousand tags are refused in one problem, a study's summary.csv keeps a `;` value in its
//! cell, a list's cursor works only in the list and filters that gave it, and a job's id
//! in a path is a UUID (400 otherwise, 404 when unknown) on every route.

mod common;

use serde_json::{Value, json};

use common::{
    Server, TempDir, args, expect_client_error, get_json, is_final, post, refused, small_scene,
    submit, wait_for, wait_for_job,
};

/// The small scene under `name`.
fn named(name: &str) -> Value {
    let mut scene = small_scene(3);
    scene["overrides"]["name"] = Value::from(name);
    scene
}

/// The field paths of a 422's body.
fn paths(body: &Value) -> Vec<&str> {
    body["fields"]
        .as_array()
        .map(|fields| fields.iter().filter_map(|f| f["path"].as_str()).collect())
        .unwrap_or_default()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn names_and_labels_are_bounded_and_refuse_hidden_characters() {
    let dir = TempDir::new("strings-names");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let jobs = server.url("/api/v1/jobs");

    let body = refused(&client, &jobs, &named(&"x".repeat(1_000_000))).await;
    // At the path in the document sent: the small scene is a preset's overrides.
    assert_eq!(paths(&body), ["overrides.name"], "{body}");
    let message = body["fields"][0]["message"].as_str().unwrap_or_default();
    assert!(message.contains("at most 200 characters"), "{message}");
    assert!(message.len() < 400, "the refusal does not echo the name");
    let body = refused(&client, &jobs, &named("run\u{202e}3 N")).await;
    assert!(
        body["fields"][0]["message"]
            .as_str()
            .is_some_and(|m| m.starts_with("holds U+202E (a bidirectional control) at character 4")),
        "{body}"
    );

    let job = submit(&client, &server.base, &named("labelled")).await;
    let url = format!("{jobs}/{}", job["id"].as_str().unwrap_or_default());
    let patch = |body: Value| client.patch(&url).json(&body).send();
    let response = patch(json!({"tags": ["ok", "\u{202e}gpj.exe"]}))
        .await
        .expect("PATCH");
    let body = expect_client_error(response, 422).await;
    assert_eq!(paths(&body), ["tags[1]"], "{body}");
    // Two such PATCHes once held the server for 43 s; the refusal is one problem now.
    let many: Vec<String> = (0..100_000).map(|i| format!("t{i}")).collect();
    let response = patch(json!({"tags": many})).await.expect("PATCH");
    let body = expect_client_error(response, 422).await;
    assert_eq!(paths(&body), ["tags"], "{body}");
    assert!(
        body["error"]
            .as_str()
            .is_some_and(|e| e.contains("100000 tags given"))
    );
    let response = patch(json!({"note": "line one\n\tline two"}))
        .await
        .expect("PATCH");
    assert_eq!(response.status(), 200);

    let study =
        json!({"name": "s".repeat(201), "base": small_scene(3), "axes": {"test.load_n": [2]}});
    let body = refused(&client, &server.url("/api/v1/studies"), &study).await;
    assert_eq!(paths(&body), ["name"], "{body}");
    let study = json!({"base": small_scene(3), "axes": {"name": ["ok", "x".repeat(201)]}});
    let body = refused(&client, &server.url("/api/v1/studies"), &study).await;
    assert_eq!(paths(&body), ["axes.name"], "{body}");
    server.stop().await;
}

/// The value: in a semicolon locale `1;=cmd|' /C calc'!A0` written unquoted was two
/// cells, the second a formula. It reaches summary.csv as one quoted, neutralised cell.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_study_value_holding_a_semicolon_is_one_text_cell_of_summary_csv() {
    let dir = TempDir::new("strings-csv");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let attack = "1;=cmd|' /C calc'!A0";
    let study = json!({"base": small_scene(3), "axes": {"name": [attack]}});
    let (code, record) = post(&client, &server.url("/api/v1/studies"), &study).await;
    assert_eq!(code, 201, "{record}");
    let url = server.url(&format!(
        "/api/v1/studies/{}",
        record["id"].as_str().unwrap_or_default()
    ));
    let ended = |s: &Value| !matches!(s["status"].as_str(), Some("queued" | "running"));
    let record = wait_for(&client, &url, ended).await;
    assert_eq!(record["status"], "succeeded", "{record}");
    let csv = client
        .get(format!("{url}/summary.csv"))
        .send()
        .await
        .expect("GET csv")
        .text()
        .await
        .expect("text");
    let row = csv.lines().nth(1).unwrap_or_default();
    assert!(row.starts_with("0,\"'1;=cmd|' /C calc'!A0\","), "{csv}");
    server.stop().await;
}

/// The `cursor` of a page's `Link` header.
fn next_cursor(response: &reqwest::Response) -> String {
    let link = response.headers()["link"].to_str().unwrap_or_default();
    let cursor = link.split("cursor=").nth(1).unwrap_or_default();
    cursor
        .split(['&', '>'])
        .next()
        .unwrap_or_default()
        .to_owned()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cursor_works_only_in_the_list_and_filters_that_gave_it() {
    let dir = TempDir::new("strings-cursor");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let mut ids = Vec::new();
    for _ in 0..3 {
        let job = submit(&client, &server.base, &small_scene(3)).await;
        ids.push(job["id"].as_str().unwrap_or_default().to_owned());
    }
    for id in &ids {
        wait_for_job(&client, &server.base, id, is_final).await;
    }
    let get = |path: String| client.get(server.url(&path)).send();
    let first = get("/api/v1/jobs?status=succeeded&limit=1".into())
        .await
        .expect("GET");
    let cursor = next_cursor(&first);
    let page = |query: &str| get(format!("/api/v1/jobs?{query}&cursor={cursor}"));

    let genuine = page("status=succeeded&limit=2").await.expect("GET");
    assert_eq!(genuine.status(), 200);
    let rest: Value = genuine.json().await.expect("JSON");
    assert_eq!(rest.as_array().map(Vec::len), Some(2), "{rest}");
    for response in [
        page("status=queued").await,
        page("limit=1").await,
        get(format!("/api/v1/studies?status=succeeded&cursor={cursor}")).await,
        get(format!(
            "/api/v1/jobs?status=succeeded&cursor=1-{}-{}",
            ids[0].replace('-', ""),
            "0".repeat(32)
        ))
        .await,
    ] {
        let body = expect_client_error(response.expect("GET"), 400).await;
        assert!(
            body["error"]
                .as_str()
                .is_some_and(|e| e.contains("not a cursor this server gave"))
        );
    }
    // The whole list, for the record: three jobs, none repeated.
    let all = get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(all.as_array().map(Vec::len), Some(3));
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_stored_before_names_were_bounded_still_runs() {
    let dir = TempDir::new("strings-stored");
    let client = reqwest::Client::new();
    let server = Server::start(args(dir.path())).await;
    let job = submit(&client, &server.base, &small_scene(3)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    wait_for_job(&client, &server.base, &id, is_final).await;
    server.stop().await;

    // As an earlier version stored it: a name of 1000 characters with a bidi override, and
    // the job queued when the server stopped.
    let job_dir = dir.path().join("jobs").join(&id);
    let read = |file: &str| -> Value {
        serde_json::from_slice(&std::fs::read(job_dir.join(file)).expect("read")).expect("JSON")
    };
    let write = |file: &str, value: &Value| {
        std::fs::write(job_dir.join(file), serde_json::to_vec(value).expect("JSON"))
            .expect("write");
    };
    let long = format!("\u{202E}{}", "n".repeat(1000));
    let mut scene = read("scene.json");
    scene["name"] = Value::from(long.clone());
    write("scene.json", &scene);
    let mut status = read("status.json");
    status["status"] = json!("queued");
    status["name"] = Value::from(long);
    write("status.json", &status);

    let server = Server::start(args(dir.path())).await;
    let done = wait_for_job(&client, &server.base, &id, is_final).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let result = get_json(&client, &server.url(&format!("/api/v1/jobs/{id}/result"))).await;
    let name = result["scene"]["name"].as_str().unwrap_or_default();
    assert_eq!(
        name,
        "n".repeat(200),
        "the name as run: hidden characters dropped, cut to 200"
    );
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_job_route_answers_404_for_an_unknown_id_and_400_for_a_malformed_one() {
    let dir = TempDir::new("ids");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let unknown = uuid::Uuid::new_v4().to_string();
    for suffix in [
        "",
        "/events",
        "/result",
        "/result.csv",
        "/scene",
        "/measurements",
    ] {
        for (id, status) in [
            (unknown.as_str(), 404),
            ("not-a-uuid", 400),
            ("..%2F..%2Fetc", 400),
            ("12345", 400),
        ] {
            let url = server.url(&format!("/api/v1/jobs/{id}{suffix}"));
            let response = client.get(&url).send().await.expect("get");
            expect_client_error(response, status).await;
        }
    }
    let response = client
        .delete(server.url(&format!("/api/v1/jobs/{unknown}")))
        .send()
        .await
        .expect("delete");
    expect_client_error(response, 404).await;
    let response = client
        .delete(server.url("/api/v1/jobs/x"))
        .send()
        .await
        .expect("delete");
    expect_client_error(response, 400).await;

    server.stop().await;
}
