//! Poses of a session: `POST /v1/sessions/{id}/poses` (multipart with an
//! image, or JSON with image points or a tracker measurement) and reads.

use axum::extract::{FromRequest, Multipart, Path, Request, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::{is_json, parse_json, read_limited, Paging};
use super::sessions::find_session;
use super::upload::{
    ingest_image, read_field_capped, read_field_limited, robot_joint_count, session_spec,
    ImageCheck,
};
use super::AppState;
use crate::domain::{label_from_file_name, ImageMeta, NewPose, PoseRecord};
use crate::schema::session::{check_joints, Instrument, PoseJsonBody, PoseSet};
use crate::schema::{Checker, PoseDoc};

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

#[derive(Debug, Serialize, ToSchema)]
pub struct PoseOut {
    pub id: String,
    pub session_id: String,
    pub joints_deg: Vec<f64>,
    pub set: PoseSet,
    /// `image`, `image_points` or `measured`.
    pub source: String,
    /// Number of image points: uploaded, or found by the dot detector on
    /// the image (at upload, and again by the last calibration job). 0 for
    /// an image whose board was not found (`detection_error` says why).
    pub detected_points: usize,
    /// The image points: as uploaded, or as the detector found them at
    /// upload, or as the last calibration job measured them (then with the
    /// perspective-bias-corrected centres as `x`, `y`, the raw ones as
    /// `raw_x`, `raw_y`, and residuals once that job succeeded).
    #[schema(value_type = Vec<PoseImagePoint>)]
    pub points: Vec<Value>,
    /// Why the dot detector found no board on this pose's image (at upload,
    /// or in the last calibration job). The image is kept either way; a
    /// job leaves such poses out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detection_error: Option<String>,
    /// Which job measured `points`, and how well the model fits them;
    /// absent until a calibration job ran its detect stage on the session.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detection: Option<PoseDetectionOut>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub image: Option<ImageMeta>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_position_mm: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_pose: Option<PoseDoc>,
    /// What the pose is called: the uploaded image's file name (multipart
    /// filename, or its path in a dataset archive) or a JSON pose's
    /// `label`. Absent when none was given; reports then number the pose.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    pub created_at: String,
}

/// One image point of a pose (schema of `points`).
#[derive(Debug, Serialize, Deserialize, ToSchema)]
pub struct PoseImagePoint {
    pub row: u32,
    pub col: u32,
    /// Dot centre in the image (px): uploaded or as the detector found it
    /// (the raw ellipse centre); after a calibration job measured the pose,
    /// the centre corrected for perspective bias by the calibrated camera
    /// model (what the fits use), the raw one then in `raw_x`, `raw_y`.
    pub x: f64,
    pub y: f64,
    /// The raw centre (px), as detected or uploaded, when `x`, `y` are
    /// the bias-corrected one (after a calibration job; absent for the
    /// origin marker, which the fits leave out).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub raw_x: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub raw_y: Option<f64>,
    /// `[dx, dy]` (px) after a successful calibration: the observed centre
    /// (corrected for perspective bias) minus the calibrated model's
    /// projection of the dot. Absent for points the fit leaves out (the
    /// origin marker).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual_px: Option<[f64; 2]>,
    /// Dropped by the camera calibration as an outlier.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outlier: Option<bool>,
}

/// The `multipart/form-data` pose upload (its schema; the parts are read
/// one by one in `add_pose`).
#[derive(ToSchema)]
#[allow(dead_code)] // a schema only
pub struct PoseImageUpload {
    /// JSON array of the joint angles in degrees, e.g. `[0, -10, 20, 0, 30, 0]`.
    pub joints_deg: String,
    /// `cal` (default) or `val`.
    pub set: Option<PoseSet>,
    /// The photo of the board, PNG or JPEG.
    #[schema(value_type = String, format = Binary)]
    pub image: Vec<u8>,
}

/// How a pose's points were measured by the last calibration job.
#[derive(Debug, Serialize, Deserialize, ToSchema)]
pub struct PoseDetectionOut {
    pub job_id: String,
    /// Why no dots were detected on this pose's image.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// RMS length of this pose's residuals (px), outliers excluded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual_rms_px: Option<f64>,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct PoseList {
    pub items: Vec<PoseOut>,
    pub next_cursor: Option<String>,
}

impl From<PoseRecord> for PoseOut {
    fn from(p: PoseRecord) -> PoseOut {
        // The last job's measurement, else the detector's at upload, else
        // the uploaded points.
        let detected = p.detection.as_ref().or(p.image_detection.as_ref());
        let points = detected
            .and_then(|d| d["points"].as_array())
            .or_else(|| p.points.as_array())
            .cloned()
            .unwrap_or_default();
        let detection_error = detected
            .and_then(|d| d["error"].as_str())
            .map(str::to_string);
        let detection = p
            .detection
            .and_then(|d| serde_json::from_value::<PoseDetectionOut>(d).ok());
        let measured = p.measured.unwrap_or(Value::Null);
        let source = if p.image.is_some() {
            "image"
        } else if measured.is_null() {
            "image_points"
        } else {
            "measured"
        };
        PoseOut {
            id: p.id,
            session_id: p.session_id,
            joints_deg: p.joints_deg,
            set: PoseSet::parse(&p.set).unwrap_or_default(),
            source: source.into(),
            detected_points: points.len(),
            points,
            detection_error,
            detection,
            image: p.image,
            measured_position_mm: serde_json::from_value(measured["measured_position_mm"].clone())
                .ok()
                .flatten(),
            measured_pose: serde_json::from_value(measured["measured_pose"].clone())
                .ok()
                .flatten(),
            label: p.label,
            created_at: p.created_at,
        }
    }
}

/// Add one pose: `multipart/form-data` (parts `joints_deg`, `set`, `image`)
/// or JSON with `image_points` (camera) or `measured_position_mm` (tracker).
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
    let session = find_session(&state, &id).await?;
    let spec = session_spec(&session)?;
    let joint_count = robot_joint_count(&state, &session.serial).await?;
    let content_type = req
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .unwrap_or("")
        .to_string();
    let pose = if content_type.starts_with("multipart/form-data") {
        if spec.instrument != Instrument::Camera {
            return Err(ApiError::invalid(
                "image",
                "a tracker session takes JSON measurements",
            ));
        }
        let multipart = Multipart::from_request(req, &state)
            .await
            .map_err(|e| ApiError::malformed("multipart", e.body_text()))?;
        multipart_pose(
            &state,
            multipart,
            &ImageCheck::of(&state, &spec),
            joint_count,
        )
        .await?
    } else if is_json(Some(&content_type)) {
        let bytes = read_limited(req, state.config.max_json_bytes, "max_json_bytes").await?;
        let body: PoseJsonBody = parse_json(&bytes)?;
        body.check(spec.instrument, spec.camera.as_ref(), joint_count)?;
        json_pose(body)
    } else {
        return Err(ApiError::unsupported_media(
            "send multipart/form-data (with an image) or application/json",
        ));
    };
    let mut stored = state.store.add_poses(&session.id, &[pose]).await?;
    let record = stored
        .pop()
        .ok_or_else(|| ApiError::internal("pose not stored"))?;
    Ok((StatusCode::CREATED, Json(record.into())))
}

