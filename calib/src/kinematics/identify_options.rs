//! How an identification is run (method.md §6): the solver variant and
//! the joint noise model.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IdentifyMode {
    /// Paper eq. 18: Marquardt schedule, plain residuals, no scaling.
    Paper,
    /// Covariance weights, column scaling, gain-ratio damping.
    #[default]
    Weighted,
}

/// Noise of the recorded joint angles (encoders, repeatability).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointNoise {
    /// The same standard deviation (rad) on every joint; 0 ignores it.
    Known { sigma_rad: f64 },
    /// Estimated from the residuals ([`estimate_joint_sigma`]): only
    /// meaningful when the measurement covariances are calibrated (camera
    /// poses from the camera step).
    Estimate,
}

impl Default for JointNoise {
    fn default() -> Self {
        Self::Known { sigma_rad: 0.0 }
    }
}

/// How to identify: the solver variant and the joint noise.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IdentifyOptions {
    pub mode: IdentifyMode,
    pub joint_noise: JointNoise,
}

impl From<IdentifyMode> for IdentifyOptions {
    fn from(mode: IdentifyMode) -> Self {
        Self {
            mode,
            joint_noise: JointNoise::default(),
        }
    }
}

impl IdentifyOptions {
    /// The joint noise to start from: the known value, or none.
    pub(super) fn initial_joint_sigma_rad(&self) -> f64 {
        match self.joint_noise {
            JointNoise::Known { sigma_rad } => sigma_rad.abs(),
            JointNoise::Estimate => 0.0,
        }
    }
}
