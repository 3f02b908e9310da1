//! Helpers for the service tests: temporary data directories, an in-process server on a
//! loopback port, and a server-sent-event reader.

// Each test crate compiles this module on its own and uses a part of it.
#![allow(dead_code)]

pub mod process;

use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::time::Duration;

use futures_util::StreamExt;
use serde_json::{Value, json};
use tokio::net::TcpListener;
use tokio::sync::oneshot;
use tokio::task::JoinHandle;
use tribosim::service::{Budgets, Limits, ServeArgs, ServeError, serve_on};

/// Generous bound on anything a test waits for: the machine may be loaded.
pub const PATIENCE: Duration = Duration::from_secs(600);

/// A directory removed when dropped.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(label: &str) -> Self {
        let path = std::env::temp_dir().join(format!("tribosim-{label}-{}", uuid::Uuid::new_v4()));
        std::fs::create_dir_all(&path).expect("create temp dir");
        Self(path)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The preset on a small grid: well under a second per run.
pub fn small_scene(cycles: u64) -> Value {
    json!({
        "preset": "dalmau2018-316l",
        "overrides": {
            "name": format!("small, {cycles} cycles"),
            "numerics": {"grid": 32, "domain_um": 256},
            "test": {"cycles": cycles}
        }
    })
}

/// A scene that solves every cycle on a finer grid, for jobs that must still be running when
/// a test acts: about 1 ms per cycle here (cycle 2339 after 2.5 s). Its domain is fixed at
/// 256 um, which the groove outgrows at cycle 2340 (the run then fails: the contact reaches
/// the domain's edge), so it runs for a few seconds at most; [`busy_scene`] outlasts a test.
pub fn long_scene(cycles: u64) -> Value {
    json!({
        "preset": "dalmau2018-316l",
        "overrides": {
            "name": format!("long, {cycles} cycles"),
            "numerics": {"grid": 128, "domain_um": 256, "cycle_step": 1},
            "test": {"cycles": cycles}
        }
    })
}

/// A run that outlasts any test, for a worker that must stay busy until the test cancels
/// it: the preset solved every cycle on a 128 grid in the automatic domain, which grows with
/// the groove (cycle 27977 of 300000 after 120 s here, still running).
pub fn busy_scene() -> Value {
    json!({
        "preset": "dalmau2018-316l",
        "overrides": {
            "name": "busy",
            "numerics": {"grid": 128, "cycle_step": 1},
            "test": {"cycles": 300_000}
        }
    })
}

pub fn args(data_dir: &Path) -> ServeArgs {
    ServeArgs {
        addr: "127.0.0.1:0".parse().expect("address"),
        data_dir: data_dir.to_owned(),
        workers: NonZeroUsize::new(2).expect("non-zero"),
        queue_capacity: NonZeroUsize::new(64).expect("non-zero"),
        max_study_members: NonZeroUsize::new(tribosim::study::MAX_MEMBERS).expect("non-zero"),
        token: None,
        token_file: None,
        cors_origins: Vec::new(),
        allowed_hosts: Vec::new(),
        static_dir: None,
        limits: Limits::default(),
        budgets: Budgets::default(),
    }
}

/// The service running in this process on a loopback port.
pub struct Server {
    pub base: String,
    stop: Option<oneshot::Sender<()>>,
    task: JoinHandle<Result<(), ServeError>>,
}

impl Server {
    pub async fn start(args: ServeArgs) -> Self {
        let listener = TcpListener::bind("127.0.0.1:0").await.expect("bind");
        let base = format!("http://{}", listener.local_addr().expect("address"));
        let (stop, stopped) = oneshot::channel::<()>();
        let task = tokio::spawn(serve_on(args, listener, async {
            let _ = stopped.await;
        }));
        Self {
            base,
            stop: Some(stop),
            task,
        }
    }

    pub fn url(&self, path: &str) -> String {
        format!("{}{path}", self.base)
    }

    /// Graceful shutdown; the server must stop cleanly.
    pub async fn stop(mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        tokio::time::timeout(PATIENCE, &mut self.task)
            .await
            .expect("server stops")
            .expect("server task")
            .expect("server ran without error");
    }
}

/// One server-sent event.
#[derive(Debug, Clone)]
pub struct Event {
    pub event: String,
    pub id: Option<String>,
    pub data: String,
}

impl Event {
    pub fn json(&self) -> Value {
        serde_json::from_str(&self.data).expect("event data is JSON")
    }
}

