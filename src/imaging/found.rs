//! The dot detector run on one decoded image at upload or by a job; what it
//! found is a [`crate::domain::ImageDetection`].

use robocal_calib::vision::DecodedGrey;

use crate::domain::{ImageDetection, Target};
use crate::schema::pose_body::ImagePointDoc;

/// Runs the board's detector on a decoded image. For dots it returns the
/// raw ellipse centres: the camera stage corrects their perspective bias
/// from the calibrated model, which is more exact, and correcting twice
/// would bias.
pub fn detect(image: &DecodedGrey, target: &Target) -> ImageDetection {
    match target.detect(image) {
        Ok(found) => ImageDetection {
            points: found
                .iter()
                .map(|p| ImagePointDoc {
                    row: p.row,
                    col: p.col,
                    x: p.x,
                    y: p.y,
                })
                .collect(),
            error: None,
            error_kind: None,
            target_missing: false,
        },
        Err(e) => ImageDetection::failed(e.to_string(), e.kind(), e.is_target_missing()),
    }
}
