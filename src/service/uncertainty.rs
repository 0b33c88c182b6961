//! Predicted uncertainty of a parameter set's poses (issue "Deploy the
//! result"): `forward`'s per-row σ and the `uncertainty-map`, from the
//! covariance stored with the set propagated through the FK Jacobian
//! (`calib::kinematics::uncertainty`).

use nalgebra::DMatrix;
use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::ik::default_seeds;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::term_uncertainty::TermCovarianceFactor;
use robocal_calib::kinematics::uncertainty::{CovarianceFactor, PoseFrame};
use robocal_calib::kinematics::{CalibratedModel, ParamLayout};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::evaluate::{pose_of, ForwardRequest, ForwardResponse, MAX_ROWS};
use super::target_stream::TargetError;
use crate::domain::{JointsDeg, ParameterSet};
use crate::schema::{Checker, FieldError, PoseDoc, MAX_ANGLE_DEG, MAX_LENGTH_MM};

/// A parameter set's covariance, ready to propagate: factored once, so
/// each row of a 10,000-row `forward` costs two Jacobians and two small
/// products.
#[derive(Debug, Clone)]
pub struct Uncertainty {
    factor: CovarianceFactor,
    /// With the kept terms' covariance, when the set stores it: the joint
    /// covariance of parameters and terms, factored once.
    with_terms: Option<TermCovarianceFactor>,
}

/// The predicted 1σ of one row (see [`PredictedStd`]'s fields).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct PredictedStd {
    /// 1σ of the tool's (the request's tool, else the camera's) 3-D position
    /// error in the target frame, board transform included: the square root
    /// of the trace of its 3x3 covariance, i.e. the RMS length of the error
    /// vector (a per-axis σ is about this over √3). mm.
    pub position_std_mm: f64,
    /// The same for its orientation: square root of the trace of the 3x3
    /// covariance of the small-angle rotation error. deg.
    pub rotation_std_deg: f64,
    /// 1σ of the flange's 3-D position in the robot base frame (link
    /// parameters only), as `position_std_mm`. mm.
    pub flange_position_std_mm: f64,
    /// 1σ of the flange's orientation in the base frame. deg.
    pub flange_rotation_std_deg: f64,
}

impl Uncertainty {
    /// The stored covariance of `set` for `model` (its calibrated model
    /// with its kept terms, whose covariance with the parameters joins it
    /// when stored); `None` for sets stored without one.
    pub fn of(set: &ParameterSet, model: &TermModel) -> Option<Result<Self, String>> {
        let covariance = match set.covariance_matrix()? {
            Ok(c) => c,
            Err(e) => return Some(Err(e)),
        };
        let layout = ParamLayout::new(&model.model.robot, set.layout_instrument());
        let with_terms = match &model.covariance {
            Some(c) => match TermCovarianceFactor::new(&layout, &covariance, c) {
                Ok(f) => Some(f),
                Err(e) => return Some(Err(e.to_string())),
            },
            None => None,
        };
        Some(Self::from_covariance(layout, covariance).map(|u| Self { with_terms, ..u }))
    }

    /// A covariance in `layout` order (internal units: mm, rad), checked
    /// once for all the poses it is propagated to.
    pub fn from_covariance(layout: ParamLayout, covariance: DMatrix<f64>) -> Result<Self, String> {
        let factor = CovarianceFactor::new(&layout, &covariance).map_err(|e| e.to_string())?;
        Ok(Self {
            factor,
            with_terms: None,
        })
    }

    /// σ at commanded joints `q_rad` of the tool `tool` (in the flange
    /// frame; the calibrated camera or tool point when `None`) and of the
    /// flange: the parameter covariance at the joints the terms deflect
    /// `q_rad` to, plus the kept terms' own σ: through their joint
    /// covariance with the parameters when the set stores it (calib's
    /// `term_uncertainty`), else taken as independent
    /// (`TermModel::term_variance`).
    pub fn at(
        &self,
        model: &TermModel,
        q_rad: &[f64],
        tool: Option<Pose>,
    ) -> Result<PredictedStd, String> {
        let text = |e: robocal_calib::kinematics::KinematicsError| e.to_string();
        let frame = tool.map_or(PoseFrame::ToolInWorld, PoseFrame::GivenToolInWorld);
        if let Some(joint) = &self.with_terms {
            let std = |frame| {
                joint
                    .pose_std(model, q_rad, frame)
                    .map_err(|e| e.to_string())
            };
            let (end, flange) = (std(frame)?, std(PoseFrame::FlangeInBase)?);
            return Ok(PredictedStd {
                position_std_mm: end.position_mm,
                rotation_std_deg: end.rotation_rad.to_degrees(),
                flange_position_std_mm: flange.position_mm,
                flange_rotation_std_deg: flange.rotation_rad.to_degrees(),
            });
        }
        let bent = model.deflected(q_rad).map_err(text)?;
        let end = self
            .factor
            .pose_std(&model.model, &bent, frame)
            .map_err(|e| e.to_string())?;
        let flange = self
            .factor
            .pose_std(&model.model, &bent, PoseFrame::FlangeInBase)
            .map_err(|e| e.to_string())?;
        let end_model = tool.map_or_else(|| model.model.clone(), |t| model.model.with_tool(t));
        let end_terms = model.term_variance(&end_model, q_rad).map_err(text)?;
        let flange_terms = model
            .term_variance(&flange_only(&model.model), q_rad)
            .map_err(text)?;
        let add = |sd: f64, var: f64| (sd * sd + var).sqrt();
        Ok(PredictedStd {
            position_std_mm: add(end.position_mm, end_terms.position_mm2),
            rotation_std_deg: add(end.rotation_rad, end_terms.rotation_rad2).to_degrees(),
            flange_position_std_mm: add(flange.position_mm, flange_terms.position_mm2),
            flange_rotation_std_deg: add(flange.rotation_rad, flange_terms.rotation_rad2)
                .to_degrees(),
        })
    }
}

