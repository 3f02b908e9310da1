//! Jobs over HTTP against a server in this process: a run streamed and downloaded equals
//! the library's run, 50 jobs at once, the queue bound, cancel, and what a bad submission
//! gets (a 4xx with the JSON error body, never a 5xx; a bad id's: `tests/strings_http.rs`).

mod common;

use std::collections::BTreeSet;
use std::num::NonZeroUsize;
use std::sync::atomic::AtomicBool;

use futures_util::future::join_all;
use serde_json::{Value, json};
use tribosim::simulation::parse_scene;

use common::{
    Server, TempDir, args, expect_client_error, follow, get_job, get_json, is_final, long_scene,
    small_scene, submit, wait_for_job, without_wall_time,
};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_streamed_and_downloaded_run_equals_the_library_run() {
    let dir = TempDir::new("stream");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let scene = small_scene(20);
    let (location, id) = submitted(&client, &server, &scene).await;

    let events_url = server.url(&format!("{location}/events"));
    let events = follow(&client, &events_url, None, async |_| {}).await;
    let cycles = cycle_events(&events);
    let downloaded = downloaded_result(&client, &server, &location).await;
    compressed_alike(
        &client,
        &server.url(&format!("{location}/result")),
        &events_url,
        &downloaded,
    )
    .await;

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
    backlog_resumed(&client, &events_url, events.len(), &streamed).await;
    tables_as_csv(&client, &server, &location, &downloaded).await;
    compact_without_maps(&client, &server, &location, &downloaded).await;

    let listed: Value = get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(listed[0]["id"], id.as_str());

    server.stop().await;
}

/// Submits `scene`: 202, with the job's location and its id.
async fn submitted(client: &reqwest::Client, server: &Server, scene: &Value) -> (String, String) {
    let response = client
        .post(server.url("/api/v1/jobs"))
        .json(scene)
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
    (location, id)
}

/// The cycle events of a finished 20-cycle run's stream, checked: in order, each with its
/// cycle as its id, then the final status.
fn cycle_events(events: &[common::Event]) -> &[common::Event] {
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
    cycles
}

/// The job's result, downloaded under the run's name.
async fn downloaded_result(client: &reqwest::Client, server: &Server, location: &str) -> Value {
    let response = client
        .get(server.url(&format!("{location}/result")))
        .send()
        .await
        .expect("result");
    assert_eq!(response.status(), 200);
    let disposition = response.headers()["content-disposition"]
        .to_str()
        .expect("ascii");
    // Named after the run ("small, 20 cycles"), not its id.
    assert_eq!(
        disposition,
        "attachment; filename=\"small-20-cycles.result.json\""
    );
    response.json().await.expect("result JSON")
}

/// Asked for gzip, the result at `result_url` comes compressed and equal to `downloaded`;
/// the event stream never does (it would be buffered).
async fn compressed_alike(
    client: &reqwest::Client,
    result_url: &str,
    events_url: &str,
    downloaded: &Value,
) {
    let response = client
        .get(result_url)
        .header("accept-encoding", "gzip")
        .send()
        .await
        .expect("result");
    assert_eq!(response.headers()["content-encoding"], "gzip");
    let events_response = client
        .get(events_url)
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
        &serde_json::from_str::<Value>(&text).expect("result JSON"),
        downloaded
    );
}

/// A late client gets the backlog (`events` events); with Last-Event-ID, only what follows
/// it.
async fn backlog_resumed(
    client: &reqwest::Client,
    events_url: &str,
    events: usize,
    streamed: &[Value],
) {
    let again = follow(client, events_url, None, async |_| {}).await;
    assert_eq!(again.len(), events);
    let middle = streamed[streamed.len() / 2]["cycle"]
        .as_u64()
        .expect("cycle");
    let resumed = follow(client, events_url, Some(middle), async |_| {}).await;
    let expected_after = streamed
        .iter()
        .filter(|record| record["cycle"].as_u64() > Some(middle))
        .count();
    assert_eq!(resumed.len(), expected_after + 1);
    assert_eq!(resumed.last().map(|e| e.event.as_str()), Some("status"));
}

