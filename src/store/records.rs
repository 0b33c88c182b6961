//! The store's rows: what `Store` reads and writes, one record per table.
//! The pose columns a job or a handler reads are typed here, converted once
//! when a row is read or written (`rows.rs`, `repo/`). The columns that
//! remain JSON documents are those the service passes through as they were
//! stored (a robot's kinematics document, a job's options and result, a
//! parameter set and its report, a job's per-pose detection): the code that
//! reads them types them once, where it reads them.

use robocal_calib::kinematics::prior::KinematicPrior;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::domain::FlangePoseDoc;
use crate::domain::ImagePointDoc;
use crate::domain::{
    CalibratedSet, CheckDoc, ImageDetection, ImageMeta, JobKind, JobResult, JobState, JobSummary,
    JointsDeg, MeasuredPose, PoseSet, Release, ReleaseStatus,
};
use crate::domain::{ControllerIdentity, PoseGroup, StageReading};
use crate::schema::job::JobOptions;
use crate::schema::session::SessionBody;
use crate::schema::PoseDoc;

/// What a laser tracker measured for one pose (the column `measured`): the
/// target position, and its orientation when the tracker gave one.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TrackerMeasurement {
    #[serde(default)]
    pub measured_position_mm: Option<[f64; 3]>,
    #[serde(default)]
    pub measured_pose: Option<PoseDoc>,
}

/// A robot as stored: the kinematics document is the *resolved* joint table
/// (conventions chosen, presets expanded).
#[derive(Debug, Clone)]
pub struct RobotRecord {
    pub serial: String,
    pub model: String,
    pub preset: Option<String>,
    pub kinematics: Value,
    /// The controller identity; written by
    /// `RobotStore::set_robot_controller`, never by `put_robot`.
    pub controller: Option<ControllerIdentity>,
    /// The prior on the kinematic deviations (docs/method.md §6.7);
    /// `None`: manufacturing tolerances.
    pub prior: Option<KinematicPrior>,
    pub created_at: String,
    pub updated_at: String,
}

#[derive(Debug, Clone)]
pub struct SessionRecord {
    pub id: String,
    pub serial: String,
    pub instrument: String,
    /// The validated session body (target, camera, guesses).
    pub spec: SessionBody,
    pub pose_count: i64,
    pub created_at: String,
}

#[derive(Debug, Clone)]
pub struct PoseRecord {
    pub id: String,
    pub session_id: String,
    pub joints_deg: JointsDeg,
    pub set: PoseSet,
    pub image: Option<ImageMeta>,
    /// The image points as uploaded (never rewritten; what a job detected
    /// is in `detection`).
    pub points: Vec<ImagePointDoc>,
    /// What the tracker measured, for tracker poses.
    pub measured: Option<TrackerMeasurement>,
    /// What the pose is called: the uploaded image's file name, or the
    /// `label` a JSON pose sent (see [`NewPose::label`]).
    pub label: Option<String>,
    /// What the last calibration job measured on this pose (see
    /// [`PoseDetection`]); `None` before any job ran its detect stage.
    pub detection: Option<Value>,
    /// What the dot detector found on the image, measured once (at upload,
    /// or by the first job for older poses): raw centres, or why it found
    /// none. `None` for JSON poses and image poses never detected.
    pub image_detection: Option<ImageDetection>,
    /// The controller's flange pose as uploaded (checked then) of a pose
    /// sent without joints (`joints_deg` is then empty).
    pub flange_pose: Option<FlangePoseDoc>,
    /// The stage's reading of a stage session's image (`joints_deg` empty).
    pub stage_reading: Option<StageReading>,
    /// The arm configuration the client named (see [`NewPose::group`]).
    pub group: Option<PoseGroup>,
    pub created_at: String,
}

/// One pose's image points as a calibration job measured them:
/// `{"job_id","points":[{"row","col","x","y","residual_px"?}],"error"?,...}`.
/// A job writes these for every pose of its session at once (after its
/// detect stage, and again with residuals when it succeeds), replacing the
/// previous job's.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseDetection {
    pub pose_id: String,
    pub detection: MeasuredPose,
    /// The detector's outcome when this job was the first to detect the
    /// pose's image (stored as the pose's `image_detection` if it has none).
    pub image_detection: Option<ImageDetection>,
}

