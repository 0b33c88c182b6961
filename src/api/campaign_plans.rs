//! `/v1/robots/{serial}/campaign-plans` (issue 16): plan which poses to
//! shoot and predict the calibration's accuracy; serve a stored plan as
//! JSON, CSV or a URScript / RAPID / KRL program.

use axum::extract::{Path, Query, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Deserialize;
use utoipa::IntoParams;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiResult, Problem};
use super::extract::{ApiJson, SerialPath};
use super::AppState;
use crate::schema::campaign_plan::{CampaignPlanBody, CampaignPlanOut};
use crate::service::campaign_plans::{create_plan, get_plan};

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(post_campaign_plan))
        .routes(routes!(get_campaign_plan))
}

/// Plan a campaign: the calibration (and validation) poses to shoot, in a
/// short joint-space order, with the predicted validation error. Uses the
/// robot's latest parameter set's kinematics, else its nominal table.
#[utoipa::path(post, path = "/v1/robots/{serial}/campaign-plans", tag = "campaign-plans",
    params(("serial" = String, Path, description = "Robot serial number")),
    request_body = CampaignPlanBody,
    responses(
        (status = 201, description = "The plan, stored", body = CampaignPlanOut),
        (status = 404, description = "No such robot (or camera_calibration_id)", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Invalid field, or infeasible: `errors[0].field` names the constraint that bound, `errors[1..]` (`candidates.<filter>`) how many candidates survived each filter", body = Problem, content_type = "application/problem+json"),
    ))]
async fn post_campaign_plan(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    ApiJson(body): ApiJson<CampaignPlanBody>,
) -> ApiResult<(StatusCode, Json<CampaignPlanOut>)> {
    let plan = create_plan(&state.store, &serial, body).await?;
    Ok((StatusCode::CREATED, Json(plan)))
}

#[derive(Debug, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
pub struct PlanFormatQuery {
    /// `json` (default, the plan document), `csv` (`pose,set,j1_deg,...`),
    /// `urscript` (`movej` in radians), `rapid` (`MoveAbsJ` to a
    /// `jointtarget` in degrees) or `krl` (`PTP` to an `AXIS` in degrees);
    /// the programs wait at each pose for the image.
    pub format: Option<String>,
}

/// A stored plan, as JSON or as a program for the cell.
#[utoipa::path(get, path = "/v1/robots/{serial}/campaign-plans/{id}", tag = "campaign-plans",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("id" = String, Path, description = "Plan id"),
           PlanFormatQuery),
    responses(
        (status = 200, description = "The plan: `application/json`, `text/csv` or a program as `text/plain`", body = CampaignPlanOut),
        (status = 404, body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Unknown `format`; the message lists the accepted ones", body = Problem, content_type = "application/problem+json")))]
async fn get_campaign_plan(
    State(state): State<AppState>,
    SerialPath(serial): SerialPath,
    Path((_serial, id)): Path<(String, String)>,
    Query(query): Query<PlanFormatQuery>,
) -> ApiResult<Response> {
    let out = get_plan(&state.store, &serial, &id, query.format.as_deref()).await?;
    let disposition = format!("inline; filename=\"{}\"", out.file_name);
    Ok((
        [
            (header::CONTENT_TYPE, out.content_type.to_string()),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        out.body,
    )
        .into_response())
}
