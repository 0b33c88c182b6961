//! Stage "detect": every camera pose's image points, from its image (the
//! dot detector, method.md §1) or as uploaded (`image_points`).
//!
//! An image's detector outcome is normally stored at upload and reused
//! here, the image never read. Images without one (uploaded before uploads
//! detected) are read, decoded and detected on scoped threads, one per
//! core, each dropped before the next is read: a job holds no images, so
//! its memory does not grow with the campaign. Every decode holds a slot
//! of the process's decode gate. The raw ellipse centres are kept: the
//! camera stage corrects them from the calibrated model (method.md §4
//! **beyond**).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

use super::{ImageSource, PipelineError, PoseImage, PoseInput};
use crate::domain::{ImageDetection, Target};
use crate::imaging;
use crate::report::{DetectionFailure, DetectionReport};
use crate::schema::pose_body::ImagePointDoc;

/// A pose's outcome: `None` for uploaded image points, else the detector's
/// and whether it ran in this job.
type Outcome = Option<(ImageDetection, bool)>;

/// How often the detection stage reports progress.
const PROGRESS_INTERVAL: std::time::Duration = std::time::Duration::from_millis(50);

/// One image point: grid position and observed centre (px).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridPoint {
    pub row: u32,
    pub col: u32,
    pub x: f64,
    pub y: f64,
}

/// The points of every pose (`None` where detection failed) and why the
/// failures failed.
#[derive(Debug, Clone, Default)]
pub struct Measured {
    pub points: Vec<Option<Vec<GridPoint>>>,
    pub failures: Vec<DetectionFailure>,
    /// Whether the target's ordering is unique (it has an origin marker).
    pub ordering_unique: bool,
    /// Per pose, the detector's outcome on its image (`None` for poses of
    /// uploaded image points).
    pub detections: Vec<Option<ImageDetection>>,
    /// Per pose, whether this job ran the detector (no stored outcome):
    /// the outcome is then stored on the pose for later jobs.
    pub detected_now: Vec<bool>,
}

impl Measured {
    /// The report's detection section: images, how many were detected,
    /// the most dots on one, and the failures.
    pub fn report(&self) -> DetectionReport {
        DetectionReport {
            images: self.points.len(),
            images_detected: self.points.iter().filter(|p| p.is_some()).count(),
            dots_per_image: self
                .points
                .iter()
                .flatten()
                .map(Vec::len)
                .max()
                .unwrap_or(0),
            failures: self.failures.clone(),
        }
    }
}

/// The detector's outcome on one pose's image: the stored one, or (for
/// images never detected) read, decoded under the gate, detected and
/// dropped here. The second value says whether it was detected now.
fn detect_pose(image: &PoseImage, target: &Target, images: &ImageSource) -> (ImageDetection, bool) {
    if let Some(stored) = &image.detection {
        return (stored.clone(), false);
    }
    let bytes = match images.read.as_ref()(&image.key) {
        Ok(bytes) => bytes,
        // Not the image's fault (a store error): not stored on the pose.
        Err(e) => return (ImageDetection::failed(e, "read", false), false),
    };
    let found = Ok(bytes).and_then(|bytes| {
        let permit = images.gate.acquire(imaging::JOBS_KEY);
        let gray = imaging::decode_checked(&bytes, Some((image.width, image.height)), &permit)
            .map_err(|e| ImageDetection::failed(e, "decode", false))?;
        drop(bytes);
        Ok(imaging::detect(&gray, target))
    });
    (found.unwrap_or_else(|failed| failed), true)
}

fn grid_points(points: &[ImagePointDoc]) -> Vec<GridPoint> {
    points
        .iter()
        .map(|p| GridPoint {
            row: p.row,
            col: p.col,
            x: p.x,
            y: p.y,
        })
        .collect()
}

