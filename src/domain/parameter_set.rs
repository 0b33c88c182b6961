//! A calibrated parameter set, typed once (api.md "Results"): the identified
//! joint table, the two frames the calibration found, the intrinsics and
//! what was held fixed. It owns the frames' names: the contract calls them
//! `target_to_base`/`flange_to_camera` for a camera session and
//! `instrument_to_base`/`flange_to_tool` for a tracker, the numerics
//! `world_to_base`/`flange_to_tool` (method.md §5). Its serde form is the
//! stored and served document, so nothing renames keys after it, and
//! [`ParameterSet::model`] is the one conversion to the numerics' model.

use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::{CalibratedModel, ParamLayout};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::numerics_schema::IntrinsicsSchema;
use super::ParameterReport;
use super::PoseOut;
use super::{
    doc_to_model, ControllerIdentity, CovarianceDoc, Instrument, KinematicsDoc, Measurement,
    TermsDoc,
};

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(into = "StoredSet", try_from = "StoredSet")]
pub struct ParameterSet {
    pub instrument: Instrument,
    /// A tracker set's measurement: `pose` when a 6-DoF probe's
    /// orientation was fitted with its position, so `flange_to_tool` is the
    /// probe's full frame and the parameters follow the camera's layout;
    /// `position` (or absent, in sets stored before it was kept) for the
    /// tool point only. Absent for camera sets.
    pub measurement: Option<Measurement>,
    pub session_id: String,
    pub kinematics: KinematicsDoc,
    /// The board's (camera) or the tracker's frame in the robot base frame.
    pub world_to_base: PoseOut,
    /// The camera (camera) or the measured tool point (tracker) in the
    /// flange frame.
    pub flange_to_tool: PoseOut,
    pub camera: Option<Intrinsics>,
    /// How `camera` was obtained: "refined", "paper" (`refine_intrinsics:
    /// false`) or "fixed" (reused from `camera_calibration_id`).
    pub camera_mode: Option<String>,
    /// The earlier calibration (`"{serial}/{version}"`) whose intrinsics
    /// `camera` repeats, when they were held fixed.
    pub camera_calibration_id: Option<String>,
    pub fixed: Vec<String>,
    pub parameters: Vec<ParameterReport>,
    /// The identified parameters' full covariance (absent from sets
    /// stored before it was kept).
    pub covariance: Option<CovarianceDoc>,
    /// Joint noise (encoders, repeatability; deg, one standard deviation
    /// per joint) the joint refinement estimated from the images (method.md
    /// §6): a re-check's covariance needs it beside `covariance`. Absent
    /// when the refinement did not run and from sets stored before it was
    /// kept.
    pub joint_noise_deg: Option<f64>,
    /// The non-geometric terms kept by the selection; absent
    /// when none was kept and in sets stored before terms were selected.
    pub terms: Option<TermsDoc>,
    /// A set calibrated over several sessions (board placements, issue
    /// 18): each session's board in the base frame, the first session's
    /// equal to `world_to_base`. Empty for a one-session set.
    pub session_target_to_base: Vec<SessionBoard>,
    /// The controller the set's session was measured on,
    /// inherited from the session; absent when none was recorded.
    pub controller: Option<ControllerIdentity>,
}

/// One session's board placement in a multi-session set.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct SessionBoard {
    pub session_id: String,
    pub target_to_base: PoseOut,
    /// The set's covariance as this session sees it: its own board's base
    /// values in the base slots (the set's `covariance` is the first
    /// session's). `forward`'s σ with this `session_id` uses it. Absent in
    /// sets stored before it existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub covariance: Option<CovarianceDoc>,
}

/// The contract's names of a set's frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameNames {
    /// The key of [`ParameterSet::world_to_base`].
    pub world_to_base: &'static str,
    /// The key of [`ParameterSet::flange_to_tool`].
    pub flange_to_end: &'static str,
    /// The world frame itself (`target`, `tracker`).
    pub world: &'static str,
    /// The frame at the end of the chain (`camera`, `tool`).
    pub end: &'static str,
}

const CAMERA_FRAMES: FrameNames = FrameNames {
    world_to_base: "target_to_base",
    flange_to_end: "flange_to_camera",
    world: "target",
    end: "camera",
};

const TRACKER_FRAMES: FrameNames = FrameNames {
    world_to_base: "instrument_to_base",
    flange_to_end: "flange_to_tool",
    world: "tracker",
    end: "tool",
};

