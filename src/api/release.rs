//! The release gate and a fleet over time (issue 17): approve or reject a
//! parameter set, a robot's history, and quick re-checks of a session
//! against the robot's latest approved set.

use axum::extract::{Path, Query, State};
use axum::response::Response;
use axum::{Extension, Json};
use serde::Deserialize;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::auth::Principal;
use super::controller_query::ControllerQuery;
use super::error::{ApiResult, Problem};
use super::extract::{OptionalJson, SerialPath};
use super::jobs::JobAccepted;
use super::results::ParameterSetOut;
use super::sessions::find_session;
use super::AppState;
use crate::domain::{controller_expectation, ControllerIdentity, ReleaseStatus, ANONYMOUS_ACTOR};
use crate::service::{checks, release};

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(approve))
        .routes(routes!(reject))
        .routes(routes!(history))
        .routes(routes!(start_check))
}

/// `approve` / `reject` body; optional.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct DecisionBody {
    /// Why (recorded with the decision); default "approved by {who}".
    #[serde(default)]
    pub reason: Option<String>,
}

/// Most characters of a decision's reason.
const MAX_REASON_CHARS: usize = 2000;

fn actor(principal: Option<Extension<Principal>>) -> String {
    principal
        .map(|Extension(p)| p.actor())
        .unwrap_or_else(|| ANONYMOUS_ACTOR.to_string())
}

async fn decide(
    state: &AppState,
    serial: &str,
    version: &str,
    status: ReleaseStatus,
    principal: Option<Extension<Principal>>,
    body: DecisionBody,
) -> ApiResult<Json<ParameterSetOut>> {
    if body
        .reason
        .as_ref()
        .is_some_and(|r| r.chars().count() > MAX_REASON_CHARS)
    {
        return Err(super::error::ApiError::invalid(
            "reason",
            format!("at most {MAX_REASON_CHARS} characters"),
        ));
    }
    let actor = actor(principal);
    let record =
        release::decide(&state.store, serial, version, status, &actor, body.reason).await?;
    Ok(Json(record.into()))
}

/// Approve a parameter set: `latest` serves the newest approved set.
#[utoipa::path(post, path = "/v1/robots/{serial}/parameter-sets/{version}/approve", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^[1-9][0-9]{0,17}$", description = "Version number")),
    request_body(content = Option<DecisionBody>, content_type = "application/json", description = "Optional: the reason recorded"),
    responses((status = 200, description = "The set, now `approved`; the decision is recorded with who (token id and name, or `anonymous`) and when", body = ParameterSetOut),
              (status = 404, description = "No such robot, or the robot has no such version (`errors` names `version`: e.g. a version of another robot)", body = Problem, content_type = "application/problem+json")))]
async fn approve(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    principal: Option<Extension<Principal>>,
    OptionalJson(body): OptionalJson<DecisionBody>,
) -> ApiResult<Json<ParameterSetOut>> {
    decide(
        &state,
        &serial,
        &version,
        ReleaseStatus::Approved,
        principal,
        body,
    )
    .await
}

/// Reject a parameter set: kept for the record, never served as `latest`.
#[utoipa::path(post, path = "/v1/robots/{serial}/parameter-sets/{version}/reject", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^[1-9][0-9]{0,17}$", description = "Version number")),
    request_body(content = Option<DecisionBody>, content_type = "application/json", description = "Optional: the reason recorded"),
    responses((status = 200, description = "The set, now `rejected`; the decision is recorded with who and when", body = ParameterSetOut),
              (status = 404, description = "No such robot, or the robot has no such version (`errors` names `version`)", body = Problem, content_type = "application/problem+json")))]
async fn reject(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    principal: Option<Extension<Principal>>,
    OptionalJson(body): OptionalJson<DecisionBody>,
) -> ApiResult<Json<ParameterSetOut>> {
    decide(
        &state,
        &serial,
        &version,
        ReleaseStatus::Rejected,
        principal,
        body,
    )
    .await
}

/// A robot over time: approved versions with each kinematic parameter's
/// change in σ units, every approve/reject decision with who and when,
/// and the re-checks' verdicts.
#[utoipa::path(get, path = "/v1/robots/{serial}/history", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number")),
    responses((status = 200, description = "The robot's history", body = release::History),
              (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn history(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
) -> ApiResult<Json<release::History>> {
    Ok(Json(release::history(&state.store, &serial).await?))
}

/// A re-check's options: only the controller the caller expects.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CheckBody {
    /// The controller the caller expects the approved set to be made on:
    /// 409 naming `controller` when it records another.
    #[serde(default)]
    pub expect_controller: Option<ControllerIdentity>,
}

/// Queue a quick re-check of the session (5–10 poses, camera or tracker)
/// against the robot's latest approved set. The job's `result` holds
/// `verdict` (`pass`, `drift`, `base_moved`, or `controller_changed` when
/// the session was measured on another controller than the set's), `mean_mm`,
/// `expected_mean_mm`, `p_value` and `suspects` (see `CheckDoc`).
#[utoipa::path(post, path = "/v1/sessions/{id}/checks", tag = "jobs",
    params(("id" = String, Path, description = "Session id"), ControllerQuery),
    request_body(content = Option<CheckBody>, content_type = "application/json", description = "Optional: `{}` or `{\"expect_controller\": {…}}`"),
    responses((status = 202, description = "The check is queued; `Location` is its job (result: `CheckDoc`)", body = JobAccepted, headers(("Location" = String, description = "/v1/jobs/{job_id}"))),
              (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The robot has no approved parameter set to check against (`errors` names `serial`), or the set was made on another controller than `expect_controller` / `controller_serial` (`errors` names `controller`, the problem's `controller` both identities)", body = Problem, content_type = "application/problem+json"),
              (status = 429, description = "The queue is full (`--max-queued`): retry after `Retry-After` seconds", body = Problem, content_type = "application/problem+json")))]
async fn start_check(
    State(state): State<AppState>,
    Path(id): Path<String>,
    Query(query): Query<ControllerQuery>,
    OptionalJson(body): OptionalJson<CheckBody>,
) -> ApiResult<Response> {
    let expect = controller_expectation(
        body.expect_controller.as_ref(),
        query.controller_serial.as_deref(),
    )?;
    let session = find_session(&state, &id).await?;
    let job = checks::start_check(&state.store, &state.policy, &session, expect.as_ref()).await?;
    state.wake.notify_one();
    Ok(JobAccepted::response(job))
}
