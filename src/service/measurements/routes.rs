//! The routes of `/api/v1/jobs/{id}/measurements`, and the API's answer to each error of
//! measurements.

use std::sync::Arc;

use axum::Json;
use axum::body::Bytes;
use axum::extract::{FromRef, FromRequest, FromRequestParts, Path, Request, State};
use axum::http::HeaderMap;
use axum::http::request::Parts;
use axum::routing::on;
use uuid::Uuid;

use super::score::{Scores, scores, scores_csv};
use super::store::{self, MeasuredError};
use super::table::{self, Format, InvalidTable, MeasurementKind, Measurements, Renamed};
use crate::scene::FieldError;
use crate::service::blocking::blocking;
use crate::service::error::ApiError;
use crate::service::extract::{Body, BodyTimeout, JobId, cut, essence, is_json, parse_id};
use crate::service::jobs::{JobError, Jobs};
use crate::service::reply::{attachment, download_name, inline_json};
use crate::service::route::{Endpoint, Verb};
use crate::simulation::SimulationResult;

/// The routes, on any state that provides the jobs and the body timeout.
pub(crate) fn endpoints<S>() -> Vec<Endpoint<S>>
where
    S: Clone + Send + Sync + 'static,
    Arc<Jobs>: FromRef<S>,
    BodyTimeout: FromRef<S>,
{
    let table = "/api/v1/jobs/{id}/measurements/{kind}";
    vec![
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/measurements", |f| {
            on(f, get_measurements)
        }),
        Endpoint::api(Verb::Put, table, |f| on(f, put_measurement)),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/scores", |f| on(f, get_scores)),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/scores.csv", |f| {
            on(f, get_scores_csv)
        }),
        Endpoint::api(Verb::Delete, table, |f| on(f, delete_measurement)),
    ]
}

/// A job id and a measurement kind from the path (`.../jobs/{id}/measurements/{kind}`).
struct JobMeasurement(Uuid, MeasurementKind);

impl<S: Send + Sync> FromRequestParts<S> for JobMeasurement {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let Path((id, kind)) = Path::<(String, String)>::from_request_parts(parts, state).await?;
        let id = parse_id(&id, "job")?;
        let kind = MeasurementKind::from_name(&kind).ok_or_else(|| {
            let kinds: Vec<&str> = MeasurementKind::ALL.iter().map(|k| k.name()).collect();
            ApiError::bad_request(format!(
                "{:?} is not a kind of measurement ({})",
                cut(&kind),
                kinds.join(", ")
            ))
        })?;
        Ok(Self(id, kind))
    }
}

/// A table's body: CSV or JSON as its content type says (415 otherwise), read as every body
/// is ([`Body`]).
struct TableBody(Format, Bytes);

impl<S> FromRequest<S> for TableBody
where
    S: Send + Sync,
    BodyTimeout: FromRef<S>,
{
    type Rejection = ApiError;

    async fn from_request(request: Request, state: &S) -> Result<Self, ApiError> {
        let format = table_format(request.headers()).ok_or_else(|| {
            ApiError::unsupported_media_type(
                "a measurement table must be sent with `Content-Type: text/csv` or \
                 `application/json`",
            )
        })?;
        let Body(bytes) = Body::from_request(request, state).await?;
        Ok(Self(format, bytes))
    }
}

/// A measurement table's format: JSON as [`is_json`] has it, or `text/csv`.
fn table_format(headers: &HeaderMap) -> Option<Format> {
    if is_json(headers) {
        return Some(Format::Json);
    }
    (essence(headers)? == "text/csv").then_some(Format::Csv)
}

/// What a PUT answers: every table of the job, and the headers of the table sent that were
/// read under another name, so that a lab sees how its export was read.
#[derive(Debug, serde::Serialize)]
struct Stored {
    #[serde(flatten)]
    tables: Measurements,
    renamed: Vec<Renamed>,
}

