//! The HTTP service (`tribosim serve`): a durable job queue for simulations, run by a fixed
//! pool of worker threads, with progress streamed as server-sent events.
//!
//! - [`serve`] is the whole server: it builds its own tokio runtime, so the command line
//!   stays synchronous. [`serve_on`] runs on a listener the caller bound (tests bind port 0).
//! - Routes are listed once in [`ROUTES`]; `openapi.yaml` at the crate root describes them
//!   and is served at `/api/v1/openapi.yaml`.
//! - Jobs live in `<data-dir>/jobs/<uuid>/` (see `store`); after a restart finished jobs are
//!   served as before, and queued or interrupted ones run (again, from scratch).
//! - Connections are served by `listen` within the [`Limits`] (header, idle and body
//!   timeouts, a cap on open connections, a bounded shutdown).
//! - Shutdown (SIGINT, SIGTERM): the listener closes, event streams end, requests under way
//!   have a grace period, running jobs are interrupted within a cycle and keep their
//!   persisted status, so they run again at the next start. Waiting for them instead could
//!   take minutes, longer than a container runtime waits before killing the process anyway.

mod assets;
mod calibration_routes;
mod calibrations;
mod error;
mod events;
mod export;
mod extract;
mod job;
mod job_routes;
mod listen;
mod measurements;
mod partial;
mod queue;
mod registry;
mod routes;
mod servable;
mod store;
mod studies;
mod study_record;
mod study_routes;
mod surface_routes;
mod surfaces;
mod worker;

use std::future::Future;
use std::io::{self, IsTerminal};
use std::net::SocketAddr;
use std::num::NonZeroUsize;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use axum::extract::DefaultBodyLimit;
use axum::http::{HeaderName, HeaderValue, Method, header};
use thiserror::Error;
use tokio::net::TcpListener;
use tokio::sync::watch;
use tower_http::compression::CompressionLayer;
use tower_http::cors::CorsLayer;
use tower_http::trace::{DefaultMakeSpan, DefaultOnResponse, TraceLayer};
use tracing::Level;

pub use routes::{MAX_URI_BYTES, OPENAPI_YAML, ROUTES, Route, Verb};

use calibrations::Calibrations;
use registry::Jobs;
use store::Store;
use studies::Studies;
use surfaces::Surfaces;

/// Largest request body accepted: a scene is a few kilobytes, a measured table some tens
/// (a profilometer trace of a few thousand points).
pub const BODY_LIMIT_BYTES: usize = 1 << 20;

/// Options of `tribosim serve`.
#[derive(Debug, Clone, clap::Args)]
pub struct ServeArgs {
    /// Address to listen on. Any address other than loopback requires a token.
    #[arg(long, default_value = "127.0.0.1:8080")]
    pub addr: SocketAddr,
    /// Directory for jobs and results (created if missing).
    #[arg(long, default_value = "data")]
    pub data_dir: PathBuf,
    /// Simulations run at once, each on its own thread (one per core by default).
    #[arg(long, default_value_t = default_workers())]
    pub workers: NonZeroUsize,
    /// Jobs that may wait for a worker; further submissions get 429.
    #[arg(long, default_value_t = NonZeroUsize::new(64).unwrap_or(NonZeroUsize::MIN))]
    pub queue_capacity: NonZeroUsize,
    /// The most members a study may have; larger studies are refused (422). A study must
    /// also fit in the queue (--queue-capacity).
    #[arg(long, default_value_t = default_max_study_members())]
    pub max_study_members: NonZeroUsize,
    /// Bearer token required on every API call (`Authorization: Bearer <token>`). A token
    /// on the command line shows in the process list: prefer TRIBOSIM_TOKEN or --token-file.
    #[arg(long, env = "TRIBOSIM_TOKEN", hide_env_values = true)]
    pub token: Option<String>,
    /// File holding the bearer token (its first line; surrounding whitespace is ignored).
    #[arg(long, value_name = "PATH")]
    pub token_file: Option<PathBuf>,
    /// Origin allowed to call the API from a browser (repeatable); CORS is off without one.
    #[arg(long = "cors-origin", value_name = "ORIGIN")]
    pub cors_origins: Vec<String>,
    /// Serve the web page's files (DIR/index.html, and the rest under /static/) from DIR
    /// instead of the copies built into the binary (for working on the page without
    /// rebuilding).
    #[arg(long, value_name = "DIR")]
    pub static_dir: Option<PathBuf>,
    /// Timeouts and the cap on connections.
    #[command(flatten)]
    pub limits: Limits,
}

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
    fn connections_under(&self, open_files: Option<u64>) -> NonZeroUsize {
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

fn default_max_study_members() -> NonZeroUsize {
    NonZeroUsize::new(crate::study::MAX_MEMBERS).unwrap_or(NonZeroUsize::MIN)
}

fn default_workers() -> NonZeroUsize {
    std::thread::available_parallelism().unwrap_or(NonZeroUsize::MIN)
}

/// Why the server did not start or stopped with an error.
#[derive(Debug, Error)]
pub enum ServeError {
    /// A non-loopback address without a token.
    #[error(
        "refusing to listen on {0} without a token: pass --token or set TRIBOSIM_TOKEN \
         (clients then send `Authorization: Bearer <token>`), or listen on a loopback \
         address such as 127.0.0.1"
    )]
    TokenRequired(SocketAddr),
    /// A `--cors-origin` that is not a valid header value.
    #[error("invalid --cors-origin {0:?}")]
    CorsOrigin(String),
    /// A token given both directly and in a file.
    #[error("a token is given twice: pass --token-file, or --token or TRIBOSIM_TOKEN, not both")]
    TokenTwice,
    /// The token file cannot be read.
    #[error("cannot read the token file {}: {source}", path.display())]
    TokenFile {
        /// The file.
        path: PathBuf,
        /// What failed.
        #[source]
        source: io::Error,
    },
    /// The data directory cannot be used.
    #[error("data directory {}: {source}", path.display())]
    DataDir {
        /// The directory.
        path: PathBuf,
        /// What failed.
        #[source]
        source: io::Error,
    },
    /// The address cannot be bound.
    #[error("cannot listen on {addr}: {source}")]
    Bind {
        /// The address.
        addr: SocketAddr,
        /// What failed.
        #[source]
        source: io::Error,
    },
    /// The runtime, a worker thread or the listener failed.
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// What every handler shares.
#[derive(Clone)]
struct AppState {
    jobs: Arc<Jobs>,
    studies: Arc<Studies>,
    calibrations: Arc<Calibrations>,
    token: Option<Arc<str>>,
    /// Where the page's files are read from; the built-in copies when `None`.
    static_dir: Option<Arc<Path>>,
    /// Seconds a request's body may take to arrive.
    body_timeout_s: u64,
    /// Time between an event stream's keep-alive comments, under the idle timeout.
    keep_alive: Duration,
    /// Turns true when the server shuts down, ending event streams.
    shutdown: watch::Receiver<bool>,
}