/// `forward` with each row's predicted σ when the set has a covariance.
pub fn forward(
    model: &TermModel,
    uncertainty: Option<&Uncertainty>,
    req: &ForwardRequest,
) -> Result<ForwardResponse, Vec<FieldError>> {
    let mut answer = super::evaluate::forward(model, req)?;
    let Some(u) = uncertainty else {
        return Ok(answer);
    };
    let mut c = Checker::default();
    let tool = req.tool.as_ref().and_then(|t| pose_of(t, "tool", &mut c));
    for (i, (row, pose)) in req.joints_deg.iter().zip(&mut answer.poses).enumerate() {
        let q: Vec<f64> = row.iter().map(|d| d.to_radians()).collect();
        let std = u
            .at(model, &q, tool)
            .map_err(|e| vec![FieldError::new(format!("joints_deg[{i}]"), e)])?;
        pose.position_std_mm = Some(std.position_std_mm);
        pose.rotation_std_deg = Some(std.rotation_std_deg);
        pose.flange_position_std_mm = Some(std.flange_position_std_mm);
        pose.flange_rotation_std_deg = Some(std.flange_rotation_std_deg);
    }
    Ok(answer)
}

/// A box of flange positions in the robot base frame, corners included.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BoxDoc {
    #[schema(min_items = 3, max_items = 3)]
    pub min_mm: [f64; 3],
    #[schema(min_items = 3, max_items = 3)]
    pub max_mm: [f64; 3],
    /// Grid spacing along each axis (mm).
    pub step_mm: f64,
}

/// Where to predict: either `joints_deg` (rows of joints) or `box` (flange
/// positions in the base frame at one flange orientation, each solved by
/// the calibrated model's inverse kinematics from the seed).
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct UncertaintyMapRequest {
    #[serde(default)]
    pub joints_deg: Option<Vec<Vec<f64>>>,
    #[serde(default, rename = "box")]
    pub region: Option<BoxDoc>,
    /// The flange's fixed-axis X-Y-Z orientation in the base frame over
    /// the box (deg); `[0, 180, 0]` (flange pointing down) when absent.
    #[serde(default)]
    pub rotation_deg: Option<[f64; 3]>,
    /// Joints (deg) whose branch the box's solutions keep; mid-range when
    /// absent.
    #[serde(default)]
    pub seed_joints_deg: Option<Vec<f64>>,
    /// A tool in the flange frame whose σ `position_std_mm` describes
    /// (the calibrated camera or tool point when absent).
    #[serde(default)]
    pub tool: Option<PoseDoc>,
    /// A multi-session set's session: the σ of the tool in that
    /// session's board frame, with that board's own covariance (as
    /// `forward`'s `session_id`).
    #[serde(default)]
    pub session_id: Option<String>,
}

/// One point of the map.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct MapPoint {
    pub joints_deg: Vec<f64>,
    /// The flange position in the base frame (mm).
    pub flange_position_mm: [f64; 3],
    #[serde(flatten)]
    pub std: PredictedStd,
}

/// Per point (grid order: x fastest, then y, then z; or the rows given),
/// `null` where `errors` names the index.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct UncertaintyMapResponse {
    pub points: Vec<Option<MapPoint>>,
    pub errors: Vec<TargetError>,
}

/// The flange orientation over a box when none is given: pointing down.
const DEFAULT_ROTATION_DEG: [f64; 3] = [0.0, 180.0, 0.0];

/// Grid positions of a checked box, x fastest.
fn box_points(b: &BoxDoc) -> Vec<[f64; 3]> {
    let counts: Vec<usize> = (0..3)
        .map(|k| ((b.max_mm[k] - b.min_mm[k]) / b.step_mm + 1e-9).floor() as usize + 1)
        .collect();
    let mut out = Vec::with_capacity(counts.iter().product());
    for iz in 0..counts[2] {
        for iy in 0..counts[1] {
            for ix in 0..counts[0] {
                let at = [ix, iy, iz];
                out.push(std::array::from_fn(|k| {
                    b.min_mm[k] + at[k] as f64 * b.step_mm
                }));
            }
        }
    }
    out
}

