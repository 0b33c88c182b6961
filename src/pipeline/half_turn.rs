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
/// one plus `DECIDE_MARGIN_DEG`.
const DECIDE_RATIO: f64 = 3.0;
const DECIDE_MARGIN_DEG: f64 = 2.0;
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
    if turned > DECIDE_RATIO * same + DECIDE_MARGIN_DEG {
        Some(false)
    } else if same > DECIDE_RATIO * turned + DECIDE_MARGIN_DEG {
        Some(true)
    } else {
        None
    }
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
    // Each view's turn relative to the first reference that decides it.
    let mut turned: Vec<Option<bool>> = vec![None; n];
    turned[0] = Some(false);
    for _ in 0..n {
        for j in 0..n {
            if turned[j].is_some() {
                continue;
            }
            turned[j] = (0..n).find_map(|r| {
                let base = turned[r]?;
                relative_turn(&flange, &camera, &turn, r, j).map(|t| t != base)
            });
        }
        if turned.iter().all(Option::is_some) {
            break;
        }
    }
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
    let (mut deciding, mut contradicting) = (0usize, 0usize);
    for i in 0..n {
        for j in i + 1..n {
            if let Some(t) = relative_turn(&flange, &camera, &turn, i, j) {
                deciding += 1;
                if t != (turned[i] != turned[j]) {
                    contradicting += 1;
                }
            }
        }
    }
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
