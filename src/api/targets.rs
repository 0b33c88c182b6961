//! `/v1/targets/render`: a printable board at exact scale (issue "Targets
//! people own"). Pure: nothing is stored, any reader may ask.

use axum::extract::RawQuery;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::AppState;
use crate::print;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(render_target))
}

/// A target drawn 1:1 on the smallest ISO sheet that holds it (or scaled to
/// fill the sheet `page` names), with a scale bar and the session `target`
/// spec in the margin.
#[utoipa::path(get, path = "/v1/targets/render", tag = "targets",
    params(
        ("kind" = Option<String>, Query, description = "Target kind: `dots` (default; robocal's dot grid), `charuco`, `chessboard` or `asymmetric_circles` (OpenCV's asymmetric grid)"),
        ("rows" = Option<u32>, Query, minimum = 2, maximum = 200, description = "dots, asymmetric_circles: rows of dots"),
        ("cols" = Option<u32>, Query, minimum = 2, maximum = 200, description = "dots, asymmetric_circles: dots per row"),
        ("pitch_mm" = Option<f64>, Query, description = "dots: centre-to-centre spacing, mm; asymmetric_circles: row spacing = half the in-row spacing (OpenCV's squareSize), mm"),
        ("dot_diameter_mm" = Option<f64>, Query, description = "dots, asymmetric_circles: diameter of an ordinary dot, mm (dots must not touch)"),
        ("origin_marker_diameter_mm" = Option<f64>, Query, description = "dots: diameter of the larger origin dot, mm; omit for a marker-less grid"),
        ("squares" = Option<String>, Query, description = "charuco: squares as `cols,rows`, e.g. `10,8`"),
        ("square_mm" = Option<f64>, Query, description = "charuco, chessboard: side of a chessboard square, mm"),
        ("inner_corners" = Option<String>, Query, description = "chessboard: inner corners as `cols,rows` (OpenCV's patternSize), e.g. `11,8`"),
        ("marker_mm" = Option<f64>, Query, description = "charuco: side of a marker with its black border, mm (below square_mm)"),
        ("dictionary" = Option<String>, Query, description = "charuco: an OpenCV predefined dictionary name, e.g. `DICT_5X5_100`"),
        ("legacy_layout" = Option<bool>, Query, description = "charuco: the layout of OpenCV < 4.6 (default false)"),
        ("format" = Option<String>, Query, description = "`svg` (default) or `pdf`"),
        ("page" = Option<String>, Query, description = "`a4`, `a3`, `a2`, `a1` or `a0`: the board scaled (every length by one factor, the pitch or square a multiple of 0.5 mm) to fill that sheet; the footer states the board as drawn"),
    ),
    responses(
        (status = 200, description = "The page: SVG in millimetres (`format=svg`) or a one-page PDF (`format=pdf`)", content_type = "image/svg+xml", body = String),
        (status = 422, description = "A parameter is missing or cannot be printed; `errors[].field` names it", body = Problem, content_type = "application/problem+json"),
    ))]
async fn render_target(RawQuery(query): RawQuery) -> ApiResult<Response> {
    let pairs = query_pairs(query.as_deref().unwrap_or(""))?;
    let request = print::parse_pairs(&pairs).map_err(ApiError::validation)?;
    let body = print::render(&request);
    Ok((
        [(header::CONTENT_TYPE, request.format.content_type())],
        body,
    )
        .into_response())
}

fn query_pairs(query: &str) -> ApiResult<Vec<(String, String)>> {
    let uri: axum::http::Uri = format!("/?{query}")
        .parse()
        .map_err(|_| ApiError::malformed("query", "unreadable query string"))?;
    axum::extract::Query::<Vec<(String, String)>>::try_from_uri(&uri)
        .map(|q| q.0)
        .map_err(|e| ApiError::malformed("query", e.body_text()))
}
