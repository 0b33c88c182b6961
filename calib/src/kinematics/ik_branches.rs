//! Closed-form branch seeds for 6R arms with a spherical wrist (method.md
//! §8): joint 1 perpendicular to joint 2, joints 2 and 3 parallel, the last
//! three axes through one point — both presets, and most industrial arms.
//!
//! Such an arm reaches a pose in up to eight ways: shoulder front or back,
//! elbow up or down, wrist flipped or not. A Levenberg–Marquardt run from
//! one seed finds the branch nearest that seed only; when that branch leaves
//! the joint limits, these eight seeds (Pieper's decomposition of the
//! model's own link geometry, its small calibrated deviations ignored) let
//! the solver refine every branch and keep the in-limit one nearest the seed.

use std::f64::consts::PI;

use nalgebra::{Point3, Rotation3, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use super::model::{Convention, RobotModel};
use crate::geometry::Pose;

/// A twist whose cosine (for 90 degrees) or sine (for 0 degrees) is below
/// this still counts: calibrated twists differ from nominal by milliradians,
/// and the seeds only need to land in the right branch.
const TWIST_TOL: f64 = 0.05;
/// Wrist offsets (`a4`, `a5`, `d5`) below this fraction of the arm's reach
/// still make a spherical wrist.
const WRIST_OFFSET_FRACTION: f64 = 0.02;
/// Upper arm and forearm shorter than this (mm) are no arm at all.
const MIN_LINK_MM: f64 = 1.0;
/// The two seeds of a branch pair are at least this far apart (rad). Near a
/// singularity (elbow stretched, wrist straight, wrist centre over joint 1)
/// the calibrated model's two solutions are close while the nominal formula
/// may give one double root; seeds on either side of it find both.
const MIN_BRANCH_SPLIT_RAD: f64 = 0.05;
/// A wrist centre this close (mm) to the shoulder-offset cylinder around
/// joint 1 is near the shoulder singularity: there the calibrated model's
/// shoulder angles can lie far from the nominal formula's (millimetres of
/// deviation turn into tens of degrees), so joint 1 is seeded on a ring.
const NEAR_SHOULDER_AXIS_MM: f64 = 20.0;
/// Joint 1 seeds on that ring.
const SHOULDER_RING: usize = 12;

/// Which side of joint 1 the wrist centre is on, along the arm's own
/// direction (the x axis of frame 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Shoulder {
    Front,
    Back,
}

/// Whether the elbow (frame 2's origin) is above or below the line from
/// the shoulder (frame 1's origin) to the wrist centre projected on the
/// arm's plane, in the base frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Elbow {
    Up,
    Down,
}

/// The sign of joint 5 (with its offset): the wrist flip.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Wrist {
    NoFlip,
    Flip,
}

/// One of the up to eight ways a spherical-wrist arm reaches a pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ArmConfiguration {
    pub shoulder: Shoulder,
    pub elbow: Elbow,
    pub wrist: Wrist,
}

/// The link geometry Pieper's decomposition needs, read off a robot model
/// whose structure allows it.
#[derive(Debug, Clone)]
pub struct SphericalWristArm {
    robot: RobotModel,
    /// Link 1 at zero angle (`A_1 = Rz(theta_1) B_1`).
    b1: Pose,
    /// Link 2's translation at zero angle: the upper arm in frame 1.
    upper_arm: Vector3<f64>,
    /// The wrist centre in frame 2 with joint 3 at zero angle: the forearm.
    forearm: Vector3<f64>,
}

fn angle(v: Vector2<f64>) -> f64 {
    v.y.atan2(v.x)
}

fn xy(v: &Vector3<f64>) -> Vector2<f64> {
    Vector2::new(v.x, v.y)
}

fn rz(theta: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), theta)
}

fn rx(alpha: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::x_axis(), alpha)
}

/// The two angles `phi` with `a cos(phi - shift) = b`, or the nearest real
/// ones when `|b| > |a|`, kept [`MIN_BRANCH_SPLIT_RAD`] apart.
fn acos_pair(b: f64, a: f64, shift: f64) -> [f64; 2] {
    let c = if a.abs() > f64::EPSILON {
        (b / a).clamp(-1.0, 1.0).acos()
    } else {
        0.0
    };
    let c = c.clamp(MIN_BRANCH_SPLIT_RAD / 2.0, PI - MIN_BRANCH_SPLIT_RAD / 2.0);
    [shift + c, shift - c]
}

