//! The report JSON of api.md (`GET .../parameter-sets/{version}/report`).
//! Built by the pipeline from the calibration results; rendered by the
//! sibling modules. Lengths in mm, angles in degrees, image data in pixels.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::schema::{AccuracySummarySchema, IntrinsicsSchema, IntrinsicsStdSchema};

/// Error statistics (method.md §7): the numerics' own types, so the
/// report carries exactly what the identification computed. `AccuracySummary`
/// is the 3-D statistics (flattened) plus the same per axis.
pub use robocal_calib::stats::{AccuracyStats as AccuracySummary, ErrorStats};

/// One camera view's fit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ViewReport {
    pub pose_id: String,
    /// The pose's label (see [`PoseReport::label`]).
    #[serde(default)]
    pub label: String,
    pub rms_px: f64,
    pub board_angle_deg: f64,
    /// E.g. "board-to-image angle under 20 degrees: focal length poorly conditioned".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub warning: Option<String>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct CameraReport {
    /// "refined" (default), "paper" (`refine_intrinsics: false`) or
    /// "fixed" (reused from `camera_calibration_id`).
    pub mode: String,
    /// The earlier calibration (`"{serial}/{version}"`) whose intrinsics
    /// were held fixed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_calibration_id: Option<String>,
    pub image_width: u32,
    pub image_height: u32,
    /// `fx, fy, cx, cy, k1, k2, p1, p2, k3`, flattened into the report.
    #[serde(flatten)]
    #[schema(value_type = IntrinsicsSchema)]
    pub intrinsics: Intrinsics,
    /// Standard deviations in the same units, when estimated.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<IntrinsicsStdSchema>)]
    pub std: Option<CameraStd>,
    pub reprojection_rms_px: f64,
    pub outliers_dropped: usize,
    pub views: Vec<ViewReport>,
}

impl CameraReport {
    /// The mode as printed: "refined", "paper" or "fixed from IRB-001/3".
    pub fn mode_label(&self) -> String {
        match &self.camera_calibration_id {
            Some(id) => format!("{} from {id}", self.mode),
            None => self.mode.clone(),
        }
    }
}

/// The calibrated intrinsics.
pub use robocal_calib::camera::Intrinsics;
/// The camera step's (or joint refinement's) intrinsics uncertainty.
pub use robocal_calib::camera::IntrinsicsStdDev as CameraStd;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct DetectionFailure {
    pub pose_id: String,
    /// The pose's label (see [`PoseReport::label`]).
    #[serde(default)]
    pub label: String,
    pub reason: String,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct DetectionReport {
    pub images: usize,
    pub images_detected: usize,
    pub dots_per_image: usize,
    pub failures: Vec<DetectionFailure>,
}

/// Per pose: position error at that pose before (nominal kinematics, only
/// base and hand–eye fitted) and after calibration, world frame, mm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct PoseReport {
    pub pose_id: String,
    /// What the pose is called: the uploaded image's file name, a JSON
    /// pose's `label`, or its number in upload order (`#12`). Empty in
    /// reports stored before labels existed.
    #[serde(default)]
    pub label: String,
    /// "cal" or "val".
    pub set: String,
    pub joints_deg: Vec<f64>,
    pub before_error_mm: [f64; 3],
    pub after_error_mm: [f64; 3],
    pub before_mm: f64,
    pub after_mm: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reprojection_rms_px: Option<f64>,
    /// Left out of the fit: the pose's joints contradict its image (a wrong
    /// joint file, a pose recorded before the robot settled). Its errors
    /// say how far the two disagree; it counts in no statistic.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub outlier: bool,
    /// Why the pose was left out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// A stage session's image: the camera pose its image alone measures
    /// with the calibrated camera (the target frame; paper eqs. 37–39).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_in_target: Option<crate::schema::PoseOut>,
}

/// The name a rendering shows for a pose: its label, or its id in reports
/// stored before labels existed.
pub fn pose_name<'a>(label: &'a str, pose_id: &'a str) -> &'a str {
    if label.is_empty() {
        pose_id
    } else {
        label
    }
}

impl PoseReport {
    pub fn name(&self) -> &str {
        pose_name(&self.label, &self.pose_id)
    }
}

impl ViewReport {
    pub fn name(&self) -> &str {
        pose_name(&self.label, &self.pose_id)
    }
}

impl DetectionFailure {
    pub fn name(&self) -> &str {
        pose_name(&self.label, &self.pose_id)
    }
}

pub use crate::domain::ParameterReport;

#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct IdentifiabilityReport {
    pub parameters: usize,
    pub rank: usize,
    pub condition_number: f64,
    pub observability_index: f64,
    pub fixed: Vec<String>,
    /// The parameters this campaign's poses determine poorly or not at
    /// all: those of `fixed` they did not determine (held at nominal; the
    /// rest of `fixed` is structurally redundant) and identified ones with
    /// little excitation (large σ). Vary the poses to identify them well.
    #[serde(default)]
    pub weak: Vec<String>,
}

