//! The joint range each kept periodic term was identified over (issue 19,
//! method.md §7). A harmonic of joint `i` fitted on part of its circle is
//! pinned down there and nowhere else: on the UR10 (Landgraf 2021) the
//! joint-4 harmonics that Series B's full poses keep (B's joint 4 spans
//! −245°…3°) and that pass every held-out test inside B make Series D
//! (−124°…201°) worse (BENCHMARKS.md, "Non-geometric terms"). No test on the
//! calibration poses can see that, so the set keeps the range and `forward`
//! says when a pose leaves it.

use serde::{Deserialize, Serialize};

use super::measurement::Measurement;
use super::nongeometric::{NonGeometric, TermKind};

/// How far a joint may lie outside a term's identified range before it is
/// called an extrapolation (rad): one degree, below which a harmonic of
/// the second order changes by a few percent of its amplitude.
pub const RANGE_MARGIN_RAD: f64 = std::f64::consts::PI / 180.0;

/// The span of one joint's angle (rad) over the calibration poses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IdentifiedRange {
    /// 0-based.
    pub joint: usize,
    pub min_rad: f64,
    pub max_rad: f64,
}

impl IdentifiedRange {
    /// Whether `q_rad` (this joint's angle) lies within the range, up to
    /// [`RANGE_MARGIN_RAD`].
    pub fn contains(&self, q_rad: f64) -> bool {
        q_rad >= self.min_rad - RANGE_MARGIN_RAD && q_rad <= self.max_rad + RANGE_MARGIN_RAD
    }
}

/// The range of every joint that has a kept periodic term, over `data`'s
/// joints (the calibration poses), in joint order. Compliance terms follow
/// a torque of several joints and get none.
pub fn identified_ranges(terms: &NonGeometric, data: &[Measurement]) -> Vec<IdentifiedRange> {
    let mut joints: Vec<usize> = terms
        .terms
        .iter()
        .filter_map(|t| match t {
            TermKind::Periodic { joint, .. } => Some(*joint),
            _ => None,
        })
        .collect();
    joints.sort_unstable();
    joints.dedup();
    joints
        .into_iter()
        .filter_map(|joint| {
            let angles = data.iter().filter_map(|m| m.joints_rad.get(joint).copied());
            let (min_rad, max_rad) = angles
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                    (lo.min(q), hi.max(q))
                });
            (min_rad <= max_rad).then_some(IdentifiedRange {
                joint,
                min_rad,
                max_rad,
            })
        })
        .collect()
}

/// The ranges `q_rad` leaves: where the kept terms extrapolate.
pub fn extrapolated<'a>(
    ranges: &'a [IdentifiedRange],
    q_rad: &'a [f64],
) -> impl Iterator<Item = &'a IdentifiedRange> + 'a {
    ranges
        .iter()
        .filter(|r| q_rad.get(r.joint).is_some_and(|&q| !r.contains(q)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::identify::Observed;
    use crate::kinematics::presets;
    use crate::kinematics::CalibratedModel;
    use nalgebra::Vector3;

    fn at(q: [f64; 6]) -> Measurement {
        Measurement {
            joints_rad: q.to_vec(),
            observed: Observed::Position {
                position_mm: Vector3::zeros(),
                covariance: None,
            },
        }
    }

    #[test]
    fn periodic_joints_get_their_span_and_compliance_none() {
        let model = CalibratedModel {
            robot: presets::ur10(),
            world_to_base: crate::geometry::Pose::identity(),
            flange_to_tool: crate::geometry::Pose::identity(),
        };
        let mut terms = NonGeometric::none(&model);
        terms.terms = vec![
            TermKind::Periodic {
                joint: 3,
                harmonic: 1,
                cosine: false,
            },
            TermKind::Periodic {
                joint: 3,
                harmonic: 2,
                cosine: true,
            },
            TermKind::ComplianceTool { joint: 1 },
        ];
        terms.values = vec![1e-4, 1e-4, 1e-5];
        let data = [
            at([0.0, 0.0, 0.0, -2.0, 0.0, 0.0]),
            at([0.0, 0.0, 0.0, 0.5, 0.0, 0.0]),
            at([0.0, 0.0, 0.0, -1.0, 0.0, 0.0]),
        ];
        let ranges = identified_ranges(&terms, &data);
        assert_eq!(
            ranges,
            [IdentifiedRange {
                joint: 3,
                min_rad: -2.0,
                max_rad: 0.5
            }]
        );
        let inside = [0.0, 1.0, 1.0, 0.5 + RANGE_MARGIN_RAD / 2.0, 3.0, 3.0];
        assert_eq!(extrapolated(&ranges, &inside).count(), 0);
        let outside = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        assert_eq!(extrapolated(&ranges, &outside).count(), 1);
        assert!(identified_ranges(&terms, &[]).is_empty());
    }
}