/// `PUT /api/v1/jobs/{id}/measurements/{kind}`: reads, checks and stores a table; answers
/// every table of the job and the headers read under another name.
async fn put_measurement(
    State(jobs): State<Arc<Jobs>>,
    JobMeasurement(id, kind): JobMeasurement,
    TableBody(format, body): TableBody,
) -> Result<Json<Stored>, ApiError> {
    let read = table::parse(kind, format, &body)?;
    let columns = read.columns;
    let change = move |dir: &std::path::Path| store::write(dir, kind, columns);
    let tables = blocking(move || store::measured(&jobs, id, change)).await?;
    Ok(Json(Stored {
        tables,
        renamed: read.renamed,
    }))
}

/// `GET /api/v1/jobs/{id}/measurements`: every table of the job, null where none.
async fn get_measurements(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<Json<Measurements>, ApiError> {
    let unchanged = |_: &std::path::Path| Ok(());
    Ok(Json(
        blocking(move || store::measured(&jobs, id, unchanged)).await?,
    ))
}

/// Job `id`'s measurements scored against its result. Blocking (files).
fn scored(jobs: &Jobs, id: Uuid) -> Result<Scores, ApiError> {
    let measurements = store::measured(jobs, id, |_| Ok(()))?;
    let json = jobs.result_json(id)?;
    let result: SimulationResult = serde_json::from_slice(&json).map_err(JobError::Export)?;
    Ok(scores(&result, &measurements))
}

/// `GET /api/v1/jobs/{id}/scores`: each attached table against the job's result, shown
/// inline, and saved as `<name>.scores.json` as every download is named.
async fn get_scores(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<axum::response::Response, ApiError> {
    let name = jobs.find(id)?.record().name;
    let scores = blocking(move || scored(&jobs, id)).await?;
    Ok(inline_json(
        &download_name(&name, id, "scores.json"),
        Json(scores),
    ))
}

/// `GET /api/v1/jobs/{id}/scores.csv`: the scores as CSV, one row per measured point.
async fn get_scores_csv(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<axum::response::Response, ApiError> {
    let name = jobs.find(id)?.record().name;
    let csv = blocking(move || scored(&jobs, id).map(|s| scores_csv(&s))).await?;
    let filename = download_name(&name, id, "scores.csv");
    Ok(attachment("text/csv; charset=utf-8", &filename, csv))
}

/// `DELETE /api/v1/jobs/{id}/measurements/{kind}`: removes a table (if there is one);
/// answers every table left.
async fn delete_measurement(
    State(jobs): State<Arc<Jobs>>,
    JobMeasurement(id, kind): JobMeasurement,
) -> Result<Json<Measurements>, ApiError> {
    let change = move |dir: &std::path::Path| store::remove(dir, kind);
    Ok(Json(
        blocking(move || store::measured(&jobs, id, change)).await?,
    ))
}

/// 422 naming the column at fault (empty for the whole table).
impl From<InvalidTable> for ApiError {
    fn from(InvalidTable { kind, error }: InvalidTable) -> Self {
        let message = error.to_string();
        Self::unprocessable(
            format!("invalid {} table: {message}", kind.name()),
            vec![FieldError::new(error.column(), message)],
        )
    }
}

/// The job's own answers (404, 409 when damaged), 409 for a table damaged on disk, 507 when
/// the disk is full.
impl From<MeasuredError> for ApiError {
    fn from(error: MeasuredError) -> Self {
        match error {
            MeasuredError::Job(e) => e.into(),
            MeasuredError::Damaged(damage) if damage.is_read_failure() => {
                Self::internal("reading measurements", &damage)
            }
            MeasuredError::Damaged(damage) => Self::conflict(format!(
                "a stored measurement table is damaged ({damage}); PUT or DELETE it again"
            )),
            MeasuredError::Storage(e) => Self::storage(
                &e,
                "the measurements were not changed",
                "storing measurements",
            ),
        }
    }
}
