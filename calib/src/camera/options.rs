//! What a camera calibration is asked to do (method.md §2–4): the paper's
//! method alone or refined, held intrinsics, reference distances, the dot
//! bias correction and the outlier rule.

use serde::{Deserialize, Serialize};

use super::model::Intrinsics;
use super::refine::StationDistance;
use super::sequence::PaperOptions;

/// Outlier threshold in robust standard deviations (issue 4).
pub const OUTLIER_SIGMAS: f64 = 5.0;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum CalibrationMode {
    /// The paper's method only (Tsai RAC + sequence searches + averages).
    Paper,
    /// Paper start, then the joint refinement.
    #[default]
    Refined,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibrationOptions {
    pub mode: CalibrationMode,
    pub paper: PaperOptions,
    /// Also estimate the radial `k3` (wide-angle lenses).
    pub estimate_k3: bool,
    /// Keep these intrinsics (an earlier calibration) and fit poses only.
    pub fixed_intrinsics: Option<Intrinsics>,
    /// Measured distances between camera stations; they tune `fx`.
    pub reference_distances: Vec<StationDistance>,
    /// Dot diameter on the board: enables the perspective/distortion bias
    /// correction of the dot centres (method.md §4).
    pub dot_diameter_mm: Option<f64>,
    pub outlier_sigmas: f64,
    pub max_bias_iterations: usize,
    /// Stop the bias iteration when no predicted offset moves more (px).
    pub bias_tolerance_px: f64,
}

impl Default for CalibrationOptions {
    fn default() -> Self {
        Self {
            mode: CalibrationMode::Refined,
            paper: PaperOptions::default(),
            estimate_k3: false,
            fixed_intrinsics: None,
            reference_distances: Vec::new(),
            dot_diameter_mm: None,
            outlier_sigmas: OUTLIER_SIGMAS,
            max_bias_iterations: 10,
            bias_tolerance_px: 1e-5,
        }
    }
}
