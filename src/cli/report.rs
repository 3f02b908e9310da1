//! `tribosim report`: a printable HTML report of a result, of several results side by side,
//! or of a study's summary, from their JSON files (`docs/report.md`).

use std::path::{Path, PathBuf};

use serde_json::Value;

use tribosim::report::{Labelled, Measured, comparison_report, run_report, study_report};
use tribosim::simulation::SimulationResult;
use tribosim::study::StudySummary;

/// The JSON of `path`.
fn read_json(path: &Path) -> Result<Value, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{} is not JSON: {e}", path.display()))
}

/// The file's name without its folder, to label a run by.
fn label(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The report of `inputs`: a study summary (a document with `axes` and `members`), one
/// result (with `measurements`, the table `GET /api/v1/jobs/{id}/measurements` answers),
/// or several results compared; written to `output`, or standard output.
pub fn report(
    inputs: &[PathBuf],
    measurements: Option<&Path>,
    output: Option<&Path>,
) -> Result<(), String> {
    let documents = inputs
        .iter()
        .map(|p| read_json(p))
        .collect::<Result<Vec<_>, _>>()?;
    let is_study = |d: &Value| d.get("axes").is_some() && d.get("members").is_some();
    let html = match documents.as_slice() {
        [single] if is_study(single) => {
            if measurements.is_some() {
                return Err("--measurements goes with a single run's result, not a study".into());
            }
            let study: StudySummary = serde_json::from_value(single.clone())
                .map_err(|e| format!("{} is not a study summary: {e}", inputs[0].display()))?;
            let name = inputs[0]
                .file_stem()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
            study_report(&name, &study)
        }
        _ => {
            let results = documents
                .into_iter()
                .zip(inputs)
                .map(|(d, path)| {
                    serde_json::from_value::<SimulationResult>(d)
                        .map_err(|e| format!("{} is not a tribosim result: {e}", path.display()))
                })
                .collect::<Result<Vec<_>, _>>()?;
            if let [result] = results.as_slice() {
                let measured = match measurements {
                    Some(path) => {
                        serde_json::from_value::<Measured>(read_json(path)?).map_err(|e| {
                            format!("{} is not a measurements table: {e}", path.display())
                        })?
                    }
                    None => Measured::default(),
                };
                run_report(result, &measured)
            } else {
                if measurements.is_some() {
                    return Err(
                        "--measurements goes with a single run's result, not a comparison".into(),
                    );
                }
                let labels: Vec<String> = inputs.iter().map(|p| label(p)).collect();
                let runs: Vec<Labelled<'_>> = labels
                    .iter()
                    .zip(&results)
                    .map(|(label, result)| Labelled { label, result })
                    .collect();
                comparison_report(&runs)
            }
        }
    }
    .map_err(|e| e.to_string())?;
    match output {
        Some(path) => {
            std::fs::write(path, html).map_err(|e| format!("cannot write {}: {e}", path.display()))
        }
        None => {
            print!("{html}");
            Ok(())
        }
    }
}
