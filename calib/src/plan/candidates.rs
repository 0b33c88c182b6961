//! Candidate generation: thousands of camera stations within the request's
//! ranges, each solved by the nominal inverse kinematics and kept only if
//! it passes every filter. Each filter counts its survivors, so that an
//! infeasible request can say which constraint bound.

use nalgebra::{DMatrix, Point3};
use rand::{rngs::StdRng, SeedableRng};

use super::error::{FilterCount, PlanError};
use super::request::PlanRequest;
use super::station::{random_station, station_at, Station};
use crate::geometry::Pose;
use crate::kinematics::ik::{nearest_within_limits, IkError, IK_ROTATION_SCALE_MM};
use crate::kinematics::jacobian::tool_pose_jacobian;
use crate::kinematics::params::PARAMS_PER_JOINT;
use crate::kinematics::{CalibratedModel, Instrument, ParamLayout};

/// Filter names, as the request names the constraint.
pub const FILTER_GENERATED: &str = "distance_mm/view_angle_deg";
pub const FILTER_IMAGE: &str = "board_in_image";
pub const FILTER_REACH: &str = "reach";
pub const FILTER_LIMITS: &str = "joint_limits_deg";
pub const FILTER_KEEP_OUT: &str = "keep_out";
pub const FILTER_SINGULARITY: &str = "singularity";

/// A feasible pose.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    pub joints_rad: Vec<f64>,
    /// Camera pose in the target frame by the planning model.
    pub target_to_camera: Pose,
    pub distance_mm: f64,
    pub view_angle_rad: f64,
}

/// The feasible candidates and every filter's survivors.
#[derive(Debug, Clone, PartialEq)]
pub struct CandidateSet {
    pub candidates: Vec<Candidate>,
    pub filters: Vec<FilterCount>,
}

/// The model with the request's tighter joint limits.
pub fn limited_model(request: &PlanRequest) -> Result<CalibratedModel, PlanError> {
    let mut model = request.model.clone();
    if let Some(limits) = &request.joint_limits_rad {
        if limits.len() != model.robot.dof() {
            return Err(PlanError::Invalid {
                field: "joint_limits_deg",
                message: format!(
                    "{} ranges for a {}-joint robot",
                    limits.len(),
                    model.robot.dof()
                ),
            });
        }
        for (k, (joint, &(lo, hi))) in model.robot.joints.iter_mut().zip(limits).enumerate() {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(PlanError::Invalid {
                    field: "joint_limits_deg",
                    message: format!("joint {}: min must be below max", k + 1),
                });
            }
            joint.min_rad = joint.min_rad.max(lo);
            joint.max_rad = joint.max_rad.min(hi);
            if joint.min_rad >= joint.max_rad {
                return Err(PlanError::Invalid {
                    field: "joint_limits_deg",
                    message: format!("joint {}: no overlap with the robot's own range", k + 1),
                });
            }
        }
    }
    Ok(model)
}

/// Pixels of every board point seen from `target_to_camera`, if all lie
/// `margin_px` inside the image.
pub fn board_in_image(request: &PlanRequest, target_to_camera: &Pose) -> bool {
    let inv = target_to_camera.inverse();
    let (w, h) = (
        f64::from(request.image_width_px),
        f64::from(request.image_height_px),
    );
    let m = request.image_margin_px;
    request.board_points.iter().all(|p| {
        request
            .intrinsics
            .project(&(inv * p))
            .is_some_and(|uv| uv.x > m && uv.y > m && uv.x < w - m && uv.y < h - m)
    })
}

/// Smallest singular value of the manipulator Jacobian at `q` (rotation
/// rows scaled to mm): how far the pose is from a singularity.
pub fn min_singular_mm(model: &CalibratedModel, layout: &ParamLayout, q: &[f64]) -> Option<f64> {
    let (_, jac) = tool_pose_jacobian(layout, model, q).ok()?;
    let n = q.len();
    let m = DMatrix::from_fn(6, n, |r, c| {
        let v = jac[(r, c * PARAMS_PER_JOINT)];
        if r >= 3 {
            v * IK_ROTATION_SCALE_MM
        } else {
            v
        }
    });
    let sv = m.svd(false, false).singular_values;
    if n < 6 {
        return Some(0.0);
    }
    Some(sv.min())
}

/// Flange and camera positions in the base frame at `q`.
fn body_points(model: &CalibratedModel, q: &[f64]) -> Option<[Point3<f64>; 2]> {
    let flange = model.robot.base_to_flange(q).ok()?;
    let camera = flange * model.flange_to_tool;
    Some([
        flange.translation.vector.into(),
        camera.translation.vector.into(),
    ])
}

