//! A pose's documents: the JSON body of `POST /v1/sessions/{id}/poses`
//! (image points, or a tracker's measurement with a 6-DoF probe's
//! `measured_pose`), its image points, and a dataset archive's entry;
//! each checked against its session.

use serde::Deserialize;
use utoipa::ToSchema;

use super::flange_pose::FlangePoseDoc;
use super::session::{CameraDoc, Instrument, MAX_POINTS_PER_POSE};
use super::{Checker, FieldError, PoseDoc, MAX_LENGTH_MM};
use crate::domain::{check_robot_pose, PoseGroup, PoseSet, RobotPose};

/// How far a pose's `measured_pose` translation may lie from its
/// `measured_position_mm` (mm): both are the one tool point, so they
/// differ by rounding only.
pub const MEASURED_POSE_AGREEMENT_MM: f64 = 1e-3;

pub use crate::domain::ImagePointDoc;

/// `POST /v1/sessions/{id}/poses` JSON body.
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PoseJsonBody {
    /// The robot's joint angles, degrees (one per joint). A camera pose may
    /// carry `flange_pose` instead; a session takes one kind only.
    #[serde(default)]
    pub joints_deg: Option<Vec<f64>>,
    /// The controller's flange pose in the base frame, instead of
    /// `joints_deg` (camera sessions: hand–eye and board calibration
    /// without kinematic identification).
    #[serde(default)]
    pub flange_pose: Option<FlangePoseDoc>,
    #[serde(default)]
    pub set: PoseSet,
    #[serde(default)]
    pub image_points: Option<Vec<ImagePointDoc>>,
    #[serde(default)]
    #[schema(min_items = 3, max_items = 3)]
    pub measured_position_mm: Option<[f64; 3]>,
    #[serde(default)]
    pub measured_pose: Option<PoseDoc>,
    /// What the pose is called in reports (e.g. the photo's file name); 1
    /// to 200 characters. Absent: the pose is numbered (`#12`).
    #[serde(default)]
    #[schema(max_length = 200)]
    pub label: Option<String>,
    /// The arm configuration the pose was taken in, e.g. `"shoulder_a"`:
    /// poses of one group are held out together when the job judges which
    /// model predicts configurations it was not fitted to. 1 to 32 of
    /// `A-Z a-z 0-9 _ -`. Absent: grouped by joints 1–3 (within 3°).
    #[serde(default)]
    #[schema(pattern = "^[A-Za-z0-9_-]{1,32}$")]
    pub group: Option<String>,
}

impl PoseJsonBody {
    /// Checks the body against the session; where it says the robot was
    /// when it passes.
    pub fn check(
        &self,
        instrument: Instrument,
        camera: Option<&CameraDoc>,
        joint_count: usize,
    ) -> Result<RobotPose, Vec<FieldError>> {
        let mut c = Checker::default();
        let (_, robot_pose) = check_robot_pose(
            &mut c,
            "",
            self.joints_deg.as_deref(),
            self.flange_pose.as_ref(),
            joint_count,
        );
        if instrument == Instrument::Tracker && self.flange_pose.is_some() {
            c.fail("flange_pose", "a tracker session takes joints_deg");
        }
        if let Some(Err(rule)) = self.label.as_deref().map(crate::domain::check_label) {
            c.fail("label", rule);
        }
        check_group(&mut c, "group", self.group.as_deref());
        match instrument {
            Instrument::Stage => c.fail(
                "image",
                "a stage session takes multipart poses: image, stage_position_mm, sequence",
            ),
            Instrument::Camera => {
                if self.measured_position_mm.is_some() || self.measured_pose.is_some() {
                    c.fail(
                        "measured_position_mm",
                        "a camera session takes image_points",
                    );
                }
                match &self.image_points {
                    None => c.fail("image_points", "required (or upload an image as multipart)"),
                    Some(points) => check_points(&mut c, points, camera),
                }
            }
            Instrument::Tracker => {
                if self.image_points.is_some() {
                    c.fail(
                        "image_points",
                        "a tracker session takes measured_position_mm",
                    );
                }
                match &self.measured_position_mm {
                    None => c.fail("measured_position_mm", "required for a tracker session"),
                    Some(p) => {
                        for (i, v) in p.iter().enumerate() {
                            c.bounded(
                                format!("measured_position_mm[{i}]"),
                                *v,
                                MAX_LENGTH_MM,
                                "mm",
                            );
                        }
                    }
                }
                if let Some(p) = &self.measured_pose {
                    p.check(&mut c, "measured_pose");
                    let apart = self.measured_position_mm.map(|m| {
                        m.iter()
                            .zip(&p.translation_mm)
                            .map(|(a, b)| (a - b).powi(2))
                            .sum::<f64>()
                            .sqrt()
                    });
                    if apart.is_some_and(|d| d.is_nan() || d > MEASURED_POSE_AGREEMENT_MM) {
                        c.fail(
                            "measured_pose.translation_mm",
                            format!(
                                "must equal measured_position_mm (within {MEASURED_POSE_AGREEMENT_MM} mm): both are the tool point"
                            ),
                        );
                    }
                }
            }
        }
        c.finish()?;
        Ok(robot_pose.expect("checked above"))
    }
}

/// Checks an optional group name, failing `field` ([`PoseGroup::parse`]);
/// the typed group when there is one and it passes.
pub fn check_group(c: &mut Checker, field: &str, group: Option<&str>) -> Option<PoseGroup> {
    match group.map(PoseGroup::parse)? {
        Ok(g) => Some(g),
        Err(rule) => {
            c.fail(field, rule);
            None
        }
    }
}

fn check_points(c: &mut Checker, points: &[ImagePointDoc], camera: Option<&CameraDoc>) {
    if points.is_empty() || points.len() > MAX_POINTS_PER_POSE {
        c.fail(
            "image_points",
            format!("must hold 1 to {MAX_POINTS_PER_POSE} points"),
        );
    }
    let (w, h) = camera
        .map(|k| (k.width as f64, k.height as f64))
        .unwrap_or((f64::MAX, f64::MAX));
    for (i, p) in points.iter().enumerate() {
        if !p.x.is_finite() || p.x < 0.0 || p.x > w {
            c.fail(format!("image_points[{i}].x"), "must lie inside the image");
        }
        if !p.y.is_finite() || p.y < 0.0 || p.y > h {
            c.fail(format!("image_points[{i}].y"), "must lie inside the image");
        }
        if c.errors.len() > 20 {
            return;
        }
    }
}

/// One entry of a dataset archive's `poses.json`.
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct DatasetPoseDoc {
    /// The joint angles, or (instead) the controller's `flange_pose`.
    #[serde(default)]
    pub joints_deg: Option<Vec<f64>>,
    #[serde(default)]
    pub flange_pose: Option<FlangePoseDoc>,
    pub image: String,
    #[serde(default)]
    pub set: PoseSet,
    /// The arm configuration the photo was taken in (as a pose's `group`).
    #[serde(default)]
    #[schema(pattern = "^[A-Za-z0-9_-]{1,32}$")]
    pub group: Option<String>,
}
