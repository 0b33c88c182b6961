//! A quick re-check's verdict (issue 17), as the job's `result` holds it:
//! a short session judged against the robot's latest approved set by the
//! chi-square test of `robocal_calib::kinematics::recheck`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::ControllerIdentity;

/// `pass`, `drift`, `base_moved` or `controller_changed`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CheckVerdict {
    /// The residuals are what the set's covariance and the measurement
    /// noise predict.
    Pass,
    /// They are not, and re-fitting the base alone does not explain them.
    Drift,
    /// Re-fitting the board's (or tracker's) transform alone explains them.
    BaseMoved,
    /// The check's session was measured on another controller than the
    /// set records: whatever the residuals, the set is not the
    /// controller's any more (swapped, re-mastered, its calibration
    /// reloaded). The test's figures are still given.
    ControllerChanged,
}

impl CheckVerdict {
    /// Its serde name (the webhook's and the job result's `verdict`).
    pub fn as_str(self) -> &'static str {
        match self {
            CheckVerdict::Pass => "pass",
            CheckVerdict::Drift => "drift",
            CheckVerdict::BaseMoved => "base_moved",
            CheckVerdict::ControllerChanged => "controller_changed",
        }
    }
}

/// A parameter that may have changed, most likely first.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct CheckSuspect {
    /// Its name in the parameter set (`dtheta_2`, `a_3`, ...), or a kept
    /// non-geometric term's (`periodic_4.cos2`, ...).
    pub name: String,
    /// `deg` or `mm`; a term's own unit (`rad`, `rad*kg/(N*m)`, ...).
    pub unit: String,
    /// The change that best explains the residuals beyond the base.
    pub change: f64,
    /// `change` in units of the set's standard deviation of the parameter.
    pub change_sigmas: f64,
    /// The part of the chi-square statistic it explains.
    pub chi2_drop: f64,
}

/// The re-check job's `result`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct CheckDoc {
    pub verdict: CheckVerdict,
    /// Mean length of the position residuals against the set (mm).
    pub mean_mm: f64,
    /// What the set predicts for it (mm): the mean over poses of the RMS
    /// length its covariance and the measurement noise give.
    pub expected_mean_mm: f64,
    /// Upper-tail probability of the chi-square statistic.
    pub p_value: f64,
    /// The same after re-fitting the base transform alone.
    pub base_p_value: f64,
    pub chi2: f64,
    pub dof: usize,
    /// The test's level: `pass` when `p_value` is at least this.
    pub significance: f64,
    /// The test, in a sentence.
    pub test: String,
    /// The set judged: `"{serial}/{version}"`.
    pub checked_against: String,
    /// That set's version (the `check.finished` event's `version`), typed
    /// so nothing parses it back out of `checked_against`. Absent from
    /// checks stored before it was carried (read as 0).
    #[serde(default)]
    pub checked_version: i64,
    /// The joint noise the test assumed (deg): the set's own estimate, or
    /// the service's fallback for a set that carries none. Absent from
    /// checks stored before it was recorded (read as 0).
    #[serde(default)]
    pub joint_noise_deg: f64,
    /// Poses measured.
    pub poses: usize,
    pub suspects: Vec<CheckSuspect>,
    /// With `controller_changed`: the controller the set records and the
    /// one the check's session was measured on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub controller_change: Option<ControllerChangeSeen>,
}

/// The two controller identities behind a `controller_changed` verdict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ControllerChangeSeen {
    /// What the checked set records.
    pub set: ControllerIdentity,
    /// What the check's session records (the robot's when it was created).
    pub session: ControllerIdentity,
}

/// The change a check sees, when both the set and the check's session
/// record a controller and they differ; a side that records none is not
/// taken as a change (nothing is known about it).
pub fn controller_change(
    set: Option<&ControllerIdentity>,
    session: Option<&ControllerIdentity>,
) -> Option<ControllerChangeSeen> {
    match (set, session) {
        (Some(a), Some(b)) if a != b => Some(ControllerChangeSeen {
            set: a.clone(),
            session: b.clone(),
        }),
        _ => None,
    }
}
