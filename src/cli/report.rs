//! `tribosim report`: a printable HTML report of a result, of several results side by side,
//! or of a study's summary, from their JSON files (`docs/report.md`).

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde_json::Value;

use tribosim::report::{Labelled, Measured, comparison_report, run_report, study_report};
use tribosim::service::{MeasurementKind, TableFormat, parse_measurements};
use tribosim::simulation::SimulationResult;
use tribosim::study::StudySummary;

use super::error::CliError;

/// The JSON of `path`.
fn read_json(path: &Path) -> Result<Value, CliError> {
    let text = std::fs::read_to_string(path).map_err(|source| CliError::File {
        action: "read",
        path: path.to_owned(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| CliError::NotA {
        path: path.to_owned(),
        what: "JSON",
        source,
    })
}

/// `document`, read from `path`, as `what`.
fn typed<T: DeserializeOwned>(
    document: Value,
    path: &Path,
    what: &'static str,
) -> Result<T, CliError> {
    serde_json::from_value(document).map_err(|source| CliError::NotA {
        path: path.to_owned(),
        what,
        source,
    })
}

/// The measurements given for a single run's report: the service's JSON of them all, and a
/// lab's table of each kind, as the service's `PUT .../measurements/{kind}` reads it.
#[derive(Default)]
pub struct MeasuredFiles<'a> {
    /// `--measurements`: `GET /api/v1/jobs/{id}/measurements`'s JSON.
    pub all: Option<&'a Path>,
    /// `--wear-volume`, `--profile`, `--ocp`: each a CSV or JSON table.
    pub tables: Vec<(MeasurementKind, &'a Path)>,
}

impl MeasuredFiles<'_> {
    fn is_empty(&self) -> bool {
        self.all.is_none() && self.tables.is_empty()
    }

    /// The measurements read: `all` first, then each kind's table in its place.
    fn read(&self) -> Result<Measured, CliError> {
        let mut measured = match self.all {
            Some(path) if is_csv(path) => return Err(CliError::MeasurementsCsv(path.to_owned())),
            Some(path) => typed::<Measured>(read_json(path)?, path, "a measurements table")?,
            None => Measured::default(),
        };
        for &(kind, path) in &self.tables {
            let option = kind.name().replace('_', "-");
            let bytes = std::fs::read(path).map_err(|source| CliError::File {
                action: "read",
                path: path.to_owned(),
                source,
            })?;
            // A table's format is its file's: JSON by its extension, CSV otherwise, as the
            // repository's own tables (`docs/calibration/*.csv`) are.
            let format = if path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("json"))
            {
                TableFormat::Json
            } else {
                TableFormat::Csv
            };
            let read =
                parse_measurements(kind, format, &bytes).map_err(|refused| CliError::Table {
                    kind: option,
                    path: path.to_owned(),
                    source: Box::new(refused.error),
                })?;
            for renamed in &read.renamed {
                eprintln!(
                    "note: {}: read the column `{}` as `{}`",
                    path.display(),
                    renamed.header,
                    renamed.column
                );
            }
            let slot = match kind {
                MeasurementKind::WearVolume => &mut measured.wear_volume,
                MeasurementKind::Profile => &mut measured.profile,
                MeasurementKind::Ocp => &mut measured.ocp,
            };
            *slot = Some(read.columns);
        }
        Ok(measured)
    }
}

/// Whether `path` names a CSV file.
fn is_csv(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
}

/// The file's name without its folder, to label a run by.
fn label(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The report of `inputs`: a study summary (a document with `axes` and `members`), one
/// result (with its `measurements`), or several results compared; written to `output`, or
/// standard output.
pub fn report(
    inputs: &[PathBuf],
    measurements: &MeasuredFiles<'_>,
    output: Option<&Path>,
) -> Result<(), CliError> {
    let documents = inputs
        .iter()
        .map(|p| read_json(p))
        .collect::<Result<Vec<_>, _>>()?;
    let is_study = |d: &Value| d.get("axes").is_some() && d.get("members").is_some();
    let html = match documents.as_slice() {
        [single] if is_study(single) => {
            if !measurements.is_empty() {
                return Err(CliError::MeasurementsAlone("a study"));
            }
            let study: StudySummary = typed(single.clone(), &inputs[0], "a study summary")?;
            let name = inputs[0]
                .file_stem()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
            study_report(&name, &study)?
        }
        _ => runs_report(documents, inputs, measurements)?,
    };
    match output {
        Some(path) => std::fs::write(path, html).map_err(|source| CliError::File {
            action: "write",
            path: path.to_owned(),
            source,
        }),
        None => {
            print!("{html}");
            Ok(())
        }
    }
}

/// The report of one result with its `measurements`, or of several compared.
fn runs_report(
    documents: Vec<Value>,
    inputs: &[PathBuf],
    measurements: &MeasuredFiles<'_>,
) -> Result<String, CliError> {
    let results = documents
        .into_iter()
        .zip(inputs)
        .map(|(d, path)| typed::<SimulationResult>(d, path, "a tribosim result"))
        .collect::<Result<Vec<_>, _>>()?;
    if let [result] = results.as_slice() {
        return Ok(run_report(result, &measurements.read()?)?);
    }
    if !measurements.is_empty() {
        return Err(CliError::MeasurementsAlone("a comparison"));
    }
    let labels: Vec<String> = inputs.iter().map(|p| label(p)).collect();
    let runs: Vec<Labelled<'_>> = labels
        .iter()
        .zip(&results)
        .map(|(label, result)| Labelled { label, result })
        .collect();
    Ok(comparison_report(&runs)?)
}
