//! What off-line programming asks of a parameter set (api.md "Results"):
//! forward kinematics and compensated joints (method.md §8), evaluated on
//! the stored calibrated model with its kept non-geometric terms (issue 19:
//! the joints a request names are the commanded ones, deflected by the
//! terms before the chain; compensation answers commanded joints).

use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::ik::{default_seeds, IkStart};
use robocal_calib::kinematics::ik_branches::{self, SphericalWristArm};
use robocal_calib::kinematics::term_model::TermModel;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::domain::JointsDeg;
use crate::schema::{Checker, FieldError, PoseDoc, PoseOut};

/// Most rows of one `forward` or `compensate` request.
pub const MAX_ROWS: usize = 10_000;
/// Unreachable targets named one by one in a 422; the rest are counted.
const MAX_TARGET_ERRORS: usize = 50;

#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ForwardRequest {
    pub joints_deg: Vec<Vec<f64>>,
    /// A tool in the flange frame (api.md: relative to the calibrated hand–eye).
    #[serde(default)]
    pub tool: Option<PoseDoc>,
}

#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ForwardPose {
    pub flange_in_base: PoseOut,
    /// The camera (or, for tracker sets, the tool point) in the world frame.
    pub camera_in_target: PoseOut,
    /// The request's tool in the world frame, when a tool was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tool_in_target: Option<PoseOut>,
    /// One message per joint outside its limits (the pose is still
    /// computed: the controller would refuse it). Empty when all are within.
    pub warnings: Vec<String>,
    /// Predicted 1σ of `tool_in_target` (or `camera_in_target` without a
    /// tool) from the set's parameter covariance, board transform included:
    /// `sqrt(trace)` of the 3x3 position covariance, the RMS length of the
    /// 3-D error (mm). Absent for sets stored without a covariance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position_std_mm: Option<f64>,
    /// The same pose's orientation 1σ: `sqrt(trace)` of its 3x3 rotation
    /// covariance (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotation_std_deg: Option<f64>,
    /// Predicted 1σ of `flange_in_base` (link parameters only), as
    /// `position_std_mm` (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flange_position_std_mm: Option<f64>,
    /// Predicted orientation 1σ of `flange_in_base` (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flange_rotation_std_deg: Option<f64>,
}

#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ForwardResponse {
    pub poses: Vec<ForwardPose>,
}

/// One seed for all targets, or one per target.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(untagged)]
pub enum Seeds {
    One(Vec<f64>),
    PerTarget(Vec<Vec<f64>>),
}

#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CompensateRequest {
    pub targets: Vec<PoseDoc>,
    #[serde(default)]
    pub tool: Option<PoseDoc>,
    #[serde(default)]
    pub seed_joints_deg: Option<Seeds>,
}

/// Where the solver's run that found a target's joints started.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum SolverStart {
    /// The seed (`seed_joints_deg`, or mid-range joints without one).
    Seed,
    /// A closed-form branch of a spherical-wrist arm: the seed's own branch
    /// left the joint limits.
    Branch,
    /// A grid of starts (arms without a spherical wrist).
    MultiStart,
}

impl From<IkStart> for SolverStart {
    fn from(s: IkStart) -> Self {
        match s {
            IkStart::Seed => SolverStart::Seed,
            IkStart::Branch => SolverStart::Branch,
            IkStart::MultiStart => SolverStart::MultiStart,
        }
    }
}

/// The arm configuration of a solution (spherical-wrist arms).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
pub struct Configuration {
    /// The wrist centre's side of joint 1, along the arm.
    #[schema(schema_with = shoulder_schema)]
    pub shoulder: ik_branches::Shoulder,
    /// The elbow above or below the shoulder–wrist line.
    #[schema(schema_with = elbow_schema)]
    pub elbow: ik_branches::Elbow,
    /// The sign of joint 5.
    #[schema(schema_with = wrist_schema)]
    pub wrist: ik_branches::Wrist,
}

/// A string enum schema (the numerics' enums carry no OpenAPI derive).
fn string_enum(values: [&str; 2], description: &str) -> utoipa::openapi::Object {
    utoipa::openapi::ObjectBuilder::new()
        .schema_type(utoipa::openapi::schema::Type::String)
        .enum_values(Some(values))
        .description(Some(description))
        .build()
}

fn shoulder_schema() -> utoipa::openapi::Object {
    string_enum(
        ["front", "back"],
        "The wrist centre's side of joint 1, along the arm.",
    )
}

fn elbow_schema() -> utoipa::openapi::Object {
    string_enum(
        ["up", "down"],
        "The elbow above or below the shoulder–wrist line (in the arm's plane).",
    )
}

