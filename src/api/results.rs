//! Results per robot serial: versioned parameter sets and their reports.

use axum::extract::{Path, State};
use axum::Json;
use serde::Serialize;
use serde_json::{Map, Value};
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::Paging;
use super::AppState;
use crate::domain::ParameterSetRecord;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(list_parameter_sets))
        .routes(routes!(get_parameter_set))
        .routes(routes!(get_report))
}

/// An identified parameter set: the stored document plus its identity.
#[derive(Debug, Serialize, ToSchema)]
pub struct ParameterSetOut {
    pub serial: String,
    pub version: i64,
    pub job_id: Option<String>,
    pub created_at: String,
    /// Kinematics, `target_to_base`, `flange_to_camera`, intrinsics, fixed parameters.
    #[serde(flatten)]
    #[schema(value_type = Object)]
    pub parameters: Map<String, Value>,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct ParameterSetList {
    pub items: Vec<ParameterSetOut>,
    pub next_cursor: Option<String>,
}

impl From<ParameterSetRecord> for ParameterSetOut {
    fn from(p: ParameterSetRecord) -> ParameterSetOut {
        let parameters = match p.parameters {
            Value::Object(map) => map,
            other => Map::from_iter([("parameters".to_string(), other)]),
        };
        ParameterSetOut {
            serial: p.serial,
            version: p.version,
            job_id: p.job_id,
            created_at: p.created_at,
            parameters,
        }
    }
}

/// `latest` or a positive integer.
fn parse_version(version: &str) -> ApiResult<Option<i64>> {
    if version == "latest" {
        return Ok(None);
    }
    match version.parse::<i64>() {
        Ok(v) if v >= 1 => Ok(Some(v)),
        _ => Err(ApiError::invalid(
            "version",
            "a positive integer or \"latest\"",
        )),
    }
}

async fn find(state: &AppState, serial: &str, version: &str) -> ApiResult<ParameterSetRecord> {
    let v = parse_version(version)?;
    state
        .store
        .get_parameter_set(serial, v)
        .await?
        .ok_or_else(|| ApiError::not_found("parameter set", &format!("{serial}/{version}")))
}

/// A robot's parameter sets, newest first.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("limit" = Option<i64>, Query, description = "Page size, 1 to 1000"),
           ("cursor" = Option<String>, Query, description = "next_cursor of the previous page")),
    responses((status = 200, body = ParameterSetList), (status = 422, body = Problem, content_type = "application/problem+json")))]
async fn list_parameter_sets(
    State(state): State<AppState>,
    Path(serial): Path<String>,
    paging: Paging,
) -> ApiResult<Json<ParameterSetList>> {
    let before = match paging.cursor.as_deref() {
        None => None,
        Some(c) => Some(
            c.parse::<i64>()
                .map_err(|_| ApiError::invalid("cursor", "not a cursor of this listing"))?,
        ),
    };
    let page = state
        .store
        .list_parameter_sets(&serial, paging.limit, before)
        .await?;
    Ok(Json(ParameterSetList {
        items: page.items.into_iter().map(Into::into).collect(),
        next_cursor: page.next_cursor,
    }))
}

/// One parameter set (`latest` allowed).
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets/{version}", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, description = "Version number or `latest`")),
    responses((status = 200, body = ParameterSetOut), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_parameter_set(
    State(state): State<AppState>,
    Path((serial, version)): Path<(String, String)>,
) -> ApiResult<Json<ParameterSetOut>> {
    Ok(Json(find(&state, &serial, &version).await?.into()))
}

/// The accuracy report of a parameter set.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets/{version}/report", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, description = "Version number or `latest`")),
    responses((status = 200, body = Object), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_report(
    State(state): State<AppState>,
    Path((serial, version)): Path<(String, String)>,
) -> ApiResult<Json<Value>> {
    let set = find(&state, &serial, &version).await?;
    let report = state
        .store
        .get_report(&serial, set.version)
        .await?
        .ok_or_else(|| ApiError::not_found("report", &format!("{serial}/{version}")))?;
    Ok(Json(report))
}
