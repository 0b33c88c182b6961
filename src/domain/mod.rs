//! Plain records shared by the store, the job workers and the HTTP layer.
//! JSON documents (kinematics, session spec, points, results) travel as
//! `serde_json::Value`: their typed form and validation live in `api/`
//! (contract shapes) and `pipeline` (numerics), the store only keeps them.

use serde::{Deserialize, Serialize};
use serde_json::Value;

mod flange_pose;
mod joints;
mod label;
mod parameter_set;
mod pose_set;
mod serial;
mod target;
pub use flange_pose::{check_robot_pose, FlangePose, PoseKind};
pub use joints::{JointsDeg, MAX_JOINT_DEG};
pub use label::{
    check_label, label_from_archive_path, label_from_file_name, label_or_number, LABEL_RULE,
    MAX_LABEL_CHARS,
};
pub use parameter_set::{FrameNames, ParameterSet};
pub use pose_set::PoseSet;
pub use serial::{InvalidSerial, Serial, MAX_SERIAL_LEN, SERIAL_RULE};
pub use target::{FoundPoint, Target};

/// A robot as stored: the kinematics document is the *resolved* joint table
/// (conventions chosen, presets expanded).
#[derive(Debug, Clone)]
pub struct RobotRecord {
    pub serial: String,
    pub model: String,
    pub preset: Option<String>,
    pub kinematics: Value,
    pub created_at: String,
    pub updated_at: String,
}

#[derive(Debug, Clone)]
pub struct SessionRecord {
    pub id: String,
    pub serial: String,
    pub instrument: String,
    /// The validated session body (target, camera, guesses).
    pub spec: Value,
    pub pose_count: i64,
    pub created_at: String,
}

/// Metadata of a stored image; the bytes live in the content-addressed blob store.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, utoipa::ToSchema)]
pub struct ImageMeta {
    pub sha256: String,
    pub size_bytes: i64,
    pub content_type: String,
    pub width: u32,
    pub height: u32,
}

#[derive(Debug, Clone)]
pub struct PoseRecord {
    pub id: String,
    pub session_id: String,
    pub joints_deg: JointsDeg,
    pub set: PoseSet,
    pub image: Option<ImageMeta>,
    /// `[{"row","col","x","y"}]`: the image points as uploaded (never rewritten;
    /// what a job detected is in `detection`).
    pub points: Value,
    /// `{"measured_position_mm":[..],"measured_pose":{..}?}` for tracker poses.
    pub measured: Option<Value>,
    /// What the pose is called: the uploaded image's file name, or the
    /// `label` a JSON pose sent (see [`NewPose::label`]).
    pub label: Option<String>,
    /// What the last calibration job measured on this pose (see
    /// [`PoseDetection`]); `None` before any job ran its detect stage.
    pub detection: Option<Value>,
    /// What the dot detector found on the image, measured once (at upload,
    /// or by the first job for older poses): `{"points":[..]}` with raw
    /// centres, or `{"points":[],"error","error_kind"}`. `None` for JSON
    /// poses and image poses never detected.
    pub image_detection: Option<Value>,
    /// The controller's flange pose (a `FlangePoseDoc` as uploaded) of a
    /// pose sent without joints (`joints_deg` is then empty).
    pub flange_pose: Option<Value>,
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
    pub detection: Value,
    /// The detector's outcome when this job was the first to detect the
    /// pose's image (stored as the pose's `image_detection` if it has none).
    pub image_detection: Option<Value>,
}

/// A pose to insert; its image blob must already be stored (`put_blob`).
#[derive(Debug, Clone)]
pub struct NewPose {
    pub joints_deg: JointsDeg,
    pub set: PoseSet,
    pub image: Option<ImageMeta>,
    pub points: Value,
    pub measured: Option<Value>,
    /// The image's file name (multipart filename, or its path inside a
    /// dataset archive) or a JSON pose's `label`, so the pose can be traced
    /// back to its photo; `None`: reports number the pose (`#12`).
    pub label: Option<String>,
    /// The detector's outcome on `image`, measured at upload.
    pub image_detection: Option<Value>,
    /// The checked `FlangePoseDoc` of a pose sent with the controller's
    /// flange pose instead of joints (`joints_deg` empty).
    pub flange_pose: Option<Value>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JobState {
    Queued,
    Running,
    Succeeded,
    Failed,
    Cancelled,
}

impl JobState {
    pub const ALL: [JobState; 5] = [
        JobState::Queued,
        JobState::Running,
        JobState::Succeeded,
        JobState::Failed,
        JobState::Cancelled,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            JobState::Queued => "queued",
            JobState::Running => "running",
            JobState::Succeeded => "succeeded",
            JobState::Failed => "failed",
            JobState::Cancelled => "cancelled",
        }
    }

    pub fn parse(s: &str) -> Option<JobState> {
        JobState::ALL.into_iter().find(|st| st.as_str() == s)
    }

    pub fn is_terminal(self) -> bool {
        matches!(
            self,
            JobState::Succeeded | JobState::Failed | JobState::Cancelled
        )
    }
}

#[derive(Debug, Clone)]
pub struct JobRecord {
    pub id: String,
    pub kind: String,
    pub session_id: String,
    pub serial: String,
    pub options: Value,
    pub state: JobState,
    pub stage: Option<String>,
    pub progress: f64,
    pub attempts: i64,
    pub max_attempts: i64,
    pub error: Option<String>,
    pub result: Option<Value>,
    pub created_at: String,
    pub started_at: Option<String>,
    pub finished_at: Option<String>,
}

