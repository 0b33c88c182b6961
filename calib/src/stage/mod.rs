//! The measurement system's own accuracy on a linear stage (paper section 4,
//! Table 1, Fig. 5; issue 18): the camera moves by pure translations whose
//! values the stage reads exactly, so all images of a sequence share one
//! camera orientation and their camera positions are the sequence's origin
//! plus the stage's translation. The intrinsics are fitted with those
//! constraints in one bundle (method.md §4: the paper tuned `fx` by hand
//! against its CMM instead), then every image's camera position is measured
//! on its own with them and assessed the paper's way.

pub mod assessment;
pub mod bundle;
pub mod calibrate;
pub mod error;
pub mod layout;
pub mod noise;
pub mod offset;

use nalgebra::Vector3;

use crate::camera::observations::ViewObservations;

pub use assessment::{SequenceAccuracy, TravelledDistanceError};
pub use calibrate::{calibrate_stage, StageCalibration, StageViewResult};
pub use error::StageError;

/// One image of a stage campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct StageView {
    /// The sequence (one board placement) the image belongs to.
    pub sequence: u32,
    /// The stage's reading when the image was taken (mm, stage axes).
    pub stage_position_mm: Vector3<f64>,
    pub observations: ViewObservations,
}