/// Runs the detector over every pose, in parallel.
pub fn measure(
    poses: &[PoseInput],
    target: &Target,
    images: &ImageSource,
    progress: &dyn Fn(&str, f64),
    cancel: &AtomicBool,
) -> Result<Measured, PipelineError> {
    let results: Vec<Mutex<Option<Outcome>>> = poses.iter().map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    std::thread::scope(|scope| {
        for _ in 0..threads.min(poses.len().max(1)) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= poses.len() || cancel.load(Ordering::Relaxed) {
                    break;
                }
                let pose = &poses[i];
                let outcome = pose
                    .image
                    .as_ref()
                    .map(|image| detect_pose(image, target, images));
                *results[i].lock().expect("no panics while held") = Some(outcome);
                done.fetch_add(1, Ordering::Relaxed);
            });
        }
        // Progress is reported from this thread: the callback need not be Sync.
        let mut reported = usize::MAX;
        loop {
            let finished = done.load(Ordering::Relaxed);
            if finished != reported {
                reported = finished;
                progress(
                    &format!("image {finished} of {}", poses.len()),
                    finished as f64 / poses.len().max(1) as f64,
                );
            }
            if finished >= poses.len() || cancel.load(Ordering::Relaxed) {
                break;
            }
            std::thread::sleep(PROGRESS_INTERVAL);
        }
    });
    if cancel.load(Ordering::Relaxed) {
        return Err(PipelineError::Cancelled);
    }
    let mut measured = Measured {
        ordering_unique: target.ordering_unique(),
        ..Measured::default()
    };
    for (pose, slot) in poses.iter().zip(results) {
        let outcome = slot
            .into_inner()
            .expect("no panics while held")
            .ok_or(PipelineError::Cancelled)?;
        let Some((found, now)) = outcome else {
            measured.points.push(Some(grid_points(&pose.image_points)));
            measured.detections.push(None);
            measured.detected_now.push(false);
            continue;
        };
        match &found.error {
            None => measured.points.push(Some(grid_points(&found.points))),
            Some(reason) => {
                measured.failures.push(DetectionFailure {
                    pose_id: pose.id.clone(),
                    label: pose.label.clone(),
                    reason: reason.clone(),
                });
                measured.points.push(None);
            }
        }
        measured.detections.push(Some(found));
        measured.detected_now.push(now);
    }
    Ok(measured)
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    use std::sync::Arc;

    use super::*;
    use crate::imaging::DecodeGate;
    use crate::schema::session::PoseSet;

    fn target() -> Target {
        let doc = serde_json::from_value(serde_json::json!({
            "rows": 7, "cols": 9, "pitch_mm": 20.0, "dot_diameter_mm": 8.0,
            "origin_marker_diameter_mm": 12.0
        }))
        .unwrap();
        Target::from_doc(&doc).unwrap()
    }

    fn pose(id: &str, detection: Option<ImageDetection>) -> PoseInput {
        PoseInput {
            id: id.into(),
            label: id.into(),
            joints_deg: crate::domain::JointsDeg::stored(vec![0.0; 6]),
            flange_pose: None,
            set: PoseSet::Cal,
            image: Some(PoseImage {
                key: id.into(),
                width: 64,
                height: 48,
                detection,
            }),
            image_points: vec![],
            measured_position_mm: None,
            stage_reading: None,
            measured_pose: None,
            group: None,
        }
    }

    /// Stored detections are reused (the image is never read); an image
    /// without one is read once, its outcome marked for storing.
    #[test]
    fn stored_detections_are_reused_and_others_read_once() {
        let stored = ImageDetection {
            points: vec![ImagePointDoc {
                row: 1,
                col: 2,
                x: 3.5,
                y: 4.5,
            }],
            error: None,
            error_kind: None,
            target_missing: false,
        };
        let reads = Arc::new(AtomicUsize::new(0));
        let counted = reads.clone();
        let images = ImageSource {
            read: Arc::new(move |key: &str| {
                counted.fetch_add(1, Ordering::SeqCst);
                assert_eq!(key, "fresh", "a stored detection's image was read");
                Ok(b"not an image".to_vec())
            }),
            gate: Arc::new(DecodeGate::new(1)),
        };
        let poses = [pose("kept", Some(stored.clone())), pose("fresh", None)];
        let m = measure(
            &poses,
            &target(),
            &images,
            &|_, _| {},
            &AtomicBool::new(false),
        )
        .unwrap();
        assert_eq!(reads.load(Ordering::SeqCst), 1);
        assert_eq!(m.detected_now, [false, true]);
        assert_eq!(m.detections[0].as_ref(), Some(&stored));
        assert_eq!(
            m.points[0].as_deref(),
            Some(
                &[GridPoint {
                    row: 1,
                    col: 2,
                    x: 3.5,
                    y: 4.5
                }][..]
            )
        );
        assert_eq!(m.points[1], None);
        assert_eq!(m.failures.len(), 1);
        assert_eq!(
            m.detections[1].as_ref().unwrap().error_kind.as_deref(),
            Some("decode")
        );
    }
}
