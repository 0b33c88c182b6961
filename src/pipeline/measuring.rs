//! What a job reads at each pose (method.md §6): the camera's pose of the
//! board, or a tracker's measurement: the tool point's position, or with a
//! 6-DoF probe (`measured_pose`, issue 19) the tool's full pose, each with
//! the instrument's own standard deviations. It also decides which of the
//! two a tracker job fits, and so which parameter layout: a full pose
//! identifies the tool's frame (6 rows, the camera's layout), a position
//! only its point.

use nalgebra::{Matrix3, Matrix6, Vector3};
use robocal_calib::camera::{estimate_pose, Intrinsics};
use robocal_calib::kinematics::identify::{Measurement, Observed};
use robocal_calib::kinematics::Instrument;

use super::camera_stage::CameraStep;
use super::{ApprovedSet, PipelineError, PoseInput};
use crate::schema::job::Measurement as MeasurementKind;
use crate::schema::session::SessionBody;

/// A laser tracker's position standard deviation when the session gives
/// none (mm): a typical few hundredths at robot range.
pub const TRACKER_SIGMA_MM: f64 = 0.02;
/// A 6-DoF probe's orientation standard deviation when the session gives
/// none (deg): a Leica T-Mac's or an NDI probe's stated 0.01°.
pub const PROBE_ORIENTATION_SIGMA_DEG: f64 = 0.01;

/// A tracker's noise, one standard deviation per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackerNoise {
    pub position_sigma_mm: f64,
    pub orientation_sigma_rad: f64,
}

impl Default for TrackerNoise {
    fn default() -> Self {
        TrackerNoise {
            position_sigma_mm: TRACKER_SIGMA_MM,
            orientation_sigma_rad: PROBE_ORIENTATION_SIGMA_DEG.to_radians(),
        }
    }
}

impl TrackerNoise {
    /// The session's (`tracker_sigma_mm`, `tracker_orientation_sigma_deg`),
    /// else the defaults.
    pub fn of(session: &SessionBody) -> TrackerNoise {
        let default = TrackerNoise::default();
        TrackerNoise {
            position_sigma_mm: session
                .tracker_sigma_mm
                .unwrap_or(default.position_sigma_mm),
            orientation_sigma_rad: session
                .tracker_orientation_sigma_deg
                .map_or(default.orientation_sigma_rad, f64::to_radians),
        }
    }

    /// `diag(σ_pos² ×3, σ_rot² ×3)` in `pose_error`'s `[dp mm; dr rad]`.
    fn pose_covariance(&self) -> Matrix6<f64> {
        let mut c = Matrix6::zeros();
        for k in 0..3 {
            c[(k, k)] = self.position_sigma_mm.powi(2);
            c[(k + 3, k + 3)] = self.orientation_sigma_rad.powi(2);
        }
        c
    }
}

/// How a job measures: the kind of each pose's observation and, for a
/// tracker, its noise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measuring {
    pub kind: MeasurementKind,
    pub tracker: TrackerNoise,
}

/// Whether every pose carries a 6-DoF probe's `measured_pose`.
fn every_pose_has_orientation(poses: &[PoseInput]) -> bool {
    !poses.is_empty() && poses.iter().all(|p| p.measured_pose.is_some())
}

/// The first pose without `measured_pose`, as the error naming it.
fn missing_orientation(poses: &[PoseInput], why: &str) -> PipelineError {
    let at = poses
        .iter()
        .position(|p| p.measured_pose.is_none())
        .unwrap_or(0);
    PipelineError::invalid(
        "measurement",
        format!(
            "{why}, but pose {} has no measured_pose: upload every pose with its measured_pose, or calibrate with {{\"measurement\": \"position\"}}",
            poses.get(at).map_or("#1", |p| p.label.as_str())
        ),
    )
}