/// A reprojection residual at an image point (observed minus predicted),
/// for the residual-field plot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ResidualSample {
    pub x_px: f64,
    pub y_px: f64,
    pub dx_px: f64,
    pub dy_px: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct Report {
    pub serial: String,
    pub version: i64,
    pub job_id: String,
    pub session_id: String,
    pub created_at: String,
    /// "camera" or "tracker".
    pub instrument: String,
    /// "pose" or "position".
    pub measurement: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detection: Option<DetectionReport>,
    /// Validation-pose statistics before and after calibration.
    #[schema(value_type = AccuracySummarySchema)]
    pub before: AccuracySummary,
    #[schema(value_type = AccuracySummarySchema)]
    pub after: AccuracySummary,
    pub per_pose: Vec<PoseReport>,
    pub parameters: Vec<ParameterReport>,
    pub identifiability: IdentifiabilityReport,
    pub residual_field: Vec<ResidualSample>,
    /// The hand–eye result of a session whose poses carry the controller's
    /// flange poses (no kinematics identified; `before` and `after` then
    /// hold the camera positions the flange poses predict against those
    /// the images measure).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hand_eye: Option<super::hand_eye::HandEyeReport>,
    /// Plain-language remarks for the cell engineer (warnings, what was
    /// held fixed and why, what remains unmodelled).
    pub notes: Vec<String>,
    /// Predicted uncertainty over a slice of the workspace (absent in
    /// reports stored before it was drawn, or when no point was reachable).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertainty_map: Option<UncertaintyMapReport>,
    /// The release gate's comparison (absent in reports stored before it,
    /// and in sets stored without a job).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gate: Option<GateReport>,
    /// A stage session's set: the measurement system's own
    /// accuracy per sequence (paper Table 1, Fig. 5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measurement_accuracy: Option<super::MeasurementAccuracyReport>,
    /// The selection of non-geometric terms (absent when it did not run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terms: Option<super::terms::TermsReport>,
    /// How much of the kinematics the campaign carried: the ladder of
    /// models judged on held-out arm configurations (absent when it did
    /// not run: too few configurations, terms selected, paper mode).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model_selection: Option<super::model_selection::ModelSelectionReport>,
    /// A multi-session set: each session's (region's)
    /// validation accuracy, before and after, on its own validation poses.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub regions: Vec<super::regions::RegionReport>,
    /// The set's current release status, filled in when the report is
    /// served (the stored document predates any decision on it).
    #[serde(flatten)]
    pub release: ReleaseView,
}

/// A parameter set's release status as a report shows it: what it is now,
/// who gave it, when and why (a person's approval overrides the gate's
/// comparison in [`GateReport`], which stays as the record of the job).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ReleaseView {
    /// `approved` (what `latest` may serve), `candidate` (waits for a
    /// person) or `rejected`; absent in a report read without its set.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub status: Option<crate::domain::ReleaseStatus>,
    /// Why it has its status (the gate's comparison or a person's reason).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub status_reason: Option<String>,
    /// Who gave it: `gate`, `token:{id} ({name})` or `anonymous`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub status_by: Option<String>,
    /// When (RFC 3339 UTC).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub status_at: Option<String>,
}

/// Predicted 1σ of the tool (camera or tracker tool point) position over a
/// horizontal slice of the workspace: flange positions on a grid in the
/// robot base frame at the campaign's median height and one flange
/// orientation, each solved by the calibrated inverse kinematics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct UncertaintyMapReport {
    /// Height of the slice: flange z in the base frame (mm).
    pub z_mm: f64,
    /// The flange's fixed-axis X-Y-Z orientation over the slice (deg).
    pub rotation_deg: [f64; 3],
    /// Grid spacing (mm).
    pub step_mm: f64,
    /// Reachable grid points with their predicted σ.
    pub cells: Vec<UncertaintyCell>,
    /// The calibration poses' flange positions (x, y mm, base frame).
    pub poses_xy_mm: Vec<[f64; 2]>,
}

/// One point of [`UncertaintyMapReport`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct UncertaintyCell {
    pub x_mm: f64,
    pub y_mm: f64,
    /// `sqrt(trace)` of the tool position's 3x3 covariance in the target
    /// (or tracker) frame: the RMS length of its 3-D error (mm).
    pub position_std_mm: f64,
}

/// The release gate's comparison in a report: what the set was
/// compared with on the same validation poses at the end of the job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct GateReport {
    /// The status the gate gave: `approved` or `candidate`.
    pub status: String,
    /// Why, in a sentence.
    pub reason: String,
    /// What it was compared with: `nominal`, or the approved set
    /// `"{serial}/{version}"` (its kinematics with the base and hand–eye
    /// frames re-fitted on this session's calibration poses, as the
    /// nominal "before" is).
    pub compared_with: String,
    /// Mean 3-D validation error of what it was compared with (mm); absent
    /// when there was nothing to compare with (a hand–eye calibration).
    pub compared_mean_mm: Option<f64>,
    /// Mean 3-D validation error of this set (mm); absent when not finite.
    pub mean_mm: Option<f64>,
    /// This set predicts the same validation poses worse than before.
    pub worse: bool,
    /// How `mean_mm` and `compared_mean_mm` were both figured, when an
    /// approved set was compared (one rule for the two sets).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub basis: Option<String>,
    /// The headline mean 3-D validation error the compared set's own
    /// report gives (mm), on its own session's poses and by its own
    /// headline rule: it differs from `compared_mean_mm` when the poses or
    /// the rule differ (`basis` says how the gate figured it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compared_own_mean_mm: Option<f64>,
    /// The session the compared set's own report measured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compared_own_session_id: Option<String>,
}
