//! An uploaded image: checked (header against the session camera before any
//! decode), decoded once under the process's decode gate, searched for the
//! session's target, hashed and stored. A board not found is no error: the
//! image is kept and the reason returned with it.

use std::sync::Arc;

use sha2::{Digest, Sha256};

use super::error::{ServiceError, ServiceResult};
use crate::domain::{ImageDetection, ImageMeta, Target};
use crate::imaging::{self, DecodeGate};
use crate::schema::session::SessionBody;
use crate::store::DynStore;

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
    /// The session's key in the decode gate's fair share.
    pub session_id: String,
    pub camera_size: Option<(u32, u32)>,
    pub target: Option<Target>,
    pub gate: Arc<DecodeGate>,
}

impl ImageCheck {
    pub fn of(session_id: &str, spec: &SessionBody, gate: Arc<DecodeGate>) -> ImageCheck {
        ImageCheck {
            session_id: session_id.to_string(),
            camera_size: spec.camera.as_ref().map(|c| (c.width, c.height)),
            // Checked when the session was created.
            target: spec.target.as_ref().and_then(|t| Target::from_doc(t).ok()),
            gate,
        }
    }
}

/// Checks an image on a blocking thread (see [`inspect_and_hash`]) and
/// stores it; returns it once it is durable. `field` names the image in
/// the error.
pub async fn ingest_image(
    store: DynStore,
    bytes: Vec<u8>,
    check: ImageCheck,
    field: String,
) -> ServiceResult<Ingested> {
    let (ingested, bytes) = tokio::task::spawn_blocking(move || {
        inspect_and_hash(&bytes, &check).map(|ingested| (ingested, bytes))
    })
    .await
    .map_err(ServiceError::internal)?
    .map_err(|message| ServiceError::invalid(field, message))?;
    store.put_blob(&ingested.meta, &bytes).await?;
    Ok(ingested)
}

/// Blocking: the header check, one bounded decode under the gate, the dot
/// detector, and the image's hash.
pub fn inspect_and_hash(bytes: &[u8], check: &ImageCheck) -> Result<Ingested, String> {
    let inspected = imaging::inspect(
        bytes,
        check.camera_size,
        check.target.as_ref(),
        &check.gate,
        &check.session_id,
    )?;
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