impl Measuring {
    /// A full calibration's: the request's `measurement`, else a camera's
    /// pose, and a tracker's full pose when every pose has `measured_pose`
    /// (its position otherwise). `measurement: "pose"` on a tracker
    /// session without every orientation is refused, naming the field.
    pub fn for_job(
        session: &SessionBody,
        requested: Option<MeasurementKind>,
        poses: &[PoseInput],
    ) -> Result<Measuring, PipelineError> {
        let tracker = TrackerNoise::of(session);
        let kind = if session.instrument.has_camera() {
            requested.unwrap_or(MeasurementKind::Pose)
        } else {
            let oriented = every_pose_has_orientation(poses);
            match requested {
                Some(MeasurementKind::Pose) if !oriented => {
                    return Err(missing_orientation(poses, "measurement is \"pose\""))
                }
                Some(k) => k,
                None if oriented => MeasurementKind::Pose,
                None => MeasurementKind::Position,
            }
        };
        Ok(Measuring { kind, tracker })
    }

    /// A camera's pose of the board (a job over camera sessions only).
    pub fn camera_pose() -> Measuring {
        Measuring {
            kind: MeasurementKind::Pose,
            tracker: TrackerNoise::default(),
        }
    }

    /// A job holding `approved` (re-check, partial scope): the set's own
    /// measurement and layout. Refused, naming `field`, when this session
    /// measures with another instrument, and a 6-DoF set needs every pose's
    /// `measured_pose`.
    pub fn for_approved(
        approved: &ApprovedSet,
        session: &SessionBody,
        poses: &[PoseInput],
        field: &str,
    ) -> Result<(Instrument, Measuring), PipelineError> {
        if approved.set.instrument.has_camera() != session.instrument.has_camera() {
            return Err(PipelineError::invalid(
                field,
                format!(
                    "the approved set {} was calibrated with another instrument than this session's",
                    approved.id
                ),
            ));
        }
        let instrument = approved.set.layout_instrument();
        let kind = match instrument {
            Instrument::Camera => MeasurementKind::Pose,
            Instrument::Tracker => MeasurementKind::Position,
        };
        if !session.instrument.has_camera()
            && kind == MeasurementKind::Pose
            && !every_pose_has_orientation(poses)
        {
            return Err(missing_orientation(
                poses,
                &format!(
                    "the approved set {} holds a 6-DoF probe's tool frame",
                    approved.id
                ),
            ));
        }
        let tracker = TrackerNoise::of(session);
        Ok((instrument, Measuring { kind, tracker }))
    }

    /// The parameter layout these measurements identify: the full tool
    /// frame from a camera's or a probe's pose, the tool point from a
    /// position.
    pub fn layout(&self, camera: bool) -> Instrument {
        if camera || self.kind == MeasurementKind::Pose {
            Instrument::Camera
        } else {
            Instrument::Tracker
        }
    }

    /// One pose's measurement: the camera pose from the camera step (with
    /// `intrinsics` when given: validation poses are re-measured with the
    /// final ones), or the tracker's; `None` when the pose has none.
    pub fn of(
        &self,
        pose: &PoseInput,
        index: usize,
        camera: Option<&CameraStep>,
        intrinsics: Option<&Intrinsics>,
    ) -> Option<Measurement> {
        let observed = match camera {
            Some(step) => {
                let estimate = match intrinsics {
                    Some(intr) => estimate_pose(intr, step.observations_of(index)?, None).ok()?,
                    None => *step.pose_estimate(index)?,
                };
                match self.kind {
                    MeasurementKind::Pose => Observed::Pose {
                        world_to_tool: estimate.target_to_camera,
                        covariance: Some(estimate.covariance_6x6),
                    },
                    MeasurementKind::Position => Observed::Position {
                        position_mm: estimate.target_to_camera.translation.vector,
                        covariance: Some(
                            estimate
                                .covariance_6x6
                                .fixed_view::<3, 3>(0, 0)
                                .into_owned(),
                        ),
                    },
                }
            }
            None => match self.kind {
                // The probe's frame in the tracker's: the tool's pose in
                // the world frame, as `Observed::Pose` reads it.
                MeasurementKind::Pose => Observed::Pose {
                    world_to_tool: super::prelude::pose_of(pose.measured_pose.as_ref()?),
                    covariance: Some(self.tracker.pose_covariance()),
                },
                MeasurementKind::Position => Observed::Position {
                    position_mm: Vector3::from(pose.measured_position_mm?),
                    covariance: Some(Matrix3::identity() * self.tracker.position_sigma_mm.powi(2)),
                },
            },
        };
        Some(Measurement {
            joints_rad: pose.joints_deg.to_radians(),
            observed,
        })
    }
}
