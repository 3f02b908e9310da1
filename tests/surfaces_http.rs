//! Height maps uploaded to the real `tribosim serve` binary: each of the three formats
//! read, listed, read back and deleted; refusals naming the problem (422) or the limit
//! (413); a scene naming a stored surface runs and its result carries the map's statistics;
//! an unknown id is refused at `disc.surface.id`; a surface in use cannot be deleted; stored
//! surfaces survive a kill -9, and a damaged one is quarantined rather than served; a
//! cancelled measured run's partial result carries the surface's statistics too.

#[path = "surfaces/bounds.rs"]
mod bounds;
mod common;

use std::path::Path;

use serde_json::{Value, json};

use common::process::ServerProcess;
use common::{TempDir, busy_scene, get_json, is_final, small_scene, submit, wait_for_job};

/// Pixels of the test map.
const NX: usize = 32;
const NY: usize = 24;
/// Its pixel, m: 4 um, the cell of `small_scene`'s grid (64 cells over 256 um).
const PIXEL_M: f64 = 4e-6;

/// Heights in m: a few wavelengths of about 0.1 um.
fn heights() -> Vec<f64> {
    (0..NX * NY)
        .map(|i| {
            let (x, y) = ((i % NX) as f64, (i / NX) as f64);
            1e-7 * ((0.9 * x).sin() + (0.7 * y + 0.3 * x).cos())
        })
        .collect()
}

/// The map as Gwyddion writes a `.gsf`: magic line, header, NUL padding to a multiple of 4,
/// f32 heights.
fn gsf() -> Vec<u8> {
    gsf_of(NX, NY, PIXEL_M, &heights())
}

/// A `.gsf` of `nx` x `ny` `heights` on pixels of `pixel_m`.
fn gsf_of(nx: usize, ny: usize, pixel_m: f64, heights: &[f64]) -> Vec<u8> {
    let mut bytes = b"Gwyddion Simple Field 1.0\n".to_vec();
    let header = format!(
        "XRes = {nx}\nYRes = {ny}\nXReal = {:e}\nYReal = {:e}\nXYUnits = m\nZUnits = m\n",
        nx as f64 * pixel_m,
        ny as f64 * pixel_m
    );
    bytes.extend_from_slice(header.as_bytes());
    let padding = 4 - bytes.len() % 4;
    bytes.extend(std::iter::repeat_n(0u8, padding));
    for h in heights {
        bytes.extend_from_slice(&(*h as f32).to_le_bytes());
    }
    bytes
}

fn matrix() -> String {
    let rows: Vec<String> = heights()
        .chunks(NX)
        .map(|row| {
            let cells: Vec<String> = row.iter().map(|h| format!("{h:e}")).collect();
            cells.join("\t")
        })
        .collect();
    format!("# heights in m\n{}\n", rows.join("\n"))
}

fn xyz() -> String {
    heights()
        .iter()
        .enumerate()
        .map(|(i, h)| {
            let (x, y) = ((i % NX) as f64 * PIXEL_M, (i / NX) as f64 * PIXEL_M);
            format!("{x:e} {y:e} {h:e}\n")
        })
        .collect()
}

/// POST a map; the status and the JSON body.
async fn upload(
    client: &reqwest::Client,
    base: &str,
    query: &str,
    content_type: &str,
    body: Vec<u8>,
) -> (u16, Value) {
    let response = client
        .post(format!("{base}/api/v1/surfaces{query}"))
        .header("content-type", content_type)
        .body(body)
        .send()
        .await
        .expect("POST surface");
    let status = response.status().as_u16();
    (status, response.json().await.expect("JSON body"))
}

