//! Campaign planning (issue 16): which poses to shoot, and how good the
//! result will be, before the robot moves.
//!
//! Candidates (camera stations within the distance and view-angle ranges,
//! solved by the nominal inverse kinematics and filtered by joint limits,
//! board visibility, keep-out boxes and distance from singularities) feed a
//! greedy D-optimal selection with exchange on the information of the
//! image-level identification a job runs (method.md §6 **beyond**: the
//! kinematics, `target_to_base`, `flange_to_camera` and the intrinsics on
//! the raw dots); a calibration plan then exchanges poses for the predicted
//! camera-position variance at random validation poses (I-optimal). The
//! chosen poses are ordered into a short joint-space
//! path; the predicted parameter covariance `sigma_px^2 (J^T J)^-1` is
//! propagated to random validation poses in the same ranges.

pub mod candidates;
pub mod error;
pub mod extension;
pub mod information;
pub mod path;
pub mod planner;
pub mod predict;
pub mod request;
pub mod select;
pub mod station;

pub use error::{FilterCount, PlanError};
pub use extension::ExistingCampaign;
pub use planner::{plan_campaign, CampaignPlan, PlannedPose};
pub use request::{KeepOutBox, PlanCriterion, PlanPurpose, PlanRequest};
