//! Simulated laser-tracker campaigns (issue 19): a true robot with small
//! geometric errors and, behind a switch, joint compliance under gravity
//! and angle-periodic joint errors; measured tool positions with white
//! noise, or (a 6-DoF probe) measured tool poses. The truth is returned so
//! tests can check what was recovered.

use nalgebra::{Matrix6, Translation3, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};
use rand_distr::{Distribution, Normal};

use super::grouped_campaign::Grouping;
use crate::geometry::{rotation_from_vector, Pose};
use crate::kinematics::identify::{Measurement, Observed};
use crate::kinematics::nongeometric::{NonGeometric, TermKind};
use crate::kinematics::{CalibratedModel, RobotModel};

/// Geometric errors of the true robot: lengths (mm) and angles (rad).
const LENGTH_ERROR_MM: f64 = 0.5;
const ANGLE_ERROR_RAD: f64 = 1e-3;
/// Joints are drawn within ± this of zero (a reachable, non-folded span).
const JOINT_SPAN_RAD: f64 = 2.6;
/// Tracker station: about 2 m from the robot.
const STATION_MM: [f64; 3] = [2000.0, -500.0, 300.0];
/// Tool point in the flange frame (a reflector about 100 mm out).
const TOOL_MM: [f64; 3] = [10.0, -5.0, 100.0];
/// A 6-DoF probe's frame on the flange (roll, pitch, yaw, rad): turned a
/// quarter about the flange axis and slightly tilted, as a T-Mac bracket
/// is, so a start at identity must find it (`initial_frames_from_poses`).
pub const PROBE_ROTATION_RPY_RAD: [f64; 3] = [0.05, -0.03, std::f64::consts::FRAC_PI_2];

/// True non-geometric terms of the switch: a shoulder and elbow softened by
/// a 10 kg wrist-and-tool (c ≈ 2e-6 rad/(N·m)) and gear eccentricities of
/// 60 µrad on the base and the wrist-1 joints.
pub fn typical_terms(truth: &CalibratedModel) -> NonGeometric {
    let mut t = NonGeometric::none(truth);
    t.terms = vec![
        TermKind::ComplianceTool { joint: 1 },
        TermKind::ComplianceTool { joint: 2 },
        TermKind::Periodic {
            joint: 0,
            harmonic: 1,
            cosine: false,
        },
        TermKind::Periodic {
            joint: 3,
            harmonic: 2,
            cosine: true,
        },
    ];
    t.values = vec![2.0e-5, 1.5e-5, 6.0e-5, -6.0e-5];
    t
}

/// What to simulate.
#[derive(Debug, Clone)]
pub struct TrackerSpec {
    pub poses: usize,
    pub noise_mm: f64,
    pub seed: u64,
    /// The switch: add [`typical_terms`] to the true robot.
    pub non_geometric: bool,
    /// A 6-DoF probe (issue 19): `Some(σ)` measures the tool's full pose,
    /// its orientation with white noise of σ (rad) per axis, and mounts the
    /// tool rotated by [`PROBE_ROTATION_RPY_RAD`] (unknown to the start);
    /// `None`, the tool point's position only.
    pub orientation_noise_rad: Option<f64>,
}

/// A simulated campaign with its truth.
#[derive(Debug, Clone)]
pub struct TrackerCampaign {
    pub truth: CalibratedModel,
    pub true_terms: NonGeometric,
    /// Nominal robot, rough station and tool: where identification starts.
    pub start: CalibratedModel,
    pub measurements: Vec<Measurement>,
}