fn wrist_schema() -> utoipa::openapi::Object {
    string_enum(
        ["no_flip", "flip"],
        "The sign of joint 5 (with its offset).",
    )
}

#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CompensateResponse {
    /// Per target: the in-limit joints nearest the seed.
    pub joints_deg: Vec<Vec<f64>>,
    pub residual_mm: Vec<f64>,
    /// Per target: where the run that found the joints started.
    pub start: Vec<SolverStart>,
    /// Per target: the configuration of the joints, null for arms without
    /// a spherical wrist.
    pub configuration: Vec<Option<Configuration>>,
}

pub(crate) fn pose_of(doc: &PoseDoc, field: &str, c: &mut Checker) -> Option<Pose> {
    doc.check(c, field);
    let pose = match doc.matrix {
        Some(m) => robocal_calib::geometry::pose_from_matrix_rows(&m),
        None => {
            robocal_calib::geometry::pose_from_xyz_rpy_deg(doc.translation_mm, doc.rotation_deg)
        }
    };
    match pose {
        Ok(p) => Some(p),
        Err(e) => {
            c.fail(format!("{field}.matrix"), e.to_string());
            None
        }
    }
}

/// A request's `targets`: 1 to [`MAX_ROWS`] poses, each checked and named
/// `targets[i]` when it is not a pose.
pub(crate) fn target_poses(targets: &[PoseDoc], c: &mut Checker) -> Vec<Option<Pose>> {
    if targets.is_empty() || targets.len() > MAX_ROWS {
        c.fail("targets", format!("1 to {MAX_ROWS} targets"));
    }
    targets
        .iter()
        .enumerate()
        .map(|(i, t)| pose_of(t, &format!("targets[{i}]"), c))
        .collect()
}

pub fn forward(
    model: &TermModel,
    req: &ForwardRequest,
) -> Result<ForwardResponse, Vec<FieldError>> {
    let mut c = Checker::default();
    if req.joints_deg.is_empty() || req.joints_deg.len() > MAX_ROWS {
        c.fail("joints_deg", format!("1 to {MAX_ROWS} rows"));
    }
    let rows: Vec<Option<JointsDeg>> = req
        .joints_deg
        .iter()
        .enumerate()
        .map(|(i, row)| {
            JointsDeg::check(
                &mut c,
                &format!("joints_deg[{i}]"),
                row,
                model.model.robot.dof(),
            )
        })
        .collect();
    let tool = req.tool.as_ref().and_then(|t| pose_of(t, "tool", &mut c));
    c.finish()?;
    let mut poses = Vec::with_capacity(rows.len());
    for (i, row) in rows.into_iter().enumerate() {
        let q = row.expect("checked above").to_radians();
        let flange = model
            .base_to_flange(&q)
            .map_err(|e| vec![FieldError::new(format!("joints_deg[{i}]"), e.to_string())])?;
        let world_flange = model.model.world_to_base * flange;
        poses.push(ForwardPose {
            flange_in_base: PoseOut::new(&flange),
            camera_in_target: PoseOut::new(&(world_flange * model.model.flange_to_tool)),
            tool_in_target: tool.map(|t| PoseOut::new(&(world_flange * t))),
            warnings: model
                .model
                .robot
                .limit_violations(&q)
                .iter()
                .map(ToString::to_string)
                .collect(),
            position_std_mm: None,
            rotation_std_deg: None,
            flange_position_std_mm: None,
            flange_rotation_std_deg: None,
        });
    }
    Ok(ForwardResponse { poses })
}

