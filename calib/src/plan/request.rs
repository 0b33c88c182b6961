//! What a campaign plan is asked for: the cell (robot model with its
//! guesses of `target_to_base` and `flange_to_camera`, camera, board) and
//! the ranges every pose must respect.

use nalgebra::{Point3, Vector3};

use crate::camera::model::Intrinsics;
use crate::kinematics::CalibratedModel;

/// Dot noise assumed when the robot has no earlier job (px per axis): the
/// simulator's and a good detector's level on a sharp board.
pub const DEFAULT_SIGMA_PX: f64 = 0.1;
/// Feasible candidates the selection chooses from by default (the issue
/// asks for thousands; its benchmark plans from at least 2,000).
pub const DEFAULT_CANDIDATES: usize = 2000;
/// Board points must lie this far inside the image border (px) by the
/// guesses: a hand–eye guess off by 1 degree moves the image by `f tan 1°`
/// (60 px for a 12 mm lens on 3.45 um pixels), the kinematic errors a few
/// more, and a planned pose must still show the whole board on the real robot.
pub const DEFAULT_IMAGE_MARGIN_PX: f64 = 120.0;
/// Smallest singular value of the manipulator Jacobian (rotation rows in mm
/// per rad at [`crate::kinematics::ik::IK_ROTATION_SCALE_MM`]) a pose may
/// have: below it a small encoder error moves the tool a lot in some
/// direction and the pose is near a (wrist) singularity.
pub const DEFAULT_MIN_SINGULAR_MM: f64 = 60.0;
/// Largest number of poses of a quick-check plan.
pub const QUICK_CHECK_MAX_POSES: usize = 10;
/// Fewest poses of a quick-check plan.
pub const QUICK_CHECK_MIN_POSES: usize = 5;

/// An axis-aligned box in the base frame the flange and the camera must
/// stay out of (fixtures, the board's stand, the cell's walls).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeepOutBox {
    pub min_mm: Vector3<f64>,
    pub max_mm: Vector3<f64>,
}

impl KeepOutBox {
    pub fn contains(&self, p: &Point3<f64>) -> bool {
        (0..3).all(|k| p[k] >= self.min_mm[k] && p[k] <= self.max_mm[k])
    }
}

/// What the plan is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanPurpose {
    /// A full calibration: every parameter the job identifies.
    Calibration,
    /// A re-check of a calibrated robot ("A fleet over time"): the poses
    /// most sensitive to drift of the joint zeros and of the base, the rest
    /// of the model known.
    QuickCheck,
}

/// What the selection optimises after its D-optimal start. By default
/// ([`PlanCriterion::for_purpose`]) a calibration plan is I-optimal: on the
/// simulator it is the one that beats 60 random poses with 30 (BENCHMARKS.md,
/// "Campaign planner"); a quick check is D-optimal, every drift
/// parameter counting alike.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanCriterion {
    /// The determinant of the information: every parameter at once.
    D,
    /// The predicted camera-position variance at random validation poses
    /// (what a job's validation error measures), by exchange from the
    /// D-optimal plan.
    I,
}

impl PlanCriterion {
    pub fn for_purpose(purpose: PlanPurpose) -> Self {
        match purpose {
            PlanPurpose::Calibration => PlanCriterion::I,
            PlanPurpose::QuickCheck => PlanCriterion::D,
        }
    }
}

/// A plan request in the numerics' units (radians inside, `_deg` in names).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanRequest {
    /// Nominal (or latest calibrated) kinematics; `world_to_base` is the
    /// guess of `target_to_base`, `flange_to_tool` of `flange_to_camera`.
    pub model: CalibratedModel,
    pub intrinsics: Intrinsics,
    pub image_width_px: u32,
    pub image_height_px: u32,
    /// Dot centres in the target frame (mm): what every image must show.
    pub board_points: Vec<Point3<f64>>,
    /// Calibration poses to choose.
    pub poses: usize,
    /// Validation poses to add (random, in the same ranges).
    pub validation_poses: usize,
    /// Camera-to-board-centre distance range (mm).
    pub distance_mm: (f64, f64),
    /// Angle between the camera's line of sight and the board normal (deg).
    pub view_angle_deg: (f64, f64),
    /// Per joint `(min, max)` (rad), tighter than the model's; `None` = the
    /// model's own limits.
    pub joint_limits_rad: Option<Vec<(f64, f64)>>,
    pub keep_out: Vec<KeepOutBox>,
    /// Where the robot starts; the path begins here.
    pub start_joints_rad: Option<Vec<f64>>,
    /// Dot noise for the prediction (px per axis).
    pub sigma_px: f64,
    /// The job will hold the intrinsics (a reused camera calibration).
    pub hold_intrinsics: bool,
    pub purpose: PlanPurpose,
    /// `None`: [`PlanCriterion::for_purpose`].
    pub criterion: Option<PlanCriterion>,
    /// Feasible candidates to choose from ([`super::candidates::generate`]).
    pub candidates: usize,
    pub image_margin_px: f64,
    pub min_singular_mm: f64,
    /// Seeds candidate generation and the validation poses: one request
    /// always gives the same plan.
    pub seed: u64,
    /// Joints of the calibration poses a campaign already has (an
    /// extension, issue 30): their information seeds the selection, only
    /// the new poses are planned, and the plan predicts the campaign with
    /// and without them. Empty: a plan from scratch.
    pub existing_joints_rad: Vec<Vec<f64>>,
}

impl PlanRequest {
    /// A request with the defaults above; the purpose follows from the
    /// pose count (5..=10 is a quick check).
    pub fn new(
        model: CalibratedModel,
        intrinsics: Intrinsics,
        image_size_px: (u32, u32),
        board_points: Vec<Point3<f64>>,
        poses: usize,
    ) -> Self {
        let purpose = if poses <= QUICK_CHECK_MAX_POSES {
            PlanPurpose::QuickCheck
        } else {
            PlanPurpose::Calibration
        };
        Self {
            model,
            intrinsics,
            image_width_px: image_size_px.0,
            image_height_px: image_size_px.1,
            board_points,
            poses,
            validation_poses: 0,
            distance_mm: (600.0, 1000.0),
            view_angle_deg: (20.0, 45.0),
            joint_limits_rad: None,
            keep_out: Vec::new(),
            start_joints_rad: None,
            sigma_px: DEFAULT_SIGMA_PX,
            hold_intrinsics: false,
            purpose,
            criterion: None,
            candidates: DEFAULT_CANDIDATES,
            image_margin_px: DEFAULT_IMAGE_MARGIN_PX,
            min_singular_mm: DEFAULT_MIN_SINGULAR_MM,
            seed: 0x91a4,
            existing_joints_rad: Vec::new(),
        }
    }

    /// The board's centre (mean of its points), what the camera aims at.
    pub fn board_centre(&self) -> Point3<f64> {
        let n = self.board_points.len().max(1) as f64;
        let sum = self
            .board_points
            .iter()
            .fold(Vector3::zeros(), |s, p| s + p.coords);
        Point3::from(sum / n)
    }
}
