//! The connection loop and its limits ([`Limits`]): HTTP/1.1 by hyper. axum::serve has no
//! header-read timeout, no cap on connections and waits without bound for open requests at
//! shutdown, so a few hundred clients sending a request a byte at a time would hold the
//! server's file handles, and a half-sent request would hold its shutdown.
//!
//! - At most `max_connections` connections are served at once: the loop takes a permit
//!   before it accepts, so the rest wait in the kernel's backlog and the process never runs
//!   out of file handles (which would take `/healthz` down too).
//! - A request's headers must arrive within `header_timeout_s` of the connection's start or
//!   of the end of its previous request (hyper's header-read timeout), else the connection is
//!   closed.
//! - A connection on which no byte moves either way for `idle_timeout_s` is closed.
//! - At shutdown the listener closes at once, idle connections close, requests under way have
//!   `shutdown_grace_s` to finish; then the connections still open are dropped.

use std::io;
use std::num::NonZeroUsize;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::task::{Context, Poll};
use std::time::Duration;

use axum::Router;
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{OwnedSemaphorePermit, Semaphore, watch};
use tokio::task::JoinSet;
use tokio::time::Instant;

/// Timeouts and the cap on connections of `tribosim serve`; `docs/operations.md` explains
/// each. The defaults suit a lab's machine on its own network.
#[derive(Debug, Clone, clap::Args)]
pub struct Limits {
    /// Seconds a client has to send a request's headers, from connecting or from the end of
    /// its previous request; slower clients are disconnected.
    #[arg(long, default_value_t = Limits::DEFAULT.header_timeout_s, value_parser = seconds())]
    pub header_timeout_s: u64,
    /// Seconds a connection may pass with no byte moving either way before it is closed.
    #[arg(long, default_value_t = Limits::DEFAULT.idle_timeout_s, value_parser = seconds())]
    pub idle_timeout_s: u64,
    /// Seconds a client has to send a request's whole body (a scene); then 408.
    #[arg(long, default_value_t = Limits::DEFAULT.body_timeout_s, value_parser = seconds())]
    pub body_timeout_s: u64,
    /// Connections served at once; more wait in the kernel's backlog until one closes.
    /// Lowered at start to leave file handles for the server's own files if the process's
    /// limit on open files (`ulimit -n`) is lower.
    #[arg(long, default_value_t = Limits::DEFAULT.max_connections)]
    pub max_connections: NonZeroUsize,
    /// Seconds shutdown waits for requests under way before it closes their connections.
    #[arg(long, default_value_t = Limits::DEFAULT.shutdown_grace_s, value_parser = seconds())]
    pub shutdown_grace_s: u64,
}

impl Limits {
    /// The defaults. Ten seconds for headers is ample on a lab network and frees a slow
    /// client's connection quickly; the idle timeout is above the 15 s between an event
    /// stream's keep-alive comments; 512 connections fit under the 1024 open files most Linux
    /// systems allow a process by default; 5 s of grace is within the 10 s `docker stop`
    /// waits before it kills.
    pub const DEFAULT: Self = Self {
        header_timeout_s: 10,
        idle_timeout_s: 60,
        body_timeout_s: 30,
        max_connections: match NonZeroUsize::new(512) {
            Some(n) => n,
            None => NonZeroUsize::MIN,
        },
        shutdown_grace_s: 5,
    };

    /// File handles kept free for the server itself (its data files, logs, the runtime)
    /// when the connection cap is lowered to fit the open-files limit.
    const RESERVED_FILES: u64 = 64;

    /// The cap on connections, lowered if needed so that the connections and
    /// [`Self::RESERVED_FILES`] fit under `open_files` (the process's limit, when known).
    pub(super) fn connections_under(&self, open_files: Option<u64>) -> NonZeroUsize {
        let Some(open_files) = open_files else {
            return self.max_connections;
        };
        let room = open_files.saturating_sub(Self::RESERVED_FILES).max(1);
        let room = NonZeroUsize::new(usize::try_from(room).unwrap_or(usize::MAX))
            .unwrap_or(NonZeroUsize::MIN);
        self.max_connections.min(room)
    }
}

impl Default for Limits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A whole number of seconds, at least one.
fn seconds() -> clap::builder::RangedU64ValueParser<u64> {
    clap::value_parser!(u64).range(1..)
}

