//! `POST …/parameter-sets/{version}/filter`: Cartesian targets for a
//! controller that runs the robot's nominal model (issue "Deploy the
//! result"), computed exactly by `calib::kinematics::filter` through the
//! set's kept non-geometric terms (issue 19: the answered joints are the
//! commanded ones); answered whole or streamed line by line
//! (`service::target_stream`), both through [`Filtering::solve`].

use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::filter::filter_target_with_terms;
use robocal_calib::kinematics::ik::default_seeds;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::RobotModel;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::evaluate::{pose_of, pose_warnings, target_poses};
use super::target_stream::TargetError;
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
    /// A multi-session set: work in this session's board frame
    /// (its `target_to_base`); absent: the set's own `target_to_base`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub session_id: Option<String>,
    /// The controller the caller is about to apply the answer on (issue
    /// 34): 409 naming `controller` when the set was made on another (a
    /// field left out is not compared). `?controller_serial=` does the
    /// same for the serial alone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub expect_controller: Option<crate::domain::ControllerIdentity>,
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
    /// Per target: the real joints outside the span the set's kept terms
    /// were identified on (they extrapolate there); empty when none or
    /// where `errors` names the target.
    pub warnings: Vec<Vec<String>>,
    pub errors: Vec<TargetError>,
}

/// One target filtered.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct FilteredTarget {
    /// The flange pose in the base frame to send to the nominal controller.
    pub nominal_target: PoseOut,
    /// The joints the real robot takes (deg).
    pub joints_deg: Vec<f64>,
    /// Where the calibrated model puts the tool when the nominal controller
    /// solves the filtered target from the seed, distance to the target (mm).
    pub residual_mm: f64,
    /// As [`FilterResponse::warnings`] for this target.
    pub warnings: Vec<String>,
}

/// One line of the `application/x-ndjson` answer (a schema only: the lines
/// are `TargetLine<FilteredTarget>`): `index`, then either the target's
/// answer or `error`.
#[derive(ToSchema)]
#[allow(dead_code)]
pub struct FilterLine {
    /// Index into `targets`; lines come in this order.
    pub index: usize,
    pub nominal_target: Option<PoseOut>,
    pub joints_deg: Option<Vec<f64>>,
    pub residual_mm: Option<f64>,
    pub warnings: Option<Vec<String>>,
    /// Why this target has no filtered pose (out of reach, beyond the limits).
    pub error: Option<String>,
}

/// A filter request checked whole: the targets as poses, the calibrated
/// model with the request's tool, the nominal chain and the seed.
pub struct Filtering {
    model: TermModel,
    nominal: RobotModel,
    targets: Vec<Pose>,
    seed: Vec<f64>,
}

