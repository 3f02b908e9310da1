//! The HTTP service against a real server on a loopback port: a run streamed and
//! downloaded equals the library's run, 50 jobs at once, the queue bound, cancel, restart after
//! kill -9, bad input, and the OpenAPI description against the route table.

mod common;

use std::collections::BTreeSet;
use std::num::NonZeroUsize;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use futures_util::future::join_all;
use serde_json::{Value, json};
use tribosim::scene::parse_scene;
use tribosim::service::{OPENAPI_YAML, ROUTES};

use common::{
    PATIENCE, Server, TempDir, args, follow, get_job, get_json, is_final, long_scene, small_scene,
    submit, wait_for_job, without_wall_time,
};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_streamed_and_downloaded_run_equals_the_library_run() {
    let dir = TempDir::new("stream");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let scene = small_scene(20);

    let response = client
        .post(server.url("/api/v1/jobs"))
        .json(&scene)
        .send()
        .await
        .expect("submit");
    assert_eq!(response.status(), 202);
    let location = response.headers()["location"]
        .to_str()
        .expect("ascii")
        .to_owned();
    let job: Value = response.json().await.expect("job");
    let id = job["id"].as_str().expect("id").to_owned();
    assert_eq!(location, format!("/api/v1/jobs/{id}"));
    assert_eq!(job["cycles_total"], 20);
    assert!(job["created_at"].as_str().is_some_and(|t| t.contains('T')));

    let events_url = server.url(&format!("{location}/events"));
    let events = follow(&client, &events_url, None, async |_| {}).await;
    let (last, cycles) = events.split_last().expect("events");
    assert_eq!(last.event, "status");
    assert_eq!(last.json()["status"], "succeeded", "{}", last.data);
    assert_eq!(last.json()["cycles_done"], 20);
    let mut previous = 0;
    for event in cycles {
        assert_eq!(event.event, "cycle");
        let cycle = event.json()["cycle"].as_u64().expect("cycle");
        assert_eq!(event.id.as_deref(), Some(cycle.to_string().as_str()));
        assert!(cycle > previous, "cycles increase");
        previous = cycle;
    }
    assert_eq!(previous, 20, "the last solved cycle is the last cycle");

    let response = client
        .get(server.url(&format!("{location}/result")))
        .send()
        .await
        .expect("result");
    assert_eq!(response.status(), 200);
    let disposition = response.headers()["content-disposition"]
        .to_str()
        .expect("ascii");
    assert_eq!(
        disposition,
        format!("attachment; filename=\"tribosim-{id}.json\"")
    );
    let downloaded: Value = response.json().await.expect("result JSON");

    // Asked for gzip, the same result comes compressed.
    let response = client
        .get(server.url(&format!("{location}/result")))
        .header("accept-encoding", "gzip")
        .send()
        .await
        .expect("result");
    assert_eq!(response.headers()["content-encoding"], "gzip");
    let events_response = client
        .get(&events_url)
        .header("accept-encoding", "gzip")
        .send()
        .await
        .expect("events");
    assert!(
        !events_response.headers().contains_key("content-encoding"),
        "an event stream is never compressed (it would be buffered)"
    );
    let compressed = response.bytes().await.expect("body");
    let mut text = String::new();
    std::io::Read::read_to_string(
        &mut flate2::read::GzDecoder::new(compressed.as_ref()),
        &mut text,
    )
    .expect("valid gzip");
    assert_eq!(
        serde_json::from_str::<Value>(&text).expect("result JSON"),
        downloaded
    );

    let parsed = parse_scene(&scene).expect("valid scene");
    let direct = tribosim::simulation::run(&parsed, &mut |_| {}, &AtomicBool::new(false))
        .expect("direct run");
    // Both sides through the same JSON text, so the comparison is of the numbers as sent.
    let direct: Value =
        serde_json::from_str(&serde_json::to_string(&direct).expect("serialise")).expect("parse");
    assert_eq!(
        without_wall_time(downloaded.clone()),
        without_wall_time(direct)
    );

    let streamed: Vec<Value> = cycles.iter().map(common::Event::json).collect();
    assert_eq!(
        Value::Array(streamed.clone()),
        downloaded["cycles"],
        "one event per solved cycle, with its record"
    );

    // A late client gets the backlog; with Last-Event-ID, only what follows it.
    let again = follow(&client, &events_url, None, async |_| {}).await;
    assert_eq!(again.len(), events.len());
    let middle = streamed[streamed.len() / 2]["cycle"]
        .as_u64()
        .expect("cycle");
    let resumed = follow(&client, &events_url, Some(middle), async |_| {}).await;
    let expected_after = streamed
        .iter()
        .filter(|record| record["cycle"].as_u64() > Some(middle))
        .count();
    assert_eq!(resumed.len(), expected_after + 1);
    assert_eq!(resumed.last().map(|e| e.event.as_str()), Some("status"));

    let response = client
        .get(server.url(&format!("{location}/result.csv")))
        .send()
        .await
        .expect("csv");
    assert_eq!(response.status(), 200);
    assert!(
        response.headers()["content-type"]
            .to_str()
            .expect("ascii")
            .starts_with("text/csv")
    );
    let csv = response.text().await.expect("csv text");
    let rows: Vec<&str> = csv.lines().collect();
    assert!(rows[0].starts_with("cycle,time_s,wear_volume_mm3,max_depth_um"));
    assert_eq!(rows.len(), streamed.len() + 1);

    let listed: Value = get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(listed[0]["id"], id.as_str());

    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn fifty_jobs_submitted_at_once_all_finish() {
    let dir = TempDir::new("fifty");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let scene = small_scene(5);
    let jobs = join_all((0..50).map(|_| submit(&client, &server.base, &scene))).await;
    let ids: BTreeSet<String> = jobs
        .iter()
        .map(|job| job["id"].as_str().expect("id").to_owned())
        .collect();
    assert_eq!(ids.len(), 50, "fifty distinct jobs");
    for id in &ids {
        let job = wait_for_job(&client, &server.base, id, is_final).await;
        assert_eq!(job["status"], "succeeded", "{job}");
    }
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_full_queue_answers_429_with_retry_after() {
    let dir = TempDir::new("queue");
    let mut args = args(dir.path());
    args.workers = NonZeroUsize::MIN;
    args.queue_capacity = NonZeroUsize::new(2).expect("non-zero");
    let server = Server::start(args).await;
    let client = reqwest::Client::new();
    // The paper's scene at its automatic grid: tens of seconds, far longer than this test
    // needs the worker busy.
    let paper = json!({"preset": "dalmau2018-316l"});
    let busy = submit(&client, &server.base, &paper).await;
    let busy = busy["id"].as_str().expect("id");
    wait_for_job(&client, &server.base, busy, |job| {
        job["status"] == "running"
    })
    .await;
    let waiting = [
        submit(&client, &server.base, &small_scene(5)).await,
        submit(&client, &server.base, &small_scene(5)).await,
    ];

    let results = join_all((0..5).map(|_| {
        client
            .post(server.url("/api/v1/jobs"))
            .json(&small_scene(5))
            .send()
    }))
    .await;
    for response in results {
        let response = response.expect("submit");
        assert_eq!(response.status(), 429);
        let retry_after: u64 = response.headers()["retry-after"]
            .to_str()
            .expect("ascii")
            .parse()
            .expect("seconds");
        assert!(retry_after >= 1);
        let body: Value = response.json().await.expect("error JSON");
        assert!(body["error"].as_str().is_some_and(|e| e.contains("queue")));
    }

    // The queued jobs are cancelled at once, the running one within a cycle.
    for job in &waiting {
        let id = job["id"].as_str().expect("id");
        let response = client
            .delete(server.url(&format!("/api/v1/jobs/{id}")))
            .send()
            .await
            .expect("delete");
        assert_eq!(response.status(), 200);
        let job: Value = response.json().await.expect("job");
        assert_eq!(job["status"], "cancelled");
    }
    let response = client
        .delete(server.url(&format!("/api/v1/jobs/{busy}")))
        .send()
        .await
        .expect("delete");
    assert_eq!(response.status(), 202);
    wait_for_job(&client, &server.base, busy, is_final).await;
    // A place is free again.
    submit(&client, &server.base, &small_scene(5)).await;
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cancelling_a_running_job_stops_it_within_a_cycle() {
    let dir = TempDir::new("cancel");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let job = submit(&client, &server.base, &long_scene(300)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    let events_url = server.url(&format!("/api/v1/jobs/{id}/events"));
    let delete_url = server.url(&format!("/api/v1/jobs/{id}"));

    // Cancel on the third cycle event; remember what the server had done when it agreed.
    let mut seen = 0;
    let mut done_at_cancel = None;
    let events = follow(&client, &events_url, None, async |event| {
        seen += 1;
        if seen == 3 {
            let response = client.delete(&delete_url).send().await.expect("delete");
            assert_eq!(response.status(), 202);
            let job: Value = response.json().await.expect("job");
            done_at_cancel = job["cycles_done"].as_u64();
        }
        assert!(event.event == "cycle" || event.event == "status");
    })
    .await;
    let done_at_cancel = done_at_cancel.expect("cancelled while running");

    let last = events.last().expect("events").json();
    assert_eq!(last["status"], "cancelled", "{last}");
    let after_cancel = events
        .iter()
        .filter(|event| event.event == "cycle")
        .filter(|event| event.json()["cycle"].as_u64() > Some(done_at_cancel))
        .count();
    assert!(
        after_cancel <= 1,
        "{after_cancel} cycles were solved after the cancel"
    );
    let job = get_job(&client, &server.base, &id).await;
    assert_eq!(job["status"], "cancelled");
    assert!(job["cycles_done"].as_u64() < Some(300));

    // What was computed before the cancel is kept: the result's shape, marked incomplete,
    // with every cycle the stream sent.
    let partial = get_json(&client, &server.url(&format!("/api/v1/jobs/{id}/result"))).await;
    assert_eq!(partial["complete"], false, "{}", partial["summary"]);
    let streamed: Vec<Value> = events
        .iter()
        .filter(|event| event.event == "cycle")
        .map(common::Event::json)
        .collect();
    assert_eq!(partial["cycles"], Value::Array(streamed.clone()));
    assert_eq!(partial["summary"]["cycles"], job["cycles_done"]);
    let last = streamed.last().expect("cycles before the cancel");
    assert_eq!(
        partial["summary"]["wear_volume_mm3"],
        last["wear_volume_mm3"]
    );
    let csv = client
        .get(server.url(&format!("/api/v1/jobs/{id}/result.csv")))
        .send()
        .await
        .expect("CSV")
        .text()
        .await
        .expect("text");
    assert_eq!(
        csv.lines().count(),
        1 + streamed.len(),
        "a header and a row per cycle"
    );

    // DELETE on a finished job removes it.
    let response = client.delete(&delete_url).send().await.expect("delete");
    assert_eq!(response.status(), 204);
    let response = client.get(&delete_url).send().await.expect("get");
    assert_eq!(response.status(), 404);
    assert!(!dir.path().join("jobs").join(&id).exists());
    server.stop().await;
}

/// Set in the environment of a child test process that is to run a server.
const CHILD_DATA_DIR: &str = "TRIBOSIM_TEST_SERVER_DATA_DIR";

/// Not a test: the server process that `restart_after_kill_9_loses_nothing` kills. It runs
/// the library's server in this test binary, so the kill hits a real, separate process.
#[test]
#[ignore = "run by restart_after_kill_9_loses_nothing as its child process"]
fn child_server() {
    let Ok(dir) = std::env::var(CHILD_DATA_DIR) else {
        return;
    };
    let dir = std::path::PathBuf::from(dir);
    let mut args = args(&dir);
    args.workers = NonZeroUsize::MIN;
    let runtime = tokio::runtime::Runtime::new().expect("runtime");
    runtime.block_on(async {
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
            .await
            .expect("bind");
        let port = listener.local_addr().expect("address").port();
        let announce = dir.join("port.tmp");
        std::fs::write(&announce, port.to_string()).expect("write port");
        std::fs::rename(&announce, dir.join("port")).expect("publish port");
        tribosim::service::serve_on(args, listener, std::future::pending())
            .await
            .expect("serve");
    });
}

/// Kills its child process when dropped, so a failing test leaves no server behind.
struct ChildServer(Child);

impl ChildServer {
    async fn start(dir: &std::path::Path) -> (Self, String) {
        let _ = std::fs::remove_file(dir.join("port"));
        let child = Command::new(std::env::current_exe().expect("test binary"))
            .args(["--exact", "child_server", "--ignored", "--nocapture"])
            .env(CHILD_DATA_DIR, dir)
            .stdout(Stdio::null())
            .spawn()
            .expect("spawn server");
        let child = Self(child);
        let port = tokio::time::timeout(PATIENCE, async {
            loop {
                if let Ok(port) = std::fs::read_to_string(dir.join("port")) {
                    return port;
                }
                tokio::time::sleep(Duration::from_millis(20)).await;
            }
        })
        .await
        .expect("server announces its port");
        (child, format!("http://127.0.0.1:{port}"))
    }

    fn kill_9(&mut self) {
        // SIGKILL on Unix: no shutdown code runs.
        self.0.kill().expect("kill");
        self.0.wait().expect("reap");
    }
}

impl Drop for ChildServer {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn restart_after_kill_9_loses_nothing() {
    let dir = TempDir::new("restart");
    let client = reqwest::Client::new();
    let (mut first, base) = ChildServer::start(dir.path()).await;

    let finished = submit(&client, &base, &small_scene(20)).await;
    let finished = finished["id"].as_str().expect("id").to_owned();
    let finished_job = wait_for_job(&client, &base, &finished, is_final).await;
    assert_eq!(finished_job["status"], "succeeded");
    let result_before = client
        .get(format!("{base}/api/v1/jobs/{finished}/result"))
        .send()
        .await
        .expect("result")
        .bytes()
        .await
        .expect("bytes");

    // One worker: the first job runs, the second waits in the queue.
    let running = submit(&client, &base, &long_scene(100)).await;
    let running = running["id"].as_str().expect("id").to_owned();
    let queued = submit(&client, &base, &small_scene(20)).await;
    let queued = queued["id"].as_str().expect("id").to_owned();
    let at_kill = wait_for_job(&client, &base, &running, |job| {
        job["cycles_done"].as_u64() >= Some(2)
    })
    .await;
    first.kill_9();
    assert_eq!(at_kill["status"], "running", "killed mid-run");

    let (second, base) = ChildServer::start(dir.path()).await;
    let listed: Value = get_json(&client, &format!("{base}/api/v1/jobs")).await;
    assert_eq!(listed.as_array().map(Vec::len), Some(3), "{listed}");
    for id in [&running, &queued] {
        let job = wait_for_job(&client, &base, id, is_final).await;
        assert_eq!(job["status"], "succeeded", "{job}");
    }
    let finished_after = get_job(&client, &base, &finished).await;
    assert_eq!(
        finished_after, finished_job,
        "a finished job is served as before"
    );
    let result_after = client
        .get(format!("{base}/api/v1/jobs/{finished}/result"))
        .send()
        .await
        .expect("result")
        .bytes()
        .await
        .expect("bytes");
    assert_eq!(
        result_before, result_after,
        "a finished result is unchanged"
    );

    // The event backlogs, replayed from disk or from the re-run, hold each cycle once.
    for id in [&finished, &running] {
        let url = format!("{base}/api/v1/jobs/{id}/events");
        let events = follow(&client, &url, None, async |_| {}).await;
        let result: Value = get_json(&client, &format!("{base}/api/v1/jobs/{id}/result")).await;
        let streamed: Vec<Value> = events
            .iter()
            .filter(|event| event.event == "cycle")
            .map(common::Event::json)
            .collect();
        assert_eq!(Value::Array(streamed), result["cycles"]);
        assert_eq!(
            events.last().map(|e| e.json()["status"].clone()),
            Some(json!("succeeded"))
        );
    }
    drop(second);
}

/// Asserts a 4xx answer with the JSON error shape; returns the body.
async fn expect_client_error(response: reqwest::Response, status: u16) -> Value {
    let url = response.url().clone();
    assert_eq!(response.status(), status, "{url}");
    let content_type = response.headers()["content-type"]
        .to_str()
        .expect("ascii")
        .to_owned();
    assert_eq!(content_type, "application/json", "{url}");
    let body: Value = response.json().await.expect("error JSON");
    assert!(
        body["error"].as_str().is_some_and(|e| !e.is_empty()),
        "{body}"
    );
    assert!(body["fields"].is_array(), "{body}");
    body
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_input_gets_a_4xx_json_error_never_a_5xx() {
    let dir = TempDir::new("bad");
    let mut args = args(dir.path());
    args.token = Some("s3cret".to_owned());
    let server = Server::start(args).await;
    let client = reqwest::Client::new();
    let jobs = server.url("/api/v1/jobs");
    let post = |body: Vec<u8>| {
        client
            .post(&jobs)
            .bearer_auth("s3cret")
            .header("content-type", "application/json")
            .body(body)
            .send()
    };

    // Invalid scenes: 422 with the field paths at fault.
    let invalid: [(Value, &[&str]); 8] = [
        (json!({"test": {"load_n": "five"}}), &["test.load_n"]),
        (json!({"test": {"load_n": "NaN"}}), &["test.load_n"]),
        (
            json!({"wear": {"archard_calibration": {"time_s": 300.0}}}),
            &["wear.archard_calibration"],
        ),
        (json!({"numerics": {"grid": 1_000_000}}), &["numerics.grid"]),
        (json!({"preset": "no-such-preset"}), &["preset"]),
        (
            json!({"ball": {"radius_mm": -1.0}, "test": {"cycles": 0, "lod_n": 5}}),
            &["ball.radius_mm", "test"],
        ),
        (json!([1, 2, 3]), &[""]),
        // Valid for `tribosim run --surface`, but no surface of this id was uploaded.
        (
            json!({"disc": {"surface": {"kind": "measured", "id": "disc.gsf"}}}),
            &["disc.surface.id"],
        ),
    ];
    for (scene, paths) in invalid {
        let response = post(serde_json::to_vec(&scene).expect("json"))
            .await
            .expect("post");
        let body = expect_client_error(response, 422).await;
        let reported: Vec<&str> = body["fields"]
            .as_array()
            .expect("fields")
            .iter()
            .map(|field| field["path"].as_str().expect("path"))
            .collect();
        for path in paths {
            assert!(
                reported.iter().any(|p| p.starts_with(path)),
                "{scene}: {path} not in {reported:?}"
            );
        }
    }

    // Not JSON at all: 400.
    let garbage: [&[u8]; 6] = [
        b"",
        b"{\"test\": {\"load_n\": NaN}}",
        b"{\"test\": ",
        &[0xff, 0xfe, 0x00, 0x9c, 0x13, 0x37],
        b"1e999",
        &[b'['; 10_000],
    ];
    for body in garbage {
        expect_client_error(post(body.to_vec()).await.expect("post"), 400).await;
    }

    // Too large: 413. The server answers without reading the body and closes the
    // connection, so this request goes on a client of its own: a pooled connection would be
    // reused by the next request after the server closed it (seen as IncompleteMessage).
    let huge = vec![b' '; 2 << 20];
    let one_shot = reqwest::Client::builder()
        .pool_max_idle_per_host(0)
        .build()
        .expect("client");
    let response = one_shot
        .post(&jobs)
        .bearer_auth("s3cret")
        .header("content-type", "application/json")
        .body(huge)
        .send()
        .await
        .expect("post");
    expect_client_error(response, 413).await;
    // Not declared JSON: 415.
    let response = client
        .post(&jobs)
        .bearer_auth("s3cret")
        .header("content-type", "text/plain")
        .body("{}")
        .send()
        .await
        .expect("post");
    expect_client_error(response, 415).await;
    let response = client
        .post(&jobs)
        .bearer_auth("s3cret")
        .body("{}")
        .send()
        .await
        .expect("post");
    expect_client_error(response, 415).await;

    // Ids: unknown UUID 404, anything else 400, on every job route.
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
            let response = client
                .get(&url)
                .bearer_auth("s3cret")
                .send()
                .await
                .expect("get");
            expect_client_error(response, status).await;
        }
    }
    let response = client
        .delete(server.url(&format!("/api/v1/jobs/{unknown}")))
        .bearer_auth("s3cret")
        .send()
        .await
        .expect("delete");
    expect_client_error(response, 404).await;
    let response = client
        .delete(server.url("/api/v1/jobs/x"))
        .bearer_auth("s3cret")
        .send()
        .await
        .expect("delete");
    expect_client_error(response, 400).await;

    // Token: missing or wrong is 401 on every API route; the public routes stay open.
    for token in [None, Some("wrong"), Some("s3cre"), Some("S3CRET")] {
        for path in [
            "/api/v1/jobs",
            "/api/v1/presets",
            &format!("/api/v1/jobs/{unknown}"),
        ] {
            let mut request = client.get(server.url(path));
            if let Some(token) = token {
                request = request.bearer_auth(token);
            }
            let response = request.send().await.expect("get");
            assert_eq!(response.headers()["www-authenticate"], "Bearer");
            expect_client_error(response, 401).await;
        }
        let mut request = client.post(&jobs).json(&small_scene(5));
        if let Some(token) = token {
            request = request.bearer_auth(token);
        }
        expect_client_error(request.send().await.expect("post"), 401).await;
    }
    for path in ["/", "/healthz", "/api/v1/openapi.yaml"] {
        let response = client.get(server.url(path)).send().await.expect("get");
        assert_eq!(response.status(), 200, "{path}");
    }

    // Unknown routes and methods.
    let response = client.get(server.url("/nope")).send().await.expect("get");
    expect_client_error(response, 404).await;
    let response = client
        .put(&jobs)
        .bearer_auth("s3cret")
        .send()
        .await
        .expect("put");
    expect_client_error(response, 405).await;

    // After all that, the server still works.
    let response = client
        .post(&jobs)
        .bearer_auth("s3cret")
        .json(&small_scene(5))
        .send()
        .await
        .expect("post");
    assert_eq!(response.status(), 202);
    server.stop().await;
}

#[test]
fn non_loopback_addresses_need_a_token() {
    let dir = TempDir::new("exposed");
    let mut args = args(dir.path());
    args.addr = "0.0.0.0:0".parse().expect("address");
    let error = tribosim::service::serve(args).expect_err("refused");
    assert!(error.to_string().contains("TRIBOSIM_TOKEN"), "{error}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_presets_and_description_are_served() {
    let dir = TempDir::new("static");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let page = client.get(server.url("/")).send().await.expect("page");
    assert!(
        page.headers()["content-type"]
            .to_str()
            .expect("ascii")
            .starts_with("text/html")
    );
    let page = page.text().await.expect("text");
    assert!(page.contains("/api/v1/openapi.yaml") && page.contains("/static/js/main.js"));
    let module = client
        .get(server.url("/static/js/main.js"))
        .send()
        .await
        .expect("module");
    assert_eq!(module.status(), 200);
    assert_eq!(
        module.headers()["content-type"],
        "text/javascript; charset=utf-8"
    );
    let response = client
        .get(server.url("/static/js/nope.js"))
        .send()
        .await
        .expect("no module");
    expect_client_error(response, 404).await;
    let health: Value = get_json(&client, &server.url("/healthz")).await;
    assert_eq!(health, json!({"status": "ok"}));
    let presets: Value = get_json(&client, &server.url("/api/v1/presets")).await;
    assert_eq!(presets[0]["name"], "dalmau2018-316l");
    let spec = client
        .get(server.url("/api/v1/openapi.yaml"))
        .send()
        .await
        .expect("spec")
        .text()
        .await
        .expect("text");
    assert_eq!(spec, OPENAPI_YAML);
    server.stop().await;
}

#[test]
fn openapi_describes_exactly_the_routes_of_the_router() {
    let spec: Value = serde_norway::from_str(OPENAPI_YAML).expect("openapi.yaml parses");
    let methods = [
        "get", "put", "post", "delete", "options", "head", "patch", "trace",
    ];
    let described: BTreeSet<(String, String)> = spec["paths"]
        .as_object()
        .expect("paths")
        .iter()
        .flat_map(|(path, item)| {
            item.as_object()
                .expect("path item")
                .keys()
                .filter(|key| methods.contains(&key.as_str()))
                .map(|method| (method.clone(), path.clone()))
                .collect::<Vec<_>>()
        })
        .collect();
    let routed: BTreeSet<(String, String)> = ROUTES
        .iter()
        .map(|route| (route.verb.openapi_name().to_owned(), route.openapi_path()))
        .collect();
    assert_eq!(routed.len(), ROUTES.len(), "no route listed twice");
    let missing: Vec<_> = routed.difference(&described).collect();
    let extra: Vec<_> = described.difference(&routed).collect();
    assert!(
        missing.is_empty(),
        "routes missing from openapi.yaml: {missing:?}"
    );
    assert!(
        extra.is_empty(),
        "openapi.yaml paths with no route: {extra:?}"
    );
}
