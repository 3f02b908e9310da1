//! A server without a token serves only its own origin: a request under
//! another host name (DNS rebinding) gets 421, a change sent by a page of another origin
//! gets 403, a height map in a type a page may send cross-site unasked gets 415, and none of
//! them stores or deletes anything; `--allowed-host` and `--cors-origin` widen what is
//! served, and a token turns the checks off. Every answer has the security headers.
//! The same attacks from a real browser are `tests/e2e/steps/origin.mjs`.

mod common;

use reqwest::{Client, Method, Response};
use serde_json::{Value, json};

use common::{Server, TempDir, args, expect_client_error, get_json, small_scene, submit};

/// The page's content policy, as every answer but a report's carries it.
const PAGE_POLICY: &str = "default-src 'self'; script-src 'self'; style-src 'self'; \
     img-src 'self' data:; connect-src 'self'; object-src 'none'; base-uri 'none'; \
     form-action 'self'; frame-ancestors 'none'";

/// A small height map as a text matrix of heights in m (16 x 16, give `pixel_um`).
fn matrix() -> Vec<u8> {
    let mut text = String::new();
    for y in 0..16 {
        let row: Vec<String> = (0..16)
            .map(|x| {
                format!(
                    "{:e}",
                    1e-7 * (0.9 * f64::from(x)).sin() * (0.7 * f64::from(y)).cos()
                )
            })
            .collect();
        text.push_str(&row.join(" "));
        text.push('\n');
    }
    text.into_bytes()
}

/// `host:port` of a server's base URL.
fn authority(server: &Server) -> String {
    server.base.trim_start_matches("http://").to_owned()
}

/// A request to `path` with the given headers; the answer.
async fn send(
    client: &Client,
    server: &Server,
    method: Method,
    path: &str,
    headers: &[(&str, &str)],
    body: Option<(&str, Vec<u8>)>,
) -> Response {
    let mut request = client.request(method, server.url(path));
    for &(name, value) in headers {
        request = request.header(name, value);
    }
    if let Some((content_type, bytes)) = body {
        request = request.header("content-type", content_type).body(bytes);
    }
    request.send().await.expect("request")
}

/// Uploads [`matrix`] as bytes, with `headers`; the answer.
async fn upload(client: &Client, server: &Server, headers: &[(&str, &str)]) -> Response {
    let body = Some(("application/octet-stream", matrix()));
    send(
        client,
        server,
        Method::POST,
        "/api/v1/surfaces?pixel_um=1",
        headers,
        body,
    )
    .await
}

/// How many records the list at `path` holds.
async fn count(client: &Client, server: &Server, path: &str) -> usize {
    let list = get_json(client, &server.url(path)).await;
    list.as_array().expect("a list").len()
}

/// Asserts the security headers of every answer; the page's content policy unless `policy`.
fn assert_secured(response: &Response, policy: &str) {
    let headers = response.headers();
    let url = response.url();
    let get = |name: &str| {
        headers
            .get(name)
            .and_then(|v| v.to_str().ok())
            .unwrap_or("")
    };
    assert_eq!(get("content-security-policy"), policy, "{url}");
    assert_eq!(get("x-content-type-options"), "nosniff", "{url}");
    assert_eq!(get("x-frame-options"), "DENY", "{url}");
    assert_eq!(get("referrer-policy"), "no-referrer", "{url}");
    assert_eq!(get("cross-origin-resource-policy"), "same-origin", "{url}");
}

