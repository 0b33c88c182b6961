//! What the dot detector finds on one image, in the form stored on the pose
//! row (`image_detection`) and reused by every job: the raw ellipse centres
//! (the camera stage corrects their perspective bias from the calibrated
//! model, method.md §4 **beyond**), or why no board was found.

use robocal_calib::vision::GrayImage;
use serde::{Deserialize, Serialize};

use crate::domain::Target;
use crate::schema::session::ImagePointDoc;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImageDetection {
    /// Dot centres as the detector found them (raw, px); empty on failure.
    #[serde(default)]
    pub points: Vec<ImagePointDoc>,
    /// Why no board was found.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// A stable name of `error`'s cause (`no_board`, `grid_mismatch`, ...),
    /// to tell when many images fail for one reason.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error_kind: Option<String>,
    /// Whether `error` means the image does not show the target as
    /// described (another board, or none).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub target_missing: bool,
}

impl ImageDetection {
    pub fn failed(message: String, kind: &str, target_missing: bool) -> ImageDetection {
        ImageDetection {
            points: Vec::new(),
            error: Some(message),
            error_kind: Some(kind.to_string()),
            target_missing,
        }
    }

    pub fn to_value(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or_default()
    }
}

/// Runs the board's detector on a decoded image. For dots it returns the
/// raw ellipse centres: the camera stage corrects their perspective bias
/// from the calibrated model, which is more exact, and correcting twice
/// would bias.
pub fn detect(image: &GrayImage, target: &Target) -> ImageDetection {
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