/// The joints the path starts from: the request's, or the robot looking
/// straight at the board from mid distance (nearest the mid-range joints).
pub fn anchor_joints(
    request: &PlanRequest,
    model: &CalibratedModel,
) -> Result<Vec<f64>, PlanError> {
    if let Some(q) = &request.start_joints_rad {
        model
            .robot
            .base_to_flange(q)
            .map_err(|e| PlanError::Invalid {
                field: "start_joints_deg",
                message: e.to_string(),
            })?;
        return Ok(q.clone());
    }
    let mid: Vec<f64> = model
        .robot
        .joints
        .iter()
        .map(|j| 0.5 * (j.min_rad + j.max_rad))
        .collect();
    let centre = request.board_centre();
    let angle = 0.5 * (request.view_angle_deg.0 + request.view_angle_deg.1).to_radians();
    let distance = 0.5 * (request.distance_mm.0 + request.distance_mm.1);
    // A few azimuths: the first one the robot reaches.
    for k in 0..8 {
        let azimuth = k as f64 * std::f64::consts::FRAC_PI_4;
        for angle in [0.0, angle] {
            let s = station_at(&centre, &centre, angle, azimuth, distance, 0.0);
            if let Ok(sol) = nearest_within_limits(model, &s.target_to_camera, &mid) {
                return Ok(sol.joints_rad);
            }
        }
    }
    Ok(mid)
}

/// Stations generated at most per feasible candidate wanted: the PUMA 560
/// keeps about one station in 4.6 of the simulator's ranges (BENCHMARKS.md,
/// "Campaign planner"), a tighter cell fewer.
pub const MAX_STATIONS_PER_CANDIDATE: usize = 8;

/// Generate stations until `request.candidates` are feasible (at most
/// [`MAX_STATIONS_PER_CANDIDATE`] per candidate wanted) and keep the
/// feasible ones. The issue asks to choose from thousands of *feasible*
/// poses: a fixed count of generated stations left the PUMA 560 with
/// ~460 of 2,000, and its 30-pose plan then fell behind 60 random poses
/// (session 8). When not one of the first `request.candidates` stations
/// is feasible the request is hopeless and generation stops there.
pub fn generate(request: &PlanRequest) -> Result<CandidateSet, PlanError> {
    let model = limited_model(request)?;
    let anchor = anchor_joints(request, &model)?;
    let layout = ParamLayout::new(&model.robot, Instrument::Camera);
    let centre = request.board_centre();
    let angles = (
        request.view_angle_deg.0.to_radians(),
        request.view_angle_deg.1.to_radians(),
    );
    let mut rng = StdRng::seed_from_u64(request.seed);
    let mut survivors = [0usize; 5];
    let mut candidates = Vec::new();
    let most = request
        .candidates
        .saturating_mul(MAX_STATIONS_PER_CANDIDATE);
    let mut generated = 0;
    while candidates.len() < request.candidates && generated < most {
        if generated == request.candidates && candidates.is_empty() {
            break;
        }
        generated += 1;
        let Station {
            target_to_camera,
            view_angle_rad,
            distance_mm,
        } = random_station(&centre, angles, request.distance_mm, &mut rng);
        if !board_in_image(request, &target_to_camera) {
            continue;
        }
        survivors[0] += 1;
        let joints = match nearest_within_limits(&model, &target_to_camera, &anchor) {
            Ok(sol) => sol.joints_rad,
            Err(IkError::Limits(_)) => {
                survivors[1] += 1;
                continue;
            }
            Err(_) => continue,
        };
        survivors[1] += 1;
        survivors[2] += 1;
        let outside = body_points(&model, &joints).is_some_and(|pts| {
            !pts.iter()
                .any(|p| request.keep_out.iter().any(|b| b.contains(p)))
        });
        if !outside {
            continue;
        }
        survivors[3] += 1;
        if min_singular_mm(&model, &layout, &joints).is_none_or(|s| s < request.min_singular_mm) {
            continue;
        }
        survivors[4] += 1;
        candidates.push(Candidate {
            joints_rad: joints,
            target_to_camera,
            distance_mm,
            view_angle_rad,
        });
    }
    let names = [
        FILTER_IMAGE,
        FILTER_REACH,
        FILTER_LIMITS,
        FILTER_KEEP_OUT,
        FILTER_SINGULARITY,
    ];
    let mut filters = vec![FilterCount {
        constraint: FILTER_GENERATED,
        survivors: generated,
    }];
    filters.extend(
        names
            .iter()
            .zip(survivors)
            .map(|(&constraint, survivors)| FilterCount {
                constraint,
                survivors,
            }),
    );
    Ok(CandidateSet {
        candidates,
        filters,
    })
}

/// The filter that bound: the one that kept the smallest fraction of what
/// it was given.
pub fn binding_constraint(filters: &[FilterCount]) -> &'static str {
    filters
        .windows(2)
        .map(|w| {
            let kept = w[1].survivors as f64 / w[0].survivors.max(1) as f64;
            (kept, w[1].constraint)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map_or(FILTER_GENERATED, |(_, c)| c)
}
