//! Printable reports: one self-contained HTML file (inline SVG figures, inline CSS, nothing
//! fetched, nothing run) of a run, a comparison of runs or a study, that prints to A4 and
//! Letter. Plain synchronous code from results to text; the service and the command line
//! decide where the text goes. See `docs/report.md`.

mod compare;
mod figure;
mod html;
mod methods;
mod palette;
mod pressure_map;
mod residuals;
mod run;
mod run_figures;
mod scene;
mod stroke_figures;
mod study;
mod ticks;
mod wear_map;

pub use compare::{Labelled, comparison_report};
pub use figure::FigureError;
pub use residuals::{Columns, Measured, Residual, residuals};
pub use run::run_report;
pub use study::study_report;
