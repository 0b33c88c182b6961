//! Uploads: image ingestion shared by the pose routes, and the streamed
//! dataset archive `POST /v1/sessions/{id}/dataset`. Bodies are streamed to
//! a temporary file (never whole in memory) under the configured limits;
//! images are checked (header first), decoded once and detected off the
//! async runtime before they are stored.

use std::sync::Arc;

use axum::extract::multipart::Field;
use axum::extract::{Path, Request, State};
use axum::http::{header, StatusCode};
use axum::Json;
use futures_util::StreamExt;
use serde::Serialize;
use sha2::{Digest, Sha256};
use tokio::io::AsyncWriteExt;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::content_length;
use super::sessions::find_session;
use super::staged_images::StagedImages;
use super::AppState;
use crate::dataset::{DatasetError, DatasetLimits, DatasetReader};
use crate::domain::{label_from_archive_path, ImageMeta, NewPose, SessionRecord};
use crate::imaging::{self, DecodeGate, ImageDetection};
use crate::schema::session::{check_joints, Instrument, SessionBody, TargetDoc};
use crate::schema::Checker;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(upload_dataset))
}

#[derive(Debug, Serialize, ToSchema)]
pub struct DatasetOut {
    pub session_id: String,
    pub poses_created: usize,
    pub pose_ids: Vec<String>,
    /// Dots the detector found on each image at upload, in `pose_ids` order
    /// (0 where the board was not found; the pose's `detection_error` says why).
    pub detected_points: Vec<usize>,
}

pub fn session_spec(session: &SessionRecord) -> ApiResult<SessionBody> {
    serde_json::from_value(session.spec.clone()).map_err(ApiError::internal)
}

pub async fn robot_joint_count(state: &AppState, serial: &str) -> ApiResult<usize> {
    let robot = state
        .store
        .get_robot(serial)
        .await?
        .ok_or_else(|| ApiError::not_found("robot", serial))?;
    Ok(robot.kinematics["joints"]
        .as_array()
        .map(Vec::len)
        .unwrap_or(0))
}

/// Reads a multipart field, refusing more than `limit` bytes.
pub async fn read_field_limited(
    field: &mut Field<'_>,
    limit: u64,
    limit_name: &'static str,
) -> ApiResult<Vec<u8>> {
    read_field_capped(field, limit, || ApiError::too_large(limit_name, limit)).await
}

/// Reads a multipart field; past `limit` bytes, the error `over` makes.
pub async fn read_field_capped(
    field: &mut Field<'_>,
    limit: u64,
    over: impl FnOnce() -> ApiError,
) -> ApiResult<Vec<u8>> {
    let mut buf = Vec::new();
    while let Some(chunk) = field
        .chunk()
        .await
        .map_err(|e| ApiError::malformed("multipart", e.body_text()))?
    {
        if (buf.len() + chunk.len()) as u64 > limit {
            return Err(over());
        }
        buf.extend_from_slice(&chunk);
    }
    Ok(buf)
}

/// An accepted image: its metadata and what the detector found on it.
pub struct Ingested {
    pub meta: ImageMeta,
    /// `None` when the session has no target to look for.
    pub detection: Option<ImageDetection>,
}

/// What an upload needs to check and detect an image: the session camera's
/// size and target, and the process's decode gate.
#[derive(Clone)]
pub struct ImageCheck {
    pub camera_size: Option<(u32, u32)>,
    pub target: Option<TargetDoc>,
    pub gate: Arc<DecodeGate>,
}

impl ImageCheck {
    pub fn of(state: &AppState, spec: &SessionBody) -> ImageCheck {
        ImageCheck {
            camera_size: spec.camera.as_ref().map(|c| (c.width, c.height)),
            target: spec.target.clone(),
            gate: state.decode_gate.clone(),
        }
    }
}

