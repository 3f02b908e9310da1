//! The HTTP service (`tribosim serve`): a durable job queue for simulations, run by a fixed
//! pool of worker threads, with progress streamed as server-sent events.
//!
//! - [`serve`] is the whole server: it builds its own tokio runtime, so the command line
//!   stays synchronous. [`serve_on`] runs on a listener the caller bound (tests bind port 0).
//! - A folder per resource (`jobs`, `measurements`, `studies`, `calibrations`, `surfaces`,
//!   and `reports`, made from the others),
//!   each with its state, its storage and its `routes.rs`: the handlers, the resource's list
//!   of routes, and the API's answer to each of its errors. `router` merges the lists into
//!   the one table ([`routes`]) that `openapi.yaml` at the crate root describes (it is served
//!   at `/api/v1/openapi.yaml`, and a test checks the two agree).
//! - What every route shares, and knows no resource: the error type (`error`), the
//!   extractors of ids and bodies (`extract`), the one helper for blocking work
//!   (`blocking`), the route table's types (`route`), the shapes of answer (`reply`), the
//!   durable-file primitives (`files`). The application's state (`state`) gives each handler
//!   its part, so no resource imports it.
//! - Jobs live in `<data-dir>/jobs/<uuid>/`; after a restart finished jobs are served as
//!   before, and queued or interrupted ones run (again, from scratch).
//! - Connections are served by `listen` within the [`Limits`] (header, idle and body
//!   timeouts, a cap on open connections, a bounded shutdown).
//! - Shutdown (SIGINT, SIGTERM): the listener closes, event streams end, requests under way
//!   have a grace period, running jobs are interrupted within a cycle and keep their
//!   persisted status, so they run again at the next start. Waiting for them instead could
//!   take minutes, longer than a container runtime waits before killing the process anyway.

mod assets;
mod blocking;
mod budget;
mod calibrations;
mod cursor;
mod docs;
mod error;
mod extract;
mod files;
mod jobs;
mod listen;
mod listing;
mod measurements;
mod meta;
mod origin;
mod reply;
mod reports;
mod route;
mod router;
mod state;
mod studies;
mod surfaces;

use std::future::Future;
use std::io::{self, IsTerminal};
use std::net::SocketAddr;
use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use axum::http::{HeaderName, HeaderValue, Method, header};
use thiserror::Error;
use tokio::net::TcpListener;
use tokio::sync::watch;
use tower_http::cors::CorsLayer;

pub use budget::Budgets;
pub use listen::Limits;
pub use measurements::{
    Format as TableFormat, MeasurementError, MeasurementKind, parse as parse_measurements,
};
pub use meta::OPENAPI_YAML;
pub use route::{Route, Verb};
pub use router::{BODY_LIMIT_BYTES, MAX_URI_BYTES, routes};

