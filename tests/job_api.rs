//! What a job carries besides its run, against the real `tribosim serve` binary: measured
//! points attached to it (stored, checked, kept across a restart, damage found by their
//! checksum, deleted with the job), the scene as run, the place of a queued job, and what a
//! cancelled run computed.

mod common;

use std::path::Path;

use serde_json::{Value, json};

use common::process::ServerProcess;
use common::{
    TempDir, busy_scene, get_job, get_json, is_final, long_scene, small_scene, submit, wait_for_job,
};

/// PUT a table; the status and the JSON body.
async fn put_table(
    client: &reqwest::Client,
    url: &str,
    content_type: &str,
    body: &str,
) -> (u16, Value) {
    let response = client
        .put(url)
        .header("content-type", content_type)
        .body(body.to_owned())
        .send()
        .await
        .expect("PUT");
    let status = response.status().as_u16();
    (status, response.json().await.expect("JSON body"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn measurements_round_trip_survive_a_restart_and_go_with_their_job() {
    let dir = TempDir::new("measurements");
    let client = reqwest::Client::new();
    let mut server = ServerProcess::start(dir.path());
    let job = submit(&client, &server.base, &small_scene(5)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    let url = |path: &str| server.url(&format!("/api/v1/jobs/{id}{path}"));

    let wear = measurements_stored(&client, &url("")).await;
    bad_tables_refused(&client, &url("")).await;
    let kept = get_json(&client, &url("/measurements")).await;
    assert_eq!(kept["wear_volume"], wear);
    assert_eq!(kept["ocp"], Value::Null);

    // Kept across a restart, even one without a shutdown.
    wait_for_job(&client, &server.base, &id, is_final).await;
    server.kill_9();
    let server = ServerProcess::start(dir.path());
    let url = |path: &str| server.url(&format!("/api/v1/jobs/{id}{path}"));
    let after = get_json(&client, &url("/measurements")).await;
    assert_eq!(after, kept);

    // DELETE removes one kind; deleting the job removes the rest with it.
    let response = client
        .delete(url("/measurements/profile"))
        .send()
        .await
        .expect("DELETE");
    assert_eq!(response.status(), 200);
    let left: Value = response.json().await.expect("JSON");
    assert_eq!(left["profile"], Value::Null);
    assert_eq!(left["wear_volume"], wear);
    let response = client.delete(url("")).send().await.expect("DELETE job");
    assert_eq!(response.status(), 204);
    assert!(!dir.path().join("jobs").join(&id).exists());
    let response = client.get(url("/measurements")).send().await.expect("GET");
    assert_eq!(response.status(), 404);
}

/// The paper's wear volumes at 5 N (Table 3), as a lab's CSV export.
const TABLE3_WEAR_CSV: &str =
    "# Table 3, 5 N\ntime_s,volume_mm3,spread_mm3\n600,0.0042,0.0005\n3600,0.0118,0.0011\n";

/// A job just accepted takes measurements already: a wear table as CSV and a profile as
/// JSON, each read back beside the other, at the job `job` (its URL). The wear table as read.
async fn measurements_stored(client: &reqwest::Client, job: &str) -> Value {
    let empty = get_json(client, &format!("{job}/measurements")).await;
    assert_eq!(
        empty,
        json!({"wear_volume": null, "profile": null, "ocp": null})
    );
    let csv = TABLE3_WEAR_CSV;
    let (status, answer) = put_table(
        client,
        &format!("{job}/measurements/wear_volume"),
        "text/csv; charset=utf-8",
        csv,
    )
    .await;
    assert_eq!(status, 200, "{answer}");
    let wear = json!({"time_s": [600.0, 3600.0], "volume_mm3": [0.0042, 0.0118],
                      "spread_mm3": [0.0005, 0.0011]});
    assert_eq!(answer["wear_volume"], wear);
    let profile = json!({"y_mm": [-0.1, 0.0, 0.1], "depth_um": [-0.2, 3.5, 0.1]});
    let (status, answer) = put_table(
        client,
        &format!("{job}/measurements/profile"),
        "application/json",
        &profile.to_string(),
    )
    .await;
    assert_eq!(status, 200, "{answer}");
    assert_eq!(answer["profile"], profile);
    assert_eq!(answer["wear_volume"], wear);

    wear
}

/// Refusals name the column, an unknown kind gets 400 and a type that is no table 415;
/// nothing of a refused table is kept (checked by the caller).
async fn bad_tables_refused(client: &reqwest::Client, job: &str) {
    let csv = TABLE3_WEAR_CSV;
    let refusals = [
        (
            "wear_volume",
            "time_s,volume_mm3\n600,0.004\n3600,-0.01\n",
            "volume_mm3",
        ),
        ("ocp", "time_s,potential_v\n10,-0.2\n5,-0.3\n", "time_s"),
        ("potential", "time_s\n10\n", "potential_v"),
        ("profile", "y_mm,depth_um\n0,1\n0.1,inf\n", "depth_um"),
    ];
    for (kind, csv, column) in refusals {
        let (status, answer) = put_table(
            client,
            &format!("{job}/measurements/{kind}"),
            "text/csv",
            csv,
        )
        .await;
        assert_eq!(status, 422, "{answer}");
        assert_eq!(answer["fields"][0]["path"], column, "{answer}");
        assert!(answer["error"].as_str().expect("message").contains(column));
    }
    let (status, _) = put_table(client, &format!("{job}/measurements/wear"), "text/csv", csv).await;
    assert_eq!(status, 400);
    let (status, _) = put_table(
        client,
        &format!("{job}/measurements/profile"),
        "text/plain",
        csv,
    )
    .await;
    assert_eq!(status, 415);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn measurements_are_scored_against_the_result_in_json_and_csv() {
    let dir = TempDir::new("scores");
    let client = reqwest::Client::new();
    let server = ServerProcess::start(dir.path());
    let job = submit(&client, &server.base, &small_scene(5)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    let url = |path: &str| server.url(&format!("/api/v1/jobs/{id}{path}"));
    let response = client.get(url("/scores")).send().await.expect("GET");
    assert!([200, 409].contains(&response.status().as_u16()));
    wait_for_job(&client, &server.base, &id, is_final).await;
    let result = get_json(&client, &url("/result")).await;
    let cycles = result["cycles"].as_array().expect("cycles");
    let (first, last) = (&cycles[0], &cycles[cycles.len() - 1]);
    // What a profilometer measures: the total volume when the run has corrosion.
    let quantity = if first.get("total_volume_mm3").is_some() {
        "total_volume_mm3"
    } else {
        "wear_volume_mm3"
    };
    let volume = |c: &Value| c[quantity].as_f64().expect("volume");
    let cycle = |c: &Value| c["cycle"].as_f64().expect("cycle");
    // At solved cycles the model is the record's own volume; past the run there is none.
    let csv = format!(
        "cycles;volume_um3;spread_um3\n{};{};{}\n{};{};0\n{};1;1\n",
        cycle(first),
        2e9 * volume(first),
        1e9 * volume(first),
        cycle(last),
        0.5e9 * volume(last),
        cycle(last) + 10.0,
    );
    let (status, answer) =
        put_table(&client, &url("/measurements/wear_volume"), "text/csv", &csv).await;
    assert_eq!(status, 200, "{answer}");
    let (status, answer) = put_table(
        &client,
        &url("/measurements/potential"),
        "text/csv",
        "time_s,potential_mv\n0,-200\n",
    )
    .await;
    assert_eq!(status, 200, "{answer}");
    assert_eq!(answer["ocp"]["potential_v"], json!([-0.2]));
    let scores = get_json(&client, &url("/scores")).await;
    let wear = &scores["wear_volume"];
    assert_eq!(wear["x_column"], "cycles");
    assert_eq!(wear["model_column"], quantity);
    let points = wear["points"].as_array().expect("points");
    let close = |a: &Value, b: f64| (a.as_f64().expect("number") - b).abs() <= 1e-12 * b.abs();
    // The um^3 columns are converted by 1e-9: 2 V measured against V is a residual of V and
    // a z-score of 1 against a spread of V.
    assert!(close(&points[0]["model"], volume(first)), "{wear}");
    assert!(close(&points[0]["residual"], volume(first)), "{wear}");
    assert!(close(&points[0]["z_score"], 1.0), "{wear}");
    assert!(close(&points[1]["residual"], -0.5 * volume(last)), "{wear}");
    assert_eq!(points[1]["z_score"], Value::Null, "a zero spread");
    assert_eq!(points[2]["model"], Value::Null, "past the run");
    assert_eq!(scores["ocp"]["column"], "potential_v");
    assert_eq!(scores["profile"], Value::Null);

    let response = client.get(url("/scores.csv")).send().await.expect("GET");
    assert_eq!(response.status(), 200);
    let text = response.text().await.expect("text");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "kind,x_column,x,column,measured,model,residual,z_score,model_column"
    );
    assert_eq!(lines.len(), 1 + 3 + 1, "{text}");
    assert!(lines[1].starts_with("wear_volume,cycles,"), "{text}");
    assert!(
        lines[4].starts_with("ocp,time_s,0,potential_v,-0.2,"),
        "{text}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn labels_are_set_at_submit_changed_after_kept_and_searched() {
    let dir = TempDir::new("labels");
    let client = reqwest::Client::new();
    let mut server = ServerProcess::start(dir.path());
    data_dir_announced(&server, dir.path()).await;
    let id = labelled_at_submit(&client, &server).await;
    wait_for_job(&client, &server.base, &id, is_final).await;
    labels_changed_within_bounds(&client, &server, &id).await;

    // Searched by any label; kept across a restart without a shutdown.
    let ids = |list: Value| -> Vec<String> {
        list.as_array()
            .expect("a list")
            .iter()
            .map(|j| j["id"].as_str().expect("id").to_owned())
            .collect()
    };
    for query in ["q=POLISHED", "q=s-12", "tag=wet", "tag=x,Paper"] {
        let list = get_json(&client, &server.url(&format!("/api/v1/jobs?{query}"))).await;
        assert_eq!(ids(list), std::slice::from_ref(&id), "{query}");
    }
    server.kill_9();
    let server = ServerProcess::start(dir.path());
    let job = get_job(&client, &server.base, &id).await;
    assert_eq!(
        (&job["sample"], &job["note"], &job["tags"]),
        (
            &json!("S-12"),
            &json!("re-polished"),
            &json!(["paper", "wet"])
        )
    );
}

/// The data directory, absolute, in the line that announces the address (which the log
/// keeps just after the address is read from it, so it is awaited).
async fn data_dir_announced(server: &ServerProcess, dir: &Path) {
    let absolute = std::fs::canonicalize(dir).expect("the data dir exists");
    let said = format!("with its data in {}", absolute.display());
    for _ in 0..100 {
        if server.log().contains(&said) {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    assert!(server.log().contains(&said), "{}", server.log());
}

/// A job submitted with a sample, a note and tags in the query carries them; one without
/// has none. The labelled job's id.
async fn labelled_at_submit(client: &reqwest::Client, server: &ServerProcess) -> String {
    let response = client
        .post(server.url("/api/v1/jobs?sample=S-12&note=first%20polish&tags=paper,5N"))
        .json(&small_scene(2))
        .send()
        .await
        .expect("submit");
    assert_eq!(response.status(), 202);
    let job: Value = response.json().await.expect("job");
    assert_eq!(job["sample"], "S-12");
    assert_eq!(job["note"], "first polish");
    assert_eq!(job["tags"], json!(["paper", "5N"]));
    let id = job["id"].as_str().expect("id").to_owned();
    let other = submit(client, &server.base, &small_scene(2)).await;
    assert_eq!(other["sample"], Value::Null);
    assert_eq!(other["tags"], json!([]));

    id
}

/// Labels changed after the run, those left out kept; refusals name the field and the
/// bound, and change nothing; too many tags at submit are refused too.
async fn labels_changed_within_bounds(client: &reqwest::Client, server: &ServerProcess, id: &str) {
    let patch = |body: Value| {
        let url = server.url(&format!("/api/v1/jobs/{id}"));
        let client = client.clone();
        async move {
            let response = client.patch(url).json(&body).send().await.expect("PATCH");
            let status = response.status().as_u16();
            (status, response.json::<Value>().await.expect("JSON"))
        }
    };
    let (status, changed) = patch(json!({"note": "re-polished", "tags": ["paper", "wet"]})).await;
    assert_eq!(status, 200, "{changed}");
    assert_eq!(changed["sample"], "S-12", "a label left out stays");
    assert_eq!(changed["note"], "re-polished");
    assert_eq!(changed["status"], "succeeded");
    // Refusals name the field and the bound; nothing changes.
    let (status, refused) = patch(json!({"sample": "x".repeat(101)})).await;
    assert_eq!(status, 422);
    assert_eq!(refused["fields"][0]["path"], "sample");
    assert!(
        refused["error"]
            .as_str()
            .expect("message")
            .contains("at most 100")
    );
    let (status, refused) = patch(json!({"colour": "red"})).await;
    assert_eq!(
        (status, refused["fields"][0]["path"].clone()),
        (422, json!("colour"))
    );
    let response = client
        .post(server.url("/api/v1/jobs?tags=a,b,c,d,e,f,g,h,i,j,k,l,m,n,o,p,q,r,s,t,u"))
        .json(&small_scene(2))
        .send()
        .await
        .expect("submit");
    assert_eq!(response.status(), 422);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_scene_as_run_has_every_default_and_runs_the_same_test() {
    let dir = TempDir::new("scene-as-run");
    let client = reqwest::Client::new();
    let server = ServerProcess::start(dir.path());
    let job = submit(&client, &server.base, &small_scene(3)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    let scene = get_json(&client, &server.url(&format!("/api/v1/jobs/{id}/scene"))).await;
    // The preset's values are filled in beside the overrides.
    assert_eq!(scene["test"]["cycles"], 3);
    assert_eq!(scene["numerics"]["grid"], 32);
    assert!(scene["test"]["load_n"].as_f64().is_some(), "{scene}");
    assert!(scene["ball"]["radius_mm"].as_f64().is_some(), "{scene}");
    let finished = wait_for_job(&client, &server.base, &id, is_final).await;
    assert_eq!(finished["status"], "succeeded");
    let result = get_json(&client, &server.url(&format!("/api/v1/jobs/{id}/result"))).await;
    assert_eq!(result["scene"], scene);
    // Submitted again, it is accepted as it stands.
    submit(&client, &server.base, &scene).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn queued_jobs_show_their_place_in_the_queue() {
    let dir = TempDir::new("queue-position");
    let client = reqwest::Client::new();
    // One worker: the long job runs, the next three wait in the order they came.
    let server = ServerProcess::start(dir.path());
    let busy = submit(&client, &server.base, &busy_scene()).await;
    let busy = busy["id"].as_str().expect("id").to_owned();
    wait_for_job(&client, &server.base, &busy, |job| {
        job["status"] == "running"
    })
    .await;
    let mut waiting = Vec::new();
    for place in 1..=3 {
        let job = submit(&client, &server.base, &small_scene(3)).await;
        assert_eq!(job["queue_position"], place, "{job}");
        waiting.push(job["id"].as_str().expect("id").to_owned());
    }
    for (id, place) in waiting.iter().zip(1..) {
        assert_eq!(
            get_job(&client, &server.base, id).await["queue_position"],
            place
        );
    }
    assert_eq!(
        get_job(&client, &server.base, &busy).await["queue_position"],
        Value::Null
    );
    // The first waiting job cancelled, the others move up.
    let response = client
        .delete(server.url(&format!("/api/v1/jobs/{}", waiting[0])))
        .send()
        .await
        .expect("DELETE");
    let cancelled: Value = response.json().await.expect("JSON");
    assert_eq!(cancelled["queue_position"], Value::Null, "{cancelled}");
    let list = get_json(&client, &server.url("/api/v1/jobs")).await;
    let place = |id: &str| {
        list.as_array()
            .expect("list")
            .iter()
            .find(|job| job["id"] == id)
            .map(|job| job["queue_position"].clone())
    };
    assert_eq!(place(&waiting[1]), Some(json!(1)));
    assert_eq!(place(&waiting[2]), Some(json!(2)));
    assert_eq!(place(&waiting[0]), Some(Value::Null));
    client
        .delete(server.url(&format!("/api/v1/jobs/{busy}")))
        .send()
        .await
        .expect("DELETE");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cancelled_run_keeps_its_cycles_across_a_restart() {
    let dir = TempDir::new("partial-result");
    let client = reqwest::Client::new();
    let mut server = ServerProcess::start(dir.path());
    let job = submit(&client, &server.base, &long_scene(3000)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    wait_for_job(&client, &server.base, &id, |job| {
        job["cycles_done"].as_u64() >= Some(3)
    })
    .await;
    let job_url = server.url(&format!("/api/v1/jobs/{id}"));
    let response = client.delete(&job_url).send().await.expect("DELETE");
    assert_eq!(response.status(), 202);
    let job = wait_for_job(&client, &server.base, &id, is_final).await;
    assert_eq!(job["status"], "cancelled");

    let result_url = format!("{job_url}/result");
    let partial = get_json(&client, &result_url).await;
    assert_eq!(partial["complete"], false);
    let cycles = partial["cycles"].as_array().expect("cycles");
    // `long_scene` solves every cycle, so the log holds cycles 1 to cycles_done.
    assert_eq!(
        cycles.len() as u64,
        job["cycles_done"].as_u64().expect("done")
    );
    assert_eq!(partial["summary"]["cycles"], job["cycles_done"]);
    assert_eq!(
        partial["summary"]["max_depth_um"],
        cycles.last().expect("a cycle")["max_depth_um"]
    );
    assert_eq!(partial["scene"]["test"]["cycles"], 3000);
    let csv = client
        .get(format!("{job_url}/result.csv"))
        .send()
        .await
        .expect("CSV")
        .text()
        .await
        .expect("text");
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), cycles.len() + 1);
    let stepped = rows[0]
        .split(',')
        .position(|name| name == "cycles_stepped_over")
        .unwrap_or_else(|| panic!("no cycles_stepped_over column: {}", rows[0]));
    assert!(
        rows[1..]
            .iter()
            .all(|row| row.split(',').nth(stepped) == Some("0")),
        "{csv}"
    );

    server.kill_9();
    let server = ServerProcess::start(dir.path());
    let again = get_json(&client, &server.url(&format!("/api/v1/jobs/{id}/result"))).await;
    assert_eq!(again, partial);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_measured_table_changed_on_disk_is_found_and_mended_by_a_put() {
    let dir = TempDir::new("measurement-damage");
    let client = reqwest::Client::new();
    let mut server = ServerProcess::start(dir.path());
    let job = submit(&client, &server.base, &small_scene(3)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    let csv = "cycles,volume_mm3\n10,0.0042\n60,0.0071\n";
    let put_url = server.url(&format!("/api/v1/jobs/{id}/measurements/wear_volume"));
    let (status, mut stored) = put_table(&client, &put_url, "text/csv", csv).await;
    assert_eq!(status, 200, "{stored}");
    // The PUT answers the tables as a GET does, and the headers it read under another name
    // (none here).
    assert_eq!(stored["renamed"], json!([]), "{stored}");
    stored.as_object_mut().expect("an object").remove("renamed");
    wait_for_job(&client, &server.base, &id, is_final).await;
    server.kill_9();

    // One digit changed: still valid JSON of the same length, so only the checksum tells.
    let file = dir
        .path()
        .join("jobs")
        .join(&id)
        .join("measured_wear_volume.json");
    let text = std::fs::read_to_string(&file).expect("stored table");
    assert!(text.contains("0.0042"), "{text}");
    std::fs::write(&file, text.replace("0.0042", "0.0043")).expect("write");

    let server = ServerProcess::start(dir.path());
    let url = server.url(&format!("/api/v1/jobs/{id}/measurements"));
    let response = client.get(&url).send().await.expect("GET");
    assert_eq!(response.status(), 409);
    let error: Value = response.json().await.expect("JSON");
    let message = error["error"].as_str().expect("message");
    assert!(message.contains("measured_wear_volume.json"), "{message}");
    // The job itself is untouched.
    let result = client
        .get(server.url(&format!("/api/v1/jobs/{id}/result")))
        .send()
        .await
        .expect("result");
    assert_eq!(result.status(), 200);
    let put_url = format!("{url}/wear_volume");
    let (status, mended) = put_table(&client, &put_url, "text/csv", csv).await;
    assert_eq!(status, 200, "{mended}");
    assert_eq!(get_json(&client, &url).await, stored);
}
