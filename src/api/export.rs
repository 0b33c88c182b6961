//! `GET /v1/robots/{serial}/parameter-sets/{version}/export`: the parameter
//! set as URDF, `dh-json` or CSV (issue "Deploy the result").

use axum::extract::{Path, Query, State};
use axum::http::header;
use axum::response::{IntoResponse, Response};
use serde::Deserialize;
use utoipa::IntoParams;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiResult, Problem};
use super::extract::SerialPath;
use super::AppState;
use crate::service::export::export;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(export_parameter_set))
}

#[derive(Debug, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
pub struct ExportQuery {
    /// `urdf` (metres, radians; chain base_link → link_1..n → flange →
    /// camera|tool, the board or tracker a fixed child of base_link),
    /// `dh-json` (the identified table with 1σ per parameter and why held
    /// parameters were held) or `csv` (the joint table, units in the column
    /// names). Required: a request without it is a 422 naming `format`.
    pub format: Option<String>,
}

/// The parameter set in a form a controller or an off-line programming tool reads.
#[utoipa::path(get, path = "/v1/robots/{serial}/parameter-sets/{version}/export", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, pattern = r"^(latest|[1-9][0-9]{0,17})$", description = "Version number (1, 2, ...) or `latest`"),
           ExportQuery),
    responses(
        (status = 200, description = "The export: `application/xml` (urdf), `application/json` (dh-json) or `text/csv` (csv)", content_type = "application/xml", body = String),
        (status = 422, description = "Unknown `format`; the message lists the accepted ones", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "The parameter set holds no calibrated model", body = Problem, content_type = "application/problem+json")))]
async fn export_parameter_set(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, version)): Path<(String, String)>,
    Query(query): Query<ExportQuery>,
) -> ApiResult<Response> {
    // A missing format is answered as an unknown one: 422 naming `format`
    // and listing the accepted ones.
    let format = query.format.as_deref().unwrap_or_default();
    let out = export(&state.store, &serial, &version, format).await?;
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