use calibrations::{CalibrationStore, Calibrations, FitLimits};
use cursor::CursorKey;
use extract::BodyTimeout;
use jobs::{Jobs, Store, Streams};
use state::AppState;
use studies::Studies;
use surfaces::{Surfaces, UploadLimits};

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
    /// Bearer token required on every API call (`Authorization: Bearer <token>`):
    /// printable ASCII without spaces; surrounding whitespace is ignored, and an empty one
    /// is none. A token on the command line shows in the process list: prefer
    /// TRIBOSIM_TOKEN or --token-file.
    #[arg(long, env = "TRIBOSIM_TOKEN", hide_env_values = true)]
    pub token: Option<String>,
    /// File holding the bearer token (its first line; surrounding whitespace is ignored). A
    /// file without a token is an error.
    #[arg(long, value_name = "PATH")]
    pub token_file: Option<PathBuf>,
    /// Origin allowed to call the API from a browser (repeatable); CORS is off without one.
    #[arg(long = "cors-origin", value_name = "ORIGIN")]
    pub cors_origins: Vec<String>,
    /// Another host name the server answers to (repeatable), as a reverse proxy forwards
    /// it in `Host`: NAME for any port, NAME:PORT for one. Without a token the server
    /// serves only requests for its own address (and localhost) and these (421 otherwise),
    /// and takes changes only from pages of these origins or --cors-origin (403 otherwise);
    /// with a token nothing is checked.
    #[arg(long = "allowed-host", value_name = "NAME[:PORT]")]
    pub allowed_hosts: Vec<String>,
    /// Serve the web page's files (DIR/index.html, and the rest under /static/) from DIR
    /// instead of the copies built into the binary (for working on the page without
    /// rebuilding).
    #[arg(long, value_name = "DIR")]
    pub static_dir: Option<PathBuf>,
    /// Timeouts and the cap on connections.
    #[command(flatten)]
    pub limits: Limits,
    /// What an upload or a fit may cost.
    #[command(flatten)]
    pub budgets: Budgets,
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
    /// An `--allowed-host` that is not a host name with an optional port.
    #[error(
        "invalid --allowed-host {0:?}: give a host name as a browser sends it in `Host`, \
         NAME or NAME:PORT (an IPv6 address in brackets), without a scheme or a path"
    )]
    AllowedHost(String),
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
    /// The token file's first line is empty or blank: starting without a token would turn
    /// authentication off while the operator meant it on.
    #[error(
        "the token file {} has no token (its first line is empty or blank); write the token \
         on its first line, or leave out --token-file to run without one",
        path.display()
    )]
    TokenFileEmpty {
        /// The file.
        path: PathBuf,
    },
    /// A token with a character other than printable ASCII (a space, a control character,
    /// a letter outside ASCII): clients send it in an HTTP header, where it cannot be
    /// matched.
    #[error(
        "the token from {from} has {found}, at character {position}: a token is printable \
         ASCII without spaces (! to ~), as HTTP headers carry it"
    )]
    TokenNotAscii {
        /// Where the token came from: `--token-file PATH` or `--token or TRIBOSIM_TOKEN`.
        from: String,
        /// The character, described without echoing the token.
        found: String,
        /// Its position in the token, from 1.
        position: usize,
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

/// Runs the service until SIGINT or SIGTERM: logs to stderr (filter with `RUST_LOG`, default
/// `info`), builds a tokio runtime, listens on `args.addr`.
pub fn serve(args: ServeArgs) -> Result<(), ServeError> {
    check_exposure(args.addr, args.token()?.as_deref())?;
    init_tracing();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    let grace = Duration::from_secs(args.limits.shutdown_grace_s);
    let served = runtime.block_on(async {
        let listener = TcpListener::bind(args.addr)
            .await
            .map_err(|source| ServeError::Bind {
                addr: args.addr,
                source,
            })?;
        serve_on(args, listener, shutdown_signal()).await
    });
    // A request's blocking work (a report, a parse) still under way when the grace period
    // ended has no one left to answer: the process does not wait for it past another grace
    // period, where dropping the runtime would wait for it however long it takes.
    runtime.shutdown_timeout(grace);
    served
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
    let guard = origin::Guard::new(
        addr,
        token.is_some(),
        &args.allowed_hosts,
        &args.cors_origins,
    )
    .map_err(|origin::NotAHostName(value)| ServeError::AllowedHost(value))?;
    if token.is_some() && !args.allowed_hosts.is_empty() {
        tracing::warn!(
            "--allowed-host has no effect with a token: a server with a token answers to any \
             host name"
        );
    }
    let stores = open_stores(&args).await?;
    let workers = stores.jobs.start_workers(args.workers.get())?;
    let jobs = Arc::clone(&stores.jobs);
    let (stop, stopped) = watch::channel(false);
    let limits = connection_limits(&args.limits);
    let app = app_state(&args, stores, token, (&limits, &stopped));
    tracing::info!(
        %addr,
        workers = args.workers.get(),
        data_dir = %app.data_dir.0.display(),
        max_connections = limits.max_connections,
        job_memory_mib = args.budgets.job_memory_bytes() >> 20,
        "tribosim serving on http://{addr} with its data in {}",
        app.data_dir.0.display()
    );
    let signal = tokio::spawn(async move {
        shutdown.await;
        tracing::info!("shutting down");
        stop.send_replace(true);
    });
    let router = router::router(app, cors, Arc::new(guard));
    listen::run(listener, router, &limits, stopped).await;
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

/// What the data directory holds, opened: the jobs, studies, surfaces and fits.
struct Stores {
    jobs: Arc<Jobs>,
    studies: Arc<Studies>,
    surfaces: Arc<Surfaces>,
    fits: CalibrationStore,
}

/// Opens the data directory's stores off the async threads (they read every stored file).
async fn open_stores(args: &ServeArgs) -> Result<Stores, ServeError> {
    let data_dir = args.data_dir.clone();
    let capacity = args.queue_capacity.get();
    let (max_members, workers) = (args.max_study_members.get(), args.workers.get());
    let upload_limits = UploadLimits {
        max_pixels: args.budgets.max_surface_pixels,
        parses: args.budgets.surface_parses.get(),
    };
    let memory_budget_bytes = args.budgets.job_memory_bytes();
    tokio::task::spawn_blocking(move || {
        let store = Store::open(&data_dir)?;
        let quarantine = store.quarantine_dir().to_owned();
        // Before the jobs load: a study interrupted as it was accepted takes its members.
        let studies = Studies::open(&data_dir, &quarantine, &store, max_members, workers)?;
        let surfaces = Arc::new(Surfaces::open(&data_dir, &quarantine, upload_limits)?);
        let jobs = Jobs::open(store, capacity, memory_budget_bytes, Arc::clone(&surfaces))?;
        let fits = CalibrationStore::open(&data_dir)?;
        Ok::<_, io::Error>(Stores {
            jobs,
            studies: Arc::new(studies),
            surfaces,
            fits,
        })
    })
    .await
    .map_err(io::Error::other)?
    .map_err(|source| ServeError::DataDir {
        path: args.data_dir.clone(),
        source,
    })
}

/// `asked`, with the connections lowered to what the limit on open files leaves room for
/// (said in the log when it does).
fn connection_limits(asked: &listen::Limits) -> listen::Limits {
    let mut limits = asked.clone();
    limits.max_connections = limits.connections_under(listen::open_files_limit());
    if limits.max_connections < asked.max_connections {
        tracing::warn!(
            "at most {} connections at once: the limit on open files leaves no room for {} \
             (raise it with `ulimit -n`)",
            limits.max_connections,
            asked.max_connections
        );
    }
    limits
}

/// The handlers' shared state: the stores, the token, and the limits of bodies and streams
/// (`stopped` ends the streams at shutdown).
fn app_state(
    args: &ServeArgs,
    stores: Stores,
    token: Option<String>,
    (limits, stopped): (&listen::Limits, &watch::Receiver<bool>),
) -> AppState {
    // Absolute, so that whoever started the server from some folder sees where it writes.
    let data_dir = std::fs::canonicalize(&args.data_dir)
        .or_else(|_| std::path::absolute(&args.data_dir))
        .unwrap_or_else(|_| args.data_dir.clone());
    let fit_limits = FitLimits {
        max_grid: args.budgets.calibration_max_grid,
        max_cell_cycles: args.budgets.calibration_max_cell_cycles,
        kept_bytes: args.budgets.calibration_kept_bytes,
    };
    AppState {
        jobs: stores.jobs,
        studies: stores.studies,
        calibrations: Arc::new(Calibrations::new(fit_limits, Some(stores.fits))),
        surfaces: stores.surfaces,
        token: token.map(Arc::from),
        static_dir: args.static_dir.as_deref().map(Arc::from),
        body_timeout: BodyTimeout(limits.body_timeout_s),
        streams: Streams {
            keep_alive: keep_alive_interval(limits.idle_timeout_s),
            shutdown: stopped.clone(),
        },
        data_dir: meta::DataDir(Arc::from(data_dir.as_path())),
        cursor_key: CursorKey::random(),
    }
}

/// An event stream's keep-alive comments come at most every 15 s (the usual interval) and
/// at least twice per idle timeout, so an idle connection's timer never closes a stream.
fn keep_alive_interval(idle_timeout_s: u64) -> Duration {
    Duration::from_secs(15).min(Duration::from_secs(idle_timeout_s) / 2)
}

impl ServeArgs {
    /// The token from `--token`, `TRIBOSIM_TOKEN` or the first line of `--token-file`,
    /// trimmed alike and checked: an empty `--token` or `TRIBOSIM_TOKEN` is none (an unset
    /// variable in a container's environment is often an empty one), a token file without
    /// one is an error, and so is a token that is not printable ASCII.
    fn token(&self) -> Result<Option<String>, ServeError> {
        let Some(path) = &self.token_file else {
            let token = self
                .token
                .as_deref()
                .map(str::trim)
                .filter(|t| !t.is_empty());
            return token
                .map(|token| printable(token, "--token or TRIBOSIM_TOKEN".to_owned()))
                .transpose();
        };
        if self.token.is_some() {
            return Err(ServeError::TokenTwice);
        }
        let text = std::fs::read_to_string(path).map_err(|source| ServeError::TokenFile {
            path: path.clone(),
            source,
        })?;
        match text.lines().next().map(str::trim).filter(|t| !t.is_empty()) {
            Some(token) => printable(token, format!("--token-file {}", path.display())).map(Some),
            None => Err(ServeError::TokenFileEmpty { path: path.clone() }),
        }
    }
}

/// `token` if every character is printable ASCII other than a space; otherwise the first
/// that is not, described without echoing the token (which may be a secret's neighbour).
fn printable(token: &str, from: String) -> Result<String, ServeError> {
    match token.chars().position(|c| !c.is_ascii_graphic()) {
        None => Ok(token.to_owned()),
        Some(index) => {
            let c = token.chars().nth(index).unwrap_or_default();
            let found = if c == ' ' {
                "a space".to_owned()
            } else if c.is_ascii_control() {
                format!("a control character (U+{:04X})", u32::from(c))
            } else {
                format!("a character outside ASCII (U+{:04X})", u32::from(c))
            };
            Err(ServeError::TokenNotAscii {
                from,
                found,
                position: index + 1,
            })
        }
    }
}

/// The token to require, if any; an error for a non-loopback address without one.
fn check_exposure(addr: SocketAddr, token: Option<&str>) -> Result<Option<String>, ServeError> {
    match token {
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
            .allow_methods([
                Method::GET,
                Method::POST,
                Method::PUT,
                Method::PATCH,
                Method::DELETE,
            ])
            .allow_headers([
                header::AUTHORIZATION,
                header::CONTENT_TYPE,
                HeaderName::from_static("last-event-id"),
            ])
            .expose_headers([header::LOCATION, header::RETRY_AFTER, header::LINK]),
    ))
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
