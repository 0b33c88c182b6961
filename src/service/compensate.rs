//! `POST …/parameter-sets/{version}/compensate`: the joints that put the
//! tool on each target by the calibrated model with its kept non-geometric
//! terms (method.md §8, issue 19), the in-limit solution nearest the seed
//! (`calib::kinematics::term_model::TermModel::nearest_within_limits`: the
//! answered joints are the commanded ones, which the terms deflect onto the
//! target).
//! A target out of reach or beyond the joint limits is an error of its own
//! index; the others are answered, whole or streamed line by line
//! (`service::target_stream`).

use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::ik::{default_seeds, IkStart};
use robocal_calib::kinematics::ik_branches::{self, SphericalWristArm};
use robocal_calib::kinematics::term_model::TermModel;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::evaluate::{pose_of, pose_warnings, target_poses};
use super::target_stream::TargetError;
use crate::domain::JointsDeg;
use crate::schema::{Checker, FieldError, PoseDoc};

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

/// One target's compensation.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CompensatedTarget {
    /// The in-limit joints nearest the seed (deg).
    pub joints_deg: Vec<f64>,
    /// The calibrated model's remaining distance to the target (mm).
    pub residual_mm: f64,
    /// Where the run that found the joints started.
    pub start: SolverStart,
    /// The configuration of the joints, null for arms without a spherical wrist.
    pub configuration: Option<Configuration>,
    /// The joints outside the span the set's kept terms were identified
    /// on (they extrapolate there); empty when none.
    pub warnings: Vec<String>,
}

/// Per target, in the order of `targets`; `null` where `errors` names the
/// target's index.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CompensateResponse {
    /// Per target: the in-limit joints nearest the seed (deg).
    pub joints_deg: Vec<Option<Vec<f64>>>,
    pub residual_mm: Vec<Option<f64>>,
    /// Per target: where the run that found the joints started.
    pub start: Vec<Option<SolverStart>>,
    /// Per target: the configuration of the joints, null for arms without
    /// a spherical wrist.
    pub configuration: Vec<Option<Configuration>>,
    /// Per target: as [`CompensatedTarget::warnings`] (empty where `errors`
    /// names the target).
    pub warnings: Vec<Vec<String>>,
    /// Targets out of reach or beyond the joint limits, by index.
    pub errors: Vec<TargetError>,
}

/// One line of the `application/x-ndjson` answer (a schema only: the lines
/// are `TargetLine<CompensatedTarget>`): `index`, then either the target's
/// answer or `error`.
#[derive(ToSchema)]
#[allow(dead_code)]
pub struct CompensateLine {
    /// Index into `targets`; lines come in this order.
    pub index: usize,
    pub joints_deg: Option<Vec<f64>>,
    pub residual_mm: Option<f64>,
    pub start: Option<SolverStart>,
    pub configuration: Option<Configuration>,
    pub warnings: Option<Vec<String>>,
    /// Why this target has no joints (out of reach, beyond the limits).
    pub error: Option<String>,
}

/// A compensate request checked whole: the targets as poses, the model
/// with the request's tool, one seed per target or one for all.
pub struct Compensation {
    model: TermModel,
    targets: Vec<Pose>,
    seeds: Vec<Vec<f64>>,
    arm: Option<SphericalWristArm>,
}

