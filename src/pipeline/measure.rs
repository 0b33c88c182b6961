//! Stage "detect": every camera pose's image points, from its image (the
//! dot detector, method.md §1) or as uploaded (`image_points`).
//!
//! Images are decoded and detected on scoped threads, one per core, so a
//! lone job uses the machine; the worker pool bounds how many jobs run.
//! The detector's own perspective-bias estimate is switched off: the camera
//! stage corrects the raw ellipse centres from the calibrated model, which
//! is more exact (method.md §4 **beyond**), and correcting twice would bias.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

use robocal_calib::vision::{self, DecodeLimits, DetectOptions, TargetSpec};

use super::{PipelineError, PoseInput, Stage};
use crate::report::DetectionFailure;
use crate::schema::session::TargetDoc;

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

/// One image's dots, or why there are none.
type DetectOutcome = Result<Vec<GridPoint>, String>;

fn detect_one(bytes: &[u8], target: &TargetSpec) -> DetectOutcome {
    let image = vision::decode_image(bytes, &DecodeLimits::default()).map_err(|e| e.to_string())?;
    let options = DetectOptions {
        correct_perspective_bias: false,
        ..DetectOptions::default()
    };
    let detection = vision::detect_with(&image, target, &options).map_err(|e| e.to_string())?;
    Ok(detection
        .dots
        .iter()
        .map(|d| GridPoint {
            row: d.row as u32,
            col: d.col as u32,
            x: d.ellipse.cx,
            y: d.ellipse.cy,
        })
        .collect())
}

fn uploaded_points(pose: &PoseInput) -> Vec<GridPoint> {
    pose.image_points
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
    target: &TargetDoc,
    progress: &dyn Fn(&str, f64),
    cancel: &AtomicBool,
) -> Result<Measured, PipelineError> {
    let spec = target_spec(target);
    spec.validate().map_err(|e| PipelineError::Numerical {
        stage: Stage::Detect.as_str(),
        message: e.to_string(),
    })?;
    let results: Vec<Mutex<Option<DetectOutcome>>> =
        poses.iter().map(|_| Mutex::new(None)).collect();
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
                let outcome = match &pose.image {
                    Some(bytes) => detect_one(bytes, &spec),
                    None => Ok(uploaded_points(pose)),
                };
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
        ordering_unique: spec.origin_marker_diameter_mm.is_some(),
        ..Measured::default()
    };
    for (pose, slot) in poses.iter().zip(results) {
        match slot.into_inner().expect("no panics while held") {
            Some(Ok(points)) => measured.points.push(Some(points)),
            Some(Err(reason)) => {
                measured.failures.push(DetectionFailure {
                    pose_id: pose.id.clone(),
                    label: pose.label.clone(),
                    reason,
                });
                measured.points.push(None);
            }
            None => return Err(PipelineError::Cancelled),
        }
    }
    Ok(measured)
}