#[tokio::test]
async fn another_host_name_gets_421_and_changes_nothing() {
    let dir = TempDir::new("origin-host");
    let server = Server::start(args(dir.path())).await;
    let client = Client::new();
    let port = authority(&server)
        .rsplit_once(':')
        .expect("port")
        .1
        .to_owned();
    let rebound = format!("rebind.example:{port}");
    let scene = serde_json::to_vec(&small_scene(2)).expect("scene");
    // The names a DNS-rebinding page would use, and a wrong port: every route refused.
    for host in [rebound.as_str(), "127.0.0.1:1", "localhost"] {
        let headers = [("host", host)];
        let body = Some(("application/json", scene.clone()));
        let response = send(
            &client,
            &server,
            Method::POST,
            "/api/v1/jobs",
            &headers,
            body,
        )
        .await;
        assert_secured(&response, PAGE_POLICY);
        let error = expect_client_error(response, 421).await;
        let message = error["error"].as_str().expect("message");
        assert!(message.contains("--allowed-host"), "{message}");
        let response = upload(&client, &server, &headers).await;
        expect_client_error(response, 421).await;
        for path in ["/api/v1/jobs", "/healthz", "/", "/static/js/main.js"] {
            let response = send(&client, &server, Method::GET, path, &headers, None).await;
            expect_client_error(response, 421).await;
        }
    }
    assert_eq!(count(&client, &server, "/api/v1/jobs").await, 0);
    assert_eq!(count(&client, &server, "/api/v1/surfaces").await, 0);
    // The server's own names are served.
    for host in [
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
        authority(&server),
    ] {
        let headers = [("host", host.as_str())];
        let response = send(&client, &server, Method::GET, "/healthz", &headers, None).await;
        assert_eq!(response.status(), 200, "{host}");
    }
    server.stop().await;
}

#[tokio::test]
async fn allowed_hosts_are_served_and_one_that_is_no_host_stops_the_start() {
    let dir = TempDir::new("origin-allowed");
    let mut served = args(dir.path());
    served.allowed_hosts = vec!["tribosim.lab".into(), "proxy.lab:8443".into()];
    let server = Server::start(served).await;
    let client = Client::new();
    // A proxy that forwards its own name, with or without a port.
    for host in ["tribosim.lab", "TRIBOSIM.lab:443", "proxy.lab:8443"] {
        let response = send(
            &client,
            &server,
            Method::GET,
            "/api/v1/jobs",
            &[("host", host)],
            None,
        )
        .await;
        assert_eq!(response.status(), 200, "{host}");
    }
    let response = send(
        &client,
        &server,
        Method::GET,
        "/healthz",
        &[("host", "proxy.lab:1")],
        None,
    )
    .await;
    expect_client_error(response, 421).await;
    // The page served under that name submits runs from its origin.
    let body = Some((
        "application/json",
        serde_json::to_vec(&small_scene(2)).expect("scene"),
    ));
    let headers = [("host", "tribosim.lab"), ("origin", "https://tribosim.lab")];
    let response = send(
        &client,
        &server,
        Method::POST,
        "/api/v1/jobs",
        &headers,
        body,
    )
    .await;
    assert_eq!(response.status(), 202);
    server.stop().await;

    let mut refused = args(dir.path());
    refused.allowed_hosts = vec!["https://tribosim.lab/".into()];
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
        .await
        .expect("bind");
    let error = tribosim::service::serve_on(refused, listener, async {})
        .await
        .expect_err("refused");
    assert!(error.to_string().contains("--allowed-host"), "{error}");
}

#[tokio::test]
async fn a_page_of_another_origin_changes_nothing() {
    let dir = TempDir::new("origin-foreign");
    let server = Server::start(args(dir.path())).await;
    let client = Client::new();
    // What the foreign page will try to change or delete, made by a client without Origin.
    let job = submit(&client, &server.base, &small_scene(2)).await;
    let job_url = format!("/api/v1/jobs/{}", job["id"].as_str().expect("id"));
    let response = upload(&client, &server, &[]).await;
    assert_eq!(response.status(), 201);
    let surface: Value = response.json().await.expect("surface");
    let surface_url = format!("/api/v1/surfaces/{}", surface["id"].as_str().expect("id"));
    let foreign = [
        vec![("origin", "http://127.0.0.1:1")],
        vec![("origin", "http://evil.example")],
        vec![("origin", "null")],
        vec![("sec-fetch-site", "cross-site")],
        vec![("sec-fetch-site", "same-site")],
    ];
    for headers in &foreign {
        every_change_refused(&client, &server, headers, (&job_url, &surface_url)).await;
        expect_client_error(upload(&client, &server, headers).await, 403).await;
    }
    // Nothing was stored, changed or deleted.
    assert_eq!(count(&client, &server, "/api/v1/jobs").await, 1);
    assert_eq!(count(&client, &server, "/api/v1/surfaces").await, 1);
    let kept = get_json(&client, &server.url(&job_url)).await;
    assert_eq!(
        kept["sample"],
        Value::Null,
        "the PATCH changed the labels: {kept}"
    );
    // Reads are answered (the browser keeps them from the page: no CORS headers).
    let response = send(&client, &server, Method::GET, &job_url, &foreign[0], None).await;
    assert_eq!(response.status(), 200);
    assert!(
        response
            .headers()
            .get("access-control-allow-origin")
            .is_none()
    );
    own_page_changes_things(&client, &server, &surface_url).await;
    server.stop().await;
}