/// The true robot and `count` measured poses (the first `count`); call
/// twice with the same seed and more poses for a validation set.
pub fn simulate_tracker(nominal: &RobotModel, spec: &TrackerSpec) -> TrackerCampaign {
    let mut rng = StdRng::seed_from_u64(spec.seed);
    let mut robot = nominal.clone();
    for j in &mut robot.joints {
        j.a_mm += rng.random_range(-LENGTH_ERROR_MM..LENGTH_ERROR_MM);
        j.d_mm += rng.random_range(-LENGTH_ERROR_MM..LENGTH_ERROR_MM);
        j.alpha_rad += rng.random_range(-ANGLE_ERROR_RAD..ANGLE_ERROR_RAD);
        j.theta_offset_rad += rng.random_range(-ANGLE_ERROR_RAD..ANGLE_ERROR_RAD);
    }
    let world_to_base = Pose::translation(STATION_MM[0], STATION_MM[1], STATION_MM[2]);
    let tool_point = Pose::translation(TOOL_MM[0], TOOL_MM[1], TOOL_MM[2]);
    let tool = match spec.orientation_noise_rad {
        Some(_) => {
            let [r, p, y] = PROBE_ROTATION_RPY_RAD;
            Pose::from_parts(
                tool_point.translation,
                UnitQuaternion::from_euler_angles(r, p, y),
            )
        }
        None => tool_point,
    };
    let truth = CalibratedModel {
        robot,
        world_to_base,
        flange_to_tool: tool,
    };
    let true_terms = if spec.non_geometric {
        typical_terms(&truth)
    } else {
        NonGeometric::none(&truth)
    };
    let noise = Normal::new(0.0, spec.noise_mm.max(f64::MIN_POSITIVE)).expect("finite sigma");
    let mut measurements = Vec::with_capacity(spec.poses);
    while measurements.len() < spec.poses {
        let q: Vec<f64> = (0..nominal.dof())
            .map(|_| rng.random_range(-JOINT_SPAN_RAD..JOINT_SPAN_RAD))
            .collect();
        let Ok(p) = true_terms.world_to_tool(&truth, &q) else {
            continue;
        };
        let e = Vector3::from_fn(|_, _| noise.sample(&mut rng));
        let observed = match spec.orientation_noise_rad {
            // The orientation error in `pose_error`'s outer (tracker) frame.
            Some(sigma_rad) => {
                let turn =
                    Normal::new(0.0, sigma_rad.max(f64::MIN_POSITIVE)).expect("finite sigma");
                let r = Vector3::from_fn(|_, _| turn.sample(&mut rng));
                let mut covariance = Matrix6::zeros();
                for k in 0..3 {
                    covariance[(k, k)] = spec.noise_mm.powi(2);
                    covariance[(k + 3, k + 3)] = sigma_rad.powi(2);
                }
                Observed::Pose {
                    world_to_tool: Pose::from_parts(
                        Translation3::from(p.translation.vector + e),
                        rotation_from_vector(&r) * p.rotation,
                    ),
                    covariance: Some(covariance),
                }
            }
            None => Observed::Position {
                position_mm: p.translation.vector + e,
                covariance: None,
            },
        };
        measurements.push(Measurement {
            joints_rad: q,
            observed,
        });
    }
    // The start knows the tool point, not a probe's rotation.
    let start = CalibratedModel {
        robot: nominal.clone(),
        world_to_base,
        flange_to_tool: tool_point,
    };
    TrackerCampaign {
        truth,
        true_terms,
        start,
        measurements,
    }
}

/// Measurements of `c`'s true robot (with its terms) at `joints_rad`, the
/// position with the campaign's white noise; `None` where it cannot be
/// evaluated.
fn measure_position(
    c: &TrackerCampaign,
    joints_rad: Vec<f64>,
    noise_mm: f64,
    rng: &mut StdRng,
) -> Option<Measurement> {
    let noise = Normal::new(0.0, noise_mm.max(f64::MIN_POSITIVE)).expect("finite sigma");
    let p = c.true_terms.world_to_tool(&c.truth, &joints_rad).ok()?;
    Some(Measurement {
        joints_rad,
        observed: Observed::Position {
            position_mm: p.translation.vector + Vector3::from_fn(|_, _| noise.sample(rng)),
            covariance: None,
        },
    })
}

/// A tracker campaign of `c`'s robot shot in configuration groups
/// (method.md §7.6), as [`super::grouped_campaign`] shoots camera ones:
/// `grouping.groups` anchors drawn over the joint span, and inside each
/// only the wrist moving (joints 1–3 within the grouping's jitter). Then
/// `val` validation positions spread over the joint span. Returns the
/// calibration measurements (group after group) and the validation ones.
pub fn grouped_positions(
    c: &TrackerCampaign,
    grouping: Grouping,
    val: usize,
    noise_mm: f64,
    seed: u64,
) -> (Vec<Measurement>, Vec<Measurement>) {
    let mut rng = StdRng::seed_from_u64(seed);
    let dof = c.truth.robot.dof();
    let spread = |rng: &mut StdRng| -> Vec<f64> {
        (0..dof)
            .map(|_| rng.random_range(-JOINT_SPAN_RAD..JOINT_SPAN_RAD))
            .collect()
    };
    let mut cal = Vec::with_capacity(grouping.groups * grouping.per_group);
    for _ in 0..grouping.groups {
        let anchor = spread(&mut rng);
        let mut placed = 0;
        while placed < grouping.per_group {
            let q: Vec<f64> = anchor
                .iter()
                .enumerate()
                .map(|(j, a)| {
                    let r = if j < 3 {
                        grouping.shoulder_jitter_deg
                    } else {
                        grouping.wrist_range_deg
                    };
                    a + rng.random_range(-r..=r).to_radians()
                })
                .collect();
            if let Some(m) = measure_position(c, q, noise_mm, &mut rng) {
                cal.push(m);
                placed += 1;
            }
        }
    }
    let mut out = Vec::with_capacity(val);
    while out.len() < val {
        let q = spread(&mut rng);
        out.extend(measure_position(c, q, noise_mm, &mut rng));
    }
    (cal, out)
}

#[cfg(test)]
#[path = "tracker_campaign_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "tracker_probe_tests.rs"]
mod probe_tests;
