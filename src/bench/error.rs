//! Why a benchmark or its report failed.

use std::path::PathBuf;

use plotters::drawing::DrawingAreaErrorKind;

use crate::contact::ContactError;
use crate::simulation::SimulationError;
use crate::surface::SurfaceError;

/// Why `tribosim bench` failed.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// A contact solve of the contact or coupling studies.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// A wear run of the paper-scene studies.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// The rough-surface study's surface could not be generated.
    #[error(transparent)]
    Surface(#[from] SurfaceError),
    /// A row could not be written as JSON.
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// The report's path has no file name to name its plot folder after.
    #[error("{}: not a file name", .0.display())]
    NotAFile(PathBuf),
    /// The report or its plot folder could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// What the file system said.
        source: std::io::Error,
    },
    /// A page lacks the markers of the section a study rewrites.
    #[error("{}: no `{begin}` ... `{end}` section to rewrite", path.display())]
    NoSection {
        /// The page.
        path: PathBuf,
        /// The first marker.
        begin: &'static str,
        /// The last marker.
        end: &'static str,
    },
    /// A plot could not be drawn.
    #[error("plot {}: {source}", path.display())]
    Plot {
        /// The SVG file.
        path: PathBuf,
        /// What the plotting library said.
        source: DrawingAreaErrorKind<std::io::Error>,
    },
}
