//! The guides, `docs/*.md` of the source, built into the binary and served at
//! `/docs/{name}`: an installed `tribosim` has no source tree, so its help points at a
//! running server's copy (`http://127.0.0.1:8080/docs/scene.md`), which always matches the
//! binary that serves it.

use axum::extract::Path;
use axum::extract::rejection::PathRejection;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use axum::routing::on;

use super::assets::CACHE_CONTROL;
use super::error::ApiError;
use super::extract::cut;
use super::route::{Endpoint, Verb};
use super::state::AppState;

/// The guides, each by its file name under `docs/`.
macro_rules! guides {
    ($($name:literal),* $(,)?) => {
        &[$((
            $name,
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/", $name)),
        )),*]
    };
}

/// Every `docs/*.md`; a test reads the folder, so a guide added there and not here fails it.
const GUIDES: &[(&str, &str)] = guides![
    "accuracy.md",
    "architecture.md",
    "calibration.md",
    "cluster.md",
    "corrosion.md",
    "materials.md",
    "notebook.md",
    "operations.md",
    "paper.md",
    "peers.md",
    "report.md",
    "result.md",
    "rig-accuracy.md",
    "scene.md",
    "stability.md",
    "study.md",
    "table3.md",
    "verification.md",
];

/// The guides' route.
pub(crate) fn endpoints() -> Vec<Endpoint<AppState>> {
    vec![Endpoint::public(Verb::Get, "/docs/{name}", |f| {
        on(f, guide)
    })]
}

/// `GET /docs/{name}`: one guide as Markdown; the JSON 404 lists the guides there are.
async fn guide(name: Result<Path<String>, PathRejection>) -> Result<Response, ApiError> {
    let Path(name) = name?;
    let text = GUIDES
        .iter()
        .find(|(file, _)| *file == name)
        .map(|(_, text)| *text)
        .ok_or_else(|| {
            let names: Vec<&str> = GUIDES.iter().map(|(file, _)| *file).collect();
            ApiError::not_found(format!(
                "no guide {:?}; the guides are {}",
                cut(&name),
                names.join(", ")
            ))
        })?;
    Ok((
        [
            (header::CONTENT_TYPE, "text/markdown; charset=utf-8"),
            (header::CACHE_CONTROL, CACHE_CONTROL),
        ],
        text,
    )
        .into_response())
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;
    use std::path::PathBuf;

    use super::GUIDES;

    #[test]
    fn every_guide_of_the_docs_folder_is_built_in_as_it_is() {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs");
        let on_disk: BTreeSet<String> = std::fs::read_dir(&dir)
            .expect("docs/")
            .map(|entry| {
                entry
                    .expect("an entry")
                    .file_name()
                    .to_string_lossy()
                    .into_owned()
            })
            .filter(|name| name.ends_with(".md"))
            .collect();
        let built_in: BTreeSet<String> =
            GUIDES.iter().map(|(name, _)| (*name).to_owned()).collect();
        assert_eq!(built_in, on_disk);
        for (name, text) in GUIDES {
            let file = std::fs::read_to_string(dir.join(name)).expect("a guide");
            assert!(file == *text, "docs/{name} differs from its built-in copy");
        }
    }
}