pub fn compensate(
    model: &TermModel,
    req: &CompensateRequest,
) -> Result<CompensateResponse, Vec<FieldError>> {
    let mut c = Checker::default();
    let targets = target_poses(&req.targets, &mut c);
    let tool = req.tool.as_ref().and_then(|t| pose_of(t, "tool", &mut c));
    let dof = model.model.robot.dof();
    let seeds: Vec<Option<JointsDeg>> = match &req.seed_joints_deg {
        Some(Seeds::One(seed)) => vec![JointsDeg::check(&mut c, "seed_joints_deg", seed, dof)],
        Some(Seeds::PerTarget(rows)) => {
            if rows.len() != req.targets.len() {
                c.fail(
                    "seed_joints_deg",
                    "one seed for all targets, or exactly one per target",
                );
            }
            rows.iter()
                .enumerate()
                .map(|(i, row)| {
                    JointsDeg::check(&mut c, &format!("seed_joints_deg[{i}]"), row, dof)
                })
                .collect()
        }
        None => Vec::new(),
    };
    c.finish()?;
    let seeds: Vec<Vec<f64>> = seeds
        .into_iter()
        .map(|s| s.expect("checked above").to_radians())
        .collect();
    let tool_model = tool.map_or_else(|| model.clone(), |t| model.with_tool(t));
    // Without a seed: mid-range joints (the first of the default grid).
    let mid_range = default_seeds(&tool_model.model).swap_remove(0);
    let arm = SphericalWristArm::of(&tool_model.model.robot);
    let mut answer = CompensateResponse {
        joints_deg: Vec::new(),
        residual_mm: Vec::new(),
        start: Vec::new(),
        configuration: Vec::new(),
    };
    let mut failed = Checker::default();
    let mut failures = 0;
    for (i, target) in targets.iter().enumerate() {
        let target = target.expect("checked above");
        // One seed for all, one per target, or none (mid-range).
        let seed = match seeds.len() {
            0 => mid_range.clone(),
            1 => seeds[0].clone(),
            _ => seeds[i].clone(),
        };
        let solution = match tool_model.nearest_within_limits(&target, &seed) {
            Ok(s) => s,
            Err(e) => {
                failures += 1;
                if failures <= MAX_TARGET_ERRORS {
                    failed.fail(format!("targets[{i}]"), e.to_string());
                }
                continue;
            }
        };
        let configuration = arm
            .as_ref()
            .and_then(|a| a.configuration(&solution.joints_rad));
        answer
            .configuration
            .push(configuration.map(|c| Configuration {
                shoulder: c.shoulder,
                elbow: c.elbow,
                wrist: c.wrist,
            }));
        answer
            .joints_deg
            .push(JointsDeg::from_radians(&solution.joints_rad).into_vec());
        answer.residual_mm.push(solution.residual_mm);
        answer.start.push(solution.start.into());
    }
    if failures > MAX_TARGET_ERRORS {
        failed.fail(
            "targets",
            format!(
                "{} more targets have no solution within reach and joint limits",
                failures - MAX_TARGET_ERRORS
            ),
        );
    }
    failed.finish()?;
    Ok(answer)
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::kinematics::presets;
    use serde_json::json;

    fn model() -> TermModel {
        TermModel::geometric(robocal_calib::kinematics::CalibratedModel {
            robot: presets::irb2400(),
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::identity(),
        })
    }

    fn fields(errors: Vec<FieldError>) -> Vec<String> {
        errors.into_iter().map(|e| e.field).collect()
    }

    #[test]
    fn forward_names_bad_rows() {
        let req: ForwardRequest =
            serde_json::from_value(json!({"joints_deg": [[0, 0, 0, 0, 0, 0], [1, 2, 3]]})).unwrap();
        assert_eq!(
            fields(forward(&model(), &req).unwrap_err()),
            ["joints_deg[1]"]
        );
        let ok: ForwardRequest =
            serde_json::from_value(json!({"joints_deg": [[0, 0, 0, 0, 0, 0]]})).unwrap();
        let answer = forward(&model(), &ok).unwrap();
        // The IRB-2400 flange at zero joints (presets.rs doc): reach 940, height 1455.
        assert!((answer.poses[0].flange_in_base.translation_mm[0] - 940.0).abs() < 1e-9);
    }

    #[test]
    fn compensate_reaches_a_reachable_target_and_names_an_unreachable_one() {
        let m = model();
        let q = [0.2, 0.3, -0.2, 0.4, 0.5, -0.3];
        let target = m.world_to_tool(&q).unwrap();
        let doc = json!({"translation_mm": [0, 0, 0], "rotation_deg": [0, 0, 0],
                         "matrix": robocal_calib::geometry::pose_to_matrix_rows(&target)});
        let req: CompensateRequest = serde_json::from_value(json!({
            "targets": [doc], "seed_joints_deg": [10, 15, -10, 20, 25, -15]}))
        .unwrap();
        let answer = compensate(&m, &req).unwrap();
        assert!(answer.residual_mm[0] < 1e-6, "{:?}", answer.residual_mm);
        let far: CompensateRequest = serde_json::from_value(json!({
            "targets": [{"translation_mm": [5000, 0, 0], "rotation_deg": [0, 0, 0]}]}))
        .unwrap();
        assert_eq!(fields(compensate(&m, &far).unwrap_err()), ["targets[0]"]);
        let seeds: CompensateRequest = serde_json::from_value(json!({
            "targets": [{"translation_mm": [900, 0, 1000], "rotation_deg": [0, 0, 0]}],
            "seed_joints_deg": [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]}))
        .unwrap();
        assert_eq!(
            fields(compensate(&m, &seeds).unwrap_err()),
            ["seed_joints_deg"]
        );
    }
}
