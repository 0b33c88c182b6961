//! What a job is given: the robot, the session, its poses (images by
//! reference), the options and the intrinsics to hold fixed.

use std::sync::Arc;
use std::time::Duration;

use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::prior::KinematicPrior;
use robocal_calib::kinematics::RobotModel;

use crate::domain::{FlangePose, ImageDetection, JobKind, JointsDeg, ParameterSet, StageReading};
use crate::imaging::DecodeGate;
use crate::report::regions::LocalModel;
use crate::schema::job::CalibrationOptions;
use crate::schema::pose_body::ImagePointDoc;
use crate::schema::robot::KinematicsDoc;
use crate::schema::session::{PoseSet, SessionBody};
use crate::schema::PoseDoc;

/// Everything a job needs, loaded from the store by the worker.
#[derive(Debug, Clone)]
pub struct Input {
    pub serial: String,
    pub session_id: String,
    /// The robot's nominal model, as the numerics take it (radians).
    pub robot: RobotModel,
    /// The prior on its kinematic deviations from nominal (the robot
    /// document's `prior`, else manufacturing tolerances).
    pub prior: KinematicPrior,
    /// The same joint table as stored and served (degrees, conventions explicit).
    pub kinematics: KinematicsDoc,
    pub session: SessionBody,
    pub poses: Vec<PoseInput>,
    pub options: CalibrationOptions,
    /// The session's `camera_calibration_id`, resolved: intrinsics the
    /// camera stage holds fixed instead of estimating them.
    pub fixed_camera: Option<FixedCamera>,
    /// Reads the images of poses without a stored detection.
    pub images: ImageSource,
    /// Test hook (`ROBOCAL_TEST_STAGE_DELAY_MS`): sleep per pose in validation.
    pub test_stage_delay: Duration,
    /// Test hook (`ROBOCAL_TEST_VALIDATE_ONLY`): stop after validation.
    pub validate_only: bool,
    /// The robot's newest approved calibrated set when the job was loaded:
    /// the release gate compares with it, partial scopes and re-checks
    /// hold it.
    pub approved: Option<ApprovedSet>,
    /// What the job was queued as: a calibration or a quick re-check
    /// (the pipeline's plan, [`super::jobs::Plan::of`], follows from it).
    pub kind: JobKind,
    /// The further sessions of a calibration over several board placements
    ///; empty for a one-session job. This input's own session
    /// is the first placement.
    pub regions: Vec<RegionInput>,
    /// Per session of a multi-session job: the newest local (one-session)
    /// set of that session when the job was loaded, for the report's side
    /// by side of local and global models.
    pub local_models: Vec<(String, LocalModel)>,
}

/// A further session of a multi-session job: its own board placement,
/// the same robot, camera and options.
#[derive(Debug, Clone)]
pub struct RegionInput {
    pub session_id: String,
    pub session: SessionBody,
    pub poses: Vec<PoseInput>,
}

/// An approved parameter set, typed, with its name.
#[derive(Debug, Clone)]
pub struct ApprovedSet {
    /// `"{serial}/{version}"`.
    pub id: String,
    /// The set's version.
    pub version: i64,
    pub set: ParameterSet,
    /// The headline mean 3-D validation error its own report gives (mm).
    pub report_mean_mm: Option<f64>,
    /// The session its own report measured.
    pub report_session_id: Option<String>,
}

impl Input {
    /// Every session of the job as a one-session input, this one first.
    pub fn sessions(&self) -> Vec<Input> {
        let first = Input {
            regions: Vec::new(),
            ..self.clone()
        };
        let further = self.regions.iter().map(|r| Input {
            session_id: r.session_id.clone(),
            session: r.session.clone(),
            poses: r.poses.clone(),
            ..first.clone()
        });
        std::iter::once(first.clone()).chain(further).collect()
    }

    /// A hand–eye session: its (first) pose carries the controller's
    /// flange pose instead of joints, so the job identifies no kinematics.
    pub fn is_flange_session(&self) -> bool {
        self.poses.first().is_some_and(|p| p.flange_pose.is_some())
    }
}

#[derive(Debug, Clone)]
pub struct PoseInput {
    pub id: String,
    /// What reports call the pose: its stored label (the photo's file
    /// name), or its number in upload order (`#12`).
    pub label: String,
    /// Empty for a pose that carries `flange_pose` instead.
    pub joints_deg: JointsDeg,
    /// The controller's flange pose, for a pose sent without joints (a
    /// hand–eye session: no kinematics are identified).
    pub flange_pose: Option<FlangePose>,
    pub set: PoseSet,
    /// The pose's image, when it was uploaded with one: a reference, never
    /// the bytes (a job holds no images; the detect stage reads, decodes and
    /// drops the ones without a stored detection, one at a time per thread).
    pub image: Option<PoseImage>,
    pub image_points: Vec<ImagePointDoc>,
    pub measured_position_mm: Option<[f64; 3]>,
    pub measured_pose: Option<PoseDoc>,
    /// A stage session's image: the stage's reading.
    pub stage_reading: Option<StageReading>,
    /// The arm configuration the client named (`None`: grouped by joints).
    pub group: Option<String>,
}

/// A pose's image as a job sees it.
#[derive(Debug, Clone)]
pub struct PoseImage {
    /// What [`Input::images`] reads it by (the blob's sha256 in the service,
    /// the file's path for `calibrate-local`).
    pub key: String,
    pub width: u32,
    pub height: u32,
    /// What the detector found on it at upload (or in an earlier job):
    /// reused as is, the image is then never decoded.
    pub detection: Option<ImageDetection>,
}

/// Reads an image's bytes by [`PoseImage::key`].
pub type ReadImage = dyn Fn(&str) -> Result<Vec<u8>, String> + Send + Sync;

/// Where the detect stage gets the images it must decode, and the gate all
/// decodes of the process share.
#[derive(Clone)]
pub struct ImageSource {
    pub read: Arc<ReadImage>,
    pub gate: Arc<DecodeGate>,
}

impl std::fmt::Debug for ImageSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ImageSource")
            .field("gate", &self.gate)
            .finish_non_exhaustive()
    }
}

impl ImageSource {
    /// No images to read (sessions of image points or tracker measurements).
    pub fn none() -> ImageSource {
        ImageSource {
            read: Arc::new(|key: &str| Err(format!("image {key} is not available"))),
            gate: Arc::new(DecodeGate::new(1)),
        }
    }
}

/// Intrinsics of an earlier calibration, reused and held fixed (the paper
/// keeps `fx` and `k` once tuned, method.md §4).
#[derive(Debug, Clone, PartialEq)]
pub struct FixedCamera {
    /// Where they come from: `"{serial}/{version}"` of a parameter set.
    pub calibration_id: String,
    pub intrinsics: Intrinsics,
}
