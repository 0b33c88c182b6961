//! `GET /v1/robots/{serial}/parameter-sets/{version}/export`: the parameter
//! set as URDF, `dh-json` or CSV (issue "Deploy the result"), or in a
//! controller's own form (issue 34).

use axum::extract::{Path, Query, State};
use axum::http::{header, HeaderMap};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;
use utoipa::IntoParams;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiResult, Problem};
use super::extract::SerialPath;
use super::AppState;
use crate::domain::controller_expectation;
use crate::service::export::{export, ExportRequest};

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(export_parameter_set))
}

#[derive(Debug, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
pub struct ExportQuery {
    /// `urdf` (metres, radians; chain base_link → link_1..n → flange →
    /// camera|tool, the board or tracker a fixed child of base_link),
    /// `dh-json` (the identified table with 1σ per parameter and why held
    /// parameters were held), `csv` (the joint table, units in the column
    /// names), `ur-kinematics` (Universal Robots' `kinematics.yaml`: six
    /// segments `{x, y, z, roll, pitch, yaw}` in metres and radians, and
    /// robocal's `hash`; 6-axis arms whose flange lies on joint 6's axis,
    /// without non-geometric terms, else 422), `dh-table` (`alpha`, `a`,
    /// `d`, `theta`, `beta` per joint, mm and degrees: INI text, or JSON
    /// with `Accept: application/json`), `krl-frames` (KUKA `$ROBROOT` and
    /// `TOOL_DATA[1]` FRAMEs) or `rapid-frames` (ABB `wobjdata` and
    /// `tooldata`). Missing or unknown: 422 naming `format`.
    #[param(required = true)]
    pub format: Option<String>,
    /// The serial of the controller the caller is about to load the export
    /// into: 409 naming `controller` (both identities in the problem's
    /// `controller`) when the set records another.
    pub controller_serial: Option<String>,
}

/// Whether `Accept` names `application/json`.
fn wants_json(headers: &HeaderMap) -> bool {
    headers
        .get_all(header::ACCEPT)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(','))
        .any(|v| v.split(';').next().unwrap_or("").trim() == "application/json")
}

/// The parameter set in a form a controller or an off-line programming tool
/// reads. Every controller form opens with a comment naming the set, its
/// version, its release status and its controller identity.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets/{version}/export", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`"),
           ExportQuery),
    responses(
        (status = 200, description = "The export: `application/xml` (urdf), `application/json` (dh-json; dh-table with `Accept: application/json`), `text/csv` (csv), `application/yaml` (ur-kinematics) or `text/plain` (dh-table, krl-frames, rapid-frames)", content_type = "application/xml", body = String),
        (status = 422, description = "Missing or unknown `format` (the message lists the accepted ones), or a set `ur-kinematics` cannot represent exactly (the message says why)", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "The parameter set holds no calibrated model, or was made on another controller than `controller_serial` (`controller` names both identities)", body = Problem, content_type = "application/problem+json")))]
async fn export_parameter_set(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    Query(query): Query<ExportQuery>,
    headers: HeaderMap,
) -> ApiResult<Response> {
    let expect_controller = controller_expectation(None, query.controller_serial.as_deref())?;
    let request = ExportRequest {
        format: query.format.as_deref(),
        json: wants_json(&headers),
        expect_controller,
    };
    let out = export(&state.store, &serial, &version, request).await?;
    let disposition = format!("attachment; filename=\"{}\"", out.file_name);
    Ok((
        [
            (header::CONTENT_TYPE, out.content_type.to_string()),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        out.body,
    )
        .into_response())
}