/// A pose to insert; its image blob must already be stored (`put_blob`).
#[derive(Debug, Clone)]
pub struct NewPose {
    pub joints_deg: JointsDeg,
    pub set: PoseSet,
    pub image: Option<ImageMeta>,
    pub points: Vec<ImagePointDoc>,
    pub measured: Option<TrackerMeasurement>,
    /// The image's file name (multipart filename, or its path inside a
    /// dataset archive) or a JSON pose's `label`, so the pose can be traced
    /// back to its photo; `None`: reports number the pose (`#12`).
    pub label: Option<String>,
    /// The detector's outcome on `image`, measured at upload.
    pub image_detection: Option<ImageDetection>,
    /// The checked flange pose of a pose sent with the controller's flange
    /// pose instead of joints (`joints_deg` empty).
    pub flange_pose: Option<FlangePoseDoc>,
    /// The checked stage reading of a stage session's image.
    pub stage_reading: Option<StageReading>,
    /// The arm configuration the client named for the pose (its `group`);
    /// `None`: a job groups the pose by its joints 1–3.
    pub group: Option<PoseGroup>,
}

#[derive(Debug, Clone)]
pub struct JobRecord {
    pub id: String,
    pub kind: JobKind,
    pub session_id: String,
    pub serial: String,
    pub options: JobOptions,
    pub state: JobState,
    pub stage: Option<String>,
    pub progress: f64,
    pub attempts: i64,
    pub max_attempts: i64,
    pub error: Option<String>,
    pub result: Option<JobResult>,
    pub created_at: String,
    pub started_at: Option<String>,
    pub finished_at: Option<String>,
}

#[derive(Debug, Clone)]
pub struct NewJob {
    pub session_id: String,
    pub serial: String,
    /// The job's options, which name its kind.
    pub options: JobOptions,
    pub max_attempts: i64,
}

/// A job a worker holds a lease on.
#[derive(Debug, Clone)]
pub struct ClaimedJob {
    pub id: String,
    pub kind: JobKind,
    pub session_id: String,
    pub serial: String,
    pub options: JobOptions,
    pub attempt: i64,
}

/// A finished job's outcome, written in one transaction with its results.
#[derive(Debug, Clone)]
// One per finished job: a box would buy nothing measurable.
#[allow(clippy::large_enum_variant)]
pub enum JobOutcome {
    Succeeded {
        /// When the pipeline identified parameters: stored as the next version.
        parameter_set: Option<NewParameterSet>,
        /// The job's `result.summary`.
        summary: JobSummary,
        /// Every pose's final image points with residuals (empty: keep
        /// what the detect stage stored).
        detections: Vec<PoseDetection>,
        /// A quick re-check's verdict document, merged into the
        /// job's `result` at its top level.
        check: Option<Box<CheckDoc>>,
    },
    /// Failed for good (bad input): no retry.
    Failed { error: String },
    /// Failed for a reason a retry may fix: requeued while attempts remain.
    Retry { error: String },
}

#[derive(Debug, Clone)]
pub struct NewParameterSet {
    pub parameters: CalibratedSet,
    pub report: Value,
    /// The release gate's decision (recorded as decided by `gate`).
    pub release: Release,
}

impl NewParameterSet {
    /// A set stored outside a job's gate: approved (see
    /// [`Release::stored_directly`]).
    pub fn approved(parameters: CalibratedSet, report: Value) -> NewParameterSet {
        NewParameterSet {
            parameters,
            report,
            release: Release::stored_directly(),
        }
    }
}

#[derive(Debug, Clone)]
pub struct ParameterSetRecord {
    pub serial: String,
    pub version: i64,
    pub job_id: Option<String>,
    pub parameters: CalibratedSet,
    pub created_at: String,
    pub status: ReleaseStatus,
    pub status_reason: Option<String>,
    /// Who gave the current status (`gate`, a token, `anonymous`); `None`
    /// for sets approved by the migration that introduced the gate.
    pub status_by: Option<String>,
    pub status_at: Option<String>,
}

/// Which jobs `list_jobs` answers (`None`: any).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct JobFilter {
    pub state: Option<JobState>,
    pub serial: Option<String>,
    pub kind: Option<JobKind>,
}

/// A webhook subscription (the secret signs every delivery's body).
#[derive(Debug, Clone, PartialEq)]
pub struct WebhookRecord {
    pub id: String,
    pub url: String,
    /// Event names, each one of `DomainEvent::NAMES`.
    pub events: Vec<String>,
    pub secret: String,
    pub created_at: String,
}

/// One event to send to one webhook, claimed by a delivery loop.
#[derive(Debug, Clone, PartialEq)]
pub struct OutboxDelivery {
    /// The outbox row (`event id/webhook id`).
    pub id: String,
    pub event_id: String,
    pub event: String,
    /// The JSON document to send, as stored (what the signature covers).
    pub body: String,
    /// Attempts made before this one.
    pub attempts: i64,
    pub url: String,
    pub secret: String,
}