/// An angle in `(-pi, pi]`.
fn principal(a: f64) -> f64 {
    let r = a.rem_euclid(2.0 * PI);
    if r > PI {
        r - 2.0 * PI
    } else {
        r
    }
}

impl SphericalWristArm {
    /// The arm's geometry, or `None` when its structure is not a 6R arm
    /// with perpendicular joints 1-2, parallel joints 2-3 and a spherical
    /// wrist (the solver then falls back to a grid of starts).
    pub fn of(robot: &RobotModel) -> Option<Self> {
        let j = &robot.joints;
        if j.len() != 6 || j[3..].iter().any(|l| l.convention != Convention::Dh) {
            return None;
        }
        let perpendicular = |alpha: f64| alpha.cos().abs() < TWIST_TOL;
        let parallel = j[1].alpha_rad.sin().abs() < TWIST_TOL
            && j[1].alpha_rad.cos() > 0.0
            && j[1].beta_rad.sin().abs() < TWIST_TOL;
        if !(perpendicular(j[0].alpha_rad)
            && parallel
            && perpendicular(j[3].alpha_rad)
            && perpendicular(j[4].alpha_rad))
        {
            return None;
        }
        let at_zero = |i: usize| j[i].link_transform(-j[i].theta_offset_rad);
        let b1 = at_zero(0);
        let upper_arm = at_zero(1).translation.vector;
        let wrist_in_3 = (j[3].link_transform(0.0) * j[4].link_transform(0.0))
            .translation
            .vector;
        let forearm = at_zero(2).transform_point(&Point3::from(wrist_in_3)).coords;
        let (upper, fore) = (xy(&upper_arm).norm(), xy(&forearm).norm());
        let reach = upper + fore;
        let wrist_offset = j[3].a_mm.abs().max(j[4].a_mm.abs()).max(j[4].d_mm.abs());
        if upper < MIN_LINK_MM || fore < MIN_LINK_MM || wrist_offset > WRIST_OFFSET_FRACTION * reach
        {
            return None;
        }
        Some(Self {
            robot: robot.clone(),
            b1,
            upper_arm,
            forearm,
        })
    }

    /// The wrist centre of a flange pose (base frame).
    fn wrist_centre(&self, base_to_flange: &Pose) -> Vector3<f64> {
        let flange_to_wrist = self.robot.joints[5].link_transform(0.0).inverse();
        (base_to_flange * flange_to_wrist).translation.vector
    }

    /// Eight joint vectors (rad, each angle in `(-pi, pi]`) that put the
    /// flange near `base_to_flange`, one per [`ArmConfiguration`]; exact for
    /// the nominal structure, a seed for the calibrated model. Near the
    /// shoulder singularity, four more per joint-1 angle of a ring.
    pub fn branch_seeds(&self, base_to_flange: &Pose) -> Vec<Vec<f64>> {
        let j = &self.robot.joints;
        let off: Vec<f64> = j.iter().map(|l| l.theta_offset_rad).collect();
        let wc = self.wrist_centre(base_to_flange);
        // Joint 1: the wrist centre lies at a fixed signed distance along
        // joint 2's axis (the shoulder offset).
        let (t1, r1) = (self.b1.translation.vector, self.b1.rotation);
        let n = r1 * Vector3::z();
        let height = self.upper_arm.z + self.forearm.z;
        let offset = n.dot(&t1) + height - n.z * wc.z;
        let (n_h, wc_h) = (xy(&n), xy(&wc));
        let radius = n_h.norm() * wc_h.norm();
        let mut shoulders = acos_pair(offset, radius, angle(wc_h) - angle(n_h)).to_vec();
        if radius - offset.abs() < NEAR_SHOULDER_AXIS_MM {
            shoulders
                .extend((0..SHOULDER_RING).map(|k| k as f64 * 2.0 * PI / SHOULDER_RING as f64));
        }
        let (upper, fore) = (xy(&self.upper_arm), xy(&self.forearm));
        let mut seeds = Vec::with_capacity(8);
        for theta1 in shoulders {
            // Joints 2 and 3: a planar two-link arm in frame 1.
            let local = r1.inverse() * (rz(-theta1) * wc - t1);
            let p = xy(&local);
            let cos_elbow = p.norm_squared() - upper.norm_squared() - fore.norm_squared();
            let elbows = acos_pair(
                cos_elbow,
                2.0 * upper.norm() * fore.norm(),
                angle(upper) - angle(fore),
            );
            for theta3 in elbows {
                let reach = upper + rz(theta3).transform_vector(&fore.push(0.0)).xy();
                let theta2 = angle(p) - angle(reach);
                let arm = [theta1 - off[0], theta2 - off[1], theta3 - off[2]];
                for wrist in self.wrist(&arm, base_to_flange) {
                    let q = arm.iter().chain(&wrist).map(|&a| principal(a)).collect();
                    seeds.push(q);
                }
            }
        }
        seeds
    }

