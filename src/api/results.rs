//! Results per robot serial: versioned parameter sets and their reports.

use axum::extract::{Path, Query, State};
use axum::Json;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use axum::http::{header, HeaderMap};
use axum::response::{Html, IntoResponse, Response};

use super::controller_query::ControllerQuery;
use super::error::{ApiError, ApiResult, Problem};
use super::extract::{ApiJson, Paging, SerialPath};
use super::{ndjson, AppState};
use crate::domain::calibrated_set_schema::{all_of, tagged_one_of, Schemas};
use crate::domain::{controller_expectation, CalibratedSet, ReleaseStatus};
use crate::report::{render_html, render_svg, Report};
use crate::service::{compensate, evaluate, filter, release, report_view, results, uncertainty};
use crate::store::ParameterSetRecord;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(list_parameter_sets))
        .routes(routes!(get_parameter_set))
        .routes(routes!(get_report))
        .routes(routes!(get_report_svg))
        .routes(routes!(get_report_html))
        .routes(routes!(forward))
        .routes(routes!(filter_targets))
        .routes(routes!(compensate))
        .routes(routes!(uncertainty_map))
}

/// An identified parameter set: the stored document plus its identity.
#[derive(Debug, Serialize)]
pub struct ParameterSetOut {
    #[serde(flatten)]
    pub identity: ParameterSetIdentity,
    /// What the set identified, told apart by `kind`.
    #[serde(flatten)]
    pub parameters: CalibratedSet,
}

/// Where a served parameter set stands: its robot, version, job and
/// release status.
#[derive(Debug, Serialize, ToSchema)]
pub struct ParameterSetIdentity {
    pub serial: String,
    pub version: i64,
    pub job_id: Option<String>,
    pub created_at: String,
    /// The release gate: `approved` (what `latest` serves, the newest
    /// one), `candidate` (waits for a person) or `rejected`.
    pub status: ReleaseStatus,
    /// Why it has its status (the gate's comparison, or a person's reason).
    pub status_reason: Option<String>,
    /// Who gave it (`gate`, `token:{id} ({name})`, `anonymous`; `null` for
    /// sets approved when the gate was introduced) and when.
    pub status_by: Option<String>,
    pub status_at: Option<String>,
}

/// Each served variant: its `kind`, its schema name and the set's.
const SERVED_SETS: [(&str, &str, &str); 3] = [
    ("kinematic", "KinematicSetOut", "KinematicSet"),
    ("hand_eye", "HandEyeSetOut", "HandEyeSet"),
    ("stage_camera", "StageCameraSetOut", "StageCameraSet"),
];

/// The served set's schema: one object per variant (the identity's
/// properties and the set's), told apart by `kind`.
impl utoipa::PartialSchema for ParameterSetOut {
    fn schema() -> utoipa::openapi::RefOr<utoipa::openapi::schema::Schema> {
        let variants = SERVED_SETS.map(|(kind, name, _)| (kind, name));
        tagged_one_of(
            &variants,
            "An identified parameter set: its identity and release status, and \
             what it identified, told apart by `kind`.",
        )
    }
}

impl ToSchema for ParameterSetOut {
    fn schemas(schemas: &mut Schemas) {
        schemas.push((
            "ParameterSetIdentity".into(),
            <ParameterSetIdentity as utoipa::PartialSchema>::schema(),
        ));
        <ParameterSetIdentity as ToSchema>::schemas(schemas);
        for (_, name, set) in SERVED_SETS {
            schemas.push((name.into(), all_of(&["ParameterSetIdentity", set])));
        }
        <CalibratedSet as ToSchema>::schemas(schemas);
    }
}

#[derive(Debug, Serialize, ToSchema)]
pub struct ParameterSetList {
    pub items: Vec<ParameterSetOut>,
    pub next_cursor: Option<String>,
}

impl From<ParameterSetRecord> for ParameterSetOut {
    fn from(p: ParameterSetRecord) -> ParameterSetOut {
        ParameterSetOut {
            identity: ParameterSetIdentity {
                serial: p.serial,
                version: p.version,
                job_id: p.job_id,
                created_at: p.created_at,
                status: p.status,
                status_reason: p.status_reason,
                status_by: p.status_by,
                status_at: p.status_at,
            },
            parameters: p.parameters,
        }
    }
}

pub(super) async fn find(
    state: &AppState,
    serial: &str,
    version: &str,
) -> ApiResult<ParameterSetRecord> {
    Ok(results::find_parameter_set(&state.store, serial, version).await?)
}

