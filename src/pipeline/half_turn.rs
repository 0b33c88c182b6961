//! Half-turn-symmetric chessboards (issue 14): a board with both sides even
//! or both odd looks the same after a half turn, so each image's corner
//! order is known only up to one. The robot's joints settle it: for every
//! pair of poses the flange motion `A = F_i⁻¹ F_j` (nominal kinematics) and
//! the camera motion `B = T_i⁻¹ T_j` (camera in the board frame) satisfy
//! `A X = X B`, so their rotation angles and screw pitches agree whatever
//! the hand–eye `X` is. Turning one view's board by a half turn changes
//! `B` grossly (by ~180° when the poses are close), so the relative turn of
//! every view is read off against a reference view, checked on all pairs,
//! and applied to the labels before the kinematic stages. A view no pair
//! decides, or pairs that contradict each other, make the job fail with an
//! error naming `target.inner_corners`: never a silent guess.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use robocal_calib::kinematics::RobotModel;

use super::camera_stage::CameraStep;
use super::measure::Measured;
use super::{PipelineError, PoseInput};
use crate::domain::Target;
use crate::schema::FieldError;

/// Screw pitches are compared at this many mm per degree of angle.
const PITCH_MM_PER_DEG: f64 = 10.0;
/// A pair decides when the wrong choice costs this many times the right
/// one plus `DECIDE_MARGIN_DEG`...
const DECIDE_RATIO: f64 = 3.0;
const DECIDE_MARGIN_DEG: f64 = 2.0;
/// ...and the right one agrees with the joints within this cost (deg, or
/// `PITCH_MM_PER_DEG` mm of pitch): nominal kinematics move the flange to
/// a few tenths of a degree, so a pair further off than this contradicts
/// its joints either way (a pose that lies, joints that did not move) and
/// says nothing about the turn.
const MAX_AGREEMENT_COST_DEG: f64 = 5.0;
/// Most pairs allowed to contradict the chosen turns, as a fraction of the
/// deciding pairs (a pose that lies is screened later; many are not turns).
const MAX_CONTRADICTING_FRACTION: f64 = 0.2;

/// Rotation angle (deg) and |screw pitch| (mm) of a rigid motion.
fn screw(m: &Isometry3<f64>) -> (f64, f64) {
    let angle = m.rotation.angle();
    let pitch = m.rotation.axis().map_or(m.translation.vector.norm(), |a| {
        a.dot(&m.translation.vector).abs()
    });
    (angle.to_degrees(), pitch)
}

fn cost(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).abs() + (a.1 - b.1).abs() / PITCH_MM_PER_DEG
}

/// Whether views `i` and `j` are turned relative to each other: `Some(true)`
/// turned, `Some(false)` not, `None` undecided.
fn relative_turn(
    flange: &[Isometry3<f64>],
    camera: &[Isometry3<f64>],
    turn: &Isometry3<f64>,
    i: usize,
    j: usize,
) -> Option<bool> {
    let a = screw(&(flange[i].inverse() * flange[j]));
    let same = cost(a, screw(&(camera[i].inverse() * camera[j])));
    let turned = cost(a, screw(&(camera[i].inverse() * turn * camera[j])));
    if same.min(turned) > MAX_AGREEMENT_COST_DEG {
        None
    } else if turned > DECIDE_RATIO * same + DECIDE_MARGIN_DEG {
        Some(false)
    } else if same > DECIDE_RATIO * turned + DECIDE_MARGIN_DEG {
        Some(true)
    } else {
        None
    }
}

/// Every deciding pair `(i, j, turned relative to each other)`, `i < j`.
fn pair_turns(
    flange: &[Isometry3<f64>],
    camera: &[Isometry3<f64>],
    turn: &Isometry3<f64>,
) -> Vec<(usize, usize, bool)> {
    let n = flange.len();
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .filter_map(|(i, j)| relative_turn(flange, camera, turn, i, j).map(|t| (i, j, t)))
        .collect()
}

/// Each view's turn relative to the view with the most deciding pairs,
/// read along deciding pairs breadth first; `None` for views no chain of
/// deciding pairs reaches. The reference is the best-connected view, so a
/// view whose joints lie cannot leave the others undecided.
fn propagate(n: usize, pairs: &[(usize, usize, bool)]) -> Vec<Option<bool>> {
    let mut degree = vec![0usize; n];
    for &(i, j, _) in pairs {
        degree[i] += 1;
        degree[j] += 1;
    }
    let mut turned: Vec<Option<bool>> = vec![None; n];
    let Some(reference) = (0..n).max_by_key(|&v| (degree[v], std::cmp::Reverse(v))) else {
        return turned;
    };
    if degree[reference] == 0 {
        return turned; // no pair decides anything
    }
    turned[reference] = Some(false);
    let mut queue = std::collections::VecDeque::from([reference]);
    while let Some(v) = queue.pop_front() {
        let base = turned[v].unwrap_or(false);
        for &(i, j, t) in pairs {
            let other = match (i == v, j == v) {
                (true, _) => j,
                (_, true) => i,
                _ => continue,
            };
            if turned[other].is_none() {
                turned[other] = Some(base != t);
                queue.push_back(other);
            }
        }
    }
    turned
}