/// Runs the service until SIGINT or SIGTERM: logs to stderr (filter with `RUST_LOG`, default
/// `info`), builds a tokio runtime, listens on `args.addr`.
pub fn serve(args: ServeArgs) -> Result<(), ServeError> {
    check_exposure(args.addr, args.token()?.as_deref())?;
    init_tracing();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    runtime.block_on(async {
        let listener = TcpListener::bind(args.addr)
            .await
            .map_err(|source| ServeError::Bind {
                addr: args.addr,
                source,
            })?;
        serve_on(args, listener, shutdown_signal()).await
    })
}

/// Runs the service on `listener` until `shutdown` completes (the address in `args` is not
/// used). On return every worker has stopped.
pub async fn serve_on(
    args: ServeArgs,
    listener: TcpListener,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> Result<(), ServeError> {
    let addr = listener.local_addr()?;
    let token = check_exposure(addr, args.token()?.as_deref())?;
    let cors = cors_layer(&args.cors_origins)?;
    let data_dir = args.data_dir.clone();
    let capacity = args.queue_capacity.get();
    let (max_members, workers) = (args.max_study_members.get(), args.workers.get());
    let (jobs, studies) = tokio::task::spawn_blocking(move || {
        let store = Store::open(&data_dir)?;
        let quarantine = store.quarantine_dir().to_owned();
        let surfaces = Arc::new(Surfaces::open(&data_dir, &quarantine)?);
        let jobs = Jobs::open(store, capacity, surfaces)?;
        let studies = Studies::open(&data_dir, &quarantine, max_members, workers)?;
        Ok::<_, io::Error>((jobs, Arc::new(studies)))
    })
    .await
    .map_err(io::Error::other)?
    .map_err(|source| ServeError::DataDir {
        path: args.data_dir.clone(),
        source,
    })?;
    // Each worker's solves get their share of the cores (`numerics.threads: "auto"`).
    crate::contact::share_cores_among(args.workers.get());
    let workers = jobs.start_workers(args.workers.get())?;
    let (stop, stopped) = watch::channel(false);
    let mut limits = args.limits.clone();
    limits.max_connections = limits.connections_under(listen::open_files_limit());
    if limits.max_connections < args.limits.max_connections {
        tracing::warn!(
            "at most {} connections at once: the limit on open files leaves no room for {} \
             (raise it with `ulimit -n`)",
            limits.max_connections,
            args.limits.max_connections
        );
    }
    let app = AppState {
        jobs: Arc::clone(&jobs),
        studies,
        calibrations: Arc::default(),
        token: token.map(Arc::from),
        static_dir: args.static_dir.as_deref().map(Arc::from),
        body_timeout_s: limits.body_timeout_s,
        keep_alive: keep_alive_interval(limits.idle_timeout_s),
        shutdown: stopped.clone(),
    };
    tracing::info!(
        %addr,
        workers = args.workers.get(),
        data_dir = %args.data_dir.display(),
        max_connections = limits.max_connections,
        "tribosim serving on http://{addr}"
    );
    let signal = tokio::spawn(async move {
        shutdown.await;
        tracing::info!("shutting down");
        stop.send_replace(true);
    });
    listen::run(listener, router(app, cors), &limits, stopped).await;
    signal.abort();
    jobs.stop();
    tokio::task::spawn_blocking(move || {
        for worker in workers {
            if worker.join().is_err() {
                tracing::error!("a worker thread panicked");
            }
        }
    })
    .await
    .map_err(io::Error::other)?;
    tracing::info!("stopped");
    Ok(())
}

/// An event stream's keep-alive comments come at most every 15 s (the usual interval) and
/// at least twice per idle timeout, so an idle connection's timer never closes a stream.
fn keep_alive_interval(idle_timeout_s: u64) -> Duration {
    Duration::from_secs(15).min(Duration::from_secs(idle_timeout_s) / 2)
}

impl ServeArgs {
    /// The token from `--token`, `TRIBOSIM_TOKEN` or the first line of `--token-file`.
    fn token(&self) -> Result<Option<String>, ServeError> {
        let Some(path) = &self.token_file else {
            return Ok(self.token.clone());
        };
        if self.token.is_some() {
            return Err(ServeError::TokenTwice);
        }
        let text = std::fs::read_to_string(path).map_err(|source| ServeError::TokenFile {
            path: path.clone(),
            source,
        })?;
        Ok(text.lines().next().map(|line| line.trim().to_owned()))
    }
}

/// The token to require, if any; an error for a non-loopback address without one. An empty
/// token (say, an empty `TRIBOSIM_TOKEN`) counts as none.
fn check_exposure(addr: SocketAddr, token: Option<&str>) -> Result<Option<String>, ServeError> {
    match token.filter(|token| !token.is_empty()) {
        Some(token) => Ok(Some(token.to_owned())),
        None if addr.ip().is_loopback() => Ok(None),
        None => Err(ServeError::TokenRequired(addr)),
    }
}

fn cors_layer(origins: &[String]) -> Result<Option<CorsLayer>, ServeError> {
    if origins.is_empty() {
        return Ok(None);
    }
    let origins = origins
        .iter()
        .map(|origin| {
            HeaderValue::from_str(origin).map_err(|_| ServeError::CorsOrigin(origin.clone()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Some(
        CorsLayer::new()
            .allow_origin(origins)
            .allow_methods([Method::GET, Method::POST, Method::PUT, Method::DELETE])
            .allow_headers([
                header::AUTHORIZATION,
                header::CONTENT_TYPE,
                HeaderName::from_static("last-event-id"),
            ])
            .expose_headers([header::LOCATION, header::RETRY_AFTER]),
    ))
}

/// The router: every route of [`ROUTES`], the token check on those that need it, JSON
/// answers for unknown paths and methods, the body limit, one log line per request.
fn router(app: AppState, cors: Option<CorsLayer>) -> Router {
    let (mut public, mut protected) = (Router::new(), Router::new());
    for route in ROUTES {
        if route.auth {
            protected = protected.route(route.path, route.method_router());
        } else {
            public = public.route(route.path, route.method_router());
        }
    }
    let protected = protected.route_layer(axum::middleware::from_fn_with_state(
        app.clone(),
        routes::require_token,
    ));
    let router = public
        .merge(protected)
        .fallback(routes::no_route)
        .method_not_allowed_fallback(routes::wrong_method)
        .layer(DefaultBodyLimit::max(BODY_LIMIT_BYTES))
        .layer(axum::middleware::from_fn(routes::limit_uri))
        .layer(axum::middleware::from_fn(routes::json_error_bodies))
        // Results with pressure maps run to megabytes of JSON (gzip: about a fifth). The
        // default predicate leaves event streams alone, so progress is not buffered.
        .layer(CompressionLayer::new())
        .layer(
            TraceLayer::new_for_http()
                .make_span_with(DefaultMakeSpan::new().level(Level::INFO))
                .on_request(())
                .on_response(DefaultOnResponse::new().level(Level::INFO)),
        )
        .with_state(app);
    match cors {
        Some(cors) => router.layer(cors),
        None => router,
    }
}

fn init_tracing() {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info"));
    // Fails only when a subscriber is already installed (by an embedding program), which
    // is then used instead.
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(io::stderr)
        // Colour codes only for a terminal, not in files or container logs.
        .with_ansi(io::stderr().is_terminal())
        .try_init();
}

/// Completes at the first SIGINT or SIGTERM.
async fn shutdown_signal() {
    let interrupt = async {
        if let Err(e) = tokio::signal::ctrl_c().await {
            tracing::error!("cannot listen for SIGINT: {e}");
            std::future::pending::<()>().await;
        }
    };
    #[cfg(unix)]
    let terminate = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut signal) => {
                signal.recv().await;
            }
            Err(e) => {
                tracing::error!("cannot listen for SIGTERM: {e}");
                std::future::pending::<()>().await;
            }
        }
    };
    #[cfg(not(unix))]
    let terminate = std::future::pending::<()>();
    tokio::select! {
        () = interrupt => {}
        () = terminate => {}
    }
}
