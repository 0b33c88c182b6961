//! Whole-campaign simulator (method.md §5–7): a robot with perturbed
//! kinematics, a flange camera with an unknown hand–eye transform, camera
//! stations 600–1000 mm from the board at 20–45 degrees reached through the
//! *nominal* inverse kinematics, encoder noise, optional joint compliance
//! (an unmodelled error) and optional non-geometric terms (issue 19's
//! switch, the ones the tracker simulator uses), and the ideal (optionally noisy) image of every
//! dot. The renderer (`sim/render.rs`) turns [`SimPose::target_to_camera`]
//! into images; this file only produces geometry and truth.

use nalgebra::{Point2, Point3, Rotation3, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};
use rand_distr::{Distribution, Normal};

use super::campaign_io::{image_name, Board, PoseEntry, PoseSet, Truth};
pub use super::campaign_spec::{CampaignSpec, SimError};
use super::true_robot::gauss;
pub use super::true_robot::{compliance, perturb_robot, true_joints, true_terms};
use crate::geometry::{pose_to_matrix_rows, Pose};
use crate::kinematics::ik::inverse_kinematics;
use crate::kinematics::nongeometric::NonGeometric;
use crate::kinematics::{CalibratedModel, RobotModel};

/// Attempts per accepted station before the campaign is declared impossible.
const MAX_ATTEMPTS_PER_POSE: usize = 200;
/// Dots must lie this far inside the image border (px).
const IMAGE_MARGIN_PX: f64 = 20.0;
/// Random aim point offset from the board centre (mm).
const AIM_JITTER_MM: f64 = 30.0;
/// Random roll of the camera about its axis (deg).
const ROLL_JITTER_DEG: f64 = 25.0;
/// Spreads [`CampaignSpec::pose_stream`] over the seed's bits (the 64-bit
/// golden ratio, as splitmix64): nearby streams get unrelated seeds.
const POSE_STREAM_STRIDE: u64 = 0x9E37_79B9_7F4A_7C15;

/// One simulated pose.
#[derive(Debug, Clone, PartialEq)]
pub struct SimPose {
    /// Joints the controller records (what the campaign file carries).
    pub joints_rad: Vec<f64>,
    /// Joints the true robot really had (encoder error, compliance).
    pub true_joints_rad: Vec<f64>,
    /// True camera pose in the target frame (the renderer's input).
    pub target_to_camera: Pose,
    pub set: PoseSet,
    /// Ideal image of every dot centre, board order (row-major).
    pub ideal_px: Vec<Point2<f64>>,
    /// `ideal_px` plus Gaussian noise of the spec's `pixel_sigma_px`.
    pub observed_px: Vec<Point2<f64>>,
}

