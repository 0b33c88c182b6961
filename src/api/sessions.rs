//! Measurement sessions: `/v1/robots/{serial}/sessions`, `/v1/sessions/{id}`.

use axum::extract::{Path, State};
use axum::http::StatusCode;
use axum::Json;
use serde::Serialize;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::{ApiJson, Paging, SerialPath};
use super::AppState;
use crate::schema::session::{CameraDoc, Instrument, SessionBody, TargetDoc};
use crate::schema::PoseDoc;
use crate::service::camera_reuse;
use crate::store::SessionRecord;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(create_session, list_sessions))
        .routes(routes!(get_session))
}

/// A session as served: its identity and the specification it was created
/// with.
#[derive(Debug, Serialize, ToSchema)]
pub struct SessionOut {
    pub id: String,
    pub serial: String,
    pub pose_count: i64,
    pub created_at: String,
    /// Served with the request's fields but documented as [`SessionSpecOut`]:
    /// the request schema forbids unknown fields, which this answer's `id`
    /// and others would violate.
    #[serde(flatten)]
    #[schema(value_type = SessionSpecOut)]
    pub spec: SessionBody,
}

/// The fields of [`SessionBody`] as they appear in a served session (its
/// response schema: open to the session's identity fields).
#[derive(Debug, ToSchema)]
#[allow(dead_code)] // a schema only: the answer serialises `SessionBody`
pub struct SessionSpecOut {
    pub instrument: Instrument,
    pub target: Option<TargetDoc>,
    pub camera: Option<CameraDoc>,
    pub flange_to_camera_guess: Option<PoseDoc>,
    /// The reused camera calibration, `latest` resolved to its version.
    pub camera_calibration_id: Option<String>,
    /// Where the board was placed in the workspace (free text).
    pub region: Option<String>,
    /// The measurement volume the poses span (free text).
    pub volume: Option<String>,
    /// Payload at the tool during the campaign (kg).
    pub payload_kg: Option<f64>,
    /// The controller the session was measured on: the one it
    /// was created with, else the robot's then.
    pub controller: Option<crate::domain::ControllerIdentity>,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct SessionList {
    pub items: Vec<SessionOut>,
    pub next_cursor: Option<String>,
}

impl TryFrom<SessionRecord> for SessionOut {
    type Error = ApiError;
    fn try_from(s: SessionRecord) -> ApiResult<SessionOut> {
        Ok(SessionOut {
            spec: s.spec,
            id: s.id,
            serial: s.serial,
            pose_count: s.pose_count,
            created_at: s.created_at,
        })
    }
}

/// Loads a session or answers 404.
pub async fn find_session(state: &AppState, id: &str) -> ApiResult<SessionRecord> {
    Ok(crate::service::intake::find_session(&state.store, id).await?)
}

/// Open a measurement session for a robot.
#[utoipa::path(post, path = "/v1/robots/{serial}/sessions", tag = "sessions",
    params(("serial" = String, Path, description = "Robot serial number")),
    request_body = SessionBody,
    responses((status = 201, description = "The created session", body = SessionOut),
              (status = 404, description = "No such robot, or no parameter set `camera_calibration_id`", body = Problem, content_type = "application/problem+json"),
              (status = 422, body = Problem, content_type = "application/problem+json")))]
async fn create_session(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    ApiJson(mut body): ApiJson<SessionBody>,
) -> ApiResult<(StatusCode, Json<SessionOut>)> {
    body.check()?;
    check_camera_pixels(&body, state.config.max_camera_pixels)?;
    if body.controller.is_none() {
        body.controller = crate::service::intake::robot_controller(&state.store, &serial).await?;
    }
    if let Some(id) = &body.camera_calibration_id {
        body.camera_calibration_id =
            Some(camera_reuse::resolve_for_session(&state.store, &body, id).await?);
    }
    let session = state
        .store
        .create_session(&serial, body.instrument.column(), &body)
        .await
        .map_err(|e| match e {
            crate::store::StoreError::NotFound(_) => ApiError::not_found("robot", &serial),
            e => e.into(),
        })?;
    Ok((StatusCode::CREATED, Json(session.try_into()?)))
}

/// A session camera over the server's pixel ceiling is refused: every
/// image of the session is decoded at that size.
fn check_camera_pixels(body: &SessionBody, max_pixels: u64) -> Result<(), ApiError> {
    let Some(camera) = &body.camera else {
        return Ok(());
    };
    let pixels = camera.width as u64 * camera.height as u64;
    if pixels > max_pixels {
        return Err(ApiError::invalid(
            "camera",
            format!(
                "{}x{} is {pixels} pixels; this server accepts at most {max_pixels} \
                 (server option --max-camera-pixels)",
                camera.width, camera.height
            ),
        ));
    }
    Ok(())
}

/// A robot's sessions, oldest first.
#[utoipa::path(get, path = "/v1/robots/{serial}/sessions", tag = "sessions",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("limit" = Option<i64>, Query, minimum = 1, maximum = 1000, description = "Page size, 1 to 1000 (default 100)"),
           ("cursor" = Option<String>, Query, description = "next_cursor of the previous page")),
    responses((status = 200, description = "One page of the robot's sessions, oldest first", body = SessionList), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn list_sessions(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    paging: Paging,
) -> ApiResult<Json<SessionList>> {
    if state.store.get_robot(&serial).await?.is_none() {
        return Err(ApiError::not_found("robot", &serial));
    }
    let page = state
        .store
        .list_sessions(&serial, paging.limit, paging.cursor.as_deref())
        .await?;
    Ok(Json(SessionList {
        items: page
            .items
            .into_iter()
            .map(SessionOut::try_from)
            .collect::<ApiResult<_>>()?,
        next_cursor: page.next_cursor,
    }))
}

/// One session.
#[utoipa::path(get, path = "/v1/sessions/{id}", tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses((status = 200, description = "The session", body = SessionOut), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_session(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Json<SessionOut>> {
    Ok(Json(find_session(&state, &id).await?.try_into()?))
}