/// A robot's parameter sets, newest first.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("limit" = Option<i64>, Query, minimum = 1, maximum = 1000, description = "Page size, 1 to 1000 (default 100)"),
           ("cursor" = Option<String>, Query, description = "next_cursor of the previous page")),
    responses((status = 200, description = "One page of the robot's parameter sets, newest first (404 for an unknown or deleted robot, as its sessions)", body = ParameterSetList), (status = 404, body = Problem, content_type = "application/problem+json"), (status = 422, body = Problem, content_type = "application/problem+json")))]
async fn list_parameter_sets(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    paging: Paging,
) -> ApiResult<Json<ParameterSetList>> {
    let before = match paging.cursor.as_deref() {
        None => None,
        Some(c) => Some(
            c.parse::<i64>()
                .map_err(|_| ApiError::invalid("cursor", "not a cursor of this listing"))?,
        ),
    };
    if state.store.get_robot(&serial).await?.is_none() {
        return Err(ApiError::not_found("robot", &serial));
    }
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
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`")),
    responses((status = 200, description = "The parameter set: identified kinematics, frames and camera intrinsics", body = ParameterSetOut), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_parameter_set(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
) -> ApiResult<Json<ParameterSetOut>> {
    Ok(Json(find(&state, &serial, &version).await?.into()))
}

/// The report's query: another version to compare with.
#[derive(Debug, Default, Deserialize, utoipa::IntoParams)]
#[into_params(parameter_in = Query)]
pub struct ReportQuery {
    /// Another version of the same robot: the report gains `comparison`
    /// (that version's status, mean validation error and each kinematic
    /// parameter's change from it to this one, in σ units).
    pub compare: Option<String>,
}

/// The accuracy report of a parameter set (`latest`: the newest approved).
/// `status` is the set's current release status; `?compare={v2}` adds
/// `comparison`, version v2 side by side.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets/{version}/report", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`"),
           ReportQuery),
    responses((status = 200, description = "The accuracy report: before/after statistics on the validation poses, per-pose errors, identified parameters, camera fit, notes", body = Report),
              (status = 404, description = "No such robot, parameter set or report", body = Problem, content_type = "application/problem+json")))]
async fn get_report(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    Query(query): Query<ReportQuery>,
) -> ApiResult<Json<Value>> {
    let mut report = report_json(&state, &serial, &version).await?;
    if let Some(other) = query.compare.as_deref() {
        let set = find(&state, &serial, &version).await?;
        let comparison = release::compare(&state.store, &set, other).await?;
        if let Some(obj) = report.as_object_mut() {
            obj.insert(
                "comparison".into(),
                serde_json::to_value(comparison).map_err(ApiError::internal)?,
            );
        }
    }
    Ok(Json(report))
}

async fn report_json(state: &AppState, serial: &str, version: &str) -> ApiResult<Value> {
    Ok(report_view::report_json(&state.store, serial, version).await?)
}

async fn typed_report(state: &AppState, serial: &str, version: &str) -> ApiResult<Report> {
    Ok(report_view::typed_report(&state.store, serial, version).await?)
}

