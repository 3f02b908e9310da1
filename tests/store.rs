//! The service's store against a real `tribosim serve` process: a data directory with every
//! kind of damage still comes up serving each intact job byte for byte, re-runs the jobs
//! whose results are damaged and lists those whose scenes are; a result damaged while the
//! server runs is never served; concurrent DELETEs each get a correct answer; a cancel
//! survives kill -9; a full disk answers 507 and leaves nothing behind, a read-only one 503
//! with its reason, with `/healthz` degraded and what it holds served.

mod common;

use std::collections::BTreeMap;
use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use futures_util::future::join_all;
use serde_json::{Value, json};

use common::process::{ServerProcess, serve_command};
use common::{
    TempDir, busy_scene, follow, get_job, get_json, is_final, small_scene, submit, wait_for_job,
    without_wall_time,
};

/// Keeps the first half of a file, as a write cut short would.
fn truncate(path: &Path) {
    let bytes = fs::read(path).expect("read");
    fs::write(path, &bytes[..bytes.len() / 2]).expect("truncate");
}

/// Overwrites eight bytes in the middle of a file with NULs: the length is unchanged, and a
/// NUL is invalid anywhere in JSON.
fn corrupt(path: &Path) {
    let mut bytes = fs::read(path).expect("read");
    let middle = bytes.len() / 2;
    bytes[middle..middle + 8].fill(0);
    fs::write(path, bytes).expect("corrupt");
}

/// A kind of damage: its label, the file it hits (none for the intact job), and how.
type Damage = (&'static str, &'static str, fn(&Path));

/// Replaces a file by an empty directory of the same name.
fn into_directory(path: &Path) {
    fs::remove_file(path).expect("remove");
    fs::create_dir(path).expect("directory");
}

fn job_file(dir: &Path, id: &str, file: &str) -> PathBuf {
    dir.join("jobs").join(id).join(file)
}

/// GET a job's result: the status and the body.
async fn result(client: &reqwest::Client, url: &str) -> (u16, Vec<u8>) {
    let response = client.get(url).send().await.expect("result");
    let status = response.status().as_u16();
    (status, response.bytes().await.expect("body").to_vec())
}

fn result_url(base: &str, id: &str) -> String {
    format!("{base}/api/v1/jobs/{id}/result")
}

fn parsed(bytes: &[u8]) -> Value {
    serde_json::from_slice(bytes).expect("result JSON")
}

