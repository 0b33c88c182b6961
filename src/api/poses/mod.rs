//! Poses of a session: `POST /v1/sessions/{id}/poses` (multipart with an
//! image, or JSON with image points or a tracker measurement) and reads.

use axum::extract::{FromRequest, Multipart, Path, Request, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::{is_json, parse_json, read_limited, Paging};
use super::sessions::find_session;
use super::upload::{read_field_capped, read_field_limited};
use super::AppState;
use crate::domain::{label_from_file_name, PoseGroup};
use crate::schema::flange_pose::FlangePoseDoc;
use crate::schema::pose_body::PoseJsonBody;
use crate::schema::session::PoseSet;
use crate::service::intake::{ImagePose, PoseIntake};
use crate::store::PoseRecord;

mod docs;

pub use docs::{PoseDetectionOut, PoseImagePoint, PoseImageUpload, PoseList, PoseOut};

/// Largest text part of a multipart pose (`joints_deg`, `set`).
const MAX_TEXT_PART: u64 = 64 * 1024;
/// Longest part name repeated back in an error, characters.
const MAX_ECHOED_NAME: usize = 64;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(add_pose, list_poses))
        .routes(routes!(get_pose))
        .routes(routes!(get_pose_image))
}

/// Add one pose: `multipart/form-data` (parts `joints_deg` or
/// `flange_pose`, or for a stage session `stage_position_mm` and
/// `sequence`; `set`, `group`, `image`) or JSON with `image_points` (camera) or `measured_position_mm` (tracker).
#[utoipa::path(post, path = "/v1/sessions/{id}/poses", tag = "poses",
    params(("id" = String, Path, description = "Session id")),
    request_body(content(
        (PoseJsonBody = "application/json"),
        (PoseImageUpload = "multipart/form-data"),
    )),
    responses((status = 201, body = PoseOut, description = "The stored pose. An image is checked (header against the session camera before any decode), decoded once and searched for the session's target at upload: `detected_points` and `points` show the dots found, `detection_error` why none were; the image is kept either way."),
              (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 413, body = Problem, content_type = "application/problem+json"),
              (status = 422, body = Problem, content_type = "application/problem+json", description = "A part or field is invalid; for an image, not PNG/JPEG, not the session camera's size, or not decodable (the error names the part).")))]
async fn add_pose(
    State(state): State<AppState>,
    Path(id): Path<String>,
    req: Request,
) -> ApiResult<(StatusCode, Json<PoseOut>)> {
    let intake = PoseIntake::open(&state.store, state.decode_gate.clone(), &id).await?;
    let content_type = req
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .unwrap_or("")
        .to_string();
    let record = if content_type.starts_with("multipart/form-data") {
        intake.check_takes_images()?;
        let multipart = Multipart::from_request(req, &state)
            .await
            .map_err(|e| ApiError::malformed("multipart", e.body_text()))?;
        let upload = read_image_pose(multipart, state.config.max_image_bytes).await?;
        intake.add_image(upload).await?
    } else if is_json(Some(&content_type)) {
        let bytes = read_limited(req, state.config.max_json_bytes, "max_json_bytes").await?;
        let body: PoseJsonBody = parse_json(&bytes)?;
        intake.add_json(body).await?
    } else {
        return Err(ApiError::unsupported_media(
            "send multipart/form-data (with an image) or application/json",
        ));
    };
    Ok((StatusCode::CREATED, Json(record.into())))
}

/// Reads the parts of a multipart pose (`joints_deg` or `flange_pose`,
/// `set`, `group`, `image`);
/// the service checks their values.
async fn read_image_pose(mut multipart: Multipart, max_image_bytes: u64) -> ApiResult<ImagePose> {
    let malformed = |e: axum::extract::multipart::MultipartError| {
        ApiError::malformed("multipart", e.body_text())
    };
    let (mut joints, mut set, mut image, mut label) = (None, PoseSet::Cal, None, None);
    let (mut flange_pose, mut stage_position_mm, mut sequence) = (None, None, None);
    let mut group = None;
    while let Some(mut field) = multipart.next_field().await.map_err(malformed)? {
        let name = field.name().unwrap_or("").to_string();
        match name.as_str() {
            "joints_deg" => {
                let bytes = read_text_part(&mut field, "joints_deg").await?;
                let parsed: Vec<f64> = serde_json::from_slice(&bytes).map_err(|e| {
                    ApiError::invalid("joints_deg", format!("a JSON array of numbers: {e}"))
                })?;
                joints = Some(parsed);
            }
            "flange_pose" => {
                let bytes = read_text_part(&mut field, "flange_pose").await?;
                let parsed: FlangePoseDoc = serde_json::from_slice(&bytes).map_err(|e| {
                    ApiError::invalid(
                        "flange_pose",
                        format!(
                            "a JSON object {{\"translation_mm\", \"rotation_deg\" or \"matrix\"}}: {e}"
                        ),
                    )
                })?;
                flange_pose = Some(parsed);
            }
            "stage_position_mm" => {
                let bytes = read_text_part(&mut field, "stage_position_mm").await?;
                let parsed: [f64; 3] = serde_json::from_slice(&bytes).map_err(|e| {
                    ApiError::invalid("stage_position_mm", format!("a JSON array [x, y, z] of mm: {e}"))
                })?;
                stage_position_mm = Some(parsed);
            }
            "sequence" => {
                let bytes = read_text_part(&mut field, "sequence").await?;
                let text = String::from_utf8_lossy(&bytes);
                let parsed: u32 = text.trim().parse().map_err(|_| {
                    ApiError::invalid("sequence", "an integer 1 to 1000")
                })?;
                sequence = Some(parsed);
            }
            "set" => {
                let bytes = read_text_part(&mut field, "set").await?;
                let text = String::from_utf8_lossy(&bytes);
                set = PoseSet::parse(text.trim().trim_matches('"'))
                    .ok_or_else(|| ApiError::invalid("set", "\"cal\" or \"val\""))?;
            }
            "group" => {
                let bytes = read_text_part(&mut field, "group").await?;
                let text = String::from_utf8_lossy(&bytes);
                let parsed = PoseGroup::parse(text.trim().trim_matches('"'))
                    .map_err(|rule| ApiError::invalid("group", rule))?;
                group = Some(parsed);
            }
            "image" => {
                label = field.file_name().and_then(label_from_file_name);
                image =
                    Some(read_field_limited(&mut field, max_image_bytes, "max_image_bytes").await?);
            }
            other => {
                return Err(ApiError::invalid(
                    shortened(other),
                    "unknown part (expected joints_deg or flange_pose, or stage_position_mm and sequence; set, group, image)",
                ))
            }
        }
    }
    let image = image.ok_or_else(|| ApiError::invalid("image", "required part (PNG or JPEG)"))?;
    Ok(ImagePose {
        joints_deg: joints,
        flange_pose,
        set,
        image,
        label,
        group,
        stage_position_mm,
        sequence,
    })
}

