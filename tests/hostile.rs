//! Requests built to cost the server the most, against a server in this process: the
//! largest bodies it reads, full of what makes parsing and checking work (a hundred thousand
//! tags, a hundred thousand unknown keys), are refused with answers of a bounded size; and
//! jobs are held to the memory budget, refused at submit past it and never run together
//! past it. That `/healthz` keeps answering meanwhile is `scripts/load_test.py`'s to measure
//! (item 10), since a test asserts no time.

mod common;

use std::num::NonZeroU64;

use serde_json::{Map, Value, json};
use time::OffsetDateTime;
use time::format_description::well_known::Rfc3339;
use tribosim::scene::MAX_LISTED_PROBLEMS;
use tribosim::service::BODY_LIMIT_BYTES;

use common::{
    Server, TempDir, args, expect_client_error, is_final, small_scene, submit, wait_for_job,
};

/// The most bytes a refusal may take: its message and [`MAX_LISTED_PROBLEMS`] fields of a
/// few hundred bytes each (a scene's unknown key lists the section's names, about 300).
const MAX_ERROR_BYTES: usize = 16 * 1024;

/// A JSON body of `value`, checked to be within the server's body limit, so the test sends
/// the largest the server reads rather than one it refuses unread.
fn body(value: &Value) -> Vec<u8> {
    let bytes = serde_json::to_vec(value).expect("JSON");
    assert!(bytes.len() <= BODY_LIMIT_BYTES, "{} bytes", bytes.len());
    assert!(bytes.len() > BODY_LIMIT_BYTES / 2, "{} bytes", bytes.len());
    bytes
}

/// Sends `bytes` as JSON with `method` to `url`; expects the refusal `status` with the
/// error shape, at most the first [`MAX_LISTED_PROBLEMS`] fields and a count of the rest,
/// and the whole answer within [`MAX_ERROR_BYTES`].
async fn bounded_refusal(method: reqwest::Method, url: String, bytes: Vec<u8>, status: u16) {
    let response = reqwest::Client::new()
        .request(method, &url)
        .header("content-type", "application/json")
        .body(bytes)
        .send()
        .await
        .expect("request");
    let length = response.content_length();
    let body = expect_client_error(response, status).await;
    let size = serde_json::to_vec(&body).expect("JSON").len();
    assert!(size <= MAX_ERROR_BYTES, "{size} bytes ({length:?} sent)");
    let fields = body["fields"].as_array().cloned().unwrap_or_default();
    assert!(
        fields.len() <= MAX_LISTED_PROBLEMS + 1,
        "{} fields",
        fields.len()
    );
    if fields.len() == MAX_LISTED_PROBLEMS + 1 {
        let last = fields
            .last()
            .map(|f| f["message"].to_string())
            .unwrap_or_default();
        assert!(last.contains("more"), "the count of the rest: {last}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_megabyte_of_tags_or_unknown_keys_gets_a_bounded_refusal() {
    let dir = TempDir::new("hostile-bodies");
    let server = Server::start(args(dir.path())).await;
    let client = reqwest::Client::new();
    let job = submit(&client, &server.base, &small_scene(3)).await;
    let id = job["id"].as_str().expect("id");

    let tags: Vec<String> = (0..100_000).map(|i| format!("t{i}")).collect();
    let tags = body(&json!({ "tags": tags }));
    let patch = reqwest::Method::PATCH;
    bounded_refusal(
        patch.clone(),
        server.url(&format!("/api/v1/jobs/{id}")),
        tags.clone(),
        422,
    )
    .await;
    // A job that does not exist: the body is refused as unreadable labels, just as cheaply.
    let nobody = format!("/api/v1/jobs/{}", uuid::Uuid::new_v4());
    bounded_refusal(patch, server.url(&nobody), tags, 422).await;

    let keys: Map<String, Value> = (0..80_000).map(|i| (format!("k{i}"), json!(1))).collect();
    let post = reqwest::Method::POST;
    let jobs = server.url("/api/v1/jobs");
    bounded_refusal(
        post.clone(),
        jobs.clone(),
        body(&json!({ "disc": keys })),
        422,
    )
    .await;
    bounded_refusal(post, jobs, body(&Value::Object(keys)), 422).await;

    // Nothing of them was kept: the job is as it was, and the only one.
    let job = wait_for_job(&client, &server.base, id, is_final).await;
    assert_eq!(job["tags"], json!([]), "{job}");
    let listed = common::get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(listed.as_array().map(Vec::len), Some(1), "{listed}");
    server.stop().await;
}

/// When a job ran, from its record: (started, finished).
fn span(job: &Value) -> (OffsetDateTime, OffsetDateTime) {
    let at = |key: &str| {
        let text = job[key]
            .as_str()
            .unwrap_or_else(|| panic!("{key} in {job}"));
        OffsetDateTime::parse(text, &Rfc3339).expect("RFC 3339")
    };
    (at("started_at"), at("finished_at"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn jobs_are_held_to_the_memory_budget() {
    let dir = TempDir::new("memory-budget");
    let mut settings = args(dir.path());
    // small_scene's estimate is 64.85 MB (61.8 MiB: the 64 MB base and 830 bytes for each
    // of its 32 x 32 cells): one fits in 100 MiB, two do not.
    settings.budgets.job_memory_mib = NonZeroU64::new(100);
    let server = Server::start(settings).await;
    let client = reqwest::Client::new();

    let big = json!({"numerics": {"grid": 2048}});
    let response = client
        .post(server.url("/api/v1/jobs"))
        .json(&big)
        .send()
        .await
        .expect("submit");
    let refusal = expect_client_error(response, 422).await;
    assert_eq!(refusal["fields"][0]["path"], "numerics.grid", "{refusal}");
    let message = refusal["fields"][0]["message"].as_str().unwrap_or_default();
    assert!(
        message.contains("3.5 GB")
            && message.contains("105 MB")
            && message.contains("--job-memory-mib"),
        "the estimate, the budget and the flag: {message}"
    );

    // Two workers, two jobs, room in the budget for one at a time.
    let scene = small_scene(40);
    let first = submit(&client, &server.base, &scene).await;
    let second = submit(&client, &server.base, &scene).await;
    let mut spans = Vec::new();
    for job in [first, second] {
        let id = job["id"].as_str().expect("id");
        let done = wait_for_job(&client, &server.base, id, is_final).await;
        assert_eq!(done["status"], "succeeded", "{done}");
        spans.push(span(&done));
    }
    spans.sort();
    assert!(
        spans[0].1 <= spans[1].0,
        "they ran one after the other: {spans:?}"
    );
    let listed = common::get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(
        listed.as_array().map(Vec::len),
        Some(2),
        "the refused job was not kept"
    );
    server.stop().await;
}
