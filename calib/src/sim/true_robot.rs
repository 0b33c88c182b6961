//! The true robot of a simulated campaign (method.md §5): the nominal
//! kinematics with Gaussian errors, and the joints it really has when its
//! encoders read a value (unmodelled compliance, optional non-geometric
//! terms). Split from [`super::campaign`], which re-exports it.

use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};

use super::campaign_spec::CampaignSpec;
use super::tracker_campaign::typical_terms;
use crate::geometry::Pose;
use crate::kinematics::nongeometric::NonGeometric;
use crate::kinematics::{CalibratedModel, Convention, RobotModel};

pub(super) fn gauss(rng: &mut StdRng, sigma: f64) -> f64 {
    Normal::new(0.0, sigma.max(0.0)).map_or(0.0, |n| n.sample(rng))
}

/// The true robot: nominal plus Gaussian errors on every parameter.
pub fn perturb_robot(nominal: &RobotModel, spec: &CampaignSpec, rng: &mut StdRng) -> RobotModel {
    let mut robot = nominal.clone();
    for j in robot.joints.iter_mut() {
        j.theta_offset_rad += gauss(rng, spec.joint_offset_sigma_deg.to_radians());
        j.a_mm += gauss(rng, spec.length_sigma_mm);
        j.alpha_rad += gauss(rng, spec.twist_sigma_deg.to_radians());
        match j.convention {
            Convention::Dh => j.d_mm += gauss(rng, spec.length_sigma_mm),
            Convention::Hayati => j.beta_rad += gauss(rng, spec.twist_sigma_deg.to_radians()),
        }
    }
    robot
}

/// Joint 2 and 3 deflection from gravity, proportional to the horizontal
/// lever arm from each joint's axis to the flange (unmodelled error): the
/// joints the true robot has when its encoders read `q`.
pub fn compliance(robot: &RobotModel, q: &[f64], rad_per_m: f64) -> Vec<f64> {
    let mut out = q.to_vec();
    if rad_per_m == 0.0 || q.len() < 3 {
        return out;
    }
    let Ok(flange) = robot.base_to_flange(q) else {
        return out;
    };
    let mut frame = Pose::identity();
    for (i, (joint, &qi)) in robot.joints.iter().zip(q).enumerate().take(3) {
        if i >= 1 {
            let lever = flange.translation.vector - frame.translation.vector;
            let horizontal_m = (lever.x * lever.x + lever.y * lever.y).sqrt() / 1000.0;
            out[i] += rad_per_m * horizontal_m;
        }
        frame *= joint.link_transform(qi);
    }
    out
}

/// The true non-geometric terms of `true_model`: [`typical_terms`] with
/// the switch, none without.
pub fn true_terms(spec: &CampaignSpec, true_model: &CalibratedModel) -> NonGeometric {
    if spec.non_geometric {
        typical_terms(true_model)
    } else {
        NonGeometric::none(true_model)
    }
}

/// The joints the true robot has when its encoders read `read_rad` (the
/// recorded joints plus their noise): [`compliance`] and the `terms`'
/// deflections (evaluated at the reading, as a model of them is).
pub fn true_joints(
    spec: &CampaignSpec,
    robot: &RobotModel,
    terms: &NonGeometric,
    read_rad: &[f64],
) -> Vec<f64> {
    let mut out = compliance(robot, read_rad, spec.compliance_rad_per_m);
    if let Ok(bent) = terms.deflected(read_rad) {
        for ((q, b), r) in out.iter_mut().zip(&bent).zip(read_rad) {
            *q += b - r;
        }
    }
    out
}
