//! What the dot detector found on one image, as the pose row keeps it
//! (`image_detection`) and every job reuses it: the raw ellipse centres
//! (the camera stage corrects their perspective bias from the calibrated
//! model, method.md §4 **beyond**), or why no board was found. The
//! detector itself is `imaging::detect`.

use serde::{Deserialize, Serialize};

use super::ImagePointDoc;

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
}
