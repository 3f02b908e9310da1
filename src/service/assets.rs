//! The web page's files: every file of `static/` (the page and what it loads), built into the
//! binary so that `serve` works from any directory, and served with its content type; `/` is
//! `index.html`, the rest is under `/static/`. With `--static-dir DIR` the files are read
//! from DIR instead, for working on the page without rebuilding.

use std::borrow::Cow;
use std::io::ErrorKind;
use std::path::Path as FsPath;

use axum::extract::rejection::PathRejection;
use axum::extract::{Path, State};
use axum::http::header;
use axum::response::{IntoResponse, Response};
use axum::routing::on;

use super::error::ApiError;
use super::extract::cut;
use super::route::{Endpoint, Verb};
use super::state::AppState;

/// One file of the page: its path under `static/` (with `/` between folders) and its bytes.
pub(super) struct Asset {
    path: &'static str,
    bytes: &'static [u8],
}

/// The page's files, each by its path under `static/`.
macro_rules! assets {
    ($($path:literal),* $(,)?) => {
        &[$(Asset {
            path: $path,
            bytes: include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/static/", $path)),
        }),*]
    };
}

/// Every file of `static/`; a test walks the folder, so a file added there and not here
/// fails it.
const ASSETS: &[Asset] = assets![
    "index.html",
    "page.css",
    "js/api.js",
    "js/calibration.js",
    "js/compare.js",
    "js/dom.js",
    "js/export.js",
    "js/fig11.js",
    "js/form.js",
    "js/hash.js",
    "js/ids.js",
    "js/jobs.js",
    "js/labels.js",
    "js/main.js",
    "js/materials.js",
    "js/measurements.js",
    "js/plots.js",
    "js/pressure.js",
    "js/rig.js",
    "js/run-figures.js",
    "js/run.js",
    "js/scores.js",
    "js/scenes.js",
    "js/sse.js",
    "js/stroke.js",
    "js/studies.js",
    "js/svg.js",
    "js/topic.js",
    "js/uplot.js",
    "js/words.js",
    "vendor/uplot/LICENSE",
    "vendor/uplot/README.md",
    "vendor/uplot/uPlot.iife.min.js",
    "vendor/uplot/uPlot.min.css",
];

/// The page itself, served at `/`.
const INDEX: &str = "index.html";

/// Every answer is revalidated (`no-cache`): the page's files load one another, so a browser
/// must not mix a cached file of one build with a fresh one of another after an upgrade, and
/// a page edited under `--static-dir` shows on reload. The cost is every file again on each
/// load: about 70 kB gzip-compressed for the page, its styles, modules and uPlot (`gzip -c`
/// of each file).
pub(super) const CACHE_CONTROL: &str = "no-cache";

/// The page's routes: the page itself and its files.
pub(crate) fn endpoints() -> Vec<Endpoint<AppState>> {
    vec![
        Endpoint::public(Verb::Get, "/", |f| on(f, index)),
        Endpoint::public(Verb::Get, "/static/{*path}", |f| on(f, asset)),
    ]
}

/// `GET /`: the page.
async fn index(State(app): State<AppState>) -> Result<Response, ApiError> {
    page_file(&app, INDEX).await
}

/// `GET /static/{*path}`: one of the page's files, by its path under `static/`.
async fn asset(
    State(app): State<AppState>,
    path: Result<Path<String>, PathRejection>,
) -> Result<Response, ApiError> {
    let Path(path) = path?;
    page_file(&app, &path).await
}

/// The file at `path` under `static/` (built in) or under `--static-dir`, with its content
/// type; the JSON 404 for a path that names no file or is not a plain relative path.
async fn page_file(app: &AppState, path: &str) -> Result<Response, ApiError> {
    if !is_plain_relative(path) {
        return Err(no_such_file(path));
    }
    let bytes: Cow<'static, [u8]> = match &app.static_dir {
        None => Cow::Borrowed(built_in(path).ok_or_else(|| no_such_file(path))?),
        Some(dir) => Cow::Owned(read_from(dir, path).await?),
    };
    Ok((
        [
            (header::CONTENT_TYPE, content_type(path)),
            (header::CACHE_CONTROL, CACHE_CONTROL),
        ],
        bytes,
    )
        .into_response())
}

fn no_such_file(path: &str) -> ApiError {
    ApiError::not_found(format!("the page has no file {:?}", cut(path)))
}

/// The built-in bytes of the file at `path` under `static/`.
fn built_in(path: &str) -> Option<&'static [u8]> {
    ASSETS
        .iter()
        .find(|asset| asset.path == path)
        .map(|asset| asset.bytes)
}

/// The file at `path` under `dir`; `path` must be plain and relative ([`is_plain_relative`]).
async fn read_from(dir: &FsPath, path: &str) -> Result<Vec<u8>, ApiError> {
    let file = dir.join(path);
    match tokio::fs::read(&file).await {
        Ok(bytes) => Ok(bytes),
        Err(e)
            if matches!(
                e.kind(),
                ErrorKind::NotFound | ErrorKind::IsADirectory | ErrorKind::NotADirectory
            ) =>
        {
            Err(ApiError::not_found(format!(
                "no page: {} is missing (see --static-dir)",
                file.display()
            )))
        }
        Err(e) => Err(ApiError::internal("reading the page", &e)),
    }
}

