//! Calibration jobs: `POST /v1/sessions/{id}/calibrations`,
//! `POST /v1/robots/{serial}/calibrations` (several sessions), `GET /v1/jobs`
//! (newest first, filtered by state, serial and kind) and `/v1/jobs/{id}`.
//! A job's live events are `job_events.rs`.

use axum::extract::{Path, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Serialize;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::{ApiJson, JobQuery, OptionalJson, Paging, SerialPath};
use super::sessions::find_session;
use super::AppState;
use crate::domain::{JobKind, JobResult, JobState};
use crate::schema::job::{CalibrationOptions, JobOptions};
use crate::store::JobRecord;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(start_calibration))
        .routes(routes!(start_robot_calibration))
        .routes(routes!(list_jobs))
        .routes(routes!(get_job, cancel_job))
}

#[derive(Debug, Serialize, ToSchema)]
pub struct JobOut {
    pub id: String,
    pub kind: JobKind,
    pub session_id: String,
    pub serial: String,
    pub state: JobState,
    pub stage: Option<String>,
    /// 0..1 over the whole job.
    pub progress: f64,
    pub attempts: i64,
    pub max_attempts: i64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// A succeeded job's result: its `summary`, `serial` and `version`
    /// when it stored a parameter set, and a re-check's verdict.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub result: Option<JobResult>,
    /// The job's options, by its kind.
    pub options: JobOptions,
    pub created_at: String,
    pub started_at: Option<String>,
    pub finished_at: Option<String>,
}

impl From<JobRecord> for JobOut {
    fn from(j: JobRecord) -> JobOut {
        JobOut {
            id: j.id,
            kind: j.kind,
            session_id: j.session_id,
            serial: j.serial,
            state: j.state,
            stage: j.stage,
            progress: j.progress,
            attempts: j.attempts,
            max_attempts: j.max_attempts,
            error: j.error,
            result: j.result,
            options: j.options,
            created_at: j.created_at,
            started_at: j.started_at,
            finished_at: j.finished_at,
        }
    }
}

/// A page of jobs, newest first.
#[derive(Debug, Serialize, ToSchema)]
pub struct JobList {
    pub items: Vec<JobOut>,
    /// Pass as `cursor` for the next (older) page; `null` on the last page.
    pub next_cursor: Option<String>,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct JobAccepted {
    pub job_id: String,
    #[serde(flatten)]
    pub job: JobOut,
}

impl JobAccepted {
    /// `202 Accepted` with `Location: /v1/jobs/{id}` and the queued job.
    pub fn response(job: JobRecord) -> Response {
        let location = format!("/v1/jobs/{}", job.id);
        (
            StatusCode::ACCEPTED,
            [(header::LOCATION, location)],
            Json(JobAccepted {
                job_id: job.id.clone(),
                job: job.into(),
            }),
        )
            .into_response()
    }
}

/// Queue a calibration of the session. Answers 429 with `Retry-After` when
/// the queue is full (nothing is written then).
#[utoipa::path(post, path = "/v1/sessions/{id}/calibrations", tag = "jobs",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = Option<CalibrationOptions>, content_type = "application/json", description = "Optional: all fields optional, and no body (or an empty one) takes the defaults"),
    responses((status = 202, description = "The job is queued; `Location` is its URL", body = JobAccepted, headers(("Location" = String, description = "/v1/jobs/{job_id}"))),
              (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "A partial `scope` (`base`, `hand_eye`) and the robot has no approved parameter set to hold (names `scope`)", body = Problem, content_type = "application/problem+json"),
              (status = 422, body = Problem, content_type = "application/problem+json"),
              (status = 429, description = "The queue is full (`--max-queued`): retry after `Retry-After` seconds", body = Problem, content_type = "application/problem+json")))]
async fn start_calibration(
    State(state): State<AppState>,
    Path(id): Path<String>,
    OptionalJson(options): OptionalJson<CalibrationOptions>,
) -> ApiResult<Response> {
    let session = find_session(&state, &id).await?;
    let job =
        crate::service::checks::start_calibration(&state.store, &state.policy, &session, &options)
            .await?;
    state.wake.notify_one();
    Ok(JobAccepted::response(job))
}

