//! Boards whose images fix the feature order only up to a turn (issue 14;
//! `domain::BoardSymmetry`): a chessboard with both sides even or both odd,
//! a dot grid without its origin marker, an asymmetric grid with even rows.
//! Each image's order is known only up to such a turn. The robot data
//! settle it: for every pair of poses the flange motion `A = F_i⁻¹ F_j`
//! (nominal kinematics from the joints, or the controller's flange poses)
//! and the camera motion `B = T_i⁻¹ T_j` (camera in the board frame)
//! satisfy `A X = X B`, so their rotation angles and screw pitches agree
//! whatever the hand–eye `X` is. Turning one view's board changes `B`
//! grossly (by ~90° or ~180° when the poses are close), so the relative turn
//! of every view is read off against a reference view, checked on all
//! pairs, and applied to the labels before the kinematic (or hand–eye)
//! stages. A view no pair decides, or pairs that contradict each other, make
//! the job fail with an error naming the target field: never a silent guess.

use nalgebra::{Isometry3, Matrix3, Matrix6};
use robocal_calib::kinematics::RobotModel;

use super::camera_stage::CameraStep;
use super::measure::Measured;
use super::{PipelineError, PoseInput};
use crate::domain::{BoardSymmetry, Target};
use crate::schema::FieldError;

/// Quarter turns in a full turn: relative turns add modulo this.
const QUARTERS: u8 = 4;
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

/// The turn of view `j` relative to view `i` (quarter turns, `0` for
/// none) when the pair decides it, `None` otherwise.
fn relative_turn(
    flange: &[Isometry3<f64>],
    camera: &[Isometry3<f64>],
    symmetry: &BoardSymmetry,
    i: usize,
    j: usize,
) -> Option<u8> {
    let a = screw(&(flange[i].inverse() * flange[j]));
    let mut costs: Vec<(f64, u8)> = std::iter::once(0)
        .chain(symmetry.turns.iter().copied())
        .map(|k| {
            let b = camera[i].inverse() * symmetry.turn(k) * camera[j];
            (cost(a, screw(&b)), k)
        })
        .collect();
    costs.sort_by(|x, y| x.0.total_cmp(&y.0));
    let (best, k) = costs[0];
    let second = costs.get(1).map_or(f64::INFINITY, |c| c.0);
    (best <= MAX_AGREEMENT_COST_DEG && second > DECIDE_RATIO * best + DECIDE_MARGIN_DEG)
        .then_some(k)
}

/// Every deciding pair `(i, j, turn of j relative to i)`, `i < j`.
fn pair_turns(
    flange: &[Isometry3<f64>],
    camera: &[Isometry3<f64>],
    symmetry: &BoardSymmetry,
) -> Vec<(usize, usize, u8)> {
    let n = flange.len();
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .filter_map(|(i, j)| relative_turn(flange, camera, symmetry, i, j).map(|t| (i, j, t)))
        .collect()
}

/// Each view's turn relative to the view with the most deciding pairs,
/// read along deciding pairs breadth first; `None` for views no chain of
/// deciding pairs reaches. The reference is the best-connected view, so a
/// view whose robot data lie cannot leave the others undecided. Turns about
/// one centre add: view `j` turned by `t` against `i` is `turn(i) + t`.
fn propagate(n: usize, pairs: &[(usize, usize, u8)]) -> Vec<Option<u8>> {
    let mut degree = vec![0usize; n];
    for &(i, j, _) in pairs {
        degree[i] += 1;
        degree[j] += 1;
    }
    let mut turned: Vec<Option<u8>> = vec![None; n];
    let Some(reference) = (0..n).max_by_key(|&v| (degree[v], std::cmp::Reverse(v))) else {
        return turned;
    };
    if degree[reference] == 0 {
        return turned; // no pair decides anything
    }
    turned[reference] = Some(0);
    let mut queue = std::collections::VecDeque::from([reference]);
    while let Some(v) = queue.pop_front() {
        let base = turned[v].unwrap_or(0);
        for &(i, j, t) in pairs {
            let (other, value) = match (i == v, j == v) {
                (true, _) => (j, (base + t) % QUARTERS),
                (_, true) => (i, (base + QUARTERS - t) % QUARTERS),
                _ => continue,
            };
            if turned[other].is_none() {
                turned[other] = Some(value);
                queue.push_back(other);
            }
        }
    }
    turned
}

fn refuse(symmetry: &BoardSymmetry, why: String) -> PipelineError {
    PipelineError::Invalid(vec![FieldError::new(symmetry.field, why)])
}

/// The turns the views need: the most common turn is taken as none, so
/// most views keep the detector's order (ties keep the reference view's).
fn corrections(turned: &[u8]) -> Vec<u8> {
    let count = |k: u8| turned.iter().filter(|&&t| t == k).count();
    let common = (0..QUARTERS)
        .max_by_key(|&k| (count(k), std::cmp::Reverse(k)))
        .unwrap_or(0);
    turned
        .iter()
        .map(|&t| (t + QUARTERS - common) % QUARTERS)
        .collect()
}

