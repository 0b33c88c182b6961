//! A calibration that leaves out the views it cannot start from. One partial
//! or nearly fronto-parallel image (no initial pose from its homography,
//! method.md §3) should not fail a whole campaign: the view is dropped, named
//! with the reason, and the calibration runs again on the rest — as long as
//! most views remain.

use super::calibrate::{calibrate, CalibrationOptions};
use super::error::CameraError;
use super::observations::ViewObservations;
use super::CameraCalibration;

/// At most one view in this many may be left out as degenerate.
pub const MAX_LEFT_OUT_FRACTION_DIV: usize = 4;

/// A view the calibration could not start from.
#[derive(Debug, Clone, PartialEq)]
pub struct LeftOutView {
    /// Index into the views given to [`calibrate_leaving_out`].
    pub view: usize,
    pub reason: String,
}

/// The calibration of the views kept.
#[derive(Debug, Clone)]
pub struct CalibrationLeavingOut {
    pub calibration: CameraCalibration,
    /// Index into the input of each of `calibration.views`, in order.
    pub kept: Vec<usize>,
    pub left_out: Vec<LeftOutView>,
}

/// The calibration failed on the views still kept.
#[derive(Debug, Clone)]
pub struct CalibrationFailed {
    /// Its view indices are into `kept`.
    pub error: CameraError,
    /// Index into the input of each view the failed calibration saw.
    pub kept: Vec<usize>,
}

/// [`calibrate`], leaving out each view it reports as degenerate (at most
/// one in [`MAX_LEFT_OUT_FRACTION_DIV`]); any other error, or one
/// degenerate view too many, fails.
pub fn calibrate_leaving_out(
    views: &[ViewObservations],
    options: &CalibrationOptions,
) -> Result<CalibrationLeavingOut, CalibrationFailed> {
    let max_left_out = views.len() / MAX_LEFT_OUT_FRACTION_DIV;
    let mut kept: Vec<usize> = (0..views.len()).collect();
    let mut left_out = Vec::new();
    loop {
        let subset: Vec<ViewObservations> = kept.iter().map(|&i| views[i].clone()).collect();
        match calibrate(&subset, options) {
            Ok(calibration) => {
                return Ok(CalibrationLeavingOut {
                    calibration,
                    kept,
                    left_out,
                })
            }
            Err(CameraError::DegenerateView { view, reason })
                if left_out.len() < max_left_out && view < kept.len() =>
            {
                left_out.push(LeftOutView {
                    view: kept.remove(view),
                    reason,
                });
            }
            Err(error) => return Err(CalibrationFailed { error, kept }),
        }
    }
}

#[cfg(test)]
#[path = "leave_out_tests.rs"]
mod tests;
