//! Conversion between the API's joint table ([`KinematicsDoc`], degrees) and
//! the numerics' [`RobotModel`] (radians), and preset expansion. The
//! convention rule (Hayati for a link between parallel axes, `d` carried to
//! the next link) is the core's `choose_conventions`.

use robocal_calib::kinematics::model::choose_conventions;
use robocal_calib::kinematics::{presets, Convention as CoreConvention, Joint, RobotModel};

use crate::schema::robot::{Convention, JointDoc, JointType, KinematicsDoc, Preset};

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