#[derive(Debug, Clone)]
pub struct NewJob {
    pub kind: String,
    pub session_id: String,
    pub serial: String,
    pub options: Value,
    pub max_attempts: i64,
}

/// A job a worker holds a lease on.
#[derive(Debug, Clone)]
pub struct ClaimedJob {
    pub id: String,
    pub session_id: String,
    pub serial: String,
    pub options: Value,
    pub attempt: i64,
}

/// What a lease renewal found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LeaseStatus {
    Held,
    /// Cancelled by a client: stop working, write nothing.
    Cancelled,
    /// The lease was lost (expired and reclaimed): stop, write nothing.
    Lost,
}

/// A finished job's outcome, written in one transaction with its results.
#[derive(Debug, Clone)]
pub enum JobOutcome {
    Succeeded {
        /// When the pipeline identified parameters: stored as the next version.
        parameter_set: Option<NewParameterSet>,
        /// Extra result document (e.g. the validation summary).
        summary: Value,
        /// Every pose's final image points with residuals (empty: keep
        /// what the detect stage stored).
        detections: Vec<PoseDetection>,
    },
    /// Failed for good (bad input): no retry.
    Failed { error: String },
    /// Failed for a reason a retry may fix: requeued while attempts remain.
    Retry { error: String },
}

#[derive(Debug, Clone)]
pub struct NewParameterSet {
    pub parameters: Value,
    pub report: Value,
}

#[derive(Debug, Clone)]
pub struct ParameterSetRecord {
    pub serial: String,
    pub version: i64,
    pub job_id: Option<String>,
    pub parameters: Value,
    pub created_at: String,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scope {
    Read,
    Write,
    Admin,
}

impl Scope {
    pub fn as_str(self) -> &'static str {
        match self {
            Scope::Read => "read",
            Scope::Write => "write",
            Scope::Admin => "admin",
        }
    }
    pub fn parse(s: &str) -> Option<Scope> {
        match s {
            "read" => Some(Scope::Read),
            "write" => Some(Scope::Write),
            "admin" => Some(Scope::Admin),
            _ => None,
        }
    }
}

#[derive(Debug, Clone)]
pub struct TokenRecord {
    pub id: String,
    pub name: String,
    pub scope: Scope,
    pub created_at: String,
    /// Unix ms after which the token is refused; `None`: never expires.
    pub expires_ms: Option<i64>,
    /// Unix ms of its revocation; a revoked token keeps its row.
    pub revoked_ms: Option<i64>,
    /// Unix ms of its last accepted use (written at most once a minute).
    pub last_used_ms: Option<i64>,
}

/// Why a known token is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TokenRefusal {
    Revoked,
    Expired,
}

impl TokenRecord {
    /// `Ok` when the token may be used at `now_ms`.
    pub fn check_usable(&self, now_ms: i64) -> Result<(), TokenRefusal> {
        if self.revoked_ms.is_some() {
            return Err(TokenRefusal::Revoked);
        }
        match self.expires_ms {
            Some(expires) if expires <= now_ms => Err(TokenRefusal::Expired),
            _ => Ok(()),
        }
    }
}

/// A response kept for `Idempotency-Key` replay.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StoredResponse {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

/// State of an idempotency key when a request first looks at it.
#[derive(Debug, Clone)]
pub enum IdempotencyClaim {
    /// First use: the caller holds the key (under a lease it renews), runs
    /// the request and then stores the response or abandons the key.
    Fresh,
    /// Another request with this key is running (its holder's lease is live).
    InFlight,
    /// The key belongs to a request with another method or path.
    OtherRequest { method: String, path: String },
    /// Done before: replay `response` if this request has the same
    /// `fingerprint` (`None`: stored without one, replayed for any body).
    Done {
        fingerprint: Option<String>,
        response: StoredResponse,
    },
}

/// Identifies the owner and target of an idempotency key, and the one
/// request (`holder`, unique per attempt) that may complete or renew it.
#[derive(Debug, Clone)]
pub struct IdempotencyScope {
    pub principal: String,
    pub method: String,
    pub path: String,
    pub key: String,
    pub holder: String,
}

/// A page of a listing, ordered by key; `next_cursor` is the last key when more may follow.
#[derive(Debug, Clone)]
pub struct Page<T> {
    pub items: Vec<T>,
    pub next_cursor: Option<String>,
}

/// RFC 3339 UTC timestamp with milliseconds, the form every `*_at` field uses.
pub fn now_rfc3339() -> String {
    humantime::format_rfc3339_millis(std::time::SystemTime::now()).to_string()
}

/// `ms` (Unix milliseconds) as an RFC 3339 UTC timestamp, like [`now_rfc3339`].
pub fn rfc3339_of_unix_ms(ms: i64) -> String {
    let time = std::time::UNIX_EPOCH + std::time::Duration::from_millis(ms.max(0) as u64);
    humantime::format_rfc3339_millis(time).to_string()
}

pub fn now_unix_ms() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_millis() as i64)
        .unwrap_or(0)
}

/// New time-ordered identifier (UUIDv7), so listing by id is listing by age.
pub fn new_id() -> String {
    uuid::Uuid::now_v7().to_string()
}
