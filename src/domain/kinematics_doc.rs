//! A robot's joint table as the contract writes it (degrees, conventions
//! named) and its conversion to and from the numerics' model (radians,
//! method.md §5); stored with the robot and in every kinematic set.

use robocal_calib::kinematics::model::choose_conventions;
use robocal_calib::kinematics::{Convention as CoreConvention, Joint, RobotModel};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::{Checker, MAX_ANGLE_DEG, MAX_LENGTH_MM};

/// Most joints of a robot.
pub const MAX_JOINTS: usize = 12;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum JointType {
    Revolute,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Convention {
    Dh,
    Hayati,
}

fn default_min_deg() -> f64 {
    -180.0
}
fn default_max_deg() -> f64 {
    180.0
}

/// One joint and the link after it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct JointDoc {
    #[serde(rename = "type", default = "revolute")]
    pub joint_type: JointType,
    /// `dh` or `hayati`; absent: chosen by the service (Hayati for parallel axes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub convention: Option<Convention>,
    pub a_mm: f64,
    pub alpha_deg: f64,
    #[serde(default)]
    pub d_mm: f64,
    #[serde(default)]
    pub theta_offset_deg: f64,
    #[serde(default)]
    pub beta_deg: f64,
    #[serde(default = "default_min_deg")]
    pub min_deg: f64,
    #[serde(default = "default_max_deg")]
    pub max_deg: f64,
}

fn revolute() -> JointType {
    JointType::Revolute
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct KinematicsDoc {
    pub joints: Vec<JointDoc>,
}

impl KinematicsDoc {
    pub fn check(&self, c: &mut Checker) {
        let n = self.joints.len();
        if n == 0 || n > MAX_JOINTS {
            c.fail(
                "kinematics.joints",
                format!("must hold 1 to {MAX_JOINTS} joints"),
            );
        }
        for (i, j) in self.joints.iter().enumerate() {
            let f = |name: &str| format!("kinematics.joints[{i}].{name}");
            c.bounded(f("a_mm"), j.a_mm, MAX_LENGTH_MM, "mm");
            c.bounded(f("d_mm"), j.d_mm, MAX_LENGTH_MM, "mm");
            c.bounded(f("alpha_deg"), j.alpha_deg, MAX_ANGLE_DEG, "deg");
            c.bounded(
                f("theta_offset_deg"),
                j.theta_offset_deg,
                MAX_ANGLE_DEG,
                "deg",
            );
            c.bounded(f("beta_deg"), j.beta_deg, MAX_ANGLE_DEG, "deg");
            c.bounded(f("min_deg"), j.min_deg, MAX_ANGLE_DEG, "deg");
            c.bounded(f("max_deg"), j.max_deg, MAX_ANGLE_DEG, "deg");
            if j.min_deg >= j.max_deg {
                c.fail(f("max_deg"), "must be greater than min_deg");
            }
            if j.convention == Some(Convention::Dh) && j.beta_deg != 0.0 {
                c.fail(f("beta_deg"), "only a hayati joint has beta");
            }
        }
    }

    /// Every joint with its convention set, as the numerics will use it
    /// (the core's `choose_conventions`: Hayati between parallel axes).
    pub fn resolved(self) -> KinematicsDoc {
        model_to_doc(&doc_to_model(&self))
    }
}

// Conversion between the joint table (degrees) and the numerics' RobotModel
// (radians), and preset expansion. The convention rule (Hayati for a link
// between parallel axes, `d` carried to the next link) is the core's
// `choose_conventions`.

/// Degrees shown to users are rounded to this many decimals, so that a
/// degree -> radian -> degree round trip prints the value that was given.
const DEG_DECIMALS: f64 = 1e9;

fn to_core(c: Convention) -> CoreConvention {
    match c {
        Convention::Dh => CoreConvention::Dh,
        Convention::Hayati => CoreConvention::Hayati,
    }
}

fn from_core(c: CoreConvention) -> Convention {
    match c {
        CoreConvention::Dh => Convention::Dh,
        CoreConvention::Hayati => Convention::Hayati,
    }
}

fn deg(rad: f64) -> f64 {
    (rad.to_degrees() * DEG_DECIMALS).round() / DEG_DECIMALS
}

/// The model the numerics use; joints without a convention get the core's choice.
pub fn doc_to_model(doc: &KinematicsDoc) -> RobotModel {
    let joints: Vec<(Option<CoreConvention>, Joint)> = doc
        .joints
        .iter()
        .map(|j| {
            let joint = Joint {
                convention: to_core(j.convention.unwrap_or(Convention::Dh)),
                a_mm: j.a_mm,
                alpha_rad: j.alpha_deg.to_radians(),
                d_mm: j.d_mm,
                theta_offset_rad: j.theta_offset_deg.to_radians(),
                beta_rad: j.beta_deg.to_radians(),
                min_rad: j.min_deg.to_radians(),
                max_rad: j.max_deg.to_radians(),
            };
            (j.convention.map(to_core), joint)
        })
        .collect();
    RobotModel {
        joints: choose_conventions(&joints),
    }
}

/// The joint table as served: every convention explicit, angles in degrees.
pub fn model_to_doc(model: &RobotModel) -> KinematicsDoc {
    KinematicsDoc {
        joints: model
            .joints
            .iter()
            .map(|j| JointDoc {
                joint_type: JointType::Revolute,
                convention: Some(from_core(j.convention)),
                a_mm: j.a_mm,
                alpha_deg: deg(j.alpha_rad),
                d_mm: j.d_mm,
                theta_offset_deg: deg(j.theta_offset_rad),
                beta_deg: deg(j.beta_rad),
                min_deg: deg(j.min_rad),
                max_deg: deg(j.max_rad),
            })
            .collect(),
    }
}