/// Reads a job's event stream to its end, calling `on_event` for each event as it arrives.
pub async fn follow(
    client: &reqwest::Client,
    url: &str,
    last_event_id: Option<u64>,
    mut on_event: impl AsyncFnMut(&Event),
) -> Vec<Event> {
    let mut request = client.get(url);
    if let Some(id) = last_event_id {
        request = request.header("Last-Event-ID", id.to_string());
    }
    let response = request.send().await.expect("events request");
    assert_eq!(response.status(), 200, "events status");
    let content_type = response.headers()["content-type"].to_str().expect("ascii");
    assert!(
        content_type.starts_with("text/event-stream"),
        "{content_type}"
    );
    let mut body = response.bytes_stream();
    let mut buffer = String::new();
    let mut events = Vec::new();
    let read = async {
        while let Some(chunk) = body.next().await {
            buffer.push_str(std::str::from_utf8(&chunk.expect("chunk")).expect("utf-8"));
            while let Some(end) = buffer.find("\n\n") {
                let block: String = buffer.drain(..end + 2).collect();
                if let Some(event) = parse_event(&block) {
                    on_event(&event).await;
                    events.push(event);
                }
            }
        }
    };
    tokio::time::timeout(PATIENCE, read)
        .await
        .expect("event stream ends");
    events
}

fn parse_event(block: &str) -> Option<Event> {
    let (mut event, mut id, mut data) = (String::from("message"), None, Vec::new());
    for line in block.lines() {
        if let Some(value) = line.strip_prefix("event:") {
            event = value.trim_start().to_owned();
        } else if let Some(value) = line.strip_prefix("id:") {
            id = Some(value.trim_start().to_owned());
        } else if let Some(value) = line.strip_prefix("data:") {
            data.push(value.strip_prefix(' ').unwrap_or(value).to_owned());
        }
    }
    // Comment-only blocks are keep-alives.
    (!data.is_empty()).then(|| Event {
        event,
        id,
        data: data.join("\n"),
    })
}

/// Submits a scene; panics unless it is accepted.
pub async fn submit(client: &reqwest::Client, base: &str, scene: &Value) -> Value {
    let response = client
        .post(format!("{base}/api/v1/jobs"))
        .json(scene)
        .send()
        .await
        .expect("submit");
    assert_eq!(response.status(), 202, "submit status");
    response.json().await.expect("job JSON")
}

/// Asserts a 4xx answer with the JSON error shape; returns the body.
pub async fn expect_client_error(response: reqwest::Response, status: u16) -> Value {
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

/// GET `url`, expect 200, parse the JSON body.
pub async fn get_json(client: &reqwest::Client, url: &str) -> Value {
    let response = client.get(url).send().await.expect("GET");
    assert_eq!(response.status(), 200, "GET {url}");
    response.json().await.expect("JSON body")
}

/// POST `body` as JSON to `url`: the status and the JSON body.
pub async fn post(client: &reqwest::Client, url: &str, body: &Value) -> (u16, Value) {
    let response = client.post(url).json(body).send().await.expect("POST");
    let status = response.status().as_u16();
    (status, response.json().await.expect("JSON body"))
}

/// POST `body` as JSON to `url`, expect it refused with 422 and the JSON error shape
/// ([`expect_client_error`]); returns the error body.
pub async fn refused(client: &reqwest::Client, url: &str, body: &Value) -> Value {
    let response = client.post(url).json(body).send().await.expect("POST");
    expect_client_error(response, 422).await
}

/// DELETE `url`: the status and the JSON body (null for none).
pub async fn delete(client: &reqwest::Client, url: &str) -> (u16, Value) {
    let response = client.delete(url).send().await.expect("DELETE");
    let status = response.status().as_u16();
    let text = response.text().await.expect("body");
    (status, serde_json::from_str(&text).unwrap_or(Value::Null))
}

/// Polls `url` until `done` holds for its JSON.
pub async fn wait_for(client: &reqwest::Client, url: &str, done: impl Fn(&Value) -> bool) -> Value {
    let poll = async {
        loop {
            let value = get_json(client, url).await;
            if done(&value) {
                return value;
            }
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    };
    tokio::time::timeout(PATIENCE, poll)
        .await
        .expect("state reached")
}

pub async fn get_job(client: &reqwest::Client, base: &str, id: &str) -> Value {
    get_json(client, &format!("{base}/api/v1/jobs/{id}")).await
}

/// Polls a job until `done` holds for it.
pub async fn wait_for_job(
    client: &reqwest::Client,
    base: &str,
    id: &str,
    done: impl Fn(&Value) -> bool,
) -> Value {
    wait_for(client, &format!("{base}/api/v1/jobs/{id}"), done).await
}

pub fn is_final(job: &Value) -> bool {
    matches!(
        job["status"].as_str(),
        Some("succeeded" | "failed" | "cancelled" | "damaged")
    )
}

/// A result with its wall-clock time and its date (the only fields that differ between
/// runs) removed.
pub fn without_wall_time(mut result: Value) -> Value {
    result["summary"]
        .as_object_mut()
        .expect("summary")
        .remove("wall_s");
    if let Some(provenance) = result.get_mut("provenance").and_then(Value::as_object_mut) {
        provenance.remove("computed_at");
    }
    result
}