/// Queue one calibration over several sessions of the robot:
/// each session one board placement (region); one kinematic model and
/// hand–eye, one `target_to_base` per session, shared intrinsics. One
/// session is that session's own calibration.
#[utoipa::path(post, path = "/v1/robots/{serial}/calibrations", tag = "jobs",
    params(("serial" = String, Path, description = "Robot serial number")),
    request_body(content = CalibrationOptions, content_type = "application/json", description = "`sessions` (required, at least one) and the other calibration options"),
    responses((status = 202, description = "The job is queued; `Location` is its URL", body = JobAccepted, headers(("Location" = String, description = "/v1/jobs/{job_id}"))),
              (status = 422, description = "`sessions` empty, naming an unknown session or one of another robot (the problem names it), or an option a multi-session fit cannot take", body = Problem, content_type = "application/problem+json"),
              (status = 429, description = "The queue is full (`--max-queued`): retry after `Retry-After` seconds", body = Problem, content_type = "application/problem+json")))]
async fn start_robot_calibration(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    ApiJson(options): ApiJson<CalibrationOptions>,
) -> ApiResult<Response> {
    let job = crate::service::multi_session::start_robot_calibration(
        &state.store,
        &state.policy,
        serial.as_str(),
        &options,
    )
    .await?;
    state.wake.notify_one();
    Ok(JobAccepted::response(job))
}

/// All jobs of every session, newest first, so one can see what runs;
/// `state`, `serial` and `kind` narrow the list (together: all must hold).
#[utoipa::path(get, path = "/v1/jobs", tag = "jobs",
    params(("limit" = Option<i64>, Query, description = "Page size, 1 to 1000 (default 100)"),
           ("cursor" = Option<String>, Query, description = "next_cursor of the previous page"),
           ("state" = Option<String>, Query, description = "Only jobs in this state: queued, running, succeeded, failed or cancelled"),
           ("serial" = Option<String>, Query, description = "Only jobs of this robot"),
           ("kind" = Option<String>, Query, description = "Only jobs of this kind (`calibration`)")),
    responses((status = 200, body = JobList, description = "A page of jobs, newest first"),
              (status = 401, body = Problem, content_type = "application/problem+json", description = "No or unknown token"),
              (status = 422, body = Problem, content_type = "application/problem+json", description = "Invalid limit, cursor, state, serial or kind (the problem names it)")))]
async fn list_jobs(
    State(state): State<AppState>,
    paging: Paging,
    JobQuery(filter): JobQuery,
) -> ApiResult<Json<JobList>> {
    let page = state
        .store
        .list_jobs(&filter, paging.limit, paging.cursor.as_deref())
        .await?;
    Ok(Json(JobList {
        items: page.items.into_iter().map(JobOut::from).collect(),
        next_cursor: page.next_cursor,
    }))
}

/// A job's state, stage, progress and result.
#[utoipa::path(get, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses((status = 200, description = "The job: state, stage, progress (0..1) and, once it ended, its result or error", body = JobOut), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_job(State(state): State<AppState>, Path(id): Path<String>) -> ApiResult<Json<JobOut>> {
    let job = state
        .store
        .get_job(&id)
        .await?
        .ok_or_else(|| ApiError::not_found("job", &id))?;
    Ok(Json(job.into()))
}

/// Cancel a queued or running job (409 when it has already finished).
#[utoipa::path(delete, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses((status = 200, description = "The job, now cancelled (a running job stops at its next stage boundary)", body = JobOut),
              (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The job has already ended", body = Problem, content_type = "application/problem+json")))]
async fn cancel_job(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Json<JobOut>> {
    let job = state
        .store
        .cancel_job(&id)
        .await?
        .ok_or_else(|| ApiError::not_found("job", &id))?;
    Ok(Json(job.into()))
}