impl Filtering {
    /// Every field of the request checked: a malformed request (a pose
    /// that is not one, wrong seed length) is a 422 naming the field,
    /// before anything is solved.
    pub fn check(
        calibrated: &TermModel,
        nominal: RobotModel,
        req: &FilterRequest,
    ) -> Result<Self, Vec<FieldError>> {
        let mut c = Checker::default();
        let targets = target_poses(&req.targets, &mut c);
        let tool = pose_of(&req.tool, "tool", &mut c);
        let dof = calibrated.model.robot.dof();
        let seed = req
            .seed_joints_deg
            .as_ref()
            .map(|seed| JointsDeg::check(&mut c, "seed_joints_deg", seed, dof));
        if nominal.dof() != dof {
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
        Ok(Filtering {
            model,
            nominal,
            targets: targets
                .into_iter()
                .map(|t| t.expect("checked above"))
                .collect(),
            seed,
        })
    }

    /// How many targets the request holds.
    pub fn len(&self) -> usize {
        self.targets.len()
    }

    /// Whether the request holds no target (never, once checked).
    pub fn is_empty(&self) -> bool {
        self.targets.is_empty()
    }

    /// Target `index` filtered, or why it cannot be.
    pub fn solve(&self, index: usize) -> Result<FilteredTarget, String> {
        let f =
            filter_target_with_terms(&self.model, &self.nominal, &self.targets[index], &self.seed)
                .map_err(|e| e.to_string())?;
        Ok(FilteredTarget {
            nominal_target: PoseOut::new(&f.nominal_base_to_flange),
            joints_deg: JointsDeg::from_radians(&f.joints_rad).into_vec(),
            residual_mm: f.residual_mm,
            warnings: pose_warnings(&self.model, &f.joints_rad),
        })
    }
}

/// Filters every target in one answer; a target out of reach or beyond
/// the joint limits is an entry of `errors`, the others are answered.
pub fn filter(plan: &Filtering) -> FilterResponse {
    let mut answer = FilterResponse {
        nominal_targets: Vec::with_capacity(plan.len()),
        joints_deg: Vec::with_capacity(plan.len()),
        residual_mm: Vec::with_capacity(plan.len()),
        warnings: Vec::with_capacity(plan.len()),
        errors: Vec::new(),
    };
    for index in 0..plan.len() {
        match plan.solve(index) {
            Ok(f) => {
                answer.nominal_targets.push(Some(f.nominal_target));
                answer.joints_deg.push(Some(f.joints_deg));
                answer.residual_mm.push(Some(f.residual_mm));
                answer.warnings.push(f.warnings);
            }
            Err(message) => {
                answer.nominal_targets.push(None);
                answer.joints_deg.push(None);
                answer.residual_mm.push(None);
                answer.warnings.push(Vec::new());
                answer.errors.push(TargetError { index, message });
            }
        }
    }
    answer
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::kinematics::presets;
    use serde_json::json;

    /// Bad input of issue 15: a target beyond reach and one only reached
    /// with joint 1 beyond its limits are errors of their own indices; the
    /// others are filtered. A tool whose matrix is not a rigid transform is
    /// refused whole, naming `tool` (it concerns every target).
    #[test]
    fn targets_out_of_reach_or_limits_are_named_and_the_others_filtered() {
        let mut robot = presets::irb2400();
        robot.joints[0].min_rad = -20f64.to_radians();
        robot.joints[0].max_rad = 20f64.to_radians();
        let calibrated = TermModel::geometric(robocal_calib::kinematics::CalibratedModel {
            robot: robot.clone(),
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::identity(),
        });
        let inside = calibrated
            .world_to_tool(&[0.1, 0.3, -0.2, 0.4, 0.5, -0.3])
            .unwrap();
        let outside = calibrated
            .world_to_tool(&[1.6, 0.3, -0.2, 0.4, 0.5, -0.3])
            .unwrap();
        let doc = |p: &Pose| {
            json!({"translation_mm": [0, 0, 0], "rotation_deg": [0, 0, 0],
                                    "matrix": robocal_calib::geometry::pose_to_matrix_rows(p)})
        };
        let far = json!({"translation_mm": [9000, 0, 0], "rotation_deg": [0, 0, 0]});
        let tool = json!({"translation_mm": [0, 0, 0], "rotation_deg": [0, 0, 0]});
        let req: FilterRequest = serde_json::from_value(json!({
            "targets": [doc(&inside), far, doc(&outside), doc(&inside)],
            "tool": tool, "seed_joints_deg": [5, 15, -10, 20, 25, -15]}))
        .unwrap();
        let plan = Filtering::check(&calibrated, robot.clone(), &req).unwrap();
        let answer = filter(&plan);
        let failed: Vec<usize> = answer.errors.iter().map(|e| e.index).collect();
        assert_eq!(failed, [1, 2], "{:?}", answer.errors);
        for i in [0, 3] {
            assert!(
                answer.residual_mm[i].unwrap() < 1e-6,
                "{:?}",
                answer.residual_mm
            );
        }
        let mut skewed = req.clone();
        skewed.tool.matrix = Some([
            [1.0, 0.5, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]);
        let fields: Vec<String> = Filtering::check(&calibrated, robot, &skewed)
            .err()
            .unwrap()
            .into_iter()
            .map(|e| e.field)
            .collect();
        assert!(fields.iter().all(|f| f.starts_with("tool")), "{fields:?}");
        assert!(!fields.is_empty());
    }
}