impl SimPose {
    /// `(target point mm, observed pixel)` pairs: the joint refinement's input.
    pub fn observations(&self, board: &Board) -> Vec<(Point3<f64>, Point2<f64>)> {
        board
            .points()
            .into_iter()
            .zip(self.observed_px.iter().copied())
            .collect()
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Campaign {
    pub truth: Truth,
    pub poses: Vec<SimPose>,
}

/// Ideal pixels of all dots, if every one is inside the image margins.
fn image_of_board(spec: &CampaignSpec, target_to_camera: &Pose) -> Option<Vec<Point2<f64>>> {
    let inv = target_to_camera.inverse();
    let (w, h) = (spec.image_size.0 as f64, spec.image_size.1 as f64);
    spec.board
        .points()
        .iter()
        .map(|p| {
            let uv = spec.intrinsics.project(&(inv * p))?;
            let inside = uv.x > IMAGE_MARGIN_PX
                && uv.y > IMAGE_MARGIN_PX
                && uv.x < w - IMAGE_MARGIN_PX
                && uv.y < h - IMAGE_MARGIN_PX;
            inside.then_some(uv)
        })
        .collect()
}

/// A camera station in the target frame: `tilt` from the board normal,
/// at `distance`, looking at the board centre (jittered), rolled a little.
fn station(spec: &CampaignSpec, rng: &mut StdRng) -> Pose {
    let centre = spec.board.centre();
    let tilt = rng
        .random_range(spec.tilt_deg.0..=spec.tilt_deg.1)
        .to_radians();
    let azimuth = rng.random_range(0.0..std::f64::consts::TAU);
    let distance = rng.random_range(spec.distance_mm.0..=spec.distance_mm.1);
    let dir = Vector3::new(
        tilt.sin() * azimuth.cos(),
        tilt.sin() * azimuth.sin(),
        -tilt.cos(),
    );
    let position = centre.coords + dir * distance;
    let aim = centre.coords
        + Vector3::new(
            rng.random_range(-AIM_JITTER_MM..=AIM_JITTER_MM),
            rng.random_range(-AIM_JITTER_MM..=AIM_JITTER_MM),
            0.0,
        );
    let z = (aim - position).normalize();
    let x0 = (Vector3::x() - z * z.x).normalize();
    let y0 = z.cross(&x0);
    let look = Rotation3::from_basis_unchecked(&[x0, y0, z]);
    let roll = Rotation3::from_axis_angle(
        &Vector3::z_axis(),
        rng.random_range(-ROLL_JITTER_DEG..=ROLL_JITTER_DEG)
            .to_radians(),
    );
    Pose::from_parts(
        position.into(),
        UnitQuaternion::from_rotation_matrix(&(look * roll)),
    )
}

/// A campaign's fixed parts: the true robot, its frames and terms, the
/// nominal model the stations are reached through.
pub(super) struct Setup {
    pub(super) robot: RobotModel,
    pub(super) nominal_model: CalibratedModel,
    pub(super) true_model: CalibratedModel,
    pub(super) terms: NonGeometric,
    pub(super) pixel: Normal<f64>,
}

/// The true robot, hand–eye and board of `spec`, drawn from `rng` (which
/// then continues with the stations).
pub(super) fn setup(spec: &CampaignSpec, rng: &mut StdRng) -> Result<Setup, SimError> {
    let dof = spec.nominal.dof();
    if spec.home_joints_rad.len() != dof || spec.cal_poses + spec.val_poses == 0 {
        return Err(SimError::Spec("home joints or pose counts".into()));
    }
    let robot = perturb_robot(&spec.nominal, spec, rng);
    let he = [0, 1, 2].map(|_| gauss(rng, spec.hand_eye_sigma_mm));
    let hr = [0, 1, 2].map(|_| gauss(rng, spec.hand_eye_sigma_deg).to_radians());
    let flange_to_camera = crate::geometry::perturb_left(
        &spec.flange_to_camera_guess,
        &nalgebra::Vector6::new(he[0], he[1], he[2], hr[0], hr[1], hr[2]),
    );
    if spec.pose_stream != 0 {
        *rng = StdRng::seed_from_u64(spec.seed ^ spec.pose_stream.wrapping_mul(POSE_STREAM_STRIDE));
    }
    // Board: centred on the nominal home camera's axis at mid distance,
    // target z along the camera z (method.md §1: z points into the board).
    let base_to_home_camera = spec
        .nominal
        .base_to_flange(&spec.home_joints_rad)
        .map_err(|e| SimError::Spec(e.to_string()))?
        * spec.flange_to_camera_guess;
    let mid = 0.5 * (spec.distance_mm.0 + spec.distance_mm.1);
    let c = spec.board.centre();
    let base_to_target = base_to_home_camera * Pose::translation(-c.x, -c.y, mid);
    let target_to_base = base_to_target.inverse();
    let nominal_model = CalibratedModel {
        robot: spec.nominal.clone(),
        world_to_base: target_to_base,
        flange_to_tool: spec.flange_to_camera_guess,
    };
    let true_model = CalibratedModel {
        robot: robot.clone(),
        world_to_base: target_to_base,
        flange_to_tool: flange_to_camera,
    };
    let terms = true_terms(spec, &true_model);
    let pixel = Normal::new(0.0, spec.pixel_sigma_px.max(f64::MIN_POSITIVE))
        .map_err(|e| SimError::Spec(e.to_string()))?;
    Ok(Setup {
        robot,
        nominal_model,
        true_model,
        terms,
        pixel,
    })
}

/// The pose the robot takes when commanded to `joints` (recorded as
/// such): encoder noise, the true joints, the image of the board; `None`
/// when the board is not wholly in view.
pub(super) fn pose_at(
    spec: &CampaignSpec,
    setup: &Setup,
    joints: Vec<f64>,
    set: PoseSet,
    rng: &mut StdRng,
) -> Option<SimPose> {
    let noisy: Vec<f64> = joints
        .iter()
        .map(|q| q + gauss(rng, spec.encoder_sigma_deg.to_radians()))
        .collect();
    let true_joints = true_joints(spec, &setup.robot, &setup.terms, &noisy);
    let target_to_camera = setup.true_model.world_to_tool(&true_joints).ok()?;
    let ideal_px = image_of_board(spec, &target_to_camera)?;
    let observed_px = ideal_px
        .iter()
        .map(|p| {
            if spec.pixel_sigma_px > 0.0 {
                Point2::new(p.x + setup.pixel.sample(rng), p.y + setup.pixel.sample(rng))
            } else {
                *p
            }
        })
        .collect();
    Some(SimPose {
        joints_rad: joints,
        true_joints_rad: true_joints,
        target_to_camera,
        set,
        ideal_px,
        observed_px,
    })
}

/// A random station reached through the nominal inverse kinematics: its
/// joints, or `None` when the nominal arm cannot reach it.
pub(super) fn station_joints(
    spec: &CampaignSpec,
    setup: &Setup,
    rng: &mut StdRng,
) -> Option<Vec<f64>> {
    let desired = station(spec, rng);
    let seeds = vec![spec.home_joints_rad.clone()];
    inverse_kinematics(&setup.nominal_model, &desired, &seeds)
        .ok()
        .map(|s| s.joints_rad)
}

/// Simulate a campaign (see the module doc).
pub fn simulate_campaign(spec: &CampaignSpec) -> Result<Campaign, SimError> {
    let mut rng = StdRng::seed_from_u64(spec.seed);
    let setup = setup(spec, &mut rng)?;
    let wanted = spec.cal_poses + spec.val_poses;
    let mut poses = Vec::with_capacity(wanted);
    let mut attempts = 0;
    while poses.len() < wanted {
        attempts += 1;
        if attempts > MAX_ATTEMPTS_PER_POSE * wanted {
            return Err(SimError::Unreachable {
                placed: poses.len(),
                wanted,
            });
        }
        let Some(joints) = station_joints(spec, &setup, &mut rng) else {
            continue;
        };
        let set = if poses.len() < spec.cal_poses {
            PoseSet::Cal
        } else {
            PoseSet::Val
        };
        if let Some(pose) = pose_at(spec, &setup, joints, set, &mut rng) {
            poses.push(pose);
        }
    }
    Ok(setup.into_campaign(spec, poses))
}

impl Setup {
    /// The campaign of `poses` with this set-up's truth.
    pub(super) fn into_campaign(self, spec: &CampaignSpec, poses: Vec<SimPose>) -> Campaign {
        let truth = campaign_truth(
            spec,
            &self.robot,
            &self.true_model.world_to_base,
            &self.true_model.flange_to_tool,
        );
        Campaign { truth, poses }
    }
}

/// The campaign-level truth (the per-pose parts are filled by
/// [`Campaign::full_truth`]).
fn campaign_truth(
    spec: &CampaignSpec,
    robot: &RobotModel,
    target_to_base: &Pose,
    flange_to_camera: &Pose,
) -> Truth {
    Truth {
        nominal: spec.nominal.clone(),
        robot: robot.clone(),
        target_to_base: pose_to_matrix_rows(target_to_base),
        flange_to_camera: pose_to_matrix_rows(flange_to_camera),
        flange_to_camera_guess: pose_to_matrix_rows(&spec.flange_to_camera_guess),
        intrinsics: spec.intrinsics,
        image_width: spec.image_size.0,
        image_height: spec.image_size.1,
        board: spec.board,
        pixel_sigma_px: spec.pixel_sigma_px,
        encoder_sigma_deg: spec.encoder_sigma_deg,
        compliance_rad_per_m: spec.compliance_rad_per_m,
        non_geometric: spec.non_geometric,
        true_joints_deg: Vec::new(),
        target_to_camera: Vec::new(),
        seed: spec.seed,
    }
}

impl Campaign {
    /// The rows of `poses.json`, images named by [`image_name`].
    pub fn pose_entries(&self) -> Vec<PoseEntry> {
        self.poses
            .iter()
            .enumerate()
            .map(|(i, p)| PoseEntry {
                joints_deg: p.joints_rad.iter().map(|q| q.to_degrees()).collect(),
                image: image_name(i),
                set: p.set,
            })
            .collect()
    }

    /// `truth.json` with the per-pose truth filled in.
    pub fn full_truth(&self) -> Truth {
        let mut t = self.truth.clone();
        t.true_joints_deg = self
            .poses
            .iter()
            .map(|p| p.true_joints_rad.iter().map(|q| q.to_degrees()).collect())
            .collect();
        t.target_to_camera = self
            .poses
            .iter()
            .map(|p| pose_to_matrix_rows(&p.target_to_camera))
            .collect();
        t
    }
}

#[cfg(test)]
#[path = "campaign_tests.rs"]
mod tests;
