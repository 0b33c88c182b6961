//! A stage campaign's shape: images grouped by sequence, the checks that
//! make the stage's orientation determinable, and the closed-form start of
//! the bundle (average rotation, Kabsch fit of the stage's axes).

use std::collections::BTreeMap;

use nalgebra::{Matrix3, Rotation3, SymmetricEigen, Vector3};

use super::{StageError, StageView};
use crate::geometry::orthonormalize;

/// Fewest stage positions per sequence (issue 18): three non-collinear
/// ones fix the stage's axes, the fourth leaves a redundancy to check them.
pub const MIN_POSITIONS_PER_SEQUENCE: usize = 4;
/// Positions whose spread across their best line is below this fraction of
/// the spread along it count as collinear: the stage's rotation about that
/// line would rest on sub-per-cent lever arms.
pub const COLLINEAR_SPREAD_RATIO: f64 = 0.01;

/// The images of one sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct SequenceLayout {
    pub sequence: u32,
    /// Indices into the campaign's views.
    pub views: Vec<usize>,
}

/// Groups the views by sequence (ascending) and refuses sequences whose
/// stage positions cannot fix the stage's axes.
pub fn group_sequences(views: &[StageView]) -> Result<Vec<SequenceLayout>, StageError> {
    let readings: Vec<(u32, Vector3<f64>)> = views
        .iter()
        .map(|v| (v.sequence, v.stage_position_mm))
        .collect();
    check_stage_positions(&readings)
}

/// [`group_sequences`] on the stage readings alone (`(sequence, position)`
/// per image): what a service checks before it queues a job.
pub fn check_stage_positions(
    readings: &[(u32, Vector3<f64>)],
) -> Result<Vec<SequenceLayout>, StageError> {
    let mut groups: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
    for (v, (sequence, position)) in readings.iter().enumerate() {
        if !position.iter().all(|c| c.is_finite()) {
            return Err(StageError::NonFinitePosition { view: v });
        }
        groups.entry(*sequence).or_default().push(v);
    }
    groups
        .into_iter()
        .map(|(sequence, members)| {
            if members.len() < MIN_POSITIONS_PER_SEQUENCE {
                return Err(StageError::TooFewPositions {
                    sequence,
                    count: members.len(),
                    required: MIN_POSITIONS_PER_SEQUENCE,
                });
            }
            let positions: Vec<Vector3<f64>> = members.iter().map(|&v| readings[v].1).collect();
            if is_collinear(&positions) {
                return Err(StageError::CollinearPositions { sequence });
            }
            Ok(SequenceLayout {
                sequence,
                views: members,
            })
        })
        .collect()
}

/// True when the positions lie (nearly) on one line or coincide.
pub fn is_collinear(positions: &[Vector3<f64>]) -> bool {
    let n = positions.len().max(1) as f64;
    let mean = positions.iter().sum::<Vector3<f64>>() / n;
    let scatter: Matrix3<f64> = positions
        .iter()
        .map(|p| (p - mean) * (p - mean).transpose())
        .sum::<Matrix3<f64>>()
        / n;
    let mut spread: Vec<f64> = SymmetricEigen::new(scatter)
        .eigenvalues
        .iter()
        .map(|l| l.max(0.0).sqrt())
        .collect();
    spread.sort_by(|a, b| b.total_cmp(a));
    !(spread[0] > 0.0 && spread[1] > COLLINEAR_SPREAD_RATIO * spread[0])
}

/// The chordal mean of rotations (the rotation nearest the sum of their
/// matrices): the paper's "average rotation matrix" of a sequence.
pub fn average_rotation(rotations: &[Rotation3<f64>]) -> Rotation3<f64> {
    let sum: Matrix3<f64> = rotations.iter().map(|r| *r.matrix()).sum();
    orthonormalize(&sum)
}

/// The rotation `S` and origin `o` with `camera_i ≈ o + S stage_i` in the
/// least-squares sense (Kabsch, reflection excluded): the stage's axes in
/// the target frame from measured camera positions. Planar stage grids fix
/// `S` too (the third axis follows from the first two).
pub fn fit_stage_axes(
    stage_mm: &[Vector3<f64>],
    camera_mm: &[Vector3<f64>],
) -> (Rotation3<f64>, Vector3<f64>) {
    let n = stage_mm.len().max(1) as f64;
    let stage_mean = stage_mm.iter().sum::<Vector3<f64>>() / n;
    let camera_mean = camera_mm.iter().sum::<Vector3<f64>>() / n;
    let h: Matrix3<f64> = stage_mm
        .iter()
        .zip(camera_mm)
        .map(|(t, p)| (t - stage_mean) * (p - camera_mean).transpose())
        .sum();
    let svd = h.svd(true, true);
    let (u, v_t) = (
        svd.u.unwrap_or_else(Matrix3::identity),
        svd.v_t.unwrap_or_else(Matrix3::identity),
    );
    let v = v_t.transpose();
    let d = (v * u.transpose()).determinant().signum();
    let rotation = Rotation3::from_matrix_unchecked(
        v * Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, d)) * u.transpose(),
    );
    (rotation, camera_mean - rotation * stage_mean)
}
