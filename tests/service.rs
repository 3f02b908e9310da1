//! The service as a whole against a real server on a loopback port: restart after kill -9,
//! the token on the API and not on the public routes, JSON answers for unknown routes and
//! methods, the refusal to listen exposed without a token, the page, the presets and the
//! description, and the OpenAPI description against the route table.

mod common;

use std::collections::BTreeSet;
use std::num::NonZeroUsize;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use serde_json::{Value, json};
use tribosim::service::{OPENAPI_YAML, routes};

use common::{
    PATIENCE, Server, TempDir, args, expect_client_error, follow, get_job, get_json, is_final,
    long_scene, small_scene, submit, wait_for_job,
};

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

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn api_calls_need_the_token_and_the_public_routes_do_not() {
    let dir = TempDir::new("token");
    let mut args = args(dir.path());
    args.token = Some("s3cret".to_owned());
    let server = Server::start(args).await;
    let client = reqwest::Client::new();
    let jobs = server.url("/api/v1/jobs");
    let unknown = uuid::Uuid::new_v4().to_string();

    // Missing or wrong: 401 on every API route.
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
    // The public routes stay open.
    for path in ["/", "/healthz", "/api/v1/openapi.yaml"] {
        let response = client.get(server.url(path)).send().await.expect("get");
        assert_eq!(response.status(), 200, "{path}");
    }

    // With the token, the API answers.
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

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn unknown_routes_and_methods_get_404_and_405_with_the_json_body() {
    let dir = TempDir::new("routes");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let jobs = server.url("/api/v1/jobs");
    let response = client.get(server.url("/nope")).send().await.expect("get");
    expect_client_error(response, 404).await;
    let response = client.put(&jobs).send().await.expect("put");
    expect_client_error(response, 405).await;
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
    // The page draws Table 3 from this answer, so it is the paper's table itself.
    let measured: Vec<(u64, f64)> = presets[0]["measured"]
        .as_array()
        .expect("the preset's measured points")
        .iter()
        .map(|p| {
            let time = p["time_s"].as_u64().expect("time_s");
            (
                time,
                p["wear_volume_mm3"].as_f64().expect("wear_volume_mm3"),
            )
        })
        .collect();
    let table3: Vec<(u64, f64)> = tribosim::scene::PAPER_TABLE3
        .iter()
        .map(|r| (r.time_s, r.wear_volume_mm3))
        .collect();
    assert_eq!(measured, table3);
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
    let routes = routes();
    let routed: BTreeSet<(String, String)> = routes
        .iter()
        .map(|route| (route.verb.openapi_name().to_owned(), route.openapi_path()))
        .collect();
    assert_eq!(routed.len(), routes.len(), "no route listed twice");
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
    // The routes open to anyone are those the description exempts from the token.
    for route in &routes {
        let verb = route.verb.openapi_name();
        let open = spec["paths"][route.openapi_path().as_str()][verb]["security"] == json!([]);
        assert_eq!(open, !route.auth, "{verb} {}: security", route.path);
    }
}