/// The report drawn as one SVG sheet.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets/{version}/report.svg", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`")),
    responses((status = 200, description = "The report's charts as one SVG document", content_type = "image/svg+xml", body = String), (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The parameter set has no accuracy report to draw", body = Problem, content_type = "application/problem+json")))]
async fn get_report_svg(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
) -> ApiResult<([(header::HeaderName, &'static str); 1], String)> {
    let report = typed_report(&state, &serial, &version).await?;
    Ok((
        [(header::CONTENT_TYPE, "image/svg+xml")],
        render_svg(&report),
    ))
}

/// The report as a self-contained printable page.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets/{version}/report.html", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`")),
    responses((status = 200, description = "The report as a self-contained printable HTML page", content_type = "text/html", body = String), (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The parameter set has no accuracy report to draw", body = Problem, content_type = "application/problem+json")))]
async fn get_report_html(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
) -> ApiResult<Html<String>> {
    let report = typed_report(&state, &serial, &version).await?;
    Ok(Html(render_html(&report)))
}

/// Forward kinematics of the calibrated model.
#[utoipa::path(post, path = "/v1/robots/{serial}/parameter-sets/{version}/forward", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`")),
    request_body = evaluate::ForwardRequest,
    responses((status = 200, description = "Per row of joints, the flange, camera (and tool) poses", body = evaluate::ForwardResponse), (status = 422, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The parameter set holds no calibrated model", body = Problem, content_type = "application/problem+json")))]
async fn forward(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    ApiJson(body): ApiJson<evaluate::ForwardRequest>,
) -> ApiResult<Json<evaluate::ForwardResponse>> {
    Ok(Json(
        results::forward(&state.store, &serial, &version, &body).await?,
    ))
}

/// Cartesian targets for a controller that runs the nominal model: sent to
/// it, they make the real robot put the tool on the desired targets. With
/// `Accept: application/x-ndjson` the answer streams, one line per target
/// in order as it is solved (`index`, then the target's answer or `error`);
/// the request is checked whole before the first line, so a bad field is
/// still a 422.
#[utoipa::path(post, path = "/v1/robots/{serial}/parameter-sets/{version}/filter", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`"),
           ControllerQuery),
    request_body = filter::FilterRequest,
    responses((status = 200, description = "Per target, the flange pose for the nominal controller, the joints the robot takes and the replayed residual; unreachable targets in `errors` with their index (streamed: one `FilterLine` per line, an `error` inline)",
               content((filter::FilterResponse = "application/json"), (filter::FilterLine = "application/x-ndjson"))),
              (status = 422, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The parameter set holds no calibrated model, or was made on another controller than `expect_controller` / `controller_serial` (`controller` names both identities)", body = Problem, content_type = "application/problem+json")))]
async fn filter_targets(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    Query(query): Query<ControllerQuery>,
    headers: HeaderMap,
    ApiJson(mut body): ApiJson<filter::FilterRequest>,
) -> ApiResult<Response> {
    body.expect_controller = controller_expectation(
        body.expect_controller.as_ref(),
        query.controller_serial.as_deref(),
    )?;
    if ndjson::wanted(&headers) {
        let lines = results::filter_stream(&state.store, &serial, &version, body).await?;
        return Ok(ndjson::response(lines));
    }
    let answer = results::filter(&state.store, &serial, &version, body).await?;
    Ok(Json(answer).into_response())
}

/// Joints that put the tool on each target according to the calibrated
/// model. With `Accept: application/x-ndjson` the answer streams, one line
/// per target (as `filter`).
#[utoipa::path(post, path = "/v1/robots/{serial}/parameter-sets/{version}/compensate", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`"),
           ControllerQuery),
    request_body = compensate::CompensateRequest,
    responses((status = 200, description = "Per target, the joints and the model's remaining distance to the target; targets out of reach or beyond the joint limits in `errors` with their index (streamed: one `CompensateLine` per line, an `error` inline)",
               content((compensate::CompensateResponse = "application/json"), (compensate::CompensateLine = "application/x-ndjson"))),
              (status = 422, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The parameter set holds no calibrated model, or was made on another controller than `expect_controller` / `controller_serial` (`controller` names both identities)", body = Problem, content_type = "application/problem+json")))]
async fn compensate(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    Query(query): Query<ControllerQuery>,
    headers: HeaderMap,
    ApiJson(mut body): ApiJson<compensate::CompensateRequest>,
) -> ApiResult<Response> {
    body.expect_controller = controller_expectation(
        body.expect_controller.as_ref(),
        query.controller_serial.as_deref(),
    )?;
    if ndjson::wanted(&headers) {
        let lines = results::compensate_stream(&state.store, &serial, &version, body).await?;
        return Ok(ndjson::response(lines));
    }
    let answer = results::compensate(&state.store, &serial, &version, body).await?;
    Ok(Json(answer).into_response())
}

/// Predicted 1σ of the calibrated model over the workspace: at rows of
/// joints, or over a box of flange positions (base frame) at one flange
/// orientation, each solved by the calibrated inverse kinematics.
#[utoipa::path(post, path = "/v1/robots/{serial}/parameter-sets/{version}/uncertainty-map", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`")),
    request_body = uncertainty::UncertaintyMapRequest,
    responses((status = 200, description = "Per point, the joints, the flange position and the predicted 1σ (`position_std_mm` is the square root of the trace of the 3x3 position covariance: the RMS length of the 3-D error); points out of reach in `errors` with their index", body = uncertainty::UncertaintyMapResponse), (status = 422, body = Problem, content_type = "application/problem+json"),
              (status = 409, description = "The parameter set holds no calibrated model, or was stored without its covariance", body = Problem, content_type = "application/problem+json")))]
async fn uncertainty_map(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    ApiJson(body): ApiJson<uncertainty::UncertaintyMapRequest>,
) -> ApiResult<Json<uncertainty::UncertaintyMapResponse>> {
    Ok(Json(
        results::uncertainty_map(&state.store, &serial, &version, body).await?,
    ))
}