/// Checks an image on a blocking thread (header against the camera before
/// any decode, then one bounded decode under the gate and the dot
/// detector), and stores it; returns it once it is durable. A board not
/// found is no error: the image is kept and the reason returned.
pub async fn ingest_image(
    state: &AppState,
    bytes: Vec<u8>,
    check: &ImageCheck,
    field: &str,
) -> ApiResult<Ingested> {
    let check = check.clone();
    let (ingested, bytes) = tokio::task::spawn_blocking(move || {
        inspect_and_hash(&bytes, &check).map(|ingested| (ingested, bytes))
    })
    .await
    .map_err(ApiError::internal)?
    .map_err(|message| ApiError::invalid(field, message))?;
    state.store.put_blob(&ingested.meta, &bytes).await?;
    Ok(ingested)
}

/// Blocking: see [`ingest_image`].
fn inspect_and_hash(bytes: &[u8], check: &ImageCheck) -> Result<Ingested, String> {
    let inspected = imaging::inspect(bytes, check.camera_size, check.target.as_ref(), &check.gate)?;
    let content_type = match image::guess_format(bytes) {
        Ok(image::ImageFormat::Jpeg) => "image/jpeg",
        _ => "image/png",
    };
    Ok(Ingested {
        meta: ImageMeta {
            sha256: hex::encode(Sha256::digest(bytes)),
            size_bytes: bytes.len() as i64,
            content_type: content_type.into(),
            width: inspected.width,
            height: inspected.height,
        },
        detection: inspected.detection,
    })
}

impl From<DatasetError> for ApiError {
    fn from(e: DatasetError) -> ApiError {
        match e {
            DatasetError::Malformed { field, message } => ApiError::malformed(field, message),
            DatasetError::Invalid(errors) => ApiError::validation(errors),
            DatasetError::TooLarge { limit, bytes } => ApiError::too_large(limit, bytes),
        }
    }
}

/// A zip archive's bytes (the dataset upload's body schema).
#[derive(ToSchema)]
#[schema(value_type = String, format = Binary)]
#[allow(dead_code)] // a schema only: the body is streamed
pub struct ZipArchive(Vec<u8>);

/// Upload a whole campaign: a zip with `poses.json`
/// (`[{"joints_deg","image","set"}]`) and the images it names. All poses are
/// stored in one transaction, or none.
#[utoipa::path(post, path = "/v1/sessions/{id}/dataset", tag = "poses",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = ZipArchive, content_type = "application/zip",
        description = "A zip with `poses.json` (`[{\"joints_deg\", \"image\", \"set\"}]`) and the images it names"),
    responses((status = 201, body = DatasetOut, description = "Every pose of the archive was stored, each image searched for the session's target at upload (`detected_points`)."),
              (status = 400, body = Problem, content_type = "application/problem+json"),
              (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 413, body = Problem, content_type = "application/problem+json"),
              (status = 422, body = Problem, content_type = "application/problem+json")))]
