//! What defines a simulated camera campaign (method.md §5–7): the robot
//! and its errors, the camera, board and noise, and the pose counts; and
//! the simulator's errors. Split from `campaign` so the true-robot
//! functions (`true_robot`) read it without an import circle.

use super::campaign_io::Board;
use crate::camera::model::Intrinsics;
use crate::geometry::{pose_from_xyz_rpy_deg, Pose};
use crate::kinematics::RobotModel;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError {
    #[error("could only place {placed} of {wanted} camera stations within reach and view")]
    Unreachable { placed: usize, wanted: usize },
    #[error("invalid campaign specification: {0}")]
    Spec(String),
}

/// Everything that defines a simulated campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct CampaignSpec {
    pub nominal: RobotModel,
    /// Joints (rad) at which the camera looks at the board centre from the
    /// middle distance along the board normal: places the board.
    pub home_joints_rad: Vec<f64>,
    pub cal_poses: usize,
    pub val_poses: usize,
    pub joint_offset_sigma_deg: f64,
    pub length_sigma_mm: f64,
    pub twist_sigma_deg: f64,
    pub encoder_sigma_deg: f64,
    /// Joint 2/3 deflection per metre of horizontal lever arm (rad/m); 0 = off.
    pub compliance_rad_per_m: f64,
    /// Issue 19's switch: the true robot also has the non-geometric terms
    /// of [`typical_terms`] (compliance of joints 2 and 3 under a tool
    /// mass, periodic errors of joints 1 and 4) on top of any
    /// `compliance_rad_per_m`.
    pub non_geometric: bool,
    pub pixel_sigma_px: f64,
    pub distance_mm: (f64, f64),
    pub tilt_deg: (f64, f64),
    pub board: Board,
    pub intrinsics: Intrinsics,
    pub image_size: (u32, u32),
    /// Hand–eye as the user would guess it; the truth differs from it.
    pub flange_to_camera_guess: Pose,
    pub hand_eye_sigma_mm: f64,
    pub hand_eye_sigma_deg: f64,
    pub seed: u64,
    /// Which draw of stations and noise: 0 continues the robot's draw (every
    /// campaign before issue 18's regions); `k > 0` takes them from stream
    /// `k` of the seed. Campaigns of one robot (one `seed`: the same true
    /// kinematics and hand–eye) in several board placements need distinct
    /// streams to be independent sessions: with one stream they redraw the
    /// same stations and pixel noise wherever their accepted stations line
    /// up (up to 22 of 50 poses, seed 18, docs/decisions/0029-regions-judged-over-campaigns.md).
    pub pose_stream: u64,
}

impl CampaignSpec {
    /// The campaign: 60 + 30 poses, ~0.1 deg offsets, ~0.8 mm
    /// lengths, ~0.05 deg twists, 0.1 px dot noise, a 2048x1536 camera with
    /// a 12 mm lens (3.45 um pixels) and the 9x9 25 mm-pitch board.
    pub fn standard(preset: &str, seed: u64) -> Result<Self, SimError> {
        let nominal = crate::kinematics::presets::by_name(preset)
            .ok_or_else(|| SimError::Spec(format!("unknown preset {preset}")))?;
        let home_deg: [f64; 6] = match preset {
            "irb2400" => [0.0, 10.0, 10.0, 0.0, 60.0, 0.0],
            _ => [0.0, 70.0, -140.0, 0.0, -20.0, 0.0],
        };
        Ok(Self {
            nominal,
            home_joints_rad: home_deg.iter().map(|d| d.to_radians()).collect(),
            cal_poses: 60,
            val_poses: 30,
            joint_offset_sigma_deg: 0.1,
            length_sigma_mm: 0.8,
            twist_sigma_deg: 0.05,
            encoder_sigma_deg: 0.0001,
            compliance_rad_per_m: 0.0,
            non_geometric: false,
            pixel_sigma_px: 0.1,
            distance_mm: (600.0, 1000.0),
            tilt_deg: (20.0, 45.0),
            board: Board::standard(),
            intrinsics: Intrinsics {
                fx: 3480.0,
                fy: 3478.0,
                cx: 1030.0,
                cy: 760.0,
                k1: -0.08,
                k2: 0.05,
                p1: 2e-4,
                p2: -1e-4,
                k3: 0.0,
            },
            image_size: (2048, 1536),
            flange_to_camera_guess: pose_from_xyz_rpy_deg([0.0, 60.0, 110.0], [0.0, 0.0, 0.0])
                .map_err(|e| SimError::Spec(e.to_string()))?,
            hand_eye_sigma_mm: 3.0,
            hand_eye_sigma_deg: 1.0,
            seed,
            pose_stream: 0,
        })
    }
}
