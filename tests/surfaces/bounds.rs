//! The uploads' bounds and the height units of text maps.

use super::*;

/// A 20 x 20 text matrix of heights, m.
fn small_matrix() -> Vec<u8> {
    let rows: Vec<String> = (0..20)
        .map(|y| {
            let cells: Vec<String> = (0..20)
                .map(|x| {
                    format!(
                        "{:e}",
                        1e-7 * ((0.9 * x as f64).sin() + (0.7 * y as f64).cos())
                    )
                })
                .collect();
            cells.join(" ")
        })
        .collect();
    (rows.join("\n") + "\n").into_bytes()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn uploads_are_bounded_before_they_are_read_and_every_accepted_map_reads_back() {
    let dir = TempDir::new("surface-budget");
    let client = reqwest::Client::new();
    let flags = ["--max-surface-pixels", "500", "--surface-parses", "1"];
    let mut command = common::process::serve_command(dir.path(), 1);
    command.args(flags);
    let mut server = ServerProcess::spawn(command);
    let base = server.base.clone();
    over_the_limits_refused(&client, &base).await;
    let accepted = accepted_one_read_at_a_time(&client, &base).await;

    // Every map accepted reads back the same after a crash.
    server.kill_9();
    let mut command = common::process::serve_command(dir.path(), 1);
    command.args(flags);
    let server = ServerProcess::spawn(command);
    for surface in &accepted {
        let record: Value = serde_json::from_str(surface).expect("JSON");
        let id = record["id"].as_str().expect("id");
        let url = server.url(&format!("/api/v1/surfaces/{id}"));
        let text = client
            .get(url)
            .send()
            .await
            .expect("GET")
            .text()
            .await
            .expect("text");
        assert_eq!(&text, surface);
    }
}

/// Declared over the limit (32 x 24 = 768 pixels): 413 naming the flag, before reading;
/// pixel sizes whose statistics JSON could not hold: refused, not lost at the next start.
async fn over_the_limits_refused(client: &reqwest::Client, base: &str) {
    let (status, answer) = upload(client, base, "", "application/octet-stream", gsf()).await;
    assert_eq!(status, 413, "{answer}");
    assert!(
        answer["error"]
            .as_str()
            .expect("message")
            .contains("--max-surface-pixels")
    );
    let (status, answer) = upload(
        client,
        base,
        "?pixel_um=1e308",
        "application/octet-stream",
        small_matrix(),
    )
    .await;
    assert_eq!(status, 422, "{answer}");
    assert_eq!(answer["fields"][0]["path"], "pixel_um", "{answer}");
    let absurd = gsf_of(20, 20, 1e306, &heights()[..400]);
    let (status, answer) = upload(client, base, "", "application/octet-stream", absurd).await;
    assert_eq!(status, 422, "{answer}");
    assert!(
        answer["error"]
            .as_str()
            .expect("message")
            .contains("pixel's side")
    );
}

/// One upload being read holds the only place: the next gets 429 with Retry-After before
/// its body is read. The uploads accepted meanwhile, and one more once the slow one is
/// gone, as their answers' text.
async fn accepted_one_read_at_a_time(client: &reqwest::Client, base: &str) -> Vec<String> {
    use std::io::Write;

    // The slow upload may reach the server after the next one: then it is the one refused,
    // and it is sent again.
    let address = base.trim_start_matches("http://").to_owned();
    let open_slow = || {
        let mut slow = std::net::TcpStream::connect(&address).expect("connect");
        let head = format!(
            "POST /api/v1/surfaces?pixel_um=4 HTTP/1.1\r\nHost: {address}\r\n\
             Content-Type: application/octet-stream\r\nContent-Length: 100000\r\n\r\n0"
        );
        slow.write_all(head.as_bytes()).expect("send the head");
        slow.set_nonblocking(true).expect("non-blocking");
        slow
    };
    let mut slow = open_slow();
    let mut accepted = Vec::new();
    let mut refused = None;
    for _ in 0..200 {
        let response = client
            .post(format!("{base}/api/v1/surfaces?pixel_um=4"))
            .header("content-type", "application/octet-stream")
            .body(small_matrix())
            .send()
            .await
            .expect("POST surface");
        if response.status() == 429 {
            refused = response.headers().get("retry-after").cloned();
            break;
        }
        assert_eq!(response.status(), 201);
        accepted.push(response.text().await.expect("the answer"));
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
        let mut answered = [0u8; 16];
        if std::io::Read::read(&mut slow, &mut answered).is_ok() {
            slow = open_slow();
        }
    }
    assert!(
        refused.is_some(),
        "a second upload while one is read gets 429 with Retry-After"
    );
    drop(slow);
    let answer = loop {
        let response = client
            .post(format!("{base}/api/v1/surfaces?pixel_um=4"))
            .header("content-type", "application/octet-stream")
            .body(small_matrix())
            .send()
            .await
            .expect("POST surface");
        if response.status() != 429 {
            assert_eq!(response.status(), 201);
            break response.text().await.expect("the answer");
        }
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    };
    accepted.push(answer);
    accepted
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn heights_in_um_or_nm_are_read_in_their_unit() {
    let dir = TempDir::new("surface-units");
    let client = reqwest::Client::new();
    let server = ServerProcess::start(dir.path());
    let base = server.base.clone();
    let (status, in_m) = upload(
        &client,
        &base,
        "?pixel_um=4",
        "application/octet-stream",
        matrix().into(),
    )
    .await;
    assert_eq!(status, 201, "{in_m}");
    let in_nm: String = matrix()
        .lines()
        .skip(1)
        .map(|row| {
            let cells: Vec<String> = row
                .split('\t')
                .map(|h| format!("{:e}", h.parse::<f64>().expect("a height") * 1e9))
                .collect();
            cells.join("\t") + "\n"
        })
        .collect();
    let query = "?pixel_um=4&height_unit=nm";
    let (status, from_nm) = upload(
        &client,
        &base,
        query,
        "application/octet-stream",
        in_nm.clone().into(),
    )
    .await;
    assert_eq!(status, 201, "{from_nm}");
    // The same heights in nm sent as m: refused at the upload, with the unit to pass.
    let (status, answer) = upload(
        &client,
        &base,
        "?pixel_um=4",
        "application/octet-stream",
        in_nm.into(),
    )
    .await;
    assert_eq!(status, 422, "{answer}");
    assert_eq!(answer["fields"][0]["path"], "height_unit", "{answer}");
    let message = answer["fields"][0]["message"].as_str().unwrap_or_default();
    assert!(message.contains("pass height_unit=um (or nm)"), "{answer}");
    // Two roundings of each height (times 1e9, then 1e-9) and the statistics' sums: far
    // within 1e-12 of the rms.
    assert!((rms_height(&from_nm) / rms_height(&in_m) - 1.0).abs() < 1e-12);
    for (query, body) in [
        ("?pixel_um=4&height_unit=ft", matrix().into_bytes()),
        ("?height_unit=um", gsf()),
    ] {
        let (status, answer) =
            upload(&client, &base, query, "application/octet-stream", body).await;
        assert_eq!(status, 422, "{answer}");
        assert_eq!(answer["fields"][0]["path"], "height_unit", "{answer}");
    }
}