impl Compensation {
    /// Every field of the request checked (a bad one is a 422 naming it,
    /// before anything is solved).
    pub fn check(model: &TermModel, req: &CompensateRequest) -> Result<Self, Vec<FieldError>> {
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
        let model = tool.map_or_else(|| model.clone(), |t| model.with_tool(t));
        let mut seeds: Vec<Vec<f64>> = seeds
            .into_iter()
            .map(|s| s.expect("checked above").to_radians())
            .collect();
        if seeds.is_empty() {
            // Without a seed: mid-range joints (the first of the default grid).
            seeds.push(default_seeds(&model.model).swap_remove(0));
        }
        Ok(Compensation {
            arm: SphericalWristArm::of(&model.model.robot),
            targets: targets
                .into_iter()
                .map(|t| t.expect("checked above"))
                .collect(),
            seeds,
            model,
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

    /// Target `index` compensated, or why it cannot be.
    pub fn solve(&self, index: usize) -> Result<CompensatedTarget, String> {
        // One seed for all, or one per target.
        let seed = &self.seeds[if self.seeds.len() == 1 { 0 } else { index }];
        let solution = self
            .model
            .nearest_within_limits(&self.targets[index], seed)
            .map_err(|e| e.to_string())?;
        let configuration = self
            .arm
            .as_ref()
            .and_then(|a| a.configuration(&solution.joints_rad))
            .map(|c| Configuration {
                shoulder: c.shoulder,
                elbow: c.elbow,
                wrist: c.wrist,
            });
        Ok(CompensatedTarget {
            warnings: pose_warnings(&self.model, &solution.joints_rad),
            joints_deg: JointsDeg::from_radians(&solution.joints_rad).into_vec(),
            residual_mm: solution.residual_mm,
            start: solution.start.into(),
            configuration,
        })
    }
}

/// Every target compensated in one answer (the columns of
/// [`CompensateResponse`]).
pub fn compensate(
    model: &TermModel,
    req: &CompensateRequest,
) -> Result<CompensateResponse, Vec<FieldError>> {
    let plan = Compensation::check(model, req)?;
    let mut answer = CompensateResponse {
        joints_deg: Vec::with_capacity(plan.len()),
        residual_mm: Vec::with_capacity(plan.len()),
        start: Vec::with_capacity(plan.len()),
        configuration: Vec::with_capacity(plan.len()),
        warnings: Vec::with_capacity(plan.len()),
        errors: Vec::new(),
    };
    for index in 0..plan.len() {
        match plan.solve(index) {
            Ok(t) => {
                answer.joints_deg.push(Some(t.joints_deg));
                answer.residual_mm.push(Some(t.residual_mm));
                answer.start.push(Some(t.start));
                answer.configuration.push(t.configuration);
                answer.warnings.push(t.warnings);
            }
            Err(error) => {
                answer.joints_deg.push(None);
                answer.residual_mm.push(None);
                answer.start.push(None);
                answer.configuration.push(None);
                answer.warnings.push(Vec::new());
                answer.errors.push(TargetError {
                    index,
                    message: error,
                });
            }
        }
    }
    Ok(answer)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::service::evaluate::tests::{fields, model};
    use serde_json::json;

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
        assert!(
            answer.residual_mm[0].unwrap() < 1e-6,
            "{:?}",
            answer.residual_mm
        );
        let far: CompensateRequest = serde_json::from_value(json!({
            "targets": [{"translation_mm": [5000, 0, 0], "rotation_deg": [0, 0, 0]}]}))
        .unwrap();
        let answer = compensate(&m, &far).unwrap();
        assert_eq!(answer.errors[0].index, 0);
        assert_eq!(answer.joints_deg, [None]);
        let seeds: CompensateRequest = serde_json::from_value(json!({
            "targets": [{"translation_mm": [900, 0, 1000], "rotation_deg": [0, 0, 0]}],
            "seed_joints_deg": [[0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]}))
        .unwrap();
        assert_eq!(
            fields(compensate(&m, &seeds).unwrap_err()),
            ["seed_joints_deg"]
        );
    }

    /// A target the arm reaches only with joint 1 beyond its limits is an
    /// error of its own index (the limits named); the target within the
    /// limits is still answered.
    #[test]
    fn a_target_beyond_the_joint_limits_is_named_and_the_others_answered() {
        let mut m = model();
        let (lo, hi) = (-20f64.to_radians(), 20f64.to_radians());
        m.model.robot.joints[0].min_rad = lo;
        m.model.robot.joints[0].max_rad = hi;
        let inside = m.world_to_tool(&[0.1, 0.3, -0.2, 0.4, 0.5, -0.3]).unwrap();
        // Joint 1 at 90 deg: the same arm pose turned out of the limits.
        let outside = m.world_to_tool(&[1.6, 0.3, -0.2, 0.4, 0.5, -0.3]).unwrap();
        let doc = |p: &Pose| {
            json!({"translation_mm": [0, 0, 0], "rotation_deg": [0, 0, 0],
                                    "matrix": robocal_calib::geometry::pose_to_matrix_rows(p)})
        };
        let req: CompensateRequest = serde_json::from_value(json!({
            "targets": [doc(&inside), doc(&outside), doc(&inside)],
            "seed_joints_deg": [5, 15, -10, 20, 25, -15]}))
        .unwrap();
        let answer = compensate(&m, &req).unwrap();
        assert_eq!(answer.errors.len(), 1, "{:?}", answer.errors);
        assert_eq!(answer.errors[0].index, 1);
        assert!(answer.joints_deg[1].is_none());
        for i in [0, 2] {
            let q: Vec<f64> = answer.joints_deg[i]
                .as_ref()
                .unwrap()
                .iter()
                .map(|d| d.to_radians())
                .collect();
            assert!(m.model.robot.check_limits(&q).is_ok(), "{q:?}");
            assert!(answer.residual_mm[i].unwrap() < 1e-6);
        }
    }
}
