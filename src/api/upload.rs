//! Uploads at the HTTP edge: multipart parts read under their limits (for
//! the pose routes), and the dataset archive `POST /v1/sessions/{id}/dataset`
//! streamed to a temporary file (never whole in memory) under the configured
//! limit, then handed to [`crate::service::intake`].

use axum::extract::multipart::Field;
use axum::extract::{Path, Request, State};
use axum::http::{header, StatusCode};
use axum::Json;
use futures_util::StreamExt;
use serde::Serialize;
use tokio::io::AsyncWriteExt;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::content_length;
use super::AppState;
use crate::service::dataset::DatasetLimits;
use crate::service::dataset_warning::detection_warning;
use crate::service::intake::PoseIntake;

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
    /// What the upload warns of although it stored every pose, e.g. "0 of
    /// 32 images show the session's target; 32 say: …" (the job would fail).
    pub warnings: Vec<String>,
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

/// A zip archive's bytes (the dataset upload's body schema).
#[derive(ToSchema)]
#[schema(value_type = String, format = Binary)]
#[allow(dead_code)] // a schema only: the body is streamed
pub struct ZipArchive(Vec<u8>);

/// Upload a whole campaign: a zip with `poses.json`
/// (`[{"joints_deg","image","set"}]`, or `flange_pose` instead of
/// `joints_deg`: the controller's flange pose in the base frame) and the
/// images it names. All poses are stored in one transaction, or none.
#[utoipa::path(post, path = "/v1/sessions/{id}/dataset", tag = "poses",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = ZipArchive, content_type = "application/zip",
        description = "A zip with `poses.json` (`[{\"joints_deg\", \"image\", \"set\"}]`; a pose may carry the controller's `flange_pose` instead of `joints_deg`, a session not both kinds) and the images it names"),
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
    let intake = PoseIntake::open(&state.store, state.decode_gate.clone(), &id).await?;
    intake.check_takes_dataset()?;
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
        test_pause_per_image: std::time::Duration::from_millis(state.config.test_upload_delay_ms),
    };
    let session_id = intake.session.id.clone();
    let stored = intake.add_dataset(archive.path(), limits).await?;
    drop(archive);
    Ok((
        StatusCode::CREATED,
        Json(DatasetOut {
            session_id,
            poses_created: stored.len(),
            warnings: detection_warning(&stored).into_iter().collect(),
            detected_points: stored
                .iter()
                .map(|p| p.image_detection.as_ref().map_or(0, |d| d.points.len()))
                .collect(),
            pose_ids: stored.into_iter().map(|p| p.id).collect(),
        }),
    ))
}

/// Streams the request body into a temporary file, stopping at `max_archive_bytes`.
async fn spool_to_file(state: &AppState, req: Request) -> ApiResult<tempfile::NamedTempFile> {
    let limit = state.config.max_archive_bytes;
    if content_length(req.headers()).is_some_and(|n| n > limit) {
        return Err(ApiError::too_large("max_archive_bytes", limit));
    }
    let dir = state.config.upload_dir();
    let temp = tempfile::Builder::new()
        .prefix(&crate::housekeeping::spool_prefix())
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