fn json_pose(body: PoseJsonBody) -> NewPose {
    let measured = body
        .measured_position_mm
        .map(|p| json!({ "measured_position_mm": p, "measured_pose": body.measured_pose }));
    NewPose {
        joints_deg: body.joints_deg,
        set: body.set.as_str().to_string(),
        image: None,
        points: serde_json::to_value(body.image_points.unwrap_or_default()).unwrap_or(json!([])),
        measured,
        label: body.label,
        image_detection: None,
    }
}

async fn multipart_pose(
    state: &AppState,
    mut multipart: Multipart,
    check: &ImageCheck,
    joint_count: usize,
) -> ApiResult<NewPose> {
    let malformed = |e: axum::extract::multipart::MultipartError| {
        ApiError::malformed("multipart", e.body_text())
    };
    let (mut joints, mut set, mut image, mut label) = (None, PoseSet::Cal, None, None);
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
            "set" => {
                let bytes = read_text_part(&mut field, "set").await?;
                let text = String::from_utf8_lossy(&bytes);
                set = PoseSet::parse(text.trim().trim_matches('"'))
                    .ok_or_else(|| ApiError::invalid("set", "\"cal\" or \"val\""))?;
            }
            "image" => {
                label = field.file_name().and_then(label_from_file_name);
                let limit = state.config.max_image_bytes;
                image = Some(read_field_limited(&mut field, limit, "max_image_bytes").await?);
            }
            other => {
                return Err(ApiError::invalid(
                    shortened(other),
                    "unknown part (expected joints_deg, set, image)",
                ))
            }
        }
    }
    let joints = joints.ok_or_else(|| ApiError::invalid("joints_deg", "required part"))?;
    let image = image.ok_or_else(|| ApiError::invalid("image", "required part (PNG or JPEG)"))?;
    let mut c = Checker::default();
    check_joints(&mut c, "joints_deg", &joints, joint_count);
    c.finish()?;
    let ingested = ingest_image(state, image, check, "image").await?;
    Ok(NewPose {
        joints_deg: joints,
        set: set.as_str().to_string(),
        image: Some(ingested.meta),
        points: json!([]),
        measured: None,
        label,
        image_detection: ingested.detection.map(|d| d.to_value()),
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
