//! What off-line programming asks of a parameter set (api.md "Results"):
//! forward kinematics (method.md §8) evaluated on the stored calibrated
//! model with its kept non-geometric terms (issue 19: the joints a request
//! names are the commanded ones, deflected by the terms before the chain),
//! and the target checks `compensate` and `filter` share.

use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::term_range::extrapolated;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::domain::JointsDeg;
use crate::schema::{Checker, FieldError, PoseDoc, PoseOut};

/// Most rows of one `forward` or `compensate` request.
pub const MAX_ROWS: usize = 10_000;

#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ForwardRequest {
    pub joints_deg: Vec<Vec<f64>>,
    /// A tool in the flange frame (api.md: relative to the calibrated hand–eye).
    #[serde(default)]
    pub tool: Option<PoseDoc>,
    /// A multi-session set: work in this session's board frame
    /// (its `target_to_base`); absent: the set's own `target_to_base`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub session_id: Option<String>,
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
    /// computed: the controller would refuse it), and per joint outside
    /// the range its kept non-geometric terms were identified on (the set's
    /// `terms.joint_ranges_deg`: they extrapolate there). Empty when all
    /// are within.
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

/// A pose's `warnings` at joints `q_rad`: each joint outside its limits,
/// and each joint outside the span its kept non-geometric terms were
/// identified on (calib's `term_range`: they extrapolate there).
pub(crate) fn pose_warnings(model: &TermModel, q_rad: &[f64]) -> Vec<String> {
    let limits = model.model.robot.limit_violations(q_rad);
    let spans = extrapolated(&model.ranges, q_rad).map(|r| {
        format!(
            "joint {} at {:.1}° lies outside {:.1}° to {:.1}°, where its kept terms were identified: they extrapolate here",
            r.joint + 1,
            q_rad[r.joint].to_degrees(),
            r.min_rad.to_degrees(),
            r.max_rad.to_degrees()
        )
    });
    limits
        .iter()
        .map(ToString::to_string)
        .chain(spans)
        .collect()
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
            warnings: pose_warnings(model, &q),
            position_std_mm: None,
            rotation_std_deg: None,
            flange_position_std_mm: None,
            flange_rotation_std_deg: None,
        });
    }
    Ok(ForwardResponse { poses })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use robocal_calib::kinematics::presets;
    use serde_json::json;

    /// The IRB 2400 preset with the base and tool at identity, no terms.
    pub(crate) fn model() -> TermModel {
        TermModel::geometric(robocal_calib::kinematics::CalibratedModel {
            robot: presets::irb2400(),
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::identity(),
        })
    }

    /// The fields a refusal names.
    pub(crate) fn fields(errors: Vec<FieldError>) -> Vec<String> {
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
}