async fn upload_dataset(
    State(state): State<AppState>,
    Path(id): Path<String>,
    req: Request,
) -> ApiResult<(StatusCode, Json<DatasetOut>)> {
    let session = find_session(&state, &id).await?;
    let spec = session_spec(&session)?;
    if spec.instrument != Instrument::Camera {
        return Err(ApiError::invalid(
            "instrument",
            "datasets of images need a camera session",
        ));
    }
    let joint_count = robot_joint_count(&state, &session.serial).await?;
    let content_type = req
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .unwrap_or("");
    if !matches!(
        content_type,
        "application/zip" | "application/x-zip-compressed" | "application/octet-stream"
    ) {
        return Err(ApiError::unsupported_media(
            "send the archive as Content-Type: application/zip",
        ));
    }
    let archive = spool_to_file(&state, req).await?;
    let limits = DatasetLimits {
        max_image_bytes: state.config.max_image_bytes,
        max_total_bytes: state.config.max_archive_bytes,
    };
    let path = archive.path().to_path_buf();
    let mut reader = tokio::task::spawn_blocking(move || DatasetReader::open(&path, limits))
        .await
        .map_err(ApiError::internal)??;
    let mut c = Checker::default();
    if reader.manifest.is_empty() {
        c.fail("poses.json", "holds no poses");
    }
    for (i, p) in reader.manifest.iter().enumerate() {
        check_joints(
            &mut c,
            &format!("poses.json[{i}].joints_deg"),
            &p.joints_deg,
            joint_count,
        );
    }
    c.finish()?;
    let check = ImageCheck::of(&state, &spec);
    let mut staged = StagedImages::new(state.store.clone());
    let mut poses = Vec::with_capacity(reader.manifest.len());
    for i in 0..reader.manifest.len() {
        let doc = reader.manifest[i].clone();
        let field = format!("poses.json[{i}].image");
        let check = check.clone();
        let (back, result) = tokio::task::spawn_blocking(move || {
            let result = reader
                .read_image(&doc.image)
                .map_err(ApiError::from)
                .and_then(|bytes| {
                    inspect_and_hash(&bytes, &check)
                        .map(|ingested| (ingested, bytes))
                        .map_err(|m| ApiError::invalid(field, m))
                });
            (reader, result)
        })
        .await
        .map_err(ApiError::internal)?;
        reader = back;
        let (ingested, bytes) = match result {
            Ok(ok) => ok,
            Err(e) => {
                staged.discard().await;
                return Err(e);
            }
        };
        state.store.put_blob(&ingested.meta, &bytes).await?;
        staged.stored(&ingested.meta.sha256);
        poses.push(NewPose {
            joints_deg: reader.manifest[i].joints_deg.clone(),
            set: reader.manifest[i].set.as_str().to_string(),
            image: Some(ingested.meta),
            points: serde_json::json!([]),
            measured: None,
            label: label_from_archive_path(&reader.manifest[i].image),
            image_detection: ingested.detection.map(|d| d.to_value()),
        });
    }
    let stored = match state.store.add_poses(&session.id, &poses).await {
        Ok(stored) => stored,
        Err(e) => {
            staged.discard().await;
            return Err(e.into());
        }
    };
    staged.keep();
    drop(archive);
    Ok((
        StatusCode::CREATED,
        Json(DatasetOut {
            session_id: session.id,
            poses_created: stored.len(),
            detected_points: stored
                .iter()
                .map(|p| found_points(p.image_detection.as_ref()).len())
                .collect(),
            pose_ids: stored.into_iter().map(|p| p.id).collect(),
        }),
    ))
}

/// The points of a stored `image_detection` document (none when absent).
pub fn found_points(doc: Option<&serde_json::Value>) -> Vec<serde_json::Value> {
    doc.and_then(|d| d["points"].as_array())
        .cloned()
        .unwrap_or_default()
}

/// Streams the request body into a temporary file, stopping at `max_archive_bytes`.
async fn spool_to_file(state: &AppState, req: Request) -> ApiResult<tempfile::NamedTempFile> {
    let limit = state.config.max_archive_bytes;
    if content_length(req.headers()).is_some_and(|n| n > limit) {
        return Err(ApiError::too_large("max_archive_bytes", limit));
    }
    let dir = state.config.upload_dir();
    let temp = tempfile::Builder::new()
        .prefix(crate::housekeeping::SPOOL_PREFIX)
        .tempfile_in(&dir)
        .map_err(|e| ApiError::internal(format!("temp file in {}: {e}", dir.display())))?;
    let std_file = temp.reopen().map_err(ApiError::internal)?;
    let mut file = tokio::io::BufWriter::new(tokio::fs::File::from_std(std_file));
    let mut stream = req.into_body().into_data_stream();
    let mut written: u64 = 0;
    while let Some(chunk) = stream.next().await {
        let chunk =
            chunk.map_err(|e| ApiError::malformed("body", format!("reading upload: {e}")))?;
        written += chunk.len() as u64;
        if written > limit {
            return Err(ApiError::too_large("max_archive_bytes", limit));
        }
        file.write_all(&chunk).await.map_err(ApiError::internal)?;
    }
    file.flush().await.map_err(ApiError::internal)?;
    Ok(temp)
}
