//! The release gate of a parameter set (issue 17): `approved` sets are what
//! `latest` serves, a `candidate` waits for a person, a `rejected` one is
//! kept for the record only. The gate's decision at the end of a job and a
//! person's approve/reject are the same [`Release`], recorded with who and
//! when ([`Decision`]).

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Who decided when the job's own gate did (not a person).
pub const GATE_ACTOR: &str = "gate";
/// Who decided when no token was presented (a server without tokens).
pub const ANONYMOUS_ACTOR: &str = "anonymous";

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ReleaseStatus {
    Approved,
    Candidate,
    Rejected,
}

impl ReleaseStatus {
    pub fn as_str(self) -> &'static str {
        match self {
            ReleaseStatus::Approved => "approved",
            ReleaseStatus::Candidate => "candidate",
            ReleaseStatus::Rejected => "rejected",
        }
    }

    pub fn parse(s: &str) -> Option<ReleaseStatus> {
        match s {
            "approved" => Some(ReleaseStatus::Approved),
            "candidate" => Some(ReleaseStatus::Candidate),
            "rejected" => Some(ReleaseStatus::Rejected),
            _ => None,
        }
    }
}

/// A status with why it was given.
#[derive(Debug, Clone, PartialEq)]
pub struct Release {
    pub status: ReleaseStatus,
    pub reason: Option<String>,
}

impl Release {
    /// A set stored outside a job's gate (imports, the test hooks): approved,
    /// as every set was before the gate existed.
    pub fn stored_directly() -> Release {
        Release {
            status: ReleaseStatus::Approved,
            reason: Some("stored without a gate decision".into()),
        }
    }
}

/// One recorded status change of a parameter set.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Decision {
    pub version: i64,
    pub status: ReleaseStatus,
    pub reason: Option<String>,
    /// `gate` (the job's automatic decision), the token's name, or `anonymous`.
    pub decided_by: String,
    pub decided_at: String,
}
