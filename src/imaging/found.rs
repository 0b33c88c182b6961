//! What the dot detector finds on one image, in the form stored on the pose
//! row (`image_detection`) and reused by every job: the raw ellipse centres
//! (the camera stage corrects their perspective bias from the calibrated
//! model, method.md §4 **beyond**), or why no board was found.

use robocal_calib::vision::{self, DetectOptions, GrayImage, TargetSpec};
use serde::{Deserialize, Serialize};

use crate::schema::session::{ImagePointDoc, TargetDoc};

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

pub fn target_spec(doc: &TargetDoc) -> TargetSpec {
    TargetSpec {
        rows: doc.rows as usize,
        cols: doc.cols as usize,
        pitch_mm: doc.pitch_mm,
        dot_diameter_mm: doc.dot_diameter_mm,
        origin_marker_diameter_mm: Some(doc.origin_marker_diameter_mm),
    }
}

/// Runs the detector on a decoded image. Its own perspective-bias estimate
/// is off: the camera stage corrects the raw centres from the calibrated
/// model, which is more exact, and correcting twice would bias.
pub fn detect(image: &GrayImage, target: &TargetDoc) -> ImageDetection {
    let options = DetectOptions {
        correct_perspective_bias: false,
        ..DetectOptions::default()
    };
    match vision::detect_with(image, &target_spec(target), &options) {
        Ok(found) => ImageDetection {
            points: found
                .dots
                .iter()
                .map(|d| ImagePointDoc {
                    row: d.row as u32,
                    col: d.col as u32,
                    x: d.ellipse.cx,
                    y: d.ellipse.cy,
                })
                .collect(),
            error: None,
            error_kind: None,
            target_missing: false,
        },
        Err(e) => ImageDetection::failed(e.to_string(), e.kind(), e.is_target_missing()),
    }
}