    /// Joints 4 to 6 (both wrist solutions) for arm joints 1 to 3: the
    /// rotation left for the wrist, `Rz(t4) Rx(a4) Rz(t5) Rx(a5) Rz(t6)`,
    /// decomposed like Euler angles.
    fn wrist(&self, arm: &[f64; 3], base_to_flange: &Pose) -> [[f64; 3]; 2] {
        let j = &self.robot.joints;
        let base_to_3 = (0..3).fold(Pose::identity(), |acc, i| acc * j[i].link_transform(arm[i]));
        let left = (base_to_3.rotation.inverse() * base_to_flange.rotation).to_rotation_matrix()
            * rx(j[5].alpha_rad).inverse();
        let (a4, a5) = (j[3].alpha_rad, j[4].alpha_rad);
        let m = left * Vector3::z();
        let p = rx(a4).inverse() * Vector3::z();
        let u = rx(a5) * Vector3::z();
        let thetas5 = acos_pair(
            m.z - p.z * u.z,
            xy(&p).norm() * xy(&u).norm(),
            angle(xy(&p)) - angle(xy(&u)),
        );
        let row = left.inverse() * Vector3::z();
        thetas5.map(|theta5| {
            let middle = rx(a4) * rz(theta5) * rx(a5);
            let v = middle * Vector3::z();
            let g = middle.inverse() * Vector3::z();
            let theta4 = angle(xy(&m)) - angle(xy(&v));
            let theta6 = angle(xy(&g)) - angle(xy(&row));
            [
                theta4 - j[3].theta_offset_rad,
                theta5 - j[4].theta_offset_rad,
                theta6 - j[5].theta_offset_rad,
            ]
        })
    }

    /// The configuration of joints `q_rad` (rad).
    pub fn configuration(&self, q_rad: &[f64]) -> Option<ArmConfiguration> {
        let j = &self.robot.joints;
        if q_rad.len() != j.len() {
            return None;
        }
        let base_to_1 = j[0].link_transform(q_rad[0]);
        let base_to_2 = base_to_1 * j[1].link_transform(q_rad[1]);
        let wc = self.wrist_centre(&self.robot.base_to_flange(q_rad).ok()?);
        let forward = base_to_1.rotation * Vector3::x();
        let shoulder = if xy(&wc).dot(&xy(&forward)) >= 0.0 {
            Shoulder::Front
        } else {
            Shoulder::Back
        };
        // The shoulder-wrist line within the arm's plane (normal: joint 2's
        // axis), so that the shoulder offset does not tilt it.
        let s = base_to_1.translation.vector;
        let axis2 = base_to_1.rotation * Vector3::z();
        let to_wrist = wc - s;
        let line = (to_wrist - axis2 * to_wrist.dot(&axis2)).normalize();
        let e = base_to_2.translation.vector - s;
        let elbow = if (e - line * e.dot(&line)).z >= 0.0 {
            Elbow::Up
        } else {
            Elbow::Down
        };
        let wrist = if principal(q_rad[4] + j[4].theta_offset_rad) >= 0.0 {
            Wrist::NoFlip
        } else {
            Wrist::Flip
        };
        Some(ArmConfiguration {
            shoulder,
            elbow,
            wrist,
        })
    }
}