/// The cycles a job's event stream sends, and its final status.
async fn streamed(client: &reqwest::Client, base: &str, id: &str) -> (Vec<Value>, Value) {
    let url = format!("{base}/api/v1/jobs/{id}/events");
    let events = follow(client, &url, None, async |_| {}).await;
    let (last, cycles) = events.split_last().expect("events");
    assert_eq!(last.event, "status");
    (
        cycles.iter().map(common::Event::json).collect(),
        last.json(),
    )
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_damaged_store_comes_up_serving_every_intact_job() {
    let dir = TempDir::new("damaged-store");
    let client = reqwest::Client::new();
    let mut first = ServerProcess::start(dir.path());
    let damage = damages();
    let mut ids = Vec::new();
    for _ in &damage {
        let job = submit(&client, &first.base, &small_scene(5)).await;
        ids.push(job["id"].as_str().expect("id").to_owned());
    }
    let mut before = BTreeMap::new();
    for id in &ids {
        let job = wait_for_job(&client, &first.base, id, is_final).await;
        assert_eq!(job["status"], "succeeded", "{job}");
        let (status, bytes) = result(&client, &result_url(&first.base, id)).await;
        assert_eq!(status, 200);
        before.insert(id.clone(), bytes);
    }
    first.kill_9();

    for (id, (_, file, how)) in ids.iter().zip(&damage) {
        if !file.is_empty() {
            how(&job_file(dir.path(), id, file));
        }
    }
    let jobs = dir.path().join("jobs");
    let strays = litter(&jobs);

    let second = ServerProcess::start(dir.path());
    let base = &second.base;
    let listed: Value = get_json(&client, &format!("{base}/api/v1/jobs")).await;
    assert_eq!(
        listed.as_array().map(Vec::len),
        Some(ids.len()),
        "no job vanished: {listed}"
    );
    for (id, &(label, file, _)) in ids.iter().zip(&damage) {
        served_after_damage(&client, base, id, (label, file), &before[id]).await;
    }
    for gone in &strays {
        assert!(!jobs.join(gone).exists(), "{gone} is swept or set aside");
    }
    let quarantined: Vec<String> = fs::read_dir(dir.path().join("quarantine"))
        .expect("a quarantine directory")
        .map(|entry| {
            entry
                .expect("entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    let file_job = &strays[3];
    assert!(
        quarantined
            .iter()
            .any(|name| name.starts_with(file_job.as_str())),
        "the file in place of a job is kept aside: {quarantined:?}"
    );
    assert!(second.log().contains("quarantined"), "{}", second.log());
}

/// One kind of damage for each job: (label, file, how), applied after the job has succeeded
/// and the server is dead.
fn damages() -> [Damage; 13] {
    [
        ("intact", "", |_| {}),
        ("status truncated", "status.json", truncate),
        ("status corrupt", "status.json", corrupt),
        // A directory cannot be read as a file nor replaced by a rename: this status can
        // neither be read nor rewritten at startup.
        ("status unreadable", "status.json", into_directory),
        ("scene truncated", "scene.json", truncate),
        ("scene unreadable", "scene.json", into_directory),
        ("scene corrupt", "scene.json", corrupt),
        ("result truncated", "result.json", truncate),
        ("result corrupt", "result.json", corrupt),
        ("result missing", "result.json", |path| {
            fs::remove_file(path).expect("remove");
        }),
        ("cycles truncated", "cycles.jsonl", truncate),
        ("cycles corrupt", "cycles.jsonl", corrupt),
        ("manifest corrupt", "manifest.json", corrupt),
    ]
}

/// Leaves in the jobs directory what a crash or a hand could: a file where a staging
/// directory goes, a half-deleted directory, a file in place of a job, and a staged job
/// never committed. Their names, the file in place of a job's last.
fn litter(jobs: &Path) -> [String; 4] {
    fs::write(
        jobs.join("x.new"),
        "a file where a staging directory is expected",
    )
    .expect("x");
    fs::create_dir_all(jobs.join("y.deleted").join("inside")).expect("y");
    let file_job = uuid::Uuid::new_v4().to_string();
    fs::write(jobs.join(&file_job), "a file in place of a job directory").expect("file");
    let staged = format!("{}.new", uuid::Uuid::new_v4());
    fs::create_dir(jobs.join(&staged)).expect("staged");
    fs::write(jobs.join(&staged).join("scene.json"), "{").expect("staged scene");
    ["x.new".to_owned(), "y.deleted".to_owned(), staged, file_job]
}

/// What the restarted server makes of job `id` whose `file` got the damage `label`: served
/// as it was (no damage, or a status it rebuilds), damaged and deletable (its scene), or
/// run again to the same numbers (its result, cycles or manifest).
async fn served_after_damage(
    client: &reqwest::Client,
    base: &str,
    id: &str,
    (label, file): (&str, &str),
    before: &[u8],
) {
    let job = wait_for_job(client, base, id, is_final).await;
    let (status, bytes) = result(client, &result_url(base, id)).await;
    match file {
        "" | "status.json" => {
            assert_eq!(job["status"], "succeeded", "{label}: {job}");
            assert_eq!(status, 200, "{label}");
            assert!(
                bytes == before,
                "{label}: the result is served byte for byte"
            );
        }
        "scene.json" => {
            assert_eq!(job["status"], "damaged", "{label}: {job}");
            let error = job["error"].as_str().unwrap_or_default();
            assert!(error.contains("scene.json"), "{label}: {job}");
            assert_eq!(status, 409, "{label}");
            let response = client
                .delete(format!("{base}/api/v1/jobs/{id}"))
                .send()
                .await
                .expect("delete");
            assert_eq!(
                response.status(),
                204,
                "{label}: a damaged job can be deleted"
            );
        }
        _ => {
            assert_eq!(job["status"], "succeeded", "{label}: {job}");
            let reason = job["rerun_reason"].as_str().unwrap_or_default();
            assert!(
                reason.contains(file),
                "{label}: the reason names {file}: {job}"
            );
            assert_eq!(status, 200, "{label}");
            // The run is deterministic: only the wall-clock time differs.
            assert_eq!(
                without_wall_time(parsed(&bytes)),
                without_wall_time(parsed(before)),
                "{label}: the re-run gives the same numbers"
            );
            let (cycles, last) = streamed(client, base, id).await;
            assert_eq!(Value::Array(cycles), parsed(&bytes)["cycles"], "{label}");
            assert_eq!(last["status"], "succeeded", "{label}");
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_result_damaged_while_the_server_runs_is_never_served() {
    let dir = TempDir::new("damaged-live");
    let client = reqwest::Client::new();
    let server = ServerProcess::start(dir.path());
    let base = &server.base;
    let mut jobs = Vec::new();
    for _ in 0..3 {
        let job = submit(&client, base, &small_scene(5)).await;
        let id = job["id"].as_str().expect("id").to_owned();
        wait_for_job(&client, base, &id, is_final).await;
        let (status, bytes) = result(&client, &result_url(base, &id)).await;
        assert_eq!(status, 200);
        jobs.push((id, bytes));
    }

    // A truncated result.json: 409 naming the damage, then the job runs again.
    let (id, original) = &jobs[0];
    truncate(&job_file(dir.path(), id, "result.json"));
    let response = client.get(result_url(base, id)).send().await.expect("get");
    assert_eq!(response.status(), 409);
    let body: Value = response.json().await.expect("error JSON");
    assert!(
        body["error"]
            .as_str()
            .is_some_and(|e| e.contains("damaged")),
        "{body}"
    );
    let job = wait_for_job(&client, base, id, is_final).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    assert!(job["rerun_reason"].is_string(), "{job}");
    let (status, bytes) = result(&client, &result_url(base, id)).await;
    assert_eq!(status, 200);
    assert_eq!(
        without_wall_time(parsed(&bytes)),
        without_wall_time(parsed(original))
    );

    // The CSV of a damaged result: 409, not a 500.
    let (id, original) = &jobs[1];
    corrupt(&job_file(dir.path(), id, "result.json"));
    let response = client
        .get(format!("{base}/api/v1/jobs/{id}/result.csv"))
        .send()
        .await
        .expect("csv");
    assert_eq!(response.status(), 409);
    let job = wait_for_job(&client, base, id, is_final).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    let (_, bytes) = result(&client, &result_url(base, id)).await;
    assert_eq!(
        without_wall_time(parsed(&bytes)),
        without_wall_time(parsed(original))
    );

    // A truncated cycle log: the stream does not end early, it follows the re-run to the
    // last cycle.
    let (id, original) = &jobs[2];
    truncate(&job_file(dir.path(), id, "cycles.jsonl"));
    let (cycles, last) = streamed(&client, base, id).await;
    assert_eq!(last["status"], "succeeded", "{last}");
    assert_eq!(Value::Array(cycles), parsed(original)["cycles"]);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn concurrent_deletes_each_get_a_correct_answer() {
    let dir = TempDir::new("deletes");
    let client = reqwest::Client::new();
    let server = ServerProcess::start(dir.path());
    let base = &server.base;
    let delete_all = async |id: &str, n: usize| -> Vec<u16> {
        let url = format!("{base}/api/v1/jobs/{id}");
        let responses = join_all((0..n).map(|_| client.delete(&url).send())).await;
        responses
            .into_iter()
            .map(|response| response.expect("delete").status().as_u16())
            .collect()
    };

    // Finished jobs: one DELETE removes each, the others find nothing.
    for _ in 0..5 {
        let job = submit(&client, base, &small_scene(5)).await;
        let id = job["id"].as_str().expect("id").to_owned();
        wait_for_job(&client, base, &id, is_final).await;
        let mut answers = delete_all(&id, 4).await;
        answers.sort_unstable();
        assert_eq!(answers, [204, 404, 404, 404], "finished job {id}");
    }

    // One worker, kept busy for far longer than the test (it is cancelled at the end): the
    // others wait in the queue.
    let busy = submit(&client, base, &busy_scene()).await;
    let busy = busy["id"].as_str().expect("id").to_owned();
    wait_for_job(&client, base, &busy, |job| job["status"] == "running").await;
    let mut queued = Vec::new();
    for _ in 0..20 {
        let job = submit(&client, base, &small_scene(5)).await;
        queued.push(job["id"].as_str().expect("id").to_owned());
    }
    for answers in join_all(queued.iter().map(|id| delete_all(id, 4))).await {
        // The first cancels (200), the next removes the cancelled job (204), the rest find
        // nothing (404).
        let mut answers = answers;
        answers.sort_unstable();
        assert_eq!(answers, [200, 204, 404, 404], "queued job");
    }
    let answers = delete_all(&busy, 4).await;
    assert!(
        answers
            .iter()
            .all(|status| [202, 204, 404].contains(status)),
        "running job: {answers:?}"
    );
    // The job stops within a cycle, cancelled; a DELETE that came after it stopped removed
    // it (204), and then it is gone.
    if answers.contains(&204) {
        let response = client
            .get(format!("{base}/api/v1/jobs/{busy}"))
            .send()
            .await
            .expect("get");
        assert_eq!(response.status(), 404);
    } else {
        let job = wait_for_job(&client, base, &busy, is_final).await;
        assert_eq!(job["status"], "cancelled", "{job}");
    }
}

/// A scene whose cycles take long enough (a 256-cell grid) that a kill right after the
/// cancel's answer lands before the worker has stopped the run.
fn slow_scene() -> Value {
    json!({
        "preset": "dalmau2018-316l",
        "overrides": {
            "name": "slow",
            "numerics": {"grid": 256, "domain_um": 256, "cycle_step": 1},
            "test": {"cycles": 3000}
        }
    })
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cancelled_job_stays_cancelled_after_kill_9() {
    let dir = TempDir::new("cancel-kill");
    let client = reqwest::Client::new();
    let mut first = ServerProcess::start(dir.path());
    let job = submit(&client, &first.base, &slow_scene()).await;
    let id = job["id"].as_str().expect("id").to_owned();
    wait_for_job(&client, &first.base, &id, |job| {
        job["cycles_done"].as_u64() >= Some(1)
    })
    .await;
    let response = client
        .delete(first.url(&format!("/api/v1/jobs/{id}")))
        .send()
        .await
        .expect("delete");
    assert_eq!(response.status(), 202);
    first.kill_9();

    let second = ServerProcess::start(dir.path());
    let job = get_job(&client, &second.base, &id).await;
    assert_eq!(job["status"], "cancelled", "{job}");
    // Long enough for a worker to have picked the job up again had it been queued.
    tokio::time::sleep(Duration::from_millis(500)).await;
    let job = get_job(&client, &second.base, &id).await;
    assert_eq!(job["status"], "cancelled", "{job}");
    assert!(job["started_at"].is_string(), "{job}");
}

/// Submits a study of two small members; the answer's status.
async fn submit_small_study(client: &reqwest::Client, server: &ServerProcess) -> u16 {
    let study = json!({"base": small_scene(5), "axes": {"test.load_n": [2, 5]}});
    let response = client
        .post(server.url("/api/v1/studies"))
        .json(&study)
        .send()
        .await
        .expect("submit a study");
    response.status().as_u16()
}

/// The server on a data directory `dir` that `script` mounts as a tmpfs in a user and mount
/// namespace of the server's own, so no privilege is needed where unprivileged namespaces
/// are allowed. `sh -c script` gets `dir` as `$0`, then `extra`, then the server's command
/// to exec. With the folder as the server sees it (through its `/proc` root); `None`, said
/// on stderr, where `unshare --user --mount` is not available.
fn server_on_tmpfs(dir: &Path, script: &str, extra: &[&OsStr]) -> Option<(ServerProcess, PathBuf)> {
    let namespaces = Command::new("unshare")
        .args(["--user", "--map-root-user", "--mount", "true"])
        .status()
        .is_ok_and(|status| status.success());
    if !namespaces {
        eprintln!("skipped: `unshare --user --mount` is not available here");
        return None;
    }
    let serve = serve_command(dir, 1);
    let mut command = Command::new("unshare");
    command
        .args(["--user", "--map-root-user", "--mount", "sh", "-c", script])
        .arg(dir)
        .args(extra)
        .arg(serve.get_program())
        .args(serve.get_args());
    let server = ServerProcess::spawn(command);
    let inside = PathBuf::from(format!("/proc/{}/root", server.pid())).join(
        dir.strip_prefix("/")
            .expect("an absolute temporary directory"),
    );
    Some((server, inside))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_full_disk_answers_507_and_leaves_nothing_behind() {
    // A 4 MiB tmpfs, filled, as the data directory.
    let dir = TempDir::new("full-disk");
    let script = "mount -t tmpfs -o size=4m tribosim \"$0\" && \
                  { cat /dev/zero > \"$0/filler\" 2>/dev/null; exec \"$@\"; }";
    let Some((server, inside)) = server_on_tmpfs(dir.path(), script, &[]) else {
        return;
    };
    let client = reqwest::Client::new();
    let response = client
        .post(server.url("/api/v1/jobs"))
        .json(&small_scene(5))
        .send()
        .await
        .expect("submit");
    assert_eq!(response.status(), 507);
    let body: Value = response.json().await.expect("error JSON");
    assert!(
        body["error"]
            .as_str()
            .is_some_and(|e| e.contains("disk is full")),
        "{body}"
    );
    let left: Vec<_> = fs::read_dir(inside.join("jobs"))
        .expect("jobs directory")
        .collect();
    assert!(left.is_empty(), "nothing left of the refused job: {left:?}");
    let listed: Value = get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(listed, json!([]));
    // A study refused the same way leaves neither its members nor its mark: with two
    // pages free, its mark is written and the disk fills as its members are.
    let filler = fs::OpenOptions::new()
        .write(true)
        .open(inside.join("filler"))
        .expect("the filler");
    let length = filler.metadata().expect("filler length").len();
    filler.set_len(length - 8192).expect("free two pages");
    assert_eq!(submit_small_study(&client, &server).await, 507);
    let left: Vec<_> = fs::read_dir(inside.join("studies"))
        .expect("studies directory")
        .collect();
    assert!(
        left.is_empty(),
        "nothing left of the refused study: {left:?}"
    );
    let left: Vec<_> = fs::read_dir(inside.join("jobs")).expect("jobs").collect();
    assert!(left.is_empty(), "nothing left of its members: {left:?}");

    // Space freed: the same submission is accepted and runs.
    fs::File::create(inside.join("filler")).expect("free the space");
    let job = submit(&client, &server.base, &small_scene(5)).await;
    let id = job["id"].as_str().expect("id");
    let job = wait_for_job(&client, &server.base, id, is_final).await;
    assert_eq!(job["status"], "succeeded", "{job}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_read_only_store_answers_503_with_the_reason_and_keeps_what_it_holds() {
    // Remounted read-only by a watcher in the server's namespace once the test creates the
    // trigger file (given up after 60 s, so no process outlives a failed test).
    let dir = TempDir::new("read-only");
    let signals = TempDir::new("read-only-trigger");
    let trigger = signals.path().join("remount");
    let script = "mount -t tmpfs -o size=16m tribosim \"$0\" || exit 1; trigger=\"$1\"; shift; \
                  ( i=0; while [ ! -e \"$trigger\" ] && [ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done; \
                    [ -e \"$trigger\" ] && mount -o remount,ro \"$0\" ) & exec \"$@\"";
    let Some((server, _)) = server_on_tmpfs(dir.path(), script, &[trigger.as_os_str()]) else {
        return;
    };
    let client = reqwest::Client::new();
    let job = submit(&client, &server.base, &small_scene(5)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    let done = wait_for_job(&client, &server.base, &id, is_final).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let (_, before) = result(&client, &result_url(&server.base, &id)).await;

    fs::write(&trigger, b"").expect("trigger the remount");
    let health = tokio::time::timeout(Duration::from_secs(30), async {
        loop {
            let response = client
                .get(server.url("/healthz"))
                .send()
                .await
                .expect("healthz");
            if response.status() == 503 {
                return response.json::<Value>().await.expect("health JSON");
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    })
    .await
    .expect("/healthz reports the store degraded");
    assert_eq!(health["status"], "degraded", "{health}");
    let reason = |body: &Value| body.to_string().contains("Read-only file system");
    assert!(reason(&health), "{health}");

    let response = client
        .post(server.url("/api/v1/jobs"))
        .json(&small_scene(5))
        .send()
        .await
        .expect("submit");
    assert_eq!(response.status(), 503);
    let refusal: Value = response.json().await.expect("error JSON");
    assert!(reason(&refusal), "{refusal}");
    let response = client
        .patch(server.url(&format!("/api/v1/jobs/{id}")))
        .json(&json!({"sample": "S-1"}))
        .send()
        .await
        .expect("relabel");
    assert_eq!(response.status(), 503);
    assert_eq!(submit_small_study(&client, &server).await, 503);

    // What was stored is served as it was, and nothing else was added.
    let (status, after) = result(&client, &result_url(&server.base, &id)).await;
    assert_eq!((status, after == before), (200, true));
    let listed: Value = get_json(&client, &server.url("/api/v1/jobs")).await;
    assert_eq!(listed.as_array().map(Vec::len), Some(1), "{listed}");
    assert_eq!(listed[0]["sample"], Value::Null, "{listed}");
}
