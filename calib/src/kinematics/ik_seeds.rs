//! Where the inverse kinematics of compensation (method.md §8) start and
//! how their answers are turned: a grid of seeds over the branch-selecting
//! joints for targets given without one, and whole turns for joints whose
//! range exceeds one turn.

use super::params::CalibratedModel;

/// Fractions of each joint's range tried by [`default_seeds`].
const SEED_FRACTIONS: [f64; 3] = [0.25, 0.5, 0.75];
/// Joints (0-based) whose seed values are varied: the arm's three and the
/// wrist bend, which select the elbow, shoulder and wrist-flip branches.
const SEEDED_JOINTS: [usize; 4] = [0, 1, 2, 4];

/// Seeds for a target given without any: a grid over the branch-selecting
/// joints at [`SEED_FRACTIONS`] of their ranges (others mid-range). The
/// nearest solution to the first (mid-range) seed wins.
pub fn default_seeds(model: &CalibratedModel) -> Vec<Vec<f64>> {
    let joints = &model.robot.joints;
    let at = |i: usize, f: f64| {
        let j = &joints[i];
        j.min_rad + f * (j.max_rad - j.min_rad)
    };
    let varied: Vec<usize> = SEEDED_JOINTS
        .iter()
        .copied()
        .filter(|&i| i < joints.len())
        .collect();
    let count = SEED_FRACTIONS.len().pow(varied.len() as u32);
    // Index 0 of the odometer is the middle fraction, so the first seed is mid-range.
    let order = [1usize, 0, 2];
    (0..count)
        .map(|mut k| {
            let mut q: Vec<f64> = (0..joints.len()).map(|i| at(i, 0.5)).collect();
            for &i in &varied {
                q[i] = at(i, SEED_FRACTIONS[order[k % 3]]);
                k /= 3;
            }
            q
        })
        .collect()
}

/// How a solution's angles are moved by whole turns (for joints whose
/// range exceeds one turn).
#[derive(Clone, Copy)]
pub(super) enum Turns {
    /// Into the limits where possible, otherwise unchanged (the simulator's
    /// historical rule: its campaigns stay as they were).
    IntoLimits,
    /// The in-limit turn nearest the reference seed, per joint: the joint-
    /// space distance is a sum over joints, so this is the nearest overall.
    TowardReference,
}

pub(super) fn move_by_turns(
    model: &CalibratedModel,
    q: &mut [f64],
    reference: &[f64],
    rule: Turns,
) {
    let turn = std::f64::consts::TAU;
    for ((v, j), r) in q.iter_mut().zip(&model.robot.joints).zip(reference) {
        match rule {
            Turns::IntoLimits => {
                while *v > j.max_rad && *v - turn >= j.min_rad {
                    *v -= turn;
                }
                while *v < j.min_rad && *v + turn <= j.max_rad {
                    *v += turn;
                }
            }
            Turns::TowardReference => {
                let lowest = *v - ((*v - j.min_rad) / turn).floor() * turn;
                let mut best = *v;
                let mut candidate = lowest;
                while candidate <= j.max_rad {
                    let outside = best < j.min_rad || best > j.max_rad;
                    if outside || (candidate - r).abs() < (best - r).abs() {
                        best = candidate;
                    }
                    candidate += turn;
                }
                *v = best;
            }
        }
    }
}

pub(super) fn squared_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum()
}
