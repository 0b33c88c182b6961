//! Robot documents: the joint table (DH or Hayati per joint) or a preset.

use robocal_calib::kinematics::prior::KinematicPrior;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use robocal_calib::kinematics::presets;

use super::{Checker, FieldError};
use crate::domain::ControllerIdentity;

/// Most joints a robot may have.
pub use crate::domain::MAX_JOINTS;
pub use crate::domain::MAX_SERIAL_LEN;
/// Longest model name.
pub const MAX_MODEL_LEN: usize = 200;

pub use crate::domain::{
    doc_to_model, model_to_doc, Convention, JointDoc, JointType, KinematicsDoc,
};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Preset {
    Irb2400,
    Puma560,
}

impl Preset {
    pub const ALL: [Preset; 2] = [Preset::Irb2400, Preset::Puma560];

    pub fn parse(s: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.as_str() == s)
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Preset::Irb2400 => "irb2400",
            Preset::Puma560 => "puma560",
        }
    }
}

/// `PUT /v1/robots/{serial}` body: a joint table or a preset name.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RobotBody {
    /// The robot model's name, 1 to 200 characters, not only spaces.
    #[schema(min_length = 1, max_length = 200, pattern = r"\S")]
    pub model: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kinematics: Option<KinematicsDoc>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preset: Option<Preset>,
    /// The controller the robot runs on. Sessions record it,
    /// sets inherit it; a change is recorded in the robot's history. A
    /// replacement without it removes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub controller: Option<ControllerIdentity>,
    /// The prior σ of the kinematic parameters' deviations from this table
    /// (docs/method.md §6.7): what a campaign that cannot determine a
    /// parameter leaves it at. Absent: manufacturing tolerances (joint
    /// zeros 0.2°, lengths 1 mm, twists 0.1°).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prior: Option<PriorDoc>,
}

/// The prior standard deviations of a robot's kinematic deviations from
/// its nominal table, per parameter kind.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PriorDoc {
    /// Joint zeros `dtheta` (deg), 0 < σ ≤ 10.
    #[schema(exclusive_minimum = 0.0, maximum = 10.0)]
    pub joint_offset_deg: f64,
    /// Lengths and offsets `a`, `d` (mm), 0 < σ ≤ 100.
    #[schema(exclusive_minimum = 0.0, maximum = 100.0)]
    pub length_mm: f64,
    /// Twists `alpha` and Hayati tilts `beta` (deg), 0 < σ ≤ 10.
    #[schema(exclusive_minimum = 0.0, maximum = 10.0)]
    pub twist_deg: f64,
}

/// Largest prior σ of an angle (deg) and of a length (mm): beyond them a
/// "prior" no longer says anything a table does not.
const MAX_PRIOR_DEG: f64 = 10.0;
const MAX_PRIOR_MM: f64 = 100.0;

impl PriorDoc {
    fn check(&self, c: &mut Checker) {
        for (field, value, max) in [
            (
                "prior.joint_offset_deg",
                self.joint_offset_deg,
                MAX_PRIOR_DEG,
            ),
            ("prior.length_mm", self.length_mm, MAX_PRIOR_MM),
            ("prior.twist_deg", self.twist_deg, MAX_PRIOR_DEG),
        ] {
            if !(value.is_finite() && value > 0.0 && value <= max) {
                c.fail(field, format!("must be > 0 and at most {max}"));
            }
        }
    }
}

impl From<PriorDoc> for KinematicPrior {
    fn from(d: PriorDoc) -> Self {
        Self {
            joint_offset_deg: d.joint_offset_deg,
            length_mm: d.length_mm,
            twist_deg: d.twist_deg,
        }
    }
}

impl From<KinematicPrior> for PriorDoc {
    fn from(p: KinematicPrior) -> Self {
        Self {
            joint_offset_deg: p.joint_offset_deg,
            length_mm: p.length_mm,
            twist_deg: p.twist_deg,
        }
    }
}

/// A serial as the domain type accepts it ([`crate::domain::Serial`]).
pub fn check_serial(serial: &str) -> Result<(), Vec<FieldError>> {
    crate::domain::Serial::parse(serial)
        .map(|_| ())
        .map_err(|e| vec![FieldError::new("serial", e.to_string())])
}

impl RobotBody {
    /// Checks the body and returns the resolved joint table (preset expanded,
    /// every joint's convention chosen).
    pub fn resolve(&self) -> Result<KinematicsDoc, Vec<FieldError>> {
        let mut c = Checker::default();
        if self.model.trim().is_empty() || self.model.len() > MAX_MODEL_LEN {
            c.fail("model", format!("must be 1 to {MAX_MODEL_LEN} characters"));
        }
        let doc = match (&self.kinematics, self.preset) {
            (Some(_), Some(_)) => {
                c.fail("preset", "give either kinematics or preset, not both");
                None
            }
            (None, None) => {
                c.fail("kinematics", "required (or give a preset)");
                None
            }
            (Some(k), None) => Some(k.clone()),
            (None, Some(p)) => Some(preset_doc(p)),
        };
        if let Some(doc) = &doc {
            doc.check(&mut c);
        }
        if let Some(controller) = &self.controller {
            controller.check("controller", &mut c);
        }
        if let Some(prior) = &self.prior {
            prior.check(&mut c);
        }
        c.finish()?;
        Ok(doc
            .map(|d| d.resolved())
            .unwrap_or(KinematicsDoc { joints: vec![] }))
    }
}

/// The nominal joint table of a preset (values and sources in `calib/src/kinematics/presets.rs`).
pub fn preset_doc(preset: Preset) -> KinematicsDoc {
    let model = match preset {
        Preset::Irb2400 => presets::irb2400(),
        Preset::Puma560 => presets::puma560(),
    };
    model_to_doc(&model)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_keeps_given_values() {
        let doc = preset_doc(Preset::Irb2400);
        assert_eq!(model_to_doc(&doc_to_model(&doc)), doc);
        assert_eq!(doc.joints[1].convention, Some(Convention::Hayati));
        assert_eq!(doc.joints[1].alpha_deg, 0.0);
        assert_eq!(doc.joints[0].alpha_deg, -90.0);
    }
}
