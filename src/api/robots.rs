//! `/v1/robots`: robots with their joint tables.

use axum::extract::State;
use axum::http::StatusCode;
use axum::Json;
use robocal_calib::kinematics::prior::KinematicPrior;
use serde::Serialize;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::{ApiJson, Paging, SerialPath};
use super::AppState;
use crate::domain::{now_rfc3339, ControllerIdentity};
use crate::schema::robot::{KinematicsDoc, Preset, PriorDoc, RobotBody};
use crate::store::RobotRecord;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(list_robots))
        .routes(routes!(put_robot, get_robot, delete_robot))
}

/// A robot as served: the joint table actually used (conventions chosen).
#[derive(Debug, Serialize, ToSchema)]
pub struct RobotOut {
    pub serial: String,
    pub model: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub preset: Option<Preset>,
    pub kinematics: KinematicsDoc,
    /// The controller identity; absent when none was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub controller: Option<ControllerIdentity>,
    /// The prior on the kinematic deviations; absent: manufacturing
    /// tolerances (docs/method.md §6.7).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prior: Option<PriorDoc>,
    pub created_at: String,
    pub updated_at: String,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct RobotList {
    pub items: Vec<RobotOut>,
    pub next_cursor: Option<String>,
}

impl TryFrom<RobotRecord> for RobotOut {
    type Error = ApiError;
    fn try_from(r: RobotRecord) -> ApiResult<RobotOut> {
        Ok(RobotOut {
            kinematics: serde_json::from_value(r.kinematics).map_err(ApiError::internal)?,
            preset: r
                .preset
                .as_deref()
                .map(|p| {
                    Preset::parse(p)
                        .ok_or_else(|| ApiError::internal(format!("stored preset {p:?} unknown")))
                })
                .transpose()?,
            serial: r.serial,
            model: r.model,
            controller: r.controller,
            prior: r.prior.map(PriorDoc::from),
            created_at: r.created_at,
            updated_at: r.updated_at,
        })
    }
}

/// Create or replace a robot (joint table or preset).
#[utoipa::path(put, path = "/v1/robots/{serial}", tag = "robots",
    params(("serial" = String, Path, description = "Robot serial number: 1 to 64 characters of A-Z a-z 0-9 - _ . (not \".\" or \"..\")")),
    request_body = RobotBody,
    responses(
        (status = 201, description = "Created", body = RobotOut),
        (status = 200, description = "Replaced", body = RobotOut),
        (status = 422, description = "Invalid field", body = Problem, content_type = "application/problem+json"),
    ))]
async fn put_robot(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    ApiJson(body): ApiJson<RobotBody>,
) -> ApiResult<(StatusCode, Json<RobotOut>)> {
    let kinematics = body.resolve()?;
    let now = now_rfc3339();
    let record = RobotRecord {
        serial: serial.to_string(),
        model: body.model.trim().to_string(),
        preset: body.preset.map(|p| p.as_str().to_string()),
        kinematics: serde_json::to_value(&kinematics).map_err(ApiError::internal)?,
        controller: None,
        prior: body.prior.map(KinematicPrior::from),
        created_at: now.clone(),
        updated_at: now.clone(),
    };
    let created = state.store.put_robot(&record).await?;
    state
        .store
        .set_robot_controller(&serial, body.controller.as_ref(), &now)
        .await?;
    let stored = state
        .store
        .get_robot(&serial)
        .await?
        .ok_or_else(|| ApiError::not_found("robot", &serial))?;
    let status = if created {
        StatusCode::CREATED
    } else {
        StatusCode::OK
    };
    Ok((status, Json(stored.try_into()?)))
}

/// One robot.
#[utoipa::path(get, path = "/v1/robots/{serial}", tag = "robots",
    params(("serial" = String, Path, description = "Robot serial number")),
    responses((status = 200, description = "The robot with its joint table", body = RobotOut), (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 422, description = "Not a valid serial", body = Problem, content_type = "application/problem+json")))]
async fn get_robot(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
) -> ApiResult<Json<RobotOut>> {
    let robot = state
        .store
        .get_robot(&serial)
        .await?
        .ok_or_else(|| ApiError::not_found("robot", &serial))?;
    Ok(Json(robot.try_into()?))
}

/// Delete a robot with everything it had: sessions, poses, jobs, parameter
/// sets and reports, and the images no other robot's pose names. A robot
/// created later under the same serial starts empty.
#[utoipa::path(delete, path = "/v1/robots/{serial}", tag = "robots",
    params(("serial" = String, Path, description = "Robot serial number")),
    responses((status = 204, description = "Deleted"), (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 422, description = "Not a valid serial", body = Problem, content_type = "application/problem+json")))]
async fn delete_robot(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
) -> ApiResult<StatusCode> {
    if state.store.delete_robot(&serial).await? {
        Ok(StatusCode::NO_CONTENT)
    } else {
        Err(ApiError::not_found("robot", &serial))
    }
}

/// Robots by serial, paged with `?limit=&cursor=`.
#[utoipa::path(get, path = "/v1/robots", tag = "robots",
    params(("limit" = Option<i64>, Query, minimum = 1, maximum = 1000, description = "Page size, 1 to 1000 (default 100)"),
           ("cursor" = Option<String>, Query, description = "next_cursor of the previous page")),
    responses((status = 200, description = "One page of robots by serial; `next_cursor` fetches the next", body = RobotList)))]
async fn list_robots(State(state): State<AppState>, paging: Paging) -> ApiResult<Json<RobotList>> {
    let page = state
        .store
        .list_robots(paging.limit, paging.cursor.as_deref())
        .await?;
    Ok(Json(RobotList {
        items: page
            .items
            .into_iter()
            .map(RobotOut::try_from)
            .collect::<ApiResult<_>>()?,
        next_cursor: page.next_cursor,
    }))
}