/// Whether `path` stays inside the folder it is joined to: relative (no leading `/`), with
/// no empty, `.` or `..` segment, and no `\` or `:` (a separator and a drive on Windows) or
/// NUL in it.
fn is_plain_relative(path: &str) -> bool {
    path.split('/').all(|segment| {
        !segment.is_empty()
            && segment != "."
            && segment != ".."
            && !segment.contains(['\\', ':', '\0'])
    })
}

/// The content type of a page file, by its extension; a file without one (`LICENSE`) is
/// text. Unknown extensions are sent as bytes; a test keeps every built-in file known.
fn content_type(path: &str) -> &'static str {
    let name = path.rsplit('/').next().unwrap_or(path);
    match name.rsplit_once('.').map(|(_, extension)| extension) {
        Some("html") => "text/html; charset=utf-8",
        Some("js") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("md") => "text/markdown; charset=utf-8",
        Some("txt") | None => "text/plain; charset=utf-8",
        Some("json") => "application/json",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some(_) => "application/octet-stream",
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;
    use std::path::PathBuf;

    use axum::http::StatusCode;

    use super::*;

    fn static_dir() -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("static")
    }

    /// The paths of the files under `dir`, relative to `root`, with `/` between folders.
    fn files_under(root: &FsPath, dir: &FsPath, out: &mut BTreeSet<String>) {
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
                out.insert(parts.join("/"));
            }
        }
    }

    #[test]
    fn every_file_of_static_is_built_in_and_nothing_else() {
        let mut on_disk = BTreeSet::new();
        files_under(&static_dir(), &static_dir(), &mut on_disk);
        let built_in: BTreeSet<String> = ASSETS.iter().map(|a| a.path.to_owned()).collect();
        assert_eq!(built_in.len(), ASSETS.len(), "a file listed twice");
        let missing: Vec<_> = on_disk.difference(&built_in).collect();
        let extra: Vec<_> = built_in.difference(&on_disk).collect();
        assert!(
            missing.is_empty(),
            "files of static/ not built in: {missing:?}"
        );
        assert!(extra.is_empty(), "built-in files not in static/: {extra:?}");
        assert!(built_in.contains(INDEX));
    }

    #[test]
    fn every_built_in_file_has_its_content_type() {
        for asset in ASSETS {
            assert_ne!(
                content_type(asset.path),
                "application/octet-stream",
                "{}: no content type for its extension",
                asset.path
            );
        }
        // Browsers run a module script only with a JavaScript type.
        assert_eq!(content_type("js/main.js"), "text/javascript; charset=utf-8");
        assert_eq!(content_type(INDEX), "text/html; charset=utf-8");
        assert_eq!(content_type("page.css"), "text/css; charset=utf-8");
        assert_eq!(
            content_type("vendor/uplot/LICENSE"),
            "text/plain; charset=utf-8"
        );
        assert_eq!(content_type("font.woff2"), "application/octet-stream");
    }

    #[test]
    fn only_plain_relative_paths_are_looked_up() {
        for good in [
            "index.html",
            "js/main.js",
            "vendor/uplot/uPlot.min.css",
            "a.b.c",
        ] {
            assert!(is_plain_relative(good), "{good}");
        }
        for bad in [
            "",
            "/etc/passwd",
            "..",
            "../Cargo.toml",
            "js/../../Cargo.toml",
            "js/./main.js",
            "js//main.js",
            "js/",
            "..\\Cargo.toml",
            "C:/Windows",
            "js/main.js\0",
        ] {
            assert!(!is_plain_relative(bad), "{bad:?}");
        }
    }

    #[test]
    fn built_in_files_are_found_by_their_path() {
        let styles = built_in("vendor/uplot/uPlot.min.css").expect("uPlot's styles are built in");
        let on_disk = std::fs::read(static_dir().join("vendor/uplot/uPlot.min.css")).expect("read");
        assert_eq!(styles, on_disk.as_slice());
        assert!(built_in("vendor/uplot/nope.css").is_none());
        assert!(built_in("uPlot.min.css").is_none());
    }

    #[tokio::test]
    async fn a_static_dir_serves_its_files_and_only_those() {
        let root = std::env::temp_dir().join(format!("tribosim-assets-{}", uuid::Uuid::new_v4()));
        let dir = root.join("page");
        std::fs::create_dir_all(dir.join("js")).expect("create the folders");
        std::fs::write(dir.join("js/main.js"), "draft").expect("write a module");
        std::fs::write(root.join("secret"), "outside").expect("write a file outside");

        assert_eq!(
            read_from(&dir, "js/main.js").await.expect("served"),
            b"draft"
        );
        for missing in ["js/nope.js", "js", "js/main.js/more"] {
            let error = read_from(&dir, missing).await.expect_err(missing);
            assert_eq!(
                error.into_response().status(),
                StatusCode::NOT_FOUND,
                "{missing}"
            );
        }
        // The file exists, one folder up: the path is refused before any file is read.
        assert!(dir.join("../secret").exists());
        assert!(!is_plain_relative("../secret"));
        std::fs::remove_dir_all(&root).expect("clean up");
    }
}