fn check_box(b: &BoxDoc, c: &mut Checker) {
    for k in 0..3 {
        c.bounded(format!("box.min_mm[{k}]"), b.min_mm[k], MAX_LENGTH_MM, "mm");
        c.bounded(format!("box.max_mm[{k}]"), b.max_mm[k], MAX_LENGTH_MM, "mm");
        if b.max_mm[k] < b.min_mm[k] {
            c.fail(format!("box.max_mm[{k}]"), "must not be below box.min_mm");
        }
    }
    c.positive("box.step_mm", b.step_mm, MAX_LENGTH_MM, "mm");
    if !c.errors.is_empty() {
        return;
    }
    let count: f64 = (0..3)
        .map(|k| ((b.max_mm[k] - b.min_mm[k]) / b.step_mm).floor() + 1.0)
        .product();
    if count > MAX_ROWS as f64 {
        c.fail(
            "box.step_mm",
            format!("the box holds {count} points, at most {MAX_ROWS}: use a larger step"),
        );
    }
}

/// σ over the workspace: at given joints, or at a box of flange positions
/// solved by IK (a position out of reach or beyond the limits is an entry
/// of `errors`, the others are answered).
pub fn uncertainty_map(
    model: &TermModel,
    uncertainty: &Uncertainty,
    req: &UncertaintyMapRequest,
) -> Result<UncertaintyMapResponse, Vec<FieldError>> {
    let mut c = Checker::default();
    let dof = model.model.robot.dof();
    let tool = req.tool.as_ref().and_then(|t| pose_of(t, "tool", &mut c));
    if let Some(seed) = &req.seed_joints_deg {
        JointsDeg::check(&mut c, "seed_joints_deg", seed, dof);
    }
    if let Some(r) = &req.rotation_deg {
        for (k, v) in r.iter().enumerate() {
            c.bounded(format!("rotation_deg[{k}]"), *v, MAX_ANGLE_DEG, "deg");
        }
    }
    let joints: Vec<Result<Vec<f64>, String>> = match (&req.joints_deg, &req.region) {
        (Some(rows), None) => {
            if rows.is_empty() || rows.len() > MAX_ROWS {
                c.fail("joints_deg", format!("1 to {MAX_ROWS} rows"));
            }
            for (i, row) in rows.iter().enumerate() {
                JointsDeg::check(&mut c, &format!("joints_deg[{i}]"), row, dof);
            }
            c.finish()?;
            rows.iter()
                .map(|r| Ok(r.iter().map(|d| d.to_radians()).collect()))
                .collect()
        }
        (None, Some(b)) => {
            check_box(b, &mut c);
            c.finish()?;
            solve_box(model, req, b)
        }
        _ => {
            return Err(vec![FieldError::new(
                "box",
                "give exactly one of joints_deg and box",
            )])
        }
    };
    let flange_model = TermModel {
        model: flange_only(&model.model),
        ..model.clone()
    };
    let mut answer = UncertaintyMapResponse {
        points: Vec::with_capacity(joints.len()),
        errors: Vec::new(),
    };
    for (index, q) in joints.into_iter().enumerate() {
        let point = q.and_then(|q| {
            let std = uncertainty.at(model, &q, tool)?;
            let flange = flange_model.world_to_tool(&q).map_err(|e| e.to_string())?;
            Ok(MapPoint {
                joints_deg: q.iter().map(|r| r.to_degrees()).collect(),
                flange_position_mm: flange.translation.vector.into(),
                std,
            })
        });
        match point {
            Ok(p) => answer.points.push(Some(p)),
            Err(message) => {
                answer.points.push(None);
                answer.errors.push(TargetError { index, message });
            }
        }
    }
    Ok(answer)
}

/// The model's chain alone: base frame to flange.
fn flange_only(model: &CalibratedModel) -> CalibratedModel {
    CalibratedModel {
        robot: model.robot.clone(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    }
}

/// The (commanded) joints of every box position, each from the seed (its
/// branch kept).
fn solve_box(
    model: &TermModel,
    req: &UncertaintyMapRequest,
    b: &BoxDoc,
) -> Vec<Result<Vec<f64>, String>> {
    let flange_model = TermModel {
        model: flange_only(&model.model),
        ..model.clone()
    };
    let seed: Vec<f64> = match &req.seed_joints_deg {
        Some(deg) => deg.iter().map(|d| d.to_radians()).collect(),
        None => default_seeds(&flange_model.model).swap_remove(0),
    };
    let rotation = req.rotation_deg.unwrap_or(DEFAULT_ROTATION_DEG);
    box_points(b)
        .into_iter()
        .map(|p| {
            let target = robocal_calib::geometry::pose_from_xyz_rpy_deg(p, rotation)
                .map_err(|e| e.to_string())?;
            flange_model
                .nearest_within_limits(&target, &seed)
                .map(|s| s.joints_rad)
                .map_err(|e| e.to_string())
        })
        .collect()
}

#[cfg(test)]
#[path = "uncertainty_tests.rs"]
mod tests;