/// The cycles, the profiles and the pressure maps as CSV, named after the run: one row
/// per record or point of the JSON's.
async fn tables_as_csv(
    client: &reqwest::Client,
    server: &Server,
    location: &str,
    downloaded: &Value,
) {
    let points = |key: &str, values: &str| -> usize {
        downloaded[key]
            .as_array()
            .expect("an array")
            .iter()
            .map(|item| match &item[values] {
                Value::Array(rows) if rows.first().is_some_and(Value::is_array) => rows
                    .iter()
                    .map(|row| row.as_array().map_or(0, Vec::len))
                    .sum(),
                Value::Array(values) => values.len(),
                _ => 0,
            })
            .sum()
    };
    let cycles = downloaded["cycles"].as_array().expect("cycles").len();
    // The result's header as a prefix (its columns grow with the result's), the maps' whole.
    for (route, header, expected) in [
        (
            "result.csv",
            "cycle,time_s,wear_volume_mm3,max_depth_um",
            cycles,
        ),
        (
            "profiles.csv",
            "cycle,y_um,depth_um",
            points("profiles", "depth_um"),
        ),
        (
            "pressure.csv",
            "cycle,x_um,y_um,pressure_mpa",
            points("pressure_maps", "pressure_mpa"),
        ),
    ] {
        let response = client
            .get(server.url(&format!("{location}/{route}")))
            .send()
            .await
            .expect("csv");
        assert_eq!(response.status(), 200, "{route}");
        let headers = response.headers();
        let content_type = headers["content-type"].to_str().expect("ascii");
        assert!(
            content_type.starts_with("text/csv"),
            "{route}: {content_type}"
        );
        let disposition = headers["content-disposition"].to_str().expect("ascii");
        assert!(disposition.contains(&format!("small-20-cycles.{route}")));
        let csv = response.text().await.expect("csv text");
        let rows: Vec<&str> = csv.lines().collect();
        let whole = route != "result.csv";
        assert!(
            if whole {
                rows[0] == header
            } else {
                rows[0].starts_with(header)
            },
            "{route}: {}",
            rows[0]
        );
        assert!(expected > 0, "{route}");
        assert_eq!(rows.len(), expected + 1, "{route}");
    }
}

/// `?compact=true`: the same result without its pressure maps, under its own name; any
/// other value of `compact` is refused.
async fn compact_without_maps(
    client: &reqwest::Client,
    server: &Server,
    location: &str,
    downloaded: &Value,
) {
    let response = client
        .get(server.url(&format!("{location}/result?compact=true")))
        .send()
        .await
        .expect("compact");
    assert!(
        response.headers()["content-disposition"]
            .to_str()
            .expect("ascii")
            .contains("small-20-cycles.result.compact.json")
    );
    let compact: Value = response.json().await.expect("JSON");
    let mut expected = downloaded.clone();
    expected["pressure_maps"] = Value::Array(Vec::new());
    assert_eq!(compact, expected);
    let response = client
        .get(server.url(&format!("{location}/result?compact=maybe")))
        .send()
        .await
        .expect("bad compact");
    assert_eq!(response.status(), 400);
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

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_invalid_scene_gets_422_naming_each_field_at_fault() {
    let dir = TempDir::new("invalid");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let jobs = server.url("/api/v1/jobs");
    let post = |body: Vec<u8>| {
        client
            .post(&jobs)
            .header("content-type", "application/json")
            .body(body)
            .send()
    };

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

    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_body_that_is_not_a_scene_gets_400_413_or_415_and_the_server_goes_on() {
    let dir = TempDir::new("garbage");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let jobs = server.url("/api/v1/jobs");
    let post = |body: Vec<u8>| {
        client
            .post(&jobs)
            .header("content-type", "application/json")
            .body(body)
            .send()
    };

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
        .header("content-type", "application/json")
        .body(huge)
        .send()
        .await
        .expect("post");
    expect_client_error(response, 413).await;
    // Not declared JSON: 415.
    let response = client
        .post(&jobs)
        .header("content-type", "text/plain")
        .body("{}")
        .send()
        .await
        .expect("post");
    expect_client_error(response, 415).await;
    let response = client.post(&jobs).body("{}").send().await.expect("post");
    expect_client_error(response, 415).await;

    // After all that, the server still works.
    let response = client
        .post(&jobs)
        .json(&small_scene(5))
        .send()
        .await
        .expect("post");
    assert_eq!(response.status(), 202);
    server.stop().await;
}
