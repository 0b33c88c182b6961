//! Measurement session and pose documents.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::{Checker, FieldError, PoseDoc};

pub use crate::domain::MAX_GRID_SIDE;
/// Largest image side, pixels.
pub const MAX_IMAGE_SIDE: u32 = 20_000;
/// Most image points per pose.
pub const MAX_POINTS_PER_POSE: usize = 100_000;
/// Largest pixel pitch, micrometres.
pub const MAX_PIXEL_UM: f64 = 100.0;
/// Longest focal length, millimetres.
pub const MAX_FOCAL_MM: f64 = 1000.0;
/// Longest `region` or `volume` name of a session (free text).
pub const MAX_REGION_NAME_CHARS: usize = 100;

pub use crate::domain::Instrument;

pub use crate::domain::{TargetDoc, TargetKind};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CameraDoc {
    pub width: u32,
    pub height: u32,
    pub pixel_size_um: f64,
    pub nominal_focal_mm: f64,
}

/// `POST /v1/robots/{serial}/sessions` body.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SessionBody {
    #[serde(default)]
    pub instrument: Instrument,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<TargetDoc>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraDoc>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flange_to_camera_guess: Option<PoseDoc>,
    /// An earlier calibration whose camera intrinsics this session reuses
    /// and holds fixed: a parameter set as `"{serial}/{version}"` (any
    /// robot's: the camera may have moved), or `"{serial}/latest"`, resolved
    /// to its version when the session is created. It must hold camera
    /// intrinsics measured on images of this session's size.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_calibration_id: Option<String>,
    /// Where in the workspace this session's board was placed (free text,
    /// e.g. `"left table"`): one session is one board placement, one region
    /// of the paper's section 5 (method.md §7).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<String>,
    /// The measurement volume the poses of this session span (free text,
    /// e.g. `"600x400x300 mm"`), the paper's Fig. 10 groups by it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub volume: Option<String>,
    /// Payload at the tool during the campaign (kg), when known: the
    /// compliance terms then get a candidate driven by its gravity torque.
    /// A finite mass from 0 to `MAX_PAYLOAD_KG`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub payload_kg: Option<f64>,
    /// A tracker session's position standard deviation per axis (mm),
    /// the weight of each measured position; default 0.02 mm (a laser
    /// tracker at robot range).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracker_sigma_mm: Option<f64>,
    /// A tracker session's orientation standard deviation per axis (deg)
    /// for poses with `measured_pose` (a 6-DoF probe), the
    /// weight of each measured orientation; default 0.01° (a T-Mac's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracker_orientation_sigma_deg: Option<f64>,
    /// The controller the campaign is measured on; absent: the
    /// robot's `controller` when the session is created. The session's
    /// sets inherit it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub controller: Option<crate::domain::ControllerIdentity>,
}

/// Largest payload a session may state (kg): beyond any industrial arm's.
pub const MAX_PAYLOAD_KG: f64 = 5_000.0;
/// Largest tracker noise a session may state: beyond these a campaign
/// measures nothing a robot's kinematics could be identified from.
pub const MAX_TRACKER_SIGMA_MM: f64 = 10.0;
pub const MAX_TRACKER_SIGMA_DEG: f64 = 10.0;

impl SessionBody {
    pub fn check(&self) -> Result<(), Vec<FieldError>> {
        let mut c = Checker::default();
        if let Some(controller) = &self.controller {
            controller.check("controller", &mut c);
        }
        if self.instrument.has_camera() {
            match &self.target {
                None => c.fail("target", "required for a camera or stage session"),
                Some(t) => {
                    if let Err(errors) = crate::domain::Target::from_doc(t) {
                        c.errors.extend(errors);
                    }
                }
            }
            match &self.camera {
                None => c.fail("camera", "required for a camera or stage session"),
                Some(k) => {
                    for (name, v) in [("camera.width", k.width), ("camera.height", k.height)] {
                        if !(1..=MAX_IMAGE_SIDE).contains(&v) {
                            c.fail(name, format!("must be 1 to {MAX_IMAGE_SIDE} pixels"));
                        }
                    }
                    c.positive("camera.pixel_size_um", k.pixel_size_um, MAX_PIXEL_UM, "um");
                    c.positive(
                        "camera.nominal_focal_mm",
                        k.nominal_focal_mm,
                        MAX_FOCAL_MM,
                        "mm",
                    );
                }
            }
        }
        if let Some(p) = &self.flange_to_camera_guess {
            p.check(&mut c, "flange_to_camera_guess");
        }
        if self.instrument == Instrument::Stage {
            // A stage session calibrates the camera itself: there is no
            // flange, and its intrinsics are what it measures.
            if self.flange_to_camera_guess.is_some() {
                c.fail(
                    "flange_to_camera_guess",
                    "a stage session has no robot flange",
                );
            }
            if self.camera_calibration_id.is_some() {
                c.fail(
                    "camera_calibration_id",
                    "a stage session calibrates the camera itself",
                );
            }
        }
        if let Some(kg) = self.payload_kg {
            if !(kg.is_finite() && (0.0..=MAX_PAYLOAD_KG).contains(&kg)) {
                c.fail(
                    "payload_kg",
                    format!("must be a finite mass from 0 to {MAX_PAYLOAD_KG} kg"),
                );
            }
        }
        for (field, sigma, max, unit) in [
            (
                "tracker_sigma_mm",
                self.tracker_sigma_mm,
                MAX_TRACKER_SIGMA_MM,
                "mm",
            ),
            (
                "tracker_orientation_sigma_deg",
                self.tracker_orientation_sigma_deg,
                MAX_TRACKER_SIGMA_DEG,
                "deg",
            ),
        ] {
            let Some(sigma) = sigma else { continue };
            if self.instrument != Instrument::Tracker {
                c.fail(field, "only a tracker session has a tracker's noise");
            } else {
                c.positive(field, sigma, max, unit);
            }
        }
        if let Some(id) = &self.camera_calibration_id {
            if id.is_empty() || id.len() > 100 {
                c.fail("camera_calibration_id", "must be 1 to 100 characters");
            }
        }
        for (field, text) in [("region", &self.region), ("volume", &self.volume)] {
            let chars = text.as_deref().map(|t| t.trim().chars().count());
            if chars.is_some_and(|n| !(1..=MAX_REGION_NAME_CHARS).contains(&n)) {
                c.fail(
                    field,
                    format!("must be 1 to {MAX_REGION_NAME_CHARS} characters"),
                );
            }
        }
        c.finish()
    }
}

/// Which set a pose belongs to (typed in the domain).
pub use crate::domain::PoseSet;