/// Relabels view `v` of `step` (and the pose's measured points) as turned
/// by `k` quarter turns.
fn relabel_view(
    symmetry: &BoardSymmetry,
    k: u8,
    v: usize,
    step: &mut CameraStep,
    measured: &mut Measured,
) {
    let turn = symmetry.turn(k);
    let mut labels = std::collections::HashMap::new();
    for (g, (p, _)) in step.grid[v].iter_mut().zip(step.observations[v].iter_mut()) {
        if let Some((label, q)) = symmetry.relabel(k, p) {
            labels.insert(*g, label);
            *g = label;
            *p = q;
        }
    }
    let relabel = |row: &mut u32, col: &mut u32| {
        if let Some(&(r, c)) = labels.get(&(*row, *col)) {
            (*row, *col) = (r, c);
        }
    };
    let fit = &mut step.calibration.views[v];
    fit.pose.target_to_camera = turn * fit.pose.target_to_camera;
    fit.camera_to_target = fit.pose.target_to_camera.inverse();
    // The covariance is in the target frame: its rotation and translation
    // parts turn with the board.
    let r: Matrix3<f64> = *turn.rotation.to_rotation_matrix().matrix();
    let mut d = Matrix6::zeros();
    d.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
    d.fixed_view_mut::<3, 3>(3, 3).copy_from(&r);
    fit.pose.covariance_6x6 = d * fit.pose.covariance_6x6 * d.transpose();
    for o in step.calibration.outliers.iter_mut().filter(|o| o.view == v) {
        relabel(&mut o.row, &mut o.col);
    }
    let pose = step.view_pose[v];
    if let Some(Some(points)) = measured.points.get_mut(pose) {
        for p in points.iter_mut() {
            relabel(&mut p.row, &mut p.col);
        }
    }
}

/// Settles the turn of every view of a board whose images fix its order
/// only up to a turn, and relabels the turned ones in `step` and
/// `measured`; returns the report's note naming the relabelled poses, if
/// any. The robot data are the poses' flange poses when they
/// carry them (a hand–eye session), else the nominal kinematics at their
/// joints. Boards with a unique order are left alone.
pub fn resolve(
    robot: &RobotModel,
    poses: &[PoseInput],
    target: &Target,
    step: &mut CameraStep,
    measured: &mut Measured,
) -> Result<Option<String>, PipelineError> {
    let Some(symmetry) = target.symmetry() else {
        return Ok(None);
    };
    let n = step.view_pose.len();
    if n < 2 {
        return Ok(None);
    }
    let looks_same = format!(
        "a {} looks the same after {}",
        symmetry.board_words(),
        symmetry.turn_words()
    );
    let flange_session = poses.first().is_some_and(|p| p.flange_pose.is_some());
    let data = if flange_session {
        "flange poses"
    } else {
        "joints"
    };
    let mut flange = Vec::with_capacity(n);
    for &p in &step.view_pose {
        let f = match &poses[p].flange_pose {
            Some(f) => f.base_to_flange(),
            None => robot
                .base_to_flange(&poses[p].joints_deg.to_radians())
                .map_err(|e| {
                    refuse(
                        &symmetry,
                        format!("{looks_same}, and the {data} cannot settle it: {e}"),
                    )
                })?,
        };
        flange.push(f);
    }
    let camera: Vec<Isometry3<f64>> = step
        .calibration
        .views
        .iter()
        .map(|v| v.pose.target_to_camera)
        .collect();
    let pairs = pair_turns(&flange, &camera, &symmetry);
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
        return Err(refuse(
            &symmetry,
            format!(
                "{looks_same} and the {data} cannot tell which way it lies in pose(s) {}; {}",
                names(undecided),
                symmetry.advice
            ),
        ));
    }
    let turned: Vec<u8> = turned.into_iter().map(|t| t.unwrap_or(0)).collect();
    let deciding = pairs.len();
    let contradicting = pairs
        .iter()
        .filter(|&&(i, j, t)| t != (turned[j] + QUARTERS - turned[i]) % QUARTERS)
        .count();
    if contradicting as f64 > MAX_CONTRADICTING_FRACTION * deciding as f64 {
        return Err(refuse(
            &symmetry,
            format!(
                "{looks_same} and the {data} disagree on which way it lies ({contradicting} of {deciding} pose pairs contradict); {}",
                symmetry.advice
            ),
        ));
    }
    let mut relabelled = Vec::new();
    for (v, k) in corrections(&turned).into_iter().enumerate() {
        if k != 0 {
            relabel_view(&symmetry, k, v, step, measured);
            relabelled.push(poses[step.view_pose[v]].label.as_str());
        }
    }
    Ok((!relabelled.is_empty()).then(|| {
        format!(
            "The board looks the same after {}; the {data} showed it turned in {} image(s), relabelled: {}.",
            symmetry.turn_words(),
            relabelled.len(),
            relabelled.join(", ")
        )
    }))
}