impl ParameterSet {
    /// A camera set with an empty joint table and identity frames: what
    /// the test hook stores for a job that identified nothing, and what a
    /// test stores when the set's content is not what it checks.
    pub fn placeholder(session_id: impl Into<String>) -> ParameterSet {
        let identity = PoseOut::new(&robocal_calib::geometry::Pose::identity());
        ParameterSet {
            instrument: Instrument::Camera,
            measurement: None,
            session_id: session_id.into(),
            kinematics: KinematicsDoc { joints: Vec::new() },
            world_to_base: identity.clone(),
            flange_to_tool: identity,
            camera: None,
            camera_mode: None,
            camera_calibration_id: None,
            fixed: Vec::new(),
            parameters: Vec::new(),
            covariance: None,
            joint_noise_deg: None,
            terms: None,
            session_target_to_base: Vec::new(),
            controller: None,
        }
    }

    /// What the contract calls this set's frames.
    pub fn frame_names(&self) -> FrameNames {
        match self.instrument {
            Instrument::Tracker => TRACKER_FRAMES,
            _ => CAMERA_FRAMES,
        }
    }

    /// The stored covariance in layout order and internal units (mm, rad),
    /// `None` for sets stored without one.
    pub fn covariance_matrix(&self) -> Option<Result<nalgebra::DMatrix<f64>, String>> {
        let doc = self.covariance.as_ref()?;
        let robot = doc_to_model(&self.kinematics);
        Some(doc.to_layout(&ParamLayout::new(&robot, self.layout_instrument())))
    }

    /// The instrument whose parameter layout the numerics use for this set.
    pub fn layout_instrument(&self) -> robocal_calib::kinematics::Instrument {
        match (self.instrument, self.measurement) {
            (Instrument::Tracker, Some(Measurement::Pose))
            | (Instrument::Camera | Instrument::Stage, _) => {
                robocal_calib::kinematics::Instrument::Camera
            }
            (Instrument::Tracker, _) => robocal_calib::kinematics::Instrument::Tracker,
        }
    }

    /// The set seen from session `session_id`'s board: `world_to_base` is
    /// that session's `target_to_base`. `None` when the set
    /// knows no such session (a one-session set knows its own).
    pub fn in_session(&self, session_id: &str) -> Option<ParameterSet> {
        let (board, covariance) = match self
            .session_target_to_base
            .iter()
            .find(|b| b.session_id == session_id)
        {
            Some(b) => (
                b.target_to_base.clone(),
                b.covariance.clone().or_else(|| self.covariance.clone()),
            ),
            None if session_id == self.session_id => {
                (self.world_to_base.clone(), self.covariance.clone())
            }
            None => return None,
        };
        Some(ParameterSet {
            world_to_base: board,
            covariance,
            ..self.clone()
        })
    }

    /// The sessions whose boards the set knows, the first session's first.
    pub fn session_ids(&self) -> Vec<&str> {
        if self.session_target_to_base.is_empty() {
            return vec![self.session_id.as_str()];
        }
        self.session_target_to_base
            .iter()
            .map(|b| b.session_id.as_str())
            .collect()
    }

    /// The calibrated model, as the numerics take it.
    pub fn model(&self) -> Result<CalibratedModel, String> {
        Ok(CalibratedModel {
            robot: doc_to_model(&self.kinematics),
            world_to_base: self.world_to_base.pose()?,
            flange_to_tool: self.flange_to_tool.pose()?,
        })
    }

    /// [`Self::model`] with the kept non-geometric terms (none for sets
    /// without): what `forward`, `compensate`, `filter` and the predicted
    /// uncertainty evaluate.
    pub fn term_model(&self) -> Result<TermModel, String> {
        let model = self.model()?;
        match &self.terms {
            Some(t) => t.term_model(model, self.layout_instrument()),
            None => Ok(TermModel::geometric(model)),
        }
    }
}