fn rms_height(answer: &Value) -> f64 {
    answer["statistics"]["rms_height_um"]
        .as_f64()
        .expect("rms height")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn each_format_is_read_listed_and_deleted_and_bad_maps_are_named() {
    let dir = TempDir::new("surfaces");
    let client = reqwest::Client::new();
    let server = ServerProcess::start(dir.path());
    let base = server.base.clone();
    let [from_gsf, from_matrix, from_xyz] = uploaded_in_each_format(&client, &base).await;
    listed_fetched_and_deleted(
        &client,
        &base,
        dir.path(),
        [&from_gsf, &from_matrix, &from_xyz],
    )
    .await;
    bad_maps_named(&client, &base).await;
    too_big_refused(&client, &base).await;
    let listed = get_json(&client, &format!("{base}/api/v1/surfaces")).await;
    assert_eq!(listed, json!([from_gsf, from_matrix]));
}

/// The same heights uploaded as .gsf, as a text matrix (named, its pixel in the query) and
/// as x y z columns: each read with its format's pixel, the same statistics.
async fn uploaded_in_each_format(client: &reqwest::Client, base: &str) -> [Value; 3] {
    let (status, from_gsf) = upload(client, base, "", "application/octet-stream", gsf()).await;
    assert_eq!(status, 201, "{from_gsf}");
    let query = "?pixel_um=4&name=matrix%20map";
    let (status, from_matrix) = upload(
        client,
        base,
        query,
        "application/octet-stream",
        matrix().into(),
    )
    .await;
    assert_eq!(status, 201, "{from_matrix}");
    let (status, from_xyz) =
        upload(client, base, "", "application/octet-stream", xyz().into()).await;
    assert_eq!(status, 201, "{from_xyz}");
    for (answer, format) in [
        (&from_gsf, "gsf"),
        (&from_matrix, "matrix"),
        (&from_xyz, "xyz"),
    ] {
        assert_eq!(answer["format"], format, "{answer}");
        assert_eq!(
            (answer["nx"].clone(), answer["ny"].clone()),
            (json!(NX), json!(NY))
        );
        // The pixel as each format carries it: XReal / XRes, the query's, or the spacing
        // of coordinates printed to 6 decimals ({:e}), so within 1e-6 of 4 um.
        for key in ["pixel_x_um", "pixel_y_um"] {
            let pixel = answer[key].as_f64().expect("pixel");
            assert!((pixel / 4.0 - 1.0).abs() < 1e-6, "{key} {pixel}");
        }
        let stats = &answer["statistics"];
        for key in ["rms_height_um", "rms_slope", "psd_slope"] {
            assert!(stats[key].as_f64().is_some_and(f64::is_finite), "{stats}");
        }
    }
    assert_eq!(from_matrix["name"], "matrix map");
    // The same heights: the text formats exactly, the .gsf's f32 to 6e-8 of each height.
    assert_eq!(
        from_matrix["statistics"]["rms_height_um"],
        from_xyz["statistics"]["rms_height_um"]
    );
    assert!((rms_height(&from_gsf) / rms_height(&from_matrix) - 1.0).abs() < 1e-7);

    [from_gsf, from_matrix, from_xyz]
}

/// The three uploads are listed in order and each read back; the last deleted, with its
/// directory, then 404 to a read and a delete; a malformed id gets 400.
async fn listed_fetched_and_deleted(
    client: &reqwest::Client,
    base: &str,
    data_dir: &Path,
    [from_gsf, from_matrix, from_xyz]: [&Value; 3],
) {
    let listed = get_json(client, &format!("{base}/api/v1/surfaces")).await;
    assert_eq!(listed, json!([from_gsf, from_matrix, from_xyz]));
    let id = from_xyz["id"].as_str().expect("id");
    let url = format!("{base}/api/v1/surfaces/{id}");
    assert_eq!(&get_json(client, &url).await, from_xyz);
    let deleted = client.delete(&url).send().await.expect("DELETE");
    assert_eq!(deleted.status(), 204);
    assert!(!data_dir.join("surfaces").join(id).exists());
    for response in [
        client.get(&url).send().await.expect("GET"),
        client.delete(&url).send().await.expect("DELETE"),
    ] {
        assert_eq!(response.status(), 404);
    }
    let malformed = client
        .get(format!("{base}/api/v1/surfaces/not-a-uuid"))
        .send()
        .await
        .expect("GET");
    assert_eq!(malformed.status(), 400);
}

/// Refusals name the problem and where it is; nothing refused is stored.
async fn bad_maps_named(client: &reqwest::Client, base: &str) {
    let flat = format!("{}\n", vec![vec!["0"; 16].join(" "); 16].join("\n"));
    let refusals: [(&str, &str, Vec<u8>, &str, &str); 6] = [
        (
            "?pixel_um=1",
            "application/octet-stream",
            flat.into(),
            "body",
            "psd_slope is NaN",
        ),
        (
            "?pixel_um=1",
            "application/octet-stream",
            b"1e-7 2e-7\n3e-7 NaN\n".to_vec(),
            "body",
            "column 1, row 1",
        ),
        (
            "?pixel_um=1",
            "application/octet-stream",
            b"0 0 0\n0 0\n".to_vec(),
            "body",
            "line 2",
        ),
        (
            "?format=matrix",
            "application/octet-stream",
            b"0 0\n0 0\n".to_vec(),
            "pixel_um",
            "pixel size",
        ),
        (
            "?pixel_um=-1",
            "application/octet-stream",
            b"0 0\n0 0\n".to_vec(),
            "pixel_um",
            "\"-1\"",
        ),
        (
            "",
            "application/octet-stream",
            b"\x89PNG\r\n\x1a\n".to_vec(),
            "body",
            ".gsf",
        ),
    ];
    for (query, content_type, body, path, words) in refusals {
        let (status, answer) = upload(client, base, query, content_type, body).await;
        assert_eq!(status, 422, "{answer}");
        assert_eq!(answer["fields"][0]["path"], path, "{answer}");
        let message = answer["error"].as_str().expect("message");
        assert!(message.contains(words), "{message}");
    }
    let (status, _) = upload(client, base, "", "application/json", xyz().into()).await;
    assert_eq!(status, 415);
}

/// Too big: more pixels per side than the reader takes, or more bytes than the body limit.
async fn too_big_refused(client: &reqwest::Client, base: &str) {
    let wide = format!("{}\n{0}\n", vec!["0"; 4097].join(" "));
    let (status, answer) = upload(
        client,
        base,
        "?pixel_um=1",
        "application/octet-stream",
        wide.into(),
    )
    .await;
    assert_eq!(status, 413, "{answer}");
    assert!(answer["error"].as_str().expect("message").contains("4096"));
    let huge = vec![b'0'; (64 << 20) + 1];
    let (status, answer) = upload(
        client,
        base,
        "?pixel_um=1",
        "application/octet-stream",
        huge,
    )
    .await;
    assert_eq!(status, 413, "{answer}");
    let message = answer["error"].as_str().expect("message");
    assert!(message.contains(&(64u64 << 20).to_string()), "{message}");
}

/// `small_scene` on the surface `id`, without the plastic cap (docs/scene.md's rough example).
/// A map of white noise (a linear congruential generator, Knuth's MMIX constants), 64
/// pixels a side, 0.1 um high, as a matrix in m.
fn noise_matrix() -> String {
    let mut state = 7_u64;
    let rows: Vec<String> = (0..64)
        .map(|_| {
            let cells: Vec<String> = (0..64)
                .map(|_| {
                    state = state
                        .wrapping_mul(6_364_136_223_846_793_005)
                        .wrapping_add(1_442_695_040_888_963_407);
                    format!(
                        "{:e}",
                        ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 1e-7
                    )
                })
                .collect();
            cells.join(" ")
        })
        .collect();
    rows.join("\n")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_map_of_noise_is_kept_with_a_warning_that_names_its_hurst_exponent() {
    let dir = TempDir::new("surfaces-noise");
    let client = reqwest::Client::new();
    let server = ServerProcess::start(dir.path());
    let (status, answer) = upload(
        &client,
        &server.base,
        "?pixel_um=2",
        "application/octet-stream",
        noise_matrix().into(),
    )
    .await;
    assert_eq!(status, 201, "{answer}");
    let hurst = answer["statistics"]["hurst"].as_f64().expect("hurst");
    assert!(hurst < 0.0, "white noise: {answer}");
    let warnings = answer["warnings"].as_array().expect("warnings");
    assert!(
        warnings.len() == 1
            && warnings[0]
                .as_str()
                .is_some_and(|w| w.starts_with("statistics.hurst")),
        "{answer}"
    );
    let id = answer["id"].as_str().expect("id");
    let listed = get_json(&client, &format!("{}/api/v1/surfaces/{id}", server.base)).await;
    assert_eq!(
        listed["warnings"], answer["warnings"],
        "kept with the record"
    );
}

fn measured_scene(id: &str, cycles: u64) -> Value {
    let mut scene = small_scene(cycles);
    scene["overrides"]["disc"] = json!({"surface": {"kind": "measured", "id": id}});
    scene["overrides"]["wear"] = json!({"plasticity": "off"});
    scene
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_measured_scene_runs_on_its_stored_surface_which_survives_a_restart() {
    let dir = TempDir::new("surface-runs");
    let client = reqwest::Client::new();
    let mut server = ServerProcess::start(dir.path());
    let base = server.base.clone();
    let (status, surface) =
        upload(&client, &base, "", "application/octet-stream", xyz().into()).await;
    assert_eq!(status, 201, "{surface}");
    let id = surface["id"].as_str().expect("id").to_owned();
    let (status, spare) = upload(
        &client,
        &base,
        "?pixel_um=4",
        "application/octet-stream",
        matrix().into(),
    )
    .await;
    assert_eq!(status, 201, "{spare}");

    unknown_surface_refused(&client, &base).await;
    study_on_surface(&client, &base, &id).await;
    kept_while_a_job_waits(&client, &base, &id, &surface).await;

    // Kept across a kill -9; a surface whose heights were changed on disk is quarantined.
    server.kill_9();
    let spare_id = spare["id"].as_str().expect("id");
    let heights = dir
        .path()
        .join("surfaces")
        .join(spare_id)
        .join("heights.f64");
    let mut bytes = std::fs::read(&heights).expect("heights");
    bytes[40] ^= 0x10;
    std::fs::write(&heights, bytes).expect("damage");
    let server = ServerProcess::start(dir.path());
    let base = server.base.clone();
    let surface_url = format!("{base}/api/v1/surfaces/{id}");
    assert_eq!(get_json(&client, &surface_url).await, surface);
    let listed = get_json(&client, &format!("{base}/api/v1/surfaces")).await;
    assert_eq!(listed, json!([surface]));
    let quarantined = std::fs::read_dir(dir.path().join("quarantine"))
        .expect("quarantine")
        .filter_map(Result::ok)
        .any(|entry| entry.file_name().to_string_lossy().starts_with(spare_id));
    assert!(quarantined, "the damaged surface was not quarantined");
    let again = submit(&client, &base, &measured_scene(&id, 2)).await;
    let again_id = again["id"].as_str().expect("id");
    let done = wait_for_job(&client, &base, again_id, is_final).await;
    assert_eq!(done["status"], "succeeded", "{done}");

    // No job waits for it now: deleted.
    let deleted = client.delete(&surface_url).send().await.expect("DELETE");
    assert_eq!(deleted.status(), 204);
    assert!(!dir.path().join("surfaces").join(&id).exists());
}

/// A study of `scene` at two loads.
fn two_loads(scene: &Value) -> Value {
    json!({"base": scene, "axes": {"test.load_n": [2, 5]}})
}

/// An unknown surface id is refused at the field that names it, for a job and a study alike.
async fn unknown_surface_refused(client: &reqwest::Client, base: &str) {
    let unknown = measured_scene("6b0a2f64-1d7e-4c3a-9f1e-2b8d5c4a7e90", 3);
    let response = client
        .post(format!("{base}/api/v1/jobs"))
        .json(&unknown)
        .send()
        .await
        .expect("POST job");
    assert_eq!(response.status(), 422);
    let answer: Value = response.json().await.expect("JSON");
    assert_eq!(answer["fields"][0]["path"], "disc.surface.id", "{answer}");

    let response = client
        .post(format!("{base}/api/v1/studies"))
        .json(&two_loads(&unknown))
        .send()
        .await
        .expect("POST study");
    assert_eq!(response.status(), 422);
    let answer: Value = response.json().await.expect("JSON");
    assert_eq!(
        answer["fields"][0]["path"], "base.disc.surface.id",
        "{answer}"
    );
}

/// A study on the stored surface: every member succeeds.
async fn study_on_surface(client: &reqwest::Client, base: &str, id: &str) {
    let study = two_loads(&measured_scene(id, 2));
    let response = client
        .post(format!("{base}/api/v1/studies"))
        .json(&study)
        .send()
        .await
        .expect("POST study");
    assert_eq!(response.status(), 201);
    let members: Value = response.json().await.expect("JSON");
    for member in members["members"].as_array().expect("members") {
        let member_id = member["job_id"].as_str().expect("job id");
        let done = wait_for_job(client, base, member_id, is_final).await;
        assert_eq!(done["status"], "succeeded", "{done}");
    }
}

/// The one worker busy, a measured job waits, and its surface cannot be deleted (the
/// refusal names the job); once it runs, it reads the stored map to the bit.
async fn kept_while_a_job_waits(client: &reqwest::Client, base: &str, id: &str, surface: &Value) {
    let busy = submit(client, base, &busy_scene()).await;
    let busy_id = busy["id"].as_str().expect("id");
    let job = submit(client, base, &measured_scene(id, 3)).await;
    let job_id = job["id"].as_str().expect("id").to_owned();
    let surface_url = format!("{base}/api/v1/surfaces/{id}");
    let refused = client.delete(&surface_url).send().await.expect("DELETE");
    assert_eq!(refused.status(), 409);
    let answer: Value = refused.json().await.expect("JSON");
    assert!(answer["error"].as_str().expect("message").contains(&job_id));
    let cancelled = client
        .delete(format!("{base}/api/v1/jobs/{busy_id}"))
        .send()
        .await
        .expect("cancel");
    assert!(cancelled.status().is_success());

    let done = wait_for_job(client, base, &job_id, is_final).await;
    assert_eq!(done["status"], "succeeded", "{done}");
    let result = get_json(client, &format!("{base}/api/v1/jobs/{job_id}/result")).await;
    // The run reads the stored map exactly: its statistics are the upload's, to the bit.
    assert_eq!(
        result["surface"]["measured"], surface["statistics"],
        "{result}"
    );
    assert!(
        result["surface"]["on_grid"]["rms_height_um"]
            .as_f64()
            .is_some()
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_stopped_measured_run_keeps_its_surface_statistics_in_the_partial_result() {
    let dir = TempDir::new("surface-partial");
    let client = reqwest::Client::new();
    let mut server = ServerProcess::start(dir.path());
    let base = server.base.clone();
    let (status, surface) =
        upload(&client, &base, "", "application/octet-stream", xyz().into()).await;
    assert_eq!(status, 201, "{surface}");
    let id = surface["id"].as_str().expect("id");
    // Every cycle solved, and far more cycles than the test waits for: still running when
    // cancelled.
    let mut scene = measured_scene(id, 300_000);
    scene["overrides"]["numerics"]["cycle_step"] = json!(1);
    let job = submit(&client, &base, &scene).await;
    let job_id = job["id"].as_str().expect("id").to_owned();
    wait_for_job(&client, &base, &job_id, |job| {
        job["cycles_done"].as_u64() >= Some(3)
    })
    .await;
    let job_url = format!("{base}/api/v1/jobs/{job_id}");
    let response = client.delete(&job_url).send().await.expect("DELETE");
    assert_eq!(response.status(), 202);
    let job = wait_for_job(&client, &base, &job_id, is_final).await;
    assert_eq!(job["status"], "cancelled", "{job}");

    let partial = get_json(&client, &format!("{job_url}/result")).await;
    assert_eq!(partial["complete"], false, "{partial}");
    let cycles = partial["cycles"].as_array().expect("cycles");
    assert_eq!(
        cycles.len() as u64,
        job["cycles_done"].as_u64().expect("done")
    );
    // The partial result describes the surface as the full one does: the upload's
    // statistics to the bit, and the map on the grid.
    assert!(surface["statistics"]["rms_height_um"].as_f64().is_some());
    assert_eq!(
        partial["surface"]["measured"], surface["statistics"],
        "{partial}"
    );
    assert!(
        partial["surface"]["on_grid"]["rms_height_um"]
            .as_f64()
            .is_some(),
        "{partial}"
    );

    server.kill_9();
    let server = ServerProcess::start(dir.path());
    let again = get_json(
        &client,
        &server.url(&format!("/api/v1/jobs/{job_id}/result")),
    )
    .await;
    assert_eq!(again, partial);
}
