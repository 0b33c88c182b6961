//! The session-level cause of a failed job. When most images fail
//! detection for one reason (a session whose target is 7x9 photographed
//! against a 9x9 board: every image fails), the numerical stage that then
//! fails names a symptom on one pose ("0 dots, at least 6 are needed");
//! the job's error leads with the cause, stated for the session.

use std::collections::BTreeMap;

use super::measure::Measured;
use super::{PipelineError, Stage};
use crate::domain::ImageDetection;
use crate::domain::Target;

/// What the session's images have in common when most of them (more than
/// half) failed detection for one reason; `None` otherwise.
pub fn of(measured: &Measured, target: &Target) -> Option<String> {
    let images: Vec<&ImageDetection> = measured.detections.iter().flatten().collect();
    let total = images.len();
    let mut by_kind: BTreeMap<&str, (usize, &ImageDetection)> = BTreeMap::new();
    for d in images.iter().filter(|d| d.error.is_some()) {
        let kind = d.error_kind.as_deref().unwrap_or("unknown");
        by_kind.entry(kind).or_insert((0, d)).0 += 1;
    }
    let (count, example) = by_kind.into_values().max_by_key(|(count, _)| *count)?;
    if count * 2 <= total {
        return None;
    }
    let reason = example.error.as_deref().unwrap_or("no dots detected");
    let board = target.board_name();
    Some(if example.target_missing {
        let lead = if count == total {
            "no image shows"
        } else {
            "most images do not show"
        };
        format!(
            "{lead} the session's {board} target: {count} of {total} images failed detection \
             (e.g. \"{reason}\"); check the session's target ({}) against the board \
             in the images",
            target.fields_hint()
        )
    } else {
        format!("{count} of {total} images failed detection for one reason (e.g. \"{reason}\")")
    })
}

/// Leads a numerical stage's error with the session-level `cause`.
pub fn name_in(error: PipelineError, cause: Option<String>) -> PipelineError {
    match (error, cause) {
        (PipelineError::Numerical { stage, message }, Some(cause)) => PipelineError::Numerical {
            stage: Stage::Detect.as_str(),
            message: format!("{cause}; then {stage}: {message}"),
        },
        (error, _) => error,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn target() -> Target {
        let doc = serde_json::from_value(serde_json::json!({
            "rows": 7, "cols": 9, "pitch_mm": 20.0, "dot_diameter_mm": 8.0,
            "origin_marker_diameter_mm": 12.0
        }))
        .unwrap();
        Target::from_doc(&doc).unwrap()
    }

    fn measured(failed: usize, ok: usize, kind: &str) -> Measured {
        let fail = ImageDetection::failed("no board found: x".into(), kind, kind == "no_board");
        let good = ImageDetection {
            points: vec![],
            error: None,
            error_kind: None,
            target_missing: false,
        };
        Measured {
            detections: (0..failed)
                .map(|_| Some(fail.clone()))
                .chain((0..ok).map(|_| Some(good.clone())))
                .chain([None])
                .collect(),
            ..Measured::default()
        }
    }

    #[test]
    fn most_images_failing_for_one_reason_is_a_session_cause() {
        let all = of(&measured(60, 0, "no_board"), &target()).unwrap();
        assert!(
            all.starts_with("no image shows the session's 7x9 target: 60 of 60 images"),
            "{all}"
        );
        let most = of(&measured(40, 20, "no_board"), &target()).unwrap();
        assert!(most.starts_with("most images do not show"), "{most}");
        let other = of(&measured(4, 1, "dots_too_blurred"), &target()).unwrap();
        assert!(other.starts_with("4 of 5 images failed detection for one reason"));
        assert_eq!(of(&measured(30, 30, "no_board"), &target()), None);
        assert_eq!(of(&measured(0, 10, "no_board"), &target()), None);
    }

    #[test]
    fn the_cause_leads_a_numerical_error() {
        let e = PipelineError::Numerical {
            stage: "calibrate_camera",
            message: "pose p1: 0 dots, at least 6 are needed".into(),
        };
        let named = name_in(e, Some("no image shows the session's 7x9 target".into()));
        assert_eq!(
            named.to_string(),
            "detect: no image shows the session's 7x9 target; then calibrate_camera: pose p1: 0 dots, at least 6 are needed"
        );
    }
}