/// The document as stored and served: each frame under the contract's
/// name for the set's instrument. Camera sets have `target_to_base`,
/// `flange_to_camera` and `camera`; tracker sets `instrument_to_base` and
/// `flange_to_tool`.
#[derive(Serialize, Deserialize, ToSchema)]
struct StoredSet {
    /// `camera`, `tracker` or `stage`.
    instrument: Instrument,
    /// A tracker set's measurement: `pose` when the probe's orientation
    /// was fitted with its position, `position` (or absent) for the tool
    /// point only. Absent for camera sets.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    measurement: Option<Measurement>,
    /// The session the parameters were identified from.
    session_id: String,
    /// The identified joint table.
    kinematics: KinematicsDoc,
    /// The calibration board's frame in the robot base frame (camera sets).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    target_to_base: Option<PoseOut>,
    /// The laser tracker's frame in the robot base frame (tracker sets).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    instrument_to_base: Option<PoseOut>,
    /// The camera in the flange frame (camera sets).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    flange_to_camera: Option<PoseOut>,
    /// The measured tool point in the flange frame (tracker sets).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    flange_to_tool: Option<PoseOut>,
    /// The calibrated camera intrinsics (camera sets).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<IntrinsicsSchema>)]
    camera: Option<Intrinsics>,
    /// How `camera` was obtained: `refined`, `paper` or `fixed`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    camera_mode: Option<String>,
    /// The calibration (`"{serial}/{version}"`) whose intrinsics were held fixed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    camera_calibration_id: Option<String>,
    /// Parameters held fixed as unidentifiable.
    fixed: Vec<String>,
    /// Every identified parameter against its nominal value.
    parameters: Vec<ParameterReport>,
    /// The identified parameters' full covariance, in the units of
    /// `parameters` (what `forward`'s predicted σ propagate). Absent for
    /// sets stored before it was kept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    covariance: Option<CovarianceDoc>,
    /// Joint noise (deg, one standard deviation per joint) the joint
    /// refinement estimated from the images; absent when it did not run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    joint_noise_deg: Option<f64>,
    /// The non-geometric terms kept by the selection, each with its value,
    /// σ and unit; `forward`, `compensate`, `filter` and the predicted σ
    /// include them. Absent when none was kept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    terms: Option<TermsDoc>,
    /// A set calibrated over several sessions (board placements): each
    /// session's board in the base frame, the first equal to
    /// `target_to_base`. Absent for a one-session set.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    session_target_to_base: Vec<SessionBoard>,
    /// The controller the set's session was measured on; absent when none
    /// was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    controller: Option<ControllerIdentity>,
}

/// The kinematic set's schema is its stored form's, under the name
/// `KinematicSet`.
impl utoipa::PartialSchema for ParameterSet {
    fn schema() -> utoipa::openapi::RefOr<utoipa::openapi::schema::Schema> {
        <StoredSet as utoipa::PartialSchema>::schema()
    }
}

impl ToSchema for ParameterSet {
    fn name() -> std::borrow::Cow<'static, str> {
        std::borrow::Cow::Borrowed("KinematicSet")
    }

    fn schemas(
        schemas: &mut Vec<(
            String,
            utoipa::openapi::RefOr<utoipa::openapi::schema::Schema>,
        )>,
    ) {
        <StoredSet as ToSchema>::schemas(schemas)
    }
}

impl From<ParameterSet> for StoredSet {
    fn from(set: ParameterSet) -> StoredSet {
        let tracker = set.frame_names() == TRACKER_FRAMES;
        let (world, end) = (Some(set.world_to_base), Some(set.flange_to_tool));
        StoredSet {
            instrument: set.instrument,
            measurement: set.measurement,
            session_id: set.session_id,
            kinematics: set.kinematics,
            target_to_base: if tracker { None } else { world.clone() },
            instrument_to_base: if tracker { world } else { None },
            flange_to_camera: if tracker { None } else { end.clone() },
            flange_to_tool: if tracker { end } else { None },
            camera: set.camera,
            camera_mode: set.camera_mode,
            camera_calibration_id: set.camera_calibration_id,
            fixed: set.fixed,
            parameters: set.parameters,
            covariance: set.covariance,
            joint_noise_deg: set.joint_noise_deg,
            terms: set.terms,
            session_target_to_base: set.session_target_to_base,
            controller: set.controller,
        }
    }
}

impl TryFrom<StoredSet> for ParameterSet {
    type Error = String;

    fn try_from(s: StoredSet) -> Result<ParameterSet, String> {
        let missing = |camera: &str, tracker: &str| format!("neither {camera} nor {tracker}");
        Ok(ParameterSet {
            instrument: s.instrument,
            measurement: s.measurement,
            session_id: s.session_id,
            kinematics: s.kinematics,
            world_to_base: s.target_to_base.or(s.instrument_to_base).ok_or_else(|| {
                missing(CAMERA_FRAMES.world_to_base, TRACKER_FRAMES.world_to_base)
            })?,
            flange_to_tool: s.flange_to_camera.or(s.flange_to_tool).ok_or_else(|| {
                missing(CAMERA_FRAMES.flange_to_end, TRACKER_FRAMES.flange_to_end)
            })?,
            camera: s.camera,
            camera_mode: s.camera_mode,
            camera_calibration_id: s.camera_calibration_id,
            fixed: s.fixed,
            parameters: s.parameters,
            covariance: s.covariance,
            joint_noise_deg: s.joint_noise_deg,
            terms: s.terms,
            session_target_to_base: s.session_target_to_base,
            controller: s.controller,
        })
    }
}
