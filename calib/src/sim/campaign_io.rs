//! Serialisable parts of a simulated campaign: the board, the campaign
//! directory's `poses.json` entries (api.md "Sessions": the zip upload's
//! `[{"joints_deg","image","set"}]`) and `truth.json`.

use nalgebra::Point3;
use serde::{Deserialize, Serialize};

use crate::camera::model::Intrinsics;
use crate::camera::observations::ImageSize;
use crate::geometry::{pose_from_matrix_rows, GeometryError};

/// A pose as a 4x4 row-major matrix (api.md "Poses"), exact to round-off
/// unlike roll–pitch–yaw near pitch +-90 degrees.
pub type MatrixRows = [[f64; 4]; 4];
use crate::kinematics::RobotModel;

/// Board pitch and dot size of the simulated boards (the issues').
pub const BOARD_PITCH_MM: f64 = 25.0;
pub const BOARD_DOT_DIAMETER_MM: f64 = 8.0;

/// The dot-grid board of every simulation (method.md §1): dot (r, c) at
/// `(c*p, r*p, 0)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Board {
    pub rows: usize,
    pub cols: usize,
    pub pitch_mm: f64,
    pub dot_diameter_mm: f64,
}

impl Board {
    /// The 9x9 board, 25 mm pitch, 8 mm dots.
    pub fn standard() -> Self {
        Self {
            rows: 9,
            cols: 9,
            pitch_mm: BOARD_PITCH_MM,
            dot_diameter_mm: BOARD_DOT_DIAMETER_MM,
        }
    }

    /// A board sized to the field of view, as a cell would choose it: the
    /// standard pitch and dots, and enough dots that the board spans at
    /// least `fraction` of the image width and height at `distance_mm`
    /// (pinhole field of view `size / f * distance`).
    pub fn spanning_field(
        intrinsics: &Intrinsics,
        image_size: ImageSize,
        distance_mm: f64,
        fraction: f64,
    ) -> Self {
        let standard = Self::standard();
        let dots = |pixels: u32, focal_px: f64| {
            let extent_mm = fraction * pixels as f64 / focal_px * distance_mm;
            (extent_mm / standard.pitch_mm).ceil().max(1.0) as usize + 1
        };
        Self {
            rows: dots(image_size.height, intrinsics.fy),
            cols: dots(image_size.width, intrinsics.fx),
            ..standard
        }
    }

    /// Centre of dot `(row, col)` in the target frame.
    pub fn point(&self, row: usize, col: usize) -> Point3<f64> {
        Point3::new(col as f64 * self.pitch_mm, row as f64 * self.pitch_mm, 0.0)
    }

    /// Dot centres in the target frame, row-major.
    pub fn points(&self) -> Vec<Point3<f64>> {
        (0..self.rows)
            .flat_map(|r| (0..self.cols).map(move |c| self.point(r, c)))
            .collect()
    }

    pub fn centre(&self) -> Point3<f64> {
        Point3::new(
            0.5 * (self.cols.saturating_sub(1)) as f64 * self.pitch_mm,
            0.5 * (self.rows.saturating_sub(1)) as f64 * self.pitch_mm,
            0.0,
        )
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PoseSet {
    Cal,
    Val,
}

/// One row of `poses.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PoseEntry {
    pub joints_deg: Vec<f64>,
    pub image: String,
    pub set: PoseSet,
}

/// `truth.json`: what the simulator knows and the calibration must find.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Truth {
    pub nominal: RobotModel,
    pub robot: RobotModel,
    pub target_to_base: MatrixRows,
    pub flange_to_camera: MatrixRows,
    pub flange_to_camera_guess: MatrixRows,
    pub intrinsics: Intrinsics,
    pub image_width: u32,
    pub image_height: u32,
    pub board: Board,
    pub pixel_sigma_px: f64,
    pub encoder_sigma_deg: f64,
    pub compliance_rad_per_m: f64,
    /// The true robot had [`super::tracker_campaign::typical_terms`] too
    /// (issue 19's switch); its true joints below include them.
    #[serde(default)]
    pub non_geometric: bool,
    /// The joints the true robot really had, per pose (deg).
    pub true_joints_deg: Vec<Vec<f64>>,
    /// The true camera pose per pose (the renderer's input).
    pub target_to_camera: Vec<MatrixRows>,
    pub seed: u64,
}

impl Truth {
    /// The true model: robot, `target_to_base`, `flange_to_camera`.
    pub fn model(&self) -> Result<crate::kinematics::CalibratedModel, GeometryError> {
        Ok(crate::kinematics::CalibratedModel {
            robot: self.robot.clone(),
            world_to_base: pose_from_matrix_rows(&self.target_to_base)?,
            flange_to_tool: pose_from_matrix_rows(&self.flange_to_camera)?,
        })
    }
}

/// Name of pose `index`'s image inside the campaign directory.
pub fn image_name(index: usize) -> String {
    format!("images/{:04}.png", index + 1)
}