/// Reads a text part (`joints_deg`, `set`), refusing more than
/// [`MAX_TEXT_PART`] bytes with a 413 naming the part (a fixed limit, not a
/// server option).
async fn read_text_part(
    field: &mut axum::extract::multipart::Field<'_>,
    part: &str,
) -> ApiResult<Vec<u8>> {
    read_field_capped(field, MAX_TEXT_PART, || {
        ApiError::part_too_large(part, MAX_TEXT_PART)
    })
    .await
}

/// A client-chosen name as it is echoed in an error: at most
/// [`MAX_ECHOED_NAME`] characters.
fn shortened(name: &str) -> String {
    if name.chars().count() <= MAX_ECHOED_NAME {
        return name.to_string();
    }
    let head: String = name.chars().take(MAX_ECHOED_NAME).collect();
    format!("{head}... ({} bytes)", name.len())
}

/// A session's poses, in upload order.
#[utoipa::path(get, path = "/v1/sessions/{id}/poses", tag = "poses",
    params(("id" = String, Path, description = "Session id"),
           ("limit" = Option<i64>, Query, minimum = 1, maximum = 1000, description = "Page size, 1 to 1000 (default 100)"),
           ("cursor" = Option<String>, Query, description = "next_cursor of the previous page")),
    responses((status = 200, description = "One page of the session's poses, oldest first; `next_cursor` fetches the next", body = PoseList), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn list_poses(
    State(state): State<AppState>,
    Path(id): Path<String>,
    paging: Paging,
) -> ApiResult<Json<PoseList>> {
    find_session(&state, &id).await?;
    let page = state
        .store
        .list_poses(&id, paging.limit, paging.cursor.as_deref())
        .await?;
    Ok(Json(PoseList {
        items: page.items.into_iter().map(PoseOut::from).collect(),
        next_cursor: page.next_cursor,
    }))
}

async fn find_pose(state: &AppState, id: &str, pose_id: &str) -> ApiResult<PoseRecord> {
    find_session(state, id).await?;
    state
        .store
        .get_pose(id, pose_id)
        .await?
        .ok_or_else(|| ApiError::not_found("pose", pose_id))
}

/// One pose with its image points.
#[utoipa::path(get, path = "/v1/sessions/{id}/poses/{pose_id}", tag = "poses",
    params(("id" = String, Path, description = "Session id"), ("pose_id" = String, Path, description = "Pose id")),
    responses((status = 200, description = "The pose with its image points (and residuals after a calibration)", body = PoseOut), (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_pose(
    State(state): State<AppState>,
    Path((id, pose_id)): Path<(String, String)>,
) -> ApiResult<Json<PoseOut>> {
    Ok(Json(find_pose(&state, &id, &pose_id).await?.into()))
}

/// The pose's image, byte for byte as uploaded.
#[utoipa::path(get, path = "/v1/sessions/{id}/poses/{pose_id}/image", tag = "poses",
    params(("id" = String, Path, description = "Session id"), ("pose_id" = String, Path, description = "Pose id")),
    responses((status = 200, description = "PNG or JPEG bytes", content_type = "application/octet-stream"),
              (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_pose_image(
    State(state): State<AppState>,
    Path((id, pose_id)): Path<(String, String)>,
) -> ApiResult<Response> {
    let pose = find_pose(&state, &id, &pose_id).await?;
    let meta = pose
        .image
        .ok_or_else(|| ApiError::not_found("image of pose", &pose_id))?;
    let bytes = state
        .store
        .get_blob(&meta.sha256)
        .await?
        .ok_or_else(|| ApiError::internal(format!("blob {} missing", meta.sha256)))?;
    Ok((
        [
            (header::CONTENT_TYPE, meta.content_type),
            (header::ETAG, format!("\"{}\"", meta.sha256)),
        ],
        bytes,
    )
        .into_response())
}
