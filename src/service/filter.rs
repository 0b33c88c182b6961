//! `POST …/parameter-sets/{version}/filter`: Cartesian targets for a
//! controller that runs the robot's nominal model (issue "Deploy the
//! result"), computed exactly by `calib::kinematics::filter`, through the
//! set's kept non-geometric terms (issue 19).

use robocal_calib::kinematics::filter::filter_target_with_terms;
use robocal_calib::kinematics::ik::default_seeds;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::RobotModel;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::evaluate::{pose_of, target_poses};
use crate::domain::JointsDeg;
use crate::schema::{Checker, FieldError, PoseDoc, PoseOut};

#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct FilterRequest {
    /// Desired poses of the tool in the target frame (camera sessions) or
    /// the tracker frame.
    pub targets: Vec<PoseDoc>,
    /// The tool in the flange frame (a pose of the flange, not relative to
    /// the camera).
    pub tool: PoseDoc,
    /// Joints (deg) whose branch every solution keeps: the robot's usual
    /// configuration in the program. Mid-range joints when absent.
    #[serde(default)]
    pub seed_joints_deg: Option<Vec<f64>>,
}

/// One target that could not be filtered; the others are still answered.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TargetError {
    /// Index into `targets`.
    pub index: usize,
    pub message: String,
}

/// Per target (same order; `null` where `errors` names the index).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct FilterResponse {
    /// The flange pose in the base frame to send to the nominal controller.
    pub nominal_targets: Vec<Option<PoseOut>>,
    /// The joints the real robot takes for each target (deg).
    pub joints_deg: Vec<Option<Vec<f64>>>,
    /// Where the calibrated model puts the tool when the nominal controller
    /// solves the filtered target from the seed, distance to the target (mm).
    pub residual_mm: Vec<Option<f64>>,
    pub errors: Vec<TargetError>,
}

/// Filters every target; a target out of reach or beyond the joint limits
/// is an entry of `errors`, the others are answered. A malformed request
/// (NaN in a pose, wrong seed length) is refused whole.
pub fn filter(
    calibrated: &TermModel,
    nominal: &RobotModel,
    req: &FilterRequest,
) -> Result<FilterResponse, Vec<FieldError>> {
    let mut c = Checker::default();
    let targets = target_poses(&req.targets, &mut c);
    let tool = pose_of(&req.tool, "tool", &mut c);
    let seed = req.seed_joints_deg.as_ref().map(|seed| {
        JointsDeg::check(
            &mut c,
            "seed_joints_deg",
            seed,
            calibrated.model.robot.dof(),
        )
    });
    if nominal.dof() != calibrated.model.robot.dof() {
        c.fail(
            "robot",
            "the robot's joint table no longer matches this parameter set",
        );
    }
    c.finish()?;
    let model = calibrated.with_tool(tool.expect("checked above"));
    let seed: Vec<f64> = match seed {
        Some(deg) => deg.expect("checked above").to_radians(),
        None => default_seeds(&model.model).swap_remove(0),
    };
    let mut answer = FilterResponse {
        nominal_targets: Vec::with_capacity(targets.len()),
        joints_deg: Vec::with_capacity(targets.len()),
        residual_mm: Vec::with_capacity(targets.len()),
        errors: Vec::new(),
    };
    for (index, target) in targets.iter().enumerate() {
        let target = target.expect("checked above");
        match filter_target_with_terms(&model, nominal, &target, &seed) {
            Ok(f) => {
                answer
                    .nominal_targets
                    .push(Some(PoseOut::new(&f.nominal_base_to_flange)));
                answer
                    .joints_deg
                    .push(Some(JointsDeg::from_radians(&f.joints_rad).into_vec()));
                answer.residual_mm.push(Some(f.residual_mm));
            }
            Err(e) => {
                answer.nominal_targets.push(None);
                answer.joints_deg.push(None);
                answer.residual_mm.push(None);
                answer.errors.push(TargetError {
                    index,
                    message: e.to_string(),
                });
            }
        }
    }
    Ok(answer)
}
