//! The report routes: `GET /api/v1/jobs/{id}/report`, `GET /api/v1/report?jobs=ID,ID` and
//! `GET /api/v1/studies/{id}/report`, each a self-contained HTML file as a download, and
//! the API's answer to a report that cannot be made.

use std::collections::BTreeMap;
use std::sync::Arc;

use axum::extract::{FromRef, Query, State};
use axum::http::{HeaderValue, header};
use axum::response::Response;
use axum::routing::on;
use uuid::Uuid;

use crate::report::{FigureError, Labelled, Measured, comparison_report, run_report, study_report};
use crate::service::blocking::blocking;
use crate::service::error::ApiError;
use crate::service::extract::{JobId, StudyId, parse_id};
use crate::service::jobs::Jobs;
use crate::service::measurements;
use crate::service::origin::REPORT_POLICY;
use crate::service::reply::{attachment, download_name};
use crate::service::route::{Endpoint, Verb};
use crate::service::studies::Studies;
use crate::simulation::SimulationResult;

/// The most runs one comparison takes: past eight, the figures' lines and the tables'
/// columns no longer read on a printed page.
pub const MAX_COMPARED: usize = 8;

const HTML: &str = "text/html; charset=utf-8";

/// A report as a download named `filename`, with the content policy of a report (its
/// styles are inline, which the page's policy refuses).
fn report_file(filename: &str, html: String) -> Response {
    let mut response = attachment(HTML, filename, html);
    response.headers_mut().insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(REPORT_POLICY),
    );
    response
}

/// The routes, on any state that provides the jobs and the studies.
pub(crate) fn endpoints<S>() -> Vec<Endpoint<S>>
where
    S: Clone + Send + Sync + 'static,
    Arc<Jobs>: FromRef<S>,
    Arc<Studies>: FromRef<S>,
{
    vec![
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/report", |f| on(f, job_report)),
        Endpoint::api(Verb::Get, "/api/v1/report", |f| on(f, jobs_report)),
        Endpoint::api(Verb::Get, "/api/v1/studies/{id}/report", |f| {
            on(f, study_report_route)
        }),
    ]
}

/// A job's result, as any finished job gives it (a stopped run's partial one included).
fn result_of(jobs: &Jobs, id: Uuid) -> Result<SimulationResult, ApiError> {
    let bytes = jobs.result_json(id)?;
    serde_json::from_slice(&bytes).map_err(|e| ApiError::internal("reading a stored result", &e))
}

/// A job's measurements, in the report's terms.
fn measured_of(jobs: &Jobs, id: Uuid) -> Result<Measured, ApiError> {
    let tables = measurements::read(jobs, id)?;
    Ok(Measured {
        wear_volume: tables.wear_volume,
        profile: tables.profile,
        ocp: tables.ocp,
    })
}

/// `GET /api/v1/jobs/{id}/report`: the run's report with its measurements.
async fn job_report(State(jobs): State<Arc<Jobs>>, JobId(id): JobId) -> Result<Response, ApiError> {
    let name = jobs.find(id)?.record().name;
    let html = blocking(move || {
        let result = result_of(&jobs, id)?;
        let measured = measured_of(&jobs, id)?;
        Ok::<_, ApiError>(run_report(&result, &measured)?)
    })
    .await?;
    Ok(report_file(&download_name(&name, id, "report.html"), html))
}

/// The job ids of `?jobs=ID,ID,...`: two to [`MAX_COMPARED`], each once.
fn compared_ids(query: &BTreeMap<String, String>) -> Result<Vec<Uuid>, ApiError> {
    let listed = query.get("jobs").map(String::as_str).unwrap_or_default();
    let ids = listed
        .split(',')
        .filter(|part| !part.trim().is_empty())
        .map(|part| parse_id(part.trim(), "job"))
        .collect::<Result<Vec<_>, _>>()?;
    let mut unique = ids.clone();
    unique.sort_unstable();
    unique.dedup();
    if unique.len() != ids.len() {
        return Err(ApiError::bad_request("`jobs` names a job twice"));
    }
    if !(2..=MAX_COMPARED).contains(&ids.len()) {
        return Err(ApiError::bad_request(format!(
            "`jobs` lists the jobs to compare, separated by commas: 2 to {MAX_COMPARED} ids, not {}",
            ids.len()
        )));
    }
    Ok(ids)
}

/// `GET /api/v1/report?jobs=ID,ID`: the runs side by side.
async fn jobs_report(
    State(jobs): State<Arc<Jobs>>,
    Query(query): Query<BTreeMap<String, String>>,
) -> Result<Response, ApiError> {
    let ids = compared_ids(&query)?;
    let html = blocking(move || {
        let results = ids
            .iter()
            .map(|id| result_of(&jobs, *id))
            .collect::<Result<Vec<_>, _>>()?;
        let labels: Vec<String> = ids
            .iter()
            .zip(&results)
            .map(|(id, r)| format!("{} ({})", r.scene.name, &id.to_string()[..8]))
            .collect();
        let runs: Vec<Labelled<'_>> = labels
            .iter()
            .zip(&results)
            .map(|(label, result)| Labelled { label, result })
            .collect();
        Ok::<_, ApiError>(comparison_report(&runs)?)
    })
    .await?;
    // Several runs have no one name: the download is named for what it is, by the same rule.
    Ok(report_file("comparison.report.html", html))
}

/// `GET /api/v1/studies/{id}/report`: the study's table and figures, taken now.
async fn study_report_route(
    State(studies): State<Arc<Studies>>,
    State(jobs): State<Arc<Jobs>>,
    StudyId(id): StudyId,
) -> Result<Response, ApiError> {
    let (name, html) = blocking(move || {
        let name = studies.record(&jobs, id)?.name;
        let summary = studies.summary(&jobs, id)?;
        let html = study_report(&name, &summary)?;
        Ok::<_, ApiError>((name, html))
    })
    .await?;
    Ok(report_file(&download_name(&name, id, "report.html"), html))
}

/// A figure that plotters could not draw is the server's fault.
impl From<FigureError> for ApiError {
    fn from(error: FigureError) -> Self {
        Self::internal("drawing a report", &error)
    }
}
