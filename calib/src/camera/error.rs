//! Errors of the camera stage: degenerate input is refused with a reason,
//! never answered wrongly (issue 4).

use crate::solver::SolverError;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("{usable} usable images, at least {required} are needed")]
    TooFewImages { usable: usize, required: usize },
    #[error("view {view}: {count} dots, at least {required} are needed")]
    TooFewPoints {
        view: usize,
        count: usize,
        required: usize,
    },
    #[error("view {view}: the target points are collinear")]
    CollinearPoints { view: usize },
    #[error("view {view}: the target points do not lie in the board plane z = 0")]
    NotPlanar { view: usize },
    #[error("view {view} is {width}x{height} px but view 0 is {expected_width}x{expected_height} px: all images must have one size")]
    InconsistentImageSize {
        view: usize,
        width: u32,
        height: u32,
        expected_width: u32,
        expected_height: u32,
    },
    #[error("view {view}: image size {width}x{height} is empty")]
    EmptyImage {
        view: usize,
        width: u32,
        height: u32,
    },
    #[error("view {view}: a coordinate is not finite")]
    NonFinite { view: usize },
    #[error("the views are too close to fronto-parallel (largest board-to-image angle found {max_angle_deg:.1} degrees): focal length and distance cannot be separated; tilt the board by 20-45 degrees")]
    AllFrontoParallel { max_angle_deg: f64 },
    #[error("view {view}: {reason}")]
    DegenerateView { view: usize, reason: String },
    #[error("option `{field}`: {reason}")]
    InvalidOption { field: &'static str, reason: String },
    #[error("least squares failed: {0}")]
    Solver(#[from] SolverError),
}
