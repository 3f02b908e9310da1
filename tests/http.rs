//! The service as an operator runs it: the `tribosim serve` binary in its own process. Slow
//! clients, the cap on connections, the idle timeout, the bounded shutdown on SIGTERM, the
//! token's scheme and file, duplicate keys, long targets and the page built into the binary.

use std::io::{ErrorKind, Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

mod common;

use common::process::{ServerProcess, serve_command};
use common::{PATIENCE, TempDir};

/// `tribosim serve` on a free port with `data_dir` and the extra `flags`, started in `cwd`
/// with no token in its environment.
fn served(data_dir: &Path, flags: &[&str], cwd: &Path) -> ServerProcess {
    let mut command = serve_command(data_dir, 2);
    command
        .args(flags)
        .current_dir(cwd)
        .env_remove("TRIBOSIM_TOKEN");
    ServerProcess::spawn(command)
}

fn client() -> reqwest::Client {
    reqwest::Client::builder()
        .timeout(PATIENCE)
        .build()
        .expect("client")
}

/// A client that opens a connection, sends the start of a request and then one byte every
/// 200 ms, never finishing its headers. Returns how long after connecting the server closed
/// the connection (`None` if it stayed open for [`PATIENCE`]).
fn slow_client(addr: &str) -> Option<Duration> {
    // Timed from before the connection exists, so that the server's timer, which starts
    // when it accepts, cannot have started earlier than this clock.
    let connected = Instant::now();
    let mut stream = TcpStream::connect(addr).expect("connect");
    stream
        .write_all(format!("GET /healthz HTTP/1.1\r\nHost: {addr}\r\nX-Slow: ").as_bytes())
        .expect("first bytes");
    stream
        .set_read_timeout(Some(Duration::from_millis(200)))
        .expect("read timeout");
    let mut buf = [0u8; 256];
    while connected.elapsed() < PATIENCE {
        match stream.read(&mut buf) {
            Ok(0) => return Some(connected.elapsed()),
            Ok(_) => {}
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {
                if stream.write_all(b"a").is_err() {
                    return Some(connected.elapsed());
                }
            }
            Err(_) => return Some(connected.elapsed()),
        }
    }
    None
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn slow_clients_do_not_stop_healthz_and_are_closed_after_the_header_timeout() {
    const SLOW_CLIENTS: usize = 300;
    const HEADER_TIMEOUT_S: u64 = 3;
    let dir = TempDir::new("slow");
    let timeout = HEADER_TIMEOUT_S.to_string();
    let server = served(dir.path(), &["--header-timeout-s", &timeout], dir.path());
    let slow: Vec<_> = (0..SLOW_CLIENTS)
        .map(|_| {
            let addr = server.addr().to_owned();
            std::thread::spawn(move || slow_client(&addr))
        })
        .collect();
    // The slow clients are connected and trickling while /healthz is asked.
    tokio::time::sleep(Duration::from_millis(500)).await;
    let client = client();
    let mut latencies = Vec::new();
    for _ in 0..10 {
        let asked = Instant::now();
        let response = client
            .get(server.url("/healthz"))
            .send()
            .await
            .expect("/healthz answers with slow clients connected");
        assert_eq!(response.status(), 200);
        latencies.push(asked.elapsed());
    }
    eprintln!("/healthz with {SLOW_CLIENTS} slow clients: {latencies:?}");
    let mut lifetimes = Vec::new();
    for client in slow {
        let lifetime = client
            .join()
            .expect("slow client thread")
            .expect("the server closes a client that never finishes its headers");
        lifetimes.push(lifetime);
    }
    lifetimes.sort();
    eprintln!(
        "slow clients closed after {:?} to {:?}",
        lifetimes[0],
        lifetimes[lifetimes.len() - 1]
    );
    // Closed by the header timeout, not earlier: each was trickling bytes, so neither the
    // idle timeout (60 s by default) nor anything else applies.
    assert!(lifetimes[0] >= Duration::from_secs(HEADER_TIMEOUT_S));
    let response = client
        .get(server.url("/healthz"))
        .send()
        .await
        .expect("healthz");
    assert_eq!(response.status(), 200);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sigterm_stops_the_server_within_the_grace_despite_half_sent_requests() {
    const GRACE_S: u64 = 1;
    let dir = TempDir::new("sigterm");
    let grace = GRACE_S.to_string();
    // Timeouts far beyond the test's patience: only the shutdown's grace can end these.
    let mut server = served(
        dir.path(),
        &[
            "--shutdown-grace-s",
            &grace,
            "--header-timeout-s",
            "3600",
            "--body-timeout-s",
            "3600",
            "--idle-timeout-s",
            "3600",
        ],
        dir.path(),
    );
    let mut half_body = TcpStream::connect(server.addr()).expect("connect");
    half_body
        .write_all(
            format!(
                "POST /api/v1/jobs HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\n\
                 Content-Length: 1000\r\n\r\n{{\"name\": ",
                server.addr()
            )
            .as_bytes(),
        )
        .expect("half a body");
    let mut half_head = TcpStream::connect(server.addr()).expect("connect");
    half_head
        .write_all(b"GET /healthz HTTP/1.1\r\nHo")
        .expect("half a head");
    // Both connections are being served once a later request has been answered.
    let response = client()
        .get(server.url("/healthz"))
        .send()
        .await
        .expect("healthz");
    assert_eq!(response.status(), 200);
    let (took, success) = tokio::task::spawn_blocking(move || server.terminate())
        .await
        .expect("terminate")
        .expect("the server exits after SIGTERM despite the half-sent requests");
    eprintln!("exited {took:?} after SIGTERM with {GRACE_S} s of grace");
    assert!(success, "the server exits with success after SIGTERM");
    drop((half_body, half_head));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_key_given_twice_is_refused_naming_it_by_the_service_and_the_cli() {
    let dir = TempDir::new("duplicate");
    let text = r#"{"test": {"load_n": 5, "cycles": 3, "load_n": 50}}"#;
    let server = served(dir.path(), &[], dir.path());
    let response = client()
        .post(server.url("/api/v1/jobs"))
        .header("Content-Type", "application/json")
        .body(text)
        .send()
        .await
        .expect("submit");
    assert_eq!(response.status(), 422);
    let body: Value = response.json().await.expect("JSON error body");
    assert_eq!(body["fields"][0]["path"], "test.load_n", "{body}");

    let scene = dir.path().join("scene.json");
    std::fs::write(&scene, text).expect("write scene");
    let run = Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .arg("run")
        .arg(&scene)
        .output()
        .expect("tribosim run");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "the run refuses the scene");
    assert!(stderr.contains("test.load_n"), "{stderr}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn long_targets_get_414_with_the_json_body_and_long_ids_are_cut() {
    let dir = TempDir::new("long");
    let server = served(dir.path(), &[], dir.path());
    let client = client();
    let long = "a".repeat(tribosim::service::MAX_URI_BYTES);
    let response = client
        .get(server.url(&format!("/api/v1/jobs/{long}")))
        .send()
        .await
        .expect("long target");
    assert_eq!(response.status(), 414);
    let body: Value = response.json().await.expect("414 has the JSON body");
    assert!(body["error"].is_string(), "{body}");

    let id = "b".repeat(1000);
    let response = client
        .get(server.url(&format!("/api/v1/jobs/{id}")))
        .send()
        .await
        .expect("long id");
    assert_eq!(response.status(), 400);
    let body: Value = response.json().await.expect("JSON error body");
    let message = body["error"].as_str().expect("message");
    // 40 characters of the id, the ellipsis, the sentence around it.
    assert!(message.len() < 100, "{message}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_token_from_a_file_is_accepted_with_any_case_of_bearer() {
    let dir = TempDir::new("token");
    let token_file = dir.path().join("token");
    std::fs::write(&token_file, "s3cret-token\n").expect("write token");
    let token_flag = token_file.to_str().expect("UTF-8 path");
    let server = served(dir.path(), &["--token-file", token_flag], dir.path());
    let client = client();
    let cases = [
        (Some("Bearer s3cret-token"), 200),
        (Some("bearer s3cret-token"), 200),
        (Some("BEARER  s3cret-token"), 200),
        (Some("Bearer s3cret-toke"), 401),
        (Some("Bearer s3cret-token2"), 401),
        (Some("Basic s3cret-token"), 401),
        (None, 401),
    ];
    for (authorization, status) in cases {
        let mut request = client.get(server.url("/api/v1/jobs"));
        if let Some(value) = authorization {
            request = request.header("Authorization", value);
        }
        let response = request.send().await.expect("list jobs");
        assert_eq!(response.status(), status, "{authorization:?}");
        let _: Value = response.json().await.expect("JSON body");
    }
}

/// `tribosim serve` with `flags` and `token` in TRIBOSIM_TOKEN: its exit status and stderr,
/// for a server that must refuse to start.
fn refused_start(dir: &Path, flags: &[&str], token: Option<&str>) -> (bool, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_tribosim"));
    command
        .args(["serve", "--addr", "127.0.0.1:0", "--data-dir"])
        .arg(dir.join("data"))
        .args(flags)
        .env_remove("TRIBOSIM_TOKEN");
    if let Some(token) = token {
        command.env("TRIBOSIM_TOKEN", token);
    }
    let mut child = command
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn tribosim serve");
    let deadline = std::time::Instant::now() + PATIENCE;
    while child.try_wait().expect("poll").is_none() {
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            panic!("the server started with {flags:?} and {token:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let output = child.wait_with_output().expect("its output");
    (
        output.status.success(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_token_that_cannot_work_stops_the_start_saying_why() {
    let dir = TempDir::new("token-checks");
    for (name, text) in [("empty", ""), ("blank", "  \n\nsecond-line\n")] {
        let file = dir.path().join(name);
        std::fs::write(&file, text).expect("write the token file");
        let flag = file.to_str().expect("UTF-8 path");
        let (started, stderr) = refused_start(dir.path(), &["--token-file", flag], None);
        assert!(!started, "{name}");
        assert!(stderr.contains("has no token"), "{name}: {stderr}");
        assert!(stderr.contains(flag), "{name}: {stderr}");
    }
    let file = dir.path().join("accented");
    std::fs::write(&file, "s\u{e9}cret\n").expect("write the token file");
    let flag = file.to_str().expect("UTF-8 path");
    let (started, stderr) = refused_start(dir.path(), &["--token-file", flag], None);
    assert!(!started);
    assert!(
        stderr.contains("outside ASCII (U+00E9), at character 2"),
        "{stderr}"
    );
    assert!(
        !stderr.contains("s\u{e9}cret"),
        "the token is not echoed: {stderr}"
    );
    let (started, stderr) = refused_start(dir.path(), &[], Some("two words"));
    assert!(!started);
    assert!(stderr.contains("TRIBOSIM_TOKEN has a space"), "{stderr}");

    // The environment's token is trimmed as the file's is.
    let mut command = Command::new(env!("CARGO_BIN_EXE_tribosim"));
    command
        .args(["serve", "--addr", "127.0.0.1:0", "--data-dir"])
        .arg(dir.path().join("data"))
        .env("TRIBOSIM_TOKEN", "  padded-token\n");
    let served = ServerProcess::spawn(command);
    let client = client();
    for (authorization, status) in [("Bearer padded-token", 200), ("Bearer padded", 401)] {
        let response = client
            .get(served.url("/api/v1/jobs"))
            .header("Authorization", authorization)
            .send()
            .await
            .expect("list jobs");
        assert_eq!(response.status(), status, "{authorization}");
    }
}

/// The files under `dir`, by their paths relative to `root` with `/` between folders.
fn files_under(root: &Path, dir: &Path, out: &mut Vec<(String, Vec<u8>)>) {
    for entry in std::fs::read_dir(dir).expect("read the folder") {
        let path = entry.expect("a folder entry").path();
        if path.is_dir() {
            files_under(root, &path, out);
        } else {
            let relative = path.strip_prefix(root).expect("under the root");
            let parts: Vec<_> = relative
                .components()
                .map(|c| c.as_os_str().to_str().expect("a UTF-8 file name"))
                .collect();
            out.push((
                parts.join("/"),
                std::fs::read(&path).expect("read the file"),
            ));
        }
    }
}

/// GETs `path` and checks the answer: 200, the content type starting with `content_type`,
/// `no-cache`; returns the body.
async fn page_file(client: &reqwest::Client, url: String, content_type: &str) -> Vec<u8> {
    let response = client.get(&url).send().await.expect("page file");
    assert_eq!(response.status(), 200, "{url}");
    let given = response.headers()["content-type"].to_str().expect("ascii");
    assert!(given.starts_with(content_type), "{url}: {given}");
    assert_eq!(response.headers()["cache-control"], "no-cache", "{url}");
    response.bytes().await.expect("body").to_vec()
}

/// GETs `path` and checks the answer is the JSON 404.
async fn no_page_file(client: &reqwest::Client, url: String) {
    let response = client.get(&url).send().await.expect("page file");
    assert_eq!(response.status(), 404, "{url}");
    assert_eq!(
        response.headers()["content-type"],
        "application/json",
        "{url}"
    );
    let body: Value = response.json().await.expect("error JSON");
    assert!(body["error"].is_string(), "{url}: {body}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_is_served_from_any_directory_and_static_dir_overrides_it() {
    let dir = TempDir::new("page");
    let elsewhere = TempDir::new("cwd");
    let built_in = served(dir.path(), &[], elsewhere.path());
    let client = client();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("static");
    let page = page_file(&client, built_in.url("/"), "text/html").await;
    assert_eq!(
        page,
        std::fs::read(root.join("index.html")).expect("index.html")
    );
    // Every file of static/ as it is on disk, the modules and styles with their types.
    let mut files = Vec::new();
    files_under(&root, &root, &mut files);
    for (path, bytes) in &files {
        let content_type = match path.rsplit_once('.').map(|(_, extension)| extension) {
            Some("js") => "text/javascript",
            Some("css") => "text/css",
            Some("html") => "text/html",
            _ => "",
        };
        let served = page_file(
            &client,
            built_in.url(&format!("/static/{path}")),
            content_type,
        )
        .await;
        assert!(&served == bytes, "/static/{path} is not static/{path}");
    }
    assert!(
        files
            .iter()
            .any(|(path, _)| path == "vendor/uplot/uPlot.iife.min.js")
    );
    no_page_file(&client, built_in.url("/static/js/nope.js")).await;
    // The guides the command line's help points at, as docs/ has them.
    let guide = page_file(&client, built_in.url("/docs/scene.md"), "text/markdown").await;
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    assert!(guide == std::fs::read(docs.join("scene.md")).expect("docs/scene.md"));
    no_page_file(&client, built_in.url("/docs/nope.md")).await;
    no_page_file(&client, built_in.url("/docs/..%2FREADME.md")).await;
    drop(built_in);

    let draft = elsewhere.path().join("draft");
    std::fs::create_dir_all(draft.join("js")).expect("create the draft's folders");
    std::fs::write(draft.join("index.html"), "<p>draft</p>").expect("write page");
    std::fs::write(draft.join("js/main.js"), "// draft").expect("write a module");
    std::fs::write(elsewhere.path().join("secret"), "outside the page").expect("write a file");
    let flag = draft.to_str().expect("UTF-8 path");
    let overridden = served(dir.path(), &["--static-dir", flag], dir.path());
    let page = page_file(&client, overridden.url("/"), "text/html").await;
    assert_eq!(page, b"<p>draft</p>");
    let module = page_file(
        &client,
        overridden.url("/static/js/main.js"),
        "text/javascript",
    )
    .await;
    assert_eq!(module, b"// draft");
    // The built-in files are not served in the draft's stead, and no path leaves its folder
    // (the URL keeps an encoded `/`; the server decodes it).
    no_page_file(&client, overridden.url("/static/page.css")).await;
    no_page_file(&client, overridden.url("/static/..%2Fsecret")).await;
    no_page_file(&client, overridden.url("/static/js%2F..%2F..%2Fsecret")).await;
    let absolute = elsewhere.path().join("secret");
    let absolute = absolute.to_str().expect("UTF-8 path").replace('/', "%2F");
    no_page_file(&client, overridden.url(&format!("/static/{absolute}"))).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn connections_beyond_the_cap_wait_until_one_closes() {
    let dir = TempDir::new("cap");
    // Only the cap can hold these connections: no timeout ends them during the test.
    let server = served(
        dir.path(),
        &[
            "--max-connections",
            "2",
            "--header-timeout-s",
            "3600",
            "--idle-timeout-s",
            "3600",
        ],
        dir.path(),
    );
    let held: Vec<_> = (0..2)
        .map(|_| TcpStream::connect(server.addr()).expect("connect"))
        .collect();
    let impatient = reqwest::Client::builder()
        .timeout(Duration::from_secs(1))
        .build()
        .expect("client");
    let refused = impatient.get(server.url("/healthz")).send().await;
    assert!(
        refused.is_err(),
        "a third connection is served while two are held"
    );
    drop(held);
    let response = client()
        .get(server.url("/healthz"))
        .send()
        .await
        .expect("served once the held connections close");
    assert_eq!(response.status(), 200);
}

#[test]
fn a_connection_with_no_traffic_is_closed_after_the_idle_timeout() {
    const IDLE_TIMEOUT_S: u64 = 1;
    let dir = TempDir::new("idle");
    let idle = IDLE_TIMEOUT_S.to_string();
    let server = served(
        dir.path(),
        &["--idle-timeout-s", &idle, "--header-timeout-s", "3600"],
        dir.path(),
    );
    let mut stream = TcpStream::connect(server.addr()).expect("connect");
    stream
        .write_all(format!("GET /healthz HTTP/1.1\r\nHost: {}\r\n\r\n", server.addr()).as_bytes())
        .expect("request");
    stream
        .set_read_timeout(Some(PATIENCE))
        .expect("read timeout");
    let opened = Instant::now();
    let mut answer = Vec::new();
    // The answer, then the end of the stream when the kept-alive connection idles out.
    stream
        .read_to_end(&mut answer)
        .expect("the server closes the idle connection");
    let answer = String::from_utf8_lossy(&answer);
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
    eprintln!(
        "idle connection closed {:?} after its request",
        opened.elapsed()
    );
    assert!(opened.elapsed() >= Duration::from_secs(IDLE_TIMEOUT_S));
}