fn refuse(why: String) -> PipelineError {
    PipelineError::Invalid(vec![FieldError::new("target.inner_corners", why)])
}

/// Settles the half turn of every view of a half-turn-symmetric board and
/// relabels the turned ones in `step` and `measured`; returns the indices
/// (into the session's poses) of the turned poses. Boards with a unique
/// order are left alone.
pub fn resolve(
    robot: &RobotModel,
    poses: &[PoseInput],
    target: &Target,
    step: &mut CameraStep,
    measured: &mut Measured,
) -> Result<Vec<usize>, PipelineError> {
    let Some(([cols, rows], size_mm)) = target.half_turn() else {
        return Ok(Vec::new());
    };
    let n = step.view_pose.len();
    if n < 2 {
        return Ok(Vec::new());
    }
    // p_old = turn * p_new: a half turn about the board's z through its centre.
    let turn = Translation3::new(size_mm[0], size_mm[1], 0.0)
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::PI);
    let mut flange = Vec::with_capacity(n);
    for &p in &step.view_pose {
        let q = poses[p].joints_deg.to_radians();
        let f = robot
            .base_to_flange(&q)
            .map_err(|e| refuse(format!("cannot settle the board's half turn: {e}")))?;
        flange.push(f);
    }
    let camera: Vec<Isometry3<f64>> = step
        .calibration
        .views
        .iter()
        .map(|v| v.pose.target_to_camera)
        .collect();
    let pairs = pair_turns(&flange, &camera, &turn);
    let turned = propagate(n, &pairs);
    let names = |views: Vec<usize>| -> String {
        views
            .iter()
            .map(|&v| poses[step.view_pose[v]].label.clone())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let undecided: Vec<usize> = (0..n).filter(|&v| turned[v].is_none()).collect();
    if !undecided.is_empty() {
        return Err(refuse(format!(
            "a {cols} x {rows} chessboard looks the same after a half turn and the joints cannot tell which way it lies in pose(s) {}; use a board with one odd and one even side",
            names(undecided)
        )));
    }
    let turned: Vec<bool> = turned.into_iter().map(|t| t.unwrap_or(false)).collect();
    let deciding = pairs.len();
    let contradicting = pairs
        .iter()
        .filter(|&&(i, j, t)| t != (turned[i] != turned[j]))
        .count();
    if contradicting as f64 > MAX_CONTRADICTING_FRACTION * deciding as f64 {
        return Err(refuse(format!(
            "a {cols} x {rows} chessboard looks the same after a half turn and the joints disagree on which way it lies ({contradicting} of {deciding} pose pairs contradict); use a board with one odd and one even side"
        )));
    }
    // Turn the minority, so most views keep the detector's order.
    let flip_value = turned.iter().filter(|&&t| t).count() * 2 <= n;
    let mut out = Vec::new();
    for v in (0..n).filter(|&v| turned[v] == flip_value) {
        let pose = step.view_pose[v];
        let relabel = |row: u32, col: u32| (rows - 1 - row, cols - 1 - col);
        for (g, (p, _)) in step.grid[v].iter_mut().zip(step.observations[v].iter_mut()) {
            *g = relabel(g.0, g.1);
            *p = Point3::new(size_mm[0] - p.x, size_mm[1] - p.y, p.z);
        }
        let fit = &mut step.calibration.views[v];
        fit.pose.target_to_camera = turn * fit.pose.target_to_camera;
        fit.camera_to_target = fit.pose.target_to_camera.inverse();
        // The covariance is in the target frame: x and y change sign.
        let d = nalgebra::Matrix6::from_diagonal(&nalgebra::Vector6::new(
            -1.0, -1.0, 1.0, -1.0, -1.0, 1.0,
        ));
        fit.pose.covariance_6x6 = d * fit.pose.covariance_6x6 * d;
        for o in step.calibration.outliers.iter_mut().filter(|o| o.view == v) {
            (o.row, o.col) = relabel(o.row, o.col);
        }
        if let Some(Some(points)) = measured.points.get_mut(pose) {
            for p in points.iter_mut() {
                (p.row, p.col) = relabel(p.row, p.col);
            }
        }
        out.push(pose);
    }
    Ok(out)
}