/// Serves `router` on `listener` until `closing` turns true, then shuts down within the
/// grace period of `limits`.
pub(super) async fn run(
    listener: TcpListener,
    router: Router,
    limits: &Limits,
    closing: watch::Receiver<bool>,
) {
    let permits = Arc::new(Semaphore::new(limits.max_connections.get()));
    let mut http = http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(Duration::from_secs(limits.header_timeout_s));
    let idle = Duration::from_secs(limits.idle_timeout_s);
    let mut connections = JoinSet::new();
    let stopping = closed(closing.clone());
    tokio::pin!(stopping);
    loop {
        let permit = tokio::select! {
            () = &mut stopping => break,
            permit = Arc::clone(&permits).acquire_owned() => permit,
            // Reaps finished connections so the set holds only open ones.
            Some(_) = connections.join_next(), if !connections.is_empty() => continue,
        };
        let Ok(permit) = permit else { break };
        let stream = tokio::select! {
            () = &mut stopping => break,
            accepted = listener.accept() => match accepted {
                Ok((stream, _)) => stream,
                Err(e) => {
                    accept_failed(&e).await;
                    continue;
                }
            },
        };
        let connection = Connection {
            http: http.clone(),
            router: router.clone(),
            idle,
            closing: closing.clone(),
            _permit: permit,
        };
        connections.spawn(connection.serve(stream));
    }
    drop(listener);
    let grace = Duration::from_secs(limits.shutdown_grace_s);
    let drained = tokio::time::timeout(grace, async {
        while connections.join_next().await.is_some() {}
    })
    .await;
    if drained.is_err() {
        tracing::warn!(
            open = connections.len(),
            "closing the connections still open {} s after shutdown began",
            limits.shutdown_grace_s
        );
        connections.shutdown().await;
    }
}

/// Completes when `closing` turns true (or its sender is gone).
async fn closed(mut closing: watch::Receiver<bool>) {
    let turned = closing.wait_for(|closing| *closing).await.is_ok();
    tracing::trace!(turned, "shutdown seen");
}

/// An accept that failed: a connection reset before it was accepted is the client's
/// business; anything else (out of file handles, say) is logged and retried after a pause,
/// so the loop does not spin.
async fn accept_failed(error: &io::Error) {
    use io::ErrorKind::{ConnectionAborted, ConnectionRefused, ConnectionReset};
    if matches!(
        error.kind(),
        ConnectionAborted | ConnectionRefused | ConnectionReset
    ) {
        return;
    }
    tracing::error!("accepting a connection: {error}");
    tokio::time::sleep(Duration::from_millis(100)).await;
}

/// What one connection's task owns; the permit is given back when the task ends.
struct Connection {
    http: http1::Builder,
    router: Router,
    idle: Duration,
    closing: watch::Receiver<bool>,
    _permit: OwnedSemaphorePermit,
}

impl Connection {
    async fn serve(self, stream: TcpStream) {
        let activity = Arc::new(Activity::new());
        let io = TokioIo::new(Watched {
            stream,
            activity: Arc::clone(&activity),
        });
        let connection = self
            .http
            .serve_connection(io, TowerToHyperService::new(self.router));
        tokio::pin!(connection);
        let draining = closed(self.closing);
        tokio::pin!(draining);
        let mut draining_started = false;
        loop {
            let deadline = activity.last() + self.idle;
            tokio::select! {
                served = connection.as_mut() => {
                    if let Err(e) = served {
                        tracing::debug!("connection closed: {e}");
                    }
                    return;
                }
                () = &mut draining, if !draining_started => {
                    draining_started = true;
                    connection.as_mut().graceful_shutdown();
                }
                () = tokio::time::sleep_until(deadline) => {
                    if activity.last() + self.idle <= Instant::now() {
                        tracing::debug!("closing a connection idle for {:?}", self.idle);
                        return;
                    }
                }
            }
        }
    }
}

/// When a byte last moved on a connection, in milliseconds after its start.
struct Activity {
    start: Instant,
    last_ms: AtomicU64,
}

impl Activity {
    fn new() -> Self {
        Self {
            start: Instant::now(),
            last_ms: AtomicU64::new(0),
        }
    }

    fn touch(&self) {
        let ms = u64::try_from(self.start.elapsed().as_millis()).unwrap_or(u64::MAX);
        self.last_ms.store(ms, Ordering::Relaxed);
    }

    fn last(&self) -> Instant {
        self.start + Duration::from_millis(self.last_ms.load(Ordering::Relaxed))
    }
}

/// A TCP stream that records in [`Activity`] each read or write that moves bytes.
struct Watched {
    stream: TcpStream,
    activity: Arc<Activity>,
}

impl AsyncRead for Watched {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        let before = buf.filled().len();
        let polled = Pin::new(&mut self.stream).poll_read(cx, buf);
        if buf.filled().len() > before {
            self.activity.touch();
        }
        polled
    }
}

impl AsyncWrite for Watched {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        let polled = Pin::new(&mut self.stream).poll_write(cx, buf);
        if matches!(polled, Poll::Ready(Ok(n)) if n > 0) {
            self.activity.touch();
        }
        polled
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        let polled = Pin::new(&mut self.stream).poll_write_vectored(cx, bufs);
        if matches!(polled, Poll::Ready(Ok(n)) if n > 0) {
            self.activity.touch();
        }
        polled
    }

    fn is_write_vectored(&self) -> bool {
        self.stream.is_write_vectored()
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.stream).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.stream).poll_shutdown(cx)
    }
}

/// The soft limit on open files of this process, from `/proc/self/limits` (Linux); `None`
/// where that file does not exist or says "unlimited".
pub(super) fn open_files_limit() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits
        .lines()
        .find(|line| line.starts_with("Max open files"))?;
    line.split_whitespace().nth(3)?.parse().ok()
}
