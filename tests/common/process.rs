//! `tribosim serve` as a separate process (the real binary), for tests that kill the server
//! with SIGKILL or damage its data directory between two runs; and the CLI run once, for
//! tests that compare the service with it.

use std::ffi::OsStr;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde_json::Value;

use super::PATIENCE;

/// The line the server logs once it is listening; the address follows it.
const SERVING_ON: &str = "serving on http://";

/// A server process, killed when dropped so a failing test leaves none behind.
pub struct ServerProcess {
    child: Child,
    /// `http://127.0.0.1:<port>`.
    pub base: String,
    log: Arc<Mutex<Vec<String>>>,
}

/// Runs `tribosim` with `args` and `-o output`, expects it to succeed, and reads the JSON it
/// wrote there.
pub fn cli_json<S: AsRef<OsStr>>(args: impl IntoIterator<Item = S>, output: &Path) -> Value {
    let status = Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(args)
        .arg("-o")
        .arg(output)
        .status()
        .expect("run tribosim");
    assert!(status.success());
    serde_json::from_slice(&std::fs::read(output).expect("read")).expect("JSON")
}

/// The command that runs the binary as `serve` on a port of its choice, with `workers`
/// workers.
pub fn serve_command(data_dir: &Path, workers: usize) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_tribosim"));
    command
        .args(["serve", "--addr", "127.0.0.1:0", "--workers"])
        .arg(workers.to_string())
        .arg("--data-dir")
        .arg(data_dir);
    command
}

impl ServerProcess {
    /// Starts `tribosim serve` with one worker on `data_dir` and waits until it listens.
    pub fn start(data_dir: &Path) -> Self {
        Self::spawn(serve_command(data_dir, 1))
    }

    /// Runs `command` (which must end up running the server) and waits until it listens;
    /// panics with the server's log if it exits first.
    pub fn spawn(mut command: Command) -> Self {
        let mut child = command
            .env("RUST_LOG", "info")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn the server");
        let stderr = child.stderr.take().expect("piped stderr");
        let log = Arc::new(Mutex::new(Vec::new()));
        let (address, announced) = mpsc::channel();
        let lines = Arc::clone(&log);
        // Reads the log to its end, so the server never blocks on a full pipe.
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines() {
                let Ok(line) = line else { break };
                if let Some(start) = line.find(SERVING_ON) {
                    let rest = &line[start + SERVING_ON.len()..];
                    let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
                    let _ = address.send(format!("http://{}", &rest[..end]));
                }
                lines.lock().expect("log lock").push(line);
            }
        });
        let mut server = Self {
            child,
            base: String::new(),
            log,
        };
        match announced.recv_timeout(PATIENCE) {
            Ok(base) => server.base = base,
            Err(_) => {
                let status = server.child.wait().expect("wait");
                panic!("the server did not start ({status}):\n{}", server.log());
            }
        }
        server
    }

    /// The process id (the server's own, as the commands used here exec it).
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// `base` + `path`.
    pub fn url(&self, path: &str) -> String {
        format!("{}{path}", self.base)
    }

    /// The address, as `host:port`.
    pub fn addr(&self) -> &str {
        self.base.trim_start_matches("http://")
    }

    /// Sends SIGTERM and returns the time until the process exited, and whether it exited
    /// with success; `None` if it had not exited after [`PATIENCE`].
    pub fn terminate(&mut self) -> Option<(Duration, bool)> {
        let sent = Instant::now();
        let status = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status()
            .expect("run kill");
        assert!(status.success(), "kill -TERM failed");
        while sent.elapsed() < PATIENCE {
            if let Some(exit) = self.child.try_wait().expect("wait for the server") {
                return Some((sent.elapsed(), exit.success()));
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        None
    }

    /// Everything the server has logged so far.
    pub fn log(&self) -> String {
        self.log.lock().expect("log lock").join("\n")
    }

    /// SIGKILL: no shutdown code runs.
    pub fn kill_9(&mut self) {
        self.child.kill().expect("kill");
        self.child.wait().expect("reap");
    }
}

impl Drop for ServerProcess {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
