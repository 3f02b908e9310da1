//! Calibrations over HTTP, against the real `tribosim serve` binary: a fit over HTTP gives
//! the numbers of `tribosim calibrate` to the last digit, a bad table or option is refused
//! before any run with the field named, and fits are bounded up front, listed, cancelled and
//! deleted.

mod common;

use std::path::Path;
use std::time::Duration;

use serde_json::{Value, json};

use common::process::{ServerProcess, cli_json};
use common::{TempDir, delete, get_json, post, refused, wait_for};

/// Fits `request` over HTTP on `server` and runs `tribosim` with `cli_args` (a `calibrate`
/// command; its output into `dir`), expects both to succeed with the same result, and
/// returns it.
async fn same_fit_as_the_cli(
    dir: &TempDir,
    cli_args: &[&str],
    request: &Value,
    server: &ServerProcess,
) -> Value {
    let cli = cli_json(cli_args, &dir.path().join("fit.json"));

    let client = reqwest::Client::new();
    let url = server.url("/api/v1/calibrations");
    let (code, started) = post(&client, &url, request).await;
    assert_eq!(code, 202, "{started}");
    let id = started["id"].as_str().expect("id");
    let fit = wait_for(&client, &format!("{url}/{id}"), |c| {
        c["status"] != "running"
    })
    .await;
    assert_eq!(fit["status"], "succeeded", "{fit}");
    assert_eq!(fit["result"], cli, "the same fit, to the last digit");
    cli
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hardness_calibration_over_http_gives_the_numbers_of_tribosim_calibrate() {
    let dir = TempDir::new("calibration-http");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let table_path = root.join("docs/calibration/table3_hardness.csv");
    let server = ServerProcess::start(&dir.path().join("data"));
    let client = reqwest::Client::new();
    let url = server.url("/api/v1/calibrations");
    let table = std::fs::read_to_string(&table_path).expect("read the table");
    let request = json!({"kind": "hardness", "table": table});
    same_fit_as_the_cli(
        &dir,
        &["calibrate", "hardness", table_path.to_str().expect("path")],
        &request,
        &server,
    )
    .await;

    let bad = json!({"kind": "hardness", "table": "cycles,hardness_mpa\n10,2551\n60,abc\n"});
    let error = refused(&client, &url, &bad).await;
    let message = error["error"].as_str().expect("message");
    assert!(
        message.contains("`hardness_mpa`") && message.contains("row 2"),
        "{message}"
    );
    let backwards =
        json!({"kind": "archard", "table": {"time_s": [60, 10], "volume_mm3": [1e-3, 2e-3]}});
    let error = refused(&client, &url, &backwards).await;
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
        let error = refused(&client, &url, &request).await;
        let field = &error["fields"][0]["path"];
        assert!(
            field == "options.regime_change" || field == "table",
            "{kind} {change}: {error}"
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn calibrations_are_bounded_up_front_listed_cancelled_and_deleted() {
    let dir = TempDir::new("calibration-limits");
    let server = ServerProcess::start(&dir.path().join("data"));
    let client = reqwest::Client::new();
    let url = server.url("/api/v1/calibrations");
    let every_cycle =
        json!({"preset": "dalmau2018-316l", "overrides": {"numerics": {"cycle_step": 1}}});
    refused_up_front(&client, &url, &every_cycle).await;
    let (running, id) = places_held_until_cancelled(&client, &url, every_cycle).await;

    // Listed newest first without results, filtered by status; DELETE forgets an ended fit.
    let listed = get_json(&client, &url).await;
    let ids: Vec<&str> = listed
        .as_array()
        .expect("a list")
        .iter()
        .filter_map(|c| c["id"].as_str())
        .collect();
    assert_eq!(ids.first().copied(), Some(id.as_str()), "{listed}");
    assert_eq!(ids.len(), 3, "{listed}");
    assert!(listed[0].get("result").is_none(), "{listed}");
    let cancelled = get_json(&client, &format!("{url}?status=cancelled")).await;
    assert_eq!(cancelled.as_array().map(Vec::len), Some(2), "{cancelled}");
    for id in running.iter().chain([&id]) {
        let (code, _) = delete(&client, &format!("{url}/{id}")).await;
        assert_eq!(code, 204);
        let response = client.get(format!("{url}/{id}")).send().await.expect("GET");
        assert_eq!(response.status(), 404);
    }
}

/// Fits past the bounds are refused before they start, at the field at fault and naming
/// the flag that sets the bound: too many cycles, too many cell-cycles (`every_cycle`, a
/// scene that solves every cycle), too fine a grid, a column twice, too many rows.
async fn refused_up_front(client: &reqwest::Client, url: &str, every_cycle: &Value) {
    let on_2048 = json!({"preset": "dalmau2018-316l", "overrides": {"numerics": {"grid": 2048}}});
    let refusals = [
        (
            "cycles,volume_mm3\n10,0.001\n2000000,0.01\n",
            json!(null),
            "table",
            "test.cycles",
        ),
        (
            "cycles,volume_mm3\n10,0.001\n1000000,0.01\n",
            every_cycle.clone(),
            "table",
            "--calibration-max-cell-cycles",
        ),
        (
            "cycles,volume_mm3\n10,0.001\n3600,0.01\n",
            on_2048,
            "scene.numerics.grid",
            "--calibration-max-grid",
        ),
        (
            "cycles,volume_mm3,cycles\n10,0.001,10\n3600,0.01,3600\n",
            json!(null),
            "table",
            "`cycles` more than once",
        ),
    ];
    for (table, scene, path, words) in refusals {
        let mut request = json!({"kind": "archard", "table": table});
        if !scene.is_null() {
            request["scene"] = scene;
        }
        let error = refused(client, url, &request).await;
        assert_eq!(error["fields"][0]["path"], path, "{error}");
        assert!(
            error["error"].as_str().expect("message").contains(words),
            "{error}"
        );
    }
    let rows: String = (1..=20_001)
        .map(|n| format!("{n},{}\n", 2500 + n % 7))
        .collect();
    let request = json!({"kind": "hardness", "table": format!("cycles,hardness_mpa\n{rows}")});
    let error = refused(client, url, &request).await;
    assert!(
        error["error"]
            .as_str()
            .expect("message")
            .contains("at most 20000")
    );
}

/// Two fits of whole runs (every cycle solved) hold both places, so a third gets 429 until
/// they are cancelled; each stops within a cycle and frees its place. The two cancelled
/// fits' ids, and the id of the fit that then ran to the end.
async fn places_held_until_cancelled(
    client: &reqwest::Client,
    url: &str,
    every_cycle: Value,
) -> (Vec<String>, String) {
    let table3 = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/calibration/table3_wear.csv"),
    )
    .expect("read the wear table");
    let archard = json!({"kind": "archard", "table": table3, "scene": every_cycle});
    let mut running = Vec::new();
    for _ in 0..2 {
        let (code, started) = post(client, url, &archard).await;
        assert_eq!(code, 202, "{started}");
        running.push(started["id"].as_str().expect("id").to_owned());
    }
    let hardness =
        json!({"kind": "hardness", "table": "cycles,hardness_mpa\n10,2551\n60,2727\n300,2842\n"});
    let (code, _) = post(client, url, &hardness).await;
    assert_eq!(code, 429, "both places are taken");
    for id in &running {
        let (code, cancelled) = delete(client, &format!("{url}/{id}")).await;
        assert_eq!(code, 202, "{cancelled}");
        assert_eq!(cancelled["status"], "cancelled");
    }
    // Each run stops within a cycle, and its place frees then.
    let fit = loop {
        let (code, fit) = post(client, url, &hardness).await;
        if code == 202 {
            break fit;
        }
        assert_eq!(code, 429, "{fit}");
        tokio::time::sleep(Duration::from_millis(50)).await;
    };
    let id = fit["id"].as_str().expect("id").to_owned();
    wait_for(client, &format!("{url}/{id}"), |c| {
        c["status"] == "succeeded"
    })
    .await;

    (running, id)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_ocp_trace_over_http_fits_the_repassivation_time_as_tribosim_calibrate() {
    let dir = TempDir::new("calibration-ocp-http");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let table_path = root.join("docs/calibration/paper_ocp_trace.csv");
    let server = ServerProcess::start(&dir.path().join("data"));
    let client = reqwest::Client::new();
    let url = server.url("/api/v1/calibrations");
    let table = std::fs::read_to_string(&table_path).expect("read the table");
    let options = json!({"rubbing_start_s": 3600, "rubbing_stop_s": 7200});
    let request = json!({"kind": "ocp", "table": table, "options": options});
    let cli = [
        "calibrate",
        "ocp",
        table_path.to_str().expect("path"),
        "--rubbing-start",
        "3600",
        "--rubbing-stop",
        "7200",
    ];
    let fit = same_fit_as_the_cli(&dir, &cli, &request, &server).await;
    assert_eq!(fit["parameter"], "repassivation_time_s");

    // Refused before any run: a rubbing time on another fit (the option named), a stop
    // without its start (the table's field).
    let error = refused(
        &client,
        &url,
        &json!({"kind": "tafel", "table": table, "options": {"rubbing_start_s": 3600}}),
    )
    .await;
    assert_eq!(
        error["fields"][0]["path"], "options.rubbing_start_s",
        "{error}"
    );
    let error = refused(
        &client,
        &url,
        &json!({"kind": "ocp", "table": table, "options": {"rubbing_stop_s": 7200}}),
    )
    .await;
    assert!(
        error["error"]
            .as_str()
            .is_some_and(|m| m.contains("rubbing start")),
        "{error}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_tafel_domains_bounds_are_options_over_http_and_on_the_command_line() {
    let dir = TempDir::new("calibration-tafel-domain");
    // Table 2's line, E_corr -0.10 V, 1 to 1000 mV below it, no noise.
    let mut table = String::from("potential_v,current_density_a_cm2\n");
    for k in 1..=1000 {
        let eta = -1e-3 * f64::from(k);
        let current = -(10f64.powf((-3.31 - eta) / 0.56));
        table.push_str(&format!("{},{current:e}\n", -0.10 + eta));
    }
    let path = dir.path().join("curve.csv");
    std::fs::write(&path, &table).expect("write the table");
    let server = ServerProcess::start(&dir.path().join("data"));
    let options = json!({"e_corr_v": -0.10, "tafel_overpotential_max_v": -0.2,
        "tafel_overpotential_min_v": -0.8});
    let request = json!({"kind": "tafel", "table": table, "options": options});
    let cli = [
        "calibrate",
        "tafel",
        path.to_str().expect("path"),
        "--e-corr",
        "-0.10",
        "--tafel-overpotential-max",
        "-0.2",
        "--tafel-overpotential-min",
        "-0.8",
    ];
    let fit = same_fit_as_the_cli(&dir, &cli, &request, &server).await;
    // 200 to 800 mV below E_corr, 1 mV apart, both ends included.
    assert_eq!(fit["domain"]["points"], 601, "{}", fit["domain"]);
    assert_eq!(fit["domain"]["given"], true);
    // A bound in mV is refused at its option, naming the slip.
    let client = reqwest::Client::new();
    let url = server.url("/api/v1/calibrations");
    let slip = json!({"kind": "tafel", "table": table,
        "options": {"e_corr_v": -0.10, "tafel_overpotential_max_v": -150}});
    let error = refused(&client, &url, &slip).await;
    assert_eq!(
        error["fields"][0]["path"], "options.tafel_overpotential_max_v",
        "{error}"
    );
    assert!(
        error["fields"][0]["message"]
            .as_str()
            .is_some_and(|m| m.contains("was it in mV?")),
        "{error}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_ended_calibration_survives_a_restart_and_its_delete_does_too() {
    let dir = TempDir::new("calibration-restart");
    let data = dir.path().join("data");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let table = std::fs::read_to_string(root.join("docs/calibration/table3_hardness.csv"))
        .expect("read the table");
    let client = reqwest::Client::new();
    let (kept, deleted) = {
        let mut server = ServerProcess::start(&data);
        let url = server.url("/api/v1/calibrations");
        let mut fits = Vec::new();
        for _ in 0..2 {
            let (code, started) =
                post(&client, &url, &json!({"kind": "hardness", "table": table})).await;
            assert_eq!(code, 202, "{started}");
            let id = started["id"].as_str().expect("id").to_owned();
            let fit = wait_for(&client, &format!("{url}/{id}"), |c| {
                c["status"] != "running"
            })
            .await;
            assert_eq!(fit["status"], "succeeded", "{fit}");
            fits.push(fit);
        }
        let gone = fits[1]["id"].as_str().expect("id").to_owned();
        let (code, _) = delete(&client, &format!("{url}/{gone}")).await;
        assert_eq!(code, 204);
        // No orderly shutdown: the record was written when the fit ended.
        server.kill_9();
        (fits.swap_remove(0), gone)
    };
    let server = ServerProcess::start(&data);
    let url = server.url("/api/v1/calibrations");
    let id = kept["id"].as_str().expect("id");
    let again = get_json(&client, &format!("{url}/{id}")).await;
    assert_eq!(
        again, kept,
        "the same record, result and all, after the restart"
    );
    let (code, _) = delete(&client, &format!("{url}/{deleted}")).await;
    assert_eq!(code, 404, "a deleted fit stays deleted");
    let listed = get_json(&client, &url).await;
    println!("{listed}");
    assert!(listed.to_string().contains(id), "{listed}");
}
