//! The typed domain shared by every service layer: serials, labels, joints,
//! targets, parameter sets, job states, tokens. The store's rows (the
//! records whose columns are JSON documents) are `store::records`.

use serde::{Deserialize, Serialize};

mod calibrated_set;
pub mod calibrated_set_schema;
mod check;
mod controller;

mod events;
mod field_error;
mod flange_pose;
pub mod flange_pose_doc;
mod frame_pose;
mod hand_eye_set;
mod image_detection;
mod image_point;
mod instrument;
mod job;
mod joints;
mod kinematics_doc;
mod label;
mod measured_pose;
pub mod numerics_schema;
mod parameter_covariance;
mod parameter_report;
mod parameter_set;
mod parameter_terms;
mod pose_group;
mod pose_set;
mod release;
mod serial;
mod stage_camera_set;
mod stage_reading;
mod target;
mod target_doc;
mod target_symmetry;

pub use calibrated_set::CalibratedSet;
pub use check::{controller_change, CheckDoc, CheckSuspect, CheckVerdict, ControllerChangeSeen};
pub use controller::{
    check_expected as check_controller, expectation as controller_expectation, ControllerChange,
    ControllerIdentity, ControllerMismatch,
};

pub use events::DomainEvent;
pub use field_error::{Checker, FieldError, MAX_ANGLE_DEG, MAX_LENGTH_MM};
pub use flange_pose::{check_robot_pose, FlangePose, PoseKind, RobotPose};
pub use flange_pose_doc::FlangePoseDoc;
pub use frame_pose::PoseOut;
pub use hand_eye_set::HandEyeSet;
pub use image_detection::ImageDetection;
pub use image_point::ImagePointDoc;
pub use instrument::{Instrument, Measurement};
pub use job::{CalibrationResult, CheckResult, JobKind, JobResult, JobSummary};
pub use joints::{JointsDeg, MAX_JOINT_DEG};
pub use kinematics_doc::{
    doc_to_model, model_to_doc, Convention, JointDoc, JointType, KinematicsDoc, MAX_JOINTS,
};
pub use label::{
    check_label, label_from_archive_path, label_from_file_name, label_or_number, LABEL_RULE,
    MAX_LABEL_CHARS,
};
pub use measured_pose::{MeasuredPoint, MeasuredPose};
pub use parameter_covariance::CovarianceDoc;
pub use parameter_report::ParameterReport;
pub use parameter_set::{FrameNames, ParameterSet, SessionBoard};
pub use parameter_terms::{KeptTerm, TermsDoc};
pub use pose_group::{PoseGroup, GROUP_RULE, MAX_GROUP_CHARS};
pub use pose_set::PoseSet;
pub use release::{Decision, Release, ReleaseStatus, ANONYMOUS_ACTOR, GATE_ACTOR};
pub use serial::{InvalidSerial, Serial, MAX_SERIAL_LEN, SERIAL_RULE};
pub use stage_camera_set::{StageCameraSet, StageSequence};
pub use stage_reading::{StageReading, MAX_SEQUENCE};
pub use target::{FoundPoint, Target};
pub use target_doc::{TargetDoc, TargetKind, MAX_GRID_SIDE};
pub use target_symmetry::BoardSymmetry;

/// Metadata of a stored image; the bytes live in the content-addressed blob store.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, utoipa::ToSchema)]
pub struct ImageMeta {
    pub sha256: String,
    pub size_bytes: i64,
    pub content_type: String,
    pub width: u32,
    pub height: u32,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, utoipa::ToSchema)]
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

/// What a lease renewal found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LeaseStatus {
    Held,
    /// Cancelled by a client: stop working, write nothing.
    Cancelled,
    /// The lease was lost (expired and reclaimed): stop, write nothing.
    Lost,
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

#[derive(Debug, Clone, PartialEq)]
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
    /// The key's request wrote (the write committed) but its process died
    /// before storing the answer: it must not run again.
    Lost,
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