/// Every change a foreign page (`headers`) could try, to the job at `job_url` and the
/// surface at `surface_url` or by a new job, is refused with 403 naming `--cors-origin`,
/// with the page's security headers and no CORS header.
async fn every_change_refused(
    client: &Client,
    server: &Server,
    headers: &[(&str, &str)],
    (job_url, surface_url): (&str, &str),
) {
    let scene = serde_json::to_vec(&small_scene(2)).expect("scene");
    let labels = serde_json::to_vec(&json!({"sample": "x"})).expect("labels");
    let tries = [
        (
            Method::POST,
            "/api/v1/jobs",
            Some(("application/json", scene.clone())),
        ),
        (Method::POST, "/api/v1/jobs", Some(("text/plain", scene))),
        (Method::PATCH, job_url, Some(("application/json", labels))),
        (Method::DELETE, job_url, None),
        (Method::DELETE, surface_url, None),
    ];
    for (method, path, body) in tries {
        let response = send(client, server, method.clone(), path, headers, body).await;
        assert_secured(&response, PAGE_POLICY);
        assert!(
            response
                .headers()
                .get("access-control-allow-origin")
                .is_none()
        );
        let error = expect_client_error(response, 403).await;
        let message = error["error"].as_str().expect("message");
        assert!(
            message.contains("--cors-origin"),
            "{method} {path} {headers:?}: {message}"
        );
    }
}

/// The server's own page, under any of its names, changes things.
async fn own_page_changes_things(client: &Client, server: &Server, surface_url: &str) {
    let own = format!("http://{}", authority(server));
    let port = authority(server)
        .rsplit_once(':')
        .expect("port")
        .1
        .to_owned();
    let localhost = format!("http://localhost:{port}");
    for origin in [own.as_str(), localhost.as_str()] {
        let headers = [("origin", origin), ("sec-fetch-site", "same-origin")];
        let response = upload(client, server, &headers).await;
        assert_eq!(response.status(), 201, "{origin}");
    }
    let headers = [("origin", own.as_str())];
    let response = send(client, server, Method::DELETE, surface_url, &headers, None).await;
    assert_eq!(response.status(), 204);
}

#[tokio::test]
async fn a_cors_origin_changes_things_and_reads_the_answers() {
    let dir = TempDir::new("origin-cors");
    let mut served = args(dir.path());
    served.cors_origins = vec!["http://localhost:3000".into()];
    let server = Server::start(served).await;
    let client = Client::new();
    let headers = [
        ("origin", "http://localhost:3000"),
        ("sec-fetch-site", "same-site"),
    ];
    let response = upload(&client, &server, &headers).await;
    assert_eq!(response.status(), 201);
    let allowed = response.headers().get("access-control-allow-origin");
    assert_eq!(
        allowed.and_then(|v| v.to_str().ok()),
        Some("http://localhost:3000")
    );
    assert_secured(&response, PAGE_POLICY);
    // The browser's preflight for the JSON and the header it sends.
    let preflight = [
        ("origin", "http://localhost:3000"),
        ("access-control-request-method", "POST"),
        ("access-control-request-headers", "content-type"),
    ];
    let response = send(
        &client,
        &server,
        Method::OPTIONS,
        "/api/v1/jobs",
        &preflight,
        None,
    )
    .await;
    assert!(response.status().is_success(), "{}", response.status());
    assert_secured(&response, PAGE_POLICY);
    // Another origin still cannot.
    let response = upload(&client, &server, &[("origin", "http://localhost:3001")]).await;
    expect_client_error(response, 403).await;
    assert_eq!(count(&client, &server, "/api/v1/surfaces").await, 1);
    server.stop().await;
}

