//! The pose documents the routes answer: a stored pose as served, its image
//! points, and the multipart upload's schema. The stored JSON of a pose
//! (points, detections, measurements) is read here, at the HTTP edge.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use utoipa::ToSchema;

use crate::domain::{ImageMeta, PoseGroup};
use crate::schema::flange_pose::FlangePoseDoc;
use crate::schema::pose_body::ImagePointDoc;
use crate::schema::session::PoseSet;
use crate::schema::PoseDoc;
use crate::store::PoseRecord;

#[derive(Debug, Serialize, ToSchema)]
pub struct PoseOut {
    pub id: String,
    pub session_id: String,
    /// The joint angles (empty for a pose sent with `flange_pose`).
    pub joints_deg: Vec<f64>,
    /// The controller's flange pose in the base frame, as uploaded, for a
    /// pose sent with it instead of joints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flange_pose: Option<FlangePoseDoc>,
    /// A stage session's image: the stage's reading (mm, stage axes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage_position_mm: Option<[f64; 3]>,
    /// A stage session's image: its sequence (board placement).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sequence: Option<u32>,
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
    /// The arm configuration the pose was taken in, as uploaded. Absent:
    /// a job groups the pose by its joints 1–3.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
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
    /// A camera pose may send `flange_pose` instead (not both).
    pub joints_deg: Option<String>,
    /// The controller's flange pose in the base frame, as JSON:
    /// `{"translation_mm": [x, y, z], "rotation_deg": [rx, ry, rz]}` (fixed
    /// X-Y-Z angles, `R = Rz Ry Rx`) or `{"translation_mm", "matrix": 3x3}`.
    pub flange_pose: Option<String>,
    /// Stage sessions (instead of joints): the stage's reading, JSON
    /// `[x, y, z]` in mm (the stage's axes).
    pub stage_position_mm: Option<String>,
    /// Stage sessions: the sequence (board placement) of the image, 1 to 1000.
    pub sequence: Option<u32>,
    /// `cal` (default) or `val`.
    pub set: Option<PoseSet>,
    /// The arm configuration the photo was taken in, e.g. `shoulder_a`
    /// (1 to 32 of `A-Z a-z 0-9 _ -`): poses of one group are held out
    /// together when the job chooses its model. Absent: grouped by joints
    /// 1–3.
    #[schema(pattern = "^[A-Za-z0-9_-]{1,32}$")]
    pub group: Option<String>,
    /// The photo of the board, PNG or JPEG.
    #[schema(value_type = String, format = Binary)]
    pub image: Vec<u8>,
}

/// How a pose's points were measured by the last calibration job.
#[derive(Debug, Serialize, ToSchema)]
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
        let uploaded = || p.points.iter().map(point_json).collect::<Vec<Value>>();
        let (points, detection_error) = match (&p.detection, &p.image_detection) {
            (Some(job), _) => (
                job["points"].as_array().cloned().unwrap_or_else(uploaded),
                job["error"].as_str().map(str::to_string),
            ),
            (None, Some(found)) => (
                found.points.iter().map(point_json).collect(),
                found.error.clone(),
            ),
            (None, None) => (uploaded(), None),
        };
        let detection = p.detection.and_then(|d| stored_detection(&p.id, d));
        let source = if p.image.is_some() {
            "image"
        } else if p.measured.is_none() {
            "image_points"
        } else {
            "measured"
        };
        let measured = p.measured.unwrap_or_default();
        PoseOut {
            id: p.id,
            session_id: p.session_id,
            joints_deg: p.joints_deg.into_vec(),
            flange_pose: p.flange_pose,
            stage_position_mm: p.stage_reading.map(|r| r.stage_position_mm),
            sequence: p.stage_reading.map(|r| r.sequence),
            set: p.set,
            source: source.into(),
            detected_points: points.len(),
            points,
            detection_error,
            detection,
            image: p.image,
            measured_position_mm: measured.measured_position_mm,
            measured_pose: measured.measured_pose,
            label: p.label,
            group: p.group.map(PoseGroup::into_string),
            created_at: p.created_at,
        }
    }
}

/// One image point in the served form (`points` mixes these with a job's
/// points, which carry residuals).
fn point_json(p: &ImagePointDoc) -> Value {
    serde_json::json!({"row": p.row, "col": p.col, "x": p.x, "y": p.y})
}

/// What a job stored of its measurement on a pose, as served: `None`
/// until a job has stamped it with its id (the detect stage's interim
/// write carries none). A document that does not read is logged with the
/// pose, not served as a blank.
fn stored_detection(pose_id: &str, doc: Value) -> Option<PoseDetectionOut> {
    #[derive(Deserialize)]
    struct Stored {
        job_id: Option<String>,
        #[serde(default)]
        error: Option<String>,
        #[serde(default)]
        residual_rms_px: Option<f64>,
    }
    match serde_json::from_value::<Stored>(doc) {
        Ok(s) => Some(PoseDetectionOut {
            job_id: s.job_id?,
            error: s.error,
            residual_rms_px: s.residual_rms_px,
        }),
        Err(e) => {
            tracing::error!(pose_id, error = %e, "stored detection unreadable");
            None
        }
    }
}
