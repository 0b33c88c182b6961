//! The paper's assessment of a stage sequence (section 4): the 3-D position
//! error of every camera position by the average-rotation method (Table 1),
//! the travelled-distance error against the stage, and the sequence's
//! distance (Fig. 5's abscissa).
//!
//! Average-rotation method: the camera position of image `i` is
//! `X_i = -R_i^T T_i` (paper eqs. 37–39, `R_i, T_i` the target's pose in the
//! camera frame). The camera never rotates within a sequence, so the true
//! `R` is one matrix; the paper takes the average `R̄` as that truth and
//! calls `X_i - (-R̄^T T_i)` the position error. It sees the rotation's
//! scatter (the dominant error of a single-camera pose) but not a common
//! depth bias: the travelled distance, compared with the stage, checks the
//! scale.
//!
//! Beside the paper's table, a stage-referenced one: the stage's readings
//! fitted rigidly to the measured positions (`o + S t_i`, Kabsch) leave, per
//! image, the error the stage sees. Unlike the average-rotation error it
//! holds each image's translation (depth) noise, so its per-axis figures
//! follow the true ones on the depth-heavy axis too. Neither method sees a
//! bias common to every image of a sequence (an offset of the whole
//! sequence, e.g. from the principal point): that needs the board's pose
//! on the stage, which no campaign measures.

use nalgebra::{Isometry3, Point3, Rotation3, Vector3};
use serde::{Deserialize, Serialize};

use super::layout::{average_rotation, fit_stage_axes};
use crate::stats::AccuracyStats;

/// Travelled-distance error of a sequence: over every pair of its images,
/// `| |X_i - X_j| - |t_i - t_j| |` (measured against stage travel, mm).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct TravelledDistanceError {
    pub mean_mm: f64,
    pub max_mm: f64,
}

/// Table 1's row of one sequence, plus its maximum and travel check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SequenceAccuracy {
    pub sequence: u32,
    /// Mean distance from the camera to the board's centre (Fig. 5).
    pub distance_mm: f64,
    pub images: usize,
    /// Per target axis x, y, z: statistics of `|error|`.
    pub mean_mm: [f64; 3],
    pub median_mm: [f64; 3],
    pub std_mm: [f64; 3],
    pub max_mm: [f64; 3],
    /// Largest 3-D error (the paper's 0.43, 0.97, 0.72 mm).
    pub max_3d_mm: f64,
    pub travelled_distance_error_mm: TravelledDistanceError,
    /// The same statistics of the stage-referenced errors
    /// ([`stage_fit_errors`]): the per-axis table the stage itself vouches for.
    pub stage_referenced: AxisTable,
    /// σ of the offset common to every image of the sequence, per target
    /// axis (mm), propagated from the dots' errors through the intrinsics
    /// and each image's pose fit ([`super::offset`]): the part of the
    /// error neither table sees. Zero until the calibration fills it in.
    pub offset_sd_mm: [f64; 3],
}

/// Per-axis statistics in Table 1's layout.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AxisTable {
    pub mean_mm: [f64; 3],
    pub median_mm: [f64; 3],
    pub std_mm: [f64; 3],
    pub max_mm: [f64; 3],
    pub max_3d_mm: f64,
}

impl AxisTable {
    pub fn from_errors(errors_mm: &[Vector3<f64>]) -> Self {
        let s = AccuracyStats::from_errors(errors_mm);
        let axes = [s.x, s.y, s.z];
        Self {
            mean_mm: axes.map(|a| a.mean_mm),
            median_mm: axes.map(|a| a.median_mm),
            std_mm: axes.map(|a| a.std_mm),
            max_mm: axes.map(|a| a.max_mm),
            max_3d_mm: s.norm.max_mm,
        }
    }
}

/// The average-rotation errors `X_i - (-R̄^T T_i)` of one sequence's
/// measured poses (`camera_to_target`: the target in the camera frame).
pub fn average_rotation_errors(camera_to_target: &[Isometry3<f64>]) -> Vec<Vector3<f64>> {
    let rotations: Vec<Rotation3<f64>> = camera_to_target
        .iter()
        .map(|p| p.rotation.to_rotation_matrix())
        .collect();
    let mean = average_rotation(&rotations);
    camera_to_target
        .iter()
        .zip(&rotations)
        .map(|(p, r)| {
            let t = p.translation.vector;
            -(r.transpose() * t) + mean.transpose() * t
        })
        .collect()
}

/// The stage-referenced errors `X_i - (o + S t_i)`: the measured camera
/// positions less the stage's readings fitted to them rigidly (rotation
/// `S` and origin `o`, [`fit_stage_axes`]), in the target frame (mm).
pub fn stage_fit_errors(
    stage_mm: &[Vector3<f64>],
    camera_mm: &[Vector3<f64>],
) -> Vec<Vector3<f64>> {
    let (axes, origin) = fit_stage_axes(stage_mm, camera_mm);
    stage_mm
        .iter()
        .zip(camera_mm)
        .map(|(t, x)| x - (origin + axes * t))
        .collect()
}