#[tokio::test]
async fn with_a_token_neither_host_nor_origin_is_checked() {
    let dir = TempDir::new("origin-token");
    let mut served = args(dir.path());
    served.token = Some("s3cret".into());
    let server = Server::start(served).await;
    let client = Client::new();
    let foreign = [("host", "tribosim.lab"), ("origin", "http://evil.example")];
    // The token is what keeps another page out: it cannot send one.
    let response = upload(&client, &server, &foreign).await;
    assert_secured(&response, PAGE_POLICY);
    expect_client_error(response, 401).await;
    let response = send(&client, &server, Method::GET, "/healthz", &foreign, None).await;
    assert_eq!(response.status(), 200);
    let with_token = [foreign[0], foreign[1], ("authorization", "Bearer s3cret")];
    let response = upload(&client, &server, &with_token).await;
    assert_eq!(response.status(), 201);
    server.stop().await;
}

#[tokio::test]
async fn a_height_map_in_a_type_a_page_sends_unasked_is_refused() {
    let dir = TempDir::new("origin-simple");
    let server = Server::start(args(dir.path())).await;
    let client = Client::new();
    let path = "/api/v1/surfaces?pixel_um=1";
    for content_type in [
        "text/plain",
        "text/plain; charset=utf-8",
        "application/x-www-form-urlencoded",
        "multipart/form-data; boundary=x",
    ] {
        let body = Some((content_type, matrix()));
        let response = send(&client, &server, Method::POST, path, &[], body).await;
        let error = expect_client_error(response, 415).await;
        let message = error["error"].as_str().expect("message");
        assert!(message.contains("application/octet-stream"), "{message}");
    }
    let response = client
        .post(server.url(path))
        .body(matrix())
        .send()
        .await
        .expect("POST");
    expect_client_error(response, 415).await;
    assert_eq!(count(&client, &server, "/api/v1/surfaces").await, 0);
    assert_eq!(upload(&client, &server, &[]).await.status(), 201);
    server.stop().await;
}

#[tokio::test]
async fn every_answer_has_the_security_headers() {
    let dir = TempDir::new("origin-headers");
    let server = Server::start(args(dir.path())).await;
    let client = Client::new();
    let job = submit(&client, &server.base, &small_scene(2)).await;
    let id = job["id"].as_str().expect("id").to_owned();
    common::wait_for_job(&client, &server.base, &id, common::is_final).await;
    let paths = [
        "/",
        "/static/js/main.js",
        "/static/page.css",
        "/healthz",
        "/api/v1/openapi.yaml",
        "/api/v1/jobs",
        &format!("/api/v1/jobs/{id}"),
        &format!("/api/v1/jobs/{id}/events"),
        &format!("/api/v1/jobs/{id}/result.csv"),
        "/no/such/route",
        "/static/no-such-file.js",
        &format!("/api/v1/jobs/{}", "x".repeat(9000)),
    ];
    for path in paths {
        let response = send(&client, &server, Method::GET, path, &[], None).await;
        assert_secured(&response, PAGE_POLICY);
    }
    let response = send(&client, &server, Method::PUT, "/healthz", &[], None).await;
    assert_eq!(response.status(), 405);
    assert_secured(&response, PAGE_POLICY);
    let body = Some(("application/json", b"{".to_vec()));
    let response = send(&client, &server, Method::POST, "/api/v1/jobs", &[], body).await;
    assert_eq!(response.status(), 400);
    assert_secured(&response, PAGE_POLICY);
    // A report has inline styles and no script: a policy of its own.
    let report = format!("/api/v1/jobs/{id}/report");
    let response = send(&client, &server, Method::GET, &report, &[], None).await;
    assert_eq!(response.status(), 200);
    let policy = "default-src 'none'; style-src 'unsafe-inline'; img-src data:; \
                  base-uri 'none'; form-action 'none'; frame-ancestors 'none'; sandbox";
    assert_secured(&response, policy);
    let html = response.text().await.expect("report");
    assert!(!html.contains("<script"), "a report with a script");
    // The page holds no inline script or style for its policy to refuse.
    let page = client.get(server.url("/")).send().await.expect("page");
    let html = page.text().await.expect("page");
    assert!(
        !html.contains("style=") && !html.contains("<style"),
        "inline style"
    );
    for tag in html.split("<script").skip(1) {
        let attributes = tag.trim_start_matches(" type=\"module\"");
        assert!(
            attributes.starts_with(" src=\"/static/"),
            "an inline script: {tag:.80}"
        );
    }
    server.stop().await;
}