/// Travelled-distance errors over every pair of images.
pub fn travelled_distance_error(
    stage_mm: &[Vector3<f64>],
    camera_mm: &[Vector3<f64>],
) -> TravelledDistanceError {
    let mut errors = Vec::new();
    for i in 0..stage_mm.len() {
        for j in i + 1..stage_mm.len() {
            let measured = (camera_mm[i] - camera_mm[j]).norm();
            let travelled = (stage_mm[i] - stage_mm[j]).norm();
            errors.push((measured - travelled).abs());
        }
    }
    let n = errors.len().max(1) as f64;
    TravelledDistanceError {
        mean_mm: errors.iter().sum::<f64>() / n,
        max_mm: errors.iter().copied().fold(0.0, f64::max),
    }
}

/// The assessment of one sequence from its measured poses, stage readings
/// and the board's centre (target frame).
pub fn assess_sequence(
    sequence: u32,
    camera_to_target: &[Isometry3<f64>],
    stage_mm: &[Vector3<f64>],
    board_centre: &Point3<f64>,
) -> SequenceAccuracy {
    let table = AxisTable::from_errors(&average_rotation_errors(camera_to_target));
    let camera_mm: Vec<Vector3<f64>> = camera_to_target
        .iter()
        .map(|p| p.inverse().translation.vector)
        .collect();
    let n = camera_to_target.len().max(1) as f64;
    let distance_mm = camera_to_target
        .iter()
        .map(|p| (p * board_centre).coords.norm())
        .sum::<f64>()
        / n;
    SequenceAccuracy {
        sequence,
        distance_mm,
        images: camera_to_target.len(),
        mean_mm: table.mean_mm,
        median_mm: table.median_mm,
        std_mm: table.std_mm,
        max_mm: table.max_mm,
        max_3d_mm: table.max_3d_mm,
        travelled_distance_error_mm: travelled_distance_error(stage_mm, &camera_mm),
        stage_referenced: AxisTable::from_errors(&stage_fit_errors(stage_mm, &camera_mm)),
        offset_sd_mm: [0.0; 3],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion};

    /// Poses that share one rotation have no average-rotation error, and a
    /// rotation error of one image shows as `|T| * angle` at that image.
    #[test]
    fn a_rotated_image_shows_its_lever_arm() {
        let rotation = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.1);
        let mut poses: Vec<Isometry3<f64>> = (0..4)
            .map(|k| {
                Isometry3::from_parts(Translation3::new(10.0 * k as f64, 0.0, 800.0), rotation)
            })
            .collect();
        assert!(average_rotation_errors(&poses)
            .iter()
            .all(|e| e.norm() < 1e-9));
        let angle = 1e-4;
        poses[0].rotation = UnitQuaternion::from_euler_angles(angle, 0.0, 0.0) * rotation;
        let errors = average_rotation_errors(&poses);
        let lever = poses[0].translation.vector.norm();
        // The average moves by a quarter of the turn: 3/4 of it remains.
        let expected = 0.75 * angle * lever;
        assert!(
            (errors[0].norm() - expected).abs() < 0.02 * expected,
            "{}",
            errors[0].norm()
        );
    }

    #[test]
    fn travel_matches_a_stage_read_exactly() {
        let stage: Vec<Vector3<f64>> = (0..4)
            .map(|k| Vector3::new(20.0 * k as f64, 5.0, 0.0))
            .collect();
        let turn = UnitQuaternion::from_euler_angles(0.5, 0.1, -0.4);
        let camera: Vec<Vector3<f64>> = stage
            .iter()
            .map(|t| turn * t + Vector3::new(1.0, 2.0, 3.0))
            .collect();
        let e = travelled_distance_error(&stage, &camera);
        assert!(e.max_mm < 1e-9);
        let scaled: Vec<Vector3<f64>> = camera.iter().map(|c| c * 1.001).collect();
        let e = travelled_distance_error(&stage, &scaled);
        assert!((e.max_mm - 0.06).abs() < 1e-9, "{e:?}");
    }

    /// A depth error of one image (its translation along the line of sight,
    /// the rotation exact) is invisible to the average-rotation method but
    /// shows whole in the stage-referenced error, less the share the rigid
    /// fit absorbs.
    #[test]
    fn a_depth_error_shows_against_the_stage_not_the_average_rotation() {
        let rotation = UnitQuaternion::from_euler_angles(0.6, -0.2, 0.1);
        let stage: Vec<Vector3<f64>> = (0..25)
            .map(|k| Vector3::new(20.0 * (k % 5) as f64, 20.0 * (k / 5) as f64, 0.0))
            .collect();
        let mut poses: Vec<Isometry3<f64>> = stage
            .iter()
            .map(|t| {
                let camera_in_target = Isometry3::from_parts(
                    Translation3::from(t + Vector3::new(-40.0, -40.0, -800.0)),
                    rotation,
                );
                camera_in_target.inverse()
            })
            .collect();
        let depth_mm = 0.05;
        poses[7].translation.vector.z += depth_mm;
        assert!(average_rotation_errors(&poses)
            .iter()
            .all(|e| e.norm() < 1e-9));
        let camera: Vec<Vector3<f64>> = poses
            .iter()
            .map(|p| p.inverse().translation.vector)
            .collect();
        let errors = stage_fit_errors(&stage, &camera);
        let shown = errors[7].norm();
        assert!(
            shown > 0.9 * depth_mm && shown < depth_mm,
            "{shown} of {depth_mm}"
        );
    }
}
