//! What a calibration job identified, as one type: a kinematic set (a
//! robot model with its frames), a hand–eye set (flange poses, no
//! kinematics) or a stage camera set (intrinsics only). A fixed-camera set
//! becomes one more variant. The stored and served document is the
//! variant's document with its `kind`; sets stored before `kind` was
//! written read as kinematic (only kinematic sets were stored without it).

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use super::{HandEyeSet, ParameterSet, StageCameraSet};

/// The key that tells the variants apart.
pub(super) const KIND_KEY: &str = "kind";

/// A calibrated parameter set, one variant per what the job identified.
///
/// Its schema is `calibrated_set_schema.rs`'s.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CalibratedSet {
    /// A robot model: the identified joint table and its two frames.
    Kinematic(ParameterSet),
    /// A hand–eye calibration from the controller's flange poses.
    HandEye(HandEyeSet),
    /// A camera calibrated on a translation stage.
    StageCamera(StageCameraSet),
}

/// The variants' names, as `kind` carries them.
pub(super) const KINEMATIC: &str = "kinematic";
pub(super) const HAND_EYE: &str = "hand_eye";
pub(super) const STAGE_CAMERA: &str = "stage_camera";

impl CalibratedSet {
    /// The variant's `kind`.
    pub fn kind(&self) -> &'static str {
        match self {
            CalibratedSet::Kinematic(_) => KINEMATIC,
            CalibratedSet::HandEye(_) => HAND_EYE,
            CalibratedSet::StageCamera(_) => STAGE_CAMERA,
        }
    }

    /// The kinematic set, `None` for a set that holds no robot model.
    pub fn kinematic(&self) -> Option<&ParameterSet> {
        match self {
            CalibratedSet::Kinematic(set) => Some(set),
            _ => None,
        }
    }

    /// [`Self::kinematic`], by value.
    pub fn into_kinematic(self) -> Option<ParameterSet> {
        match self {
            CalibratedSet::Kinematic(set) => Some(set),
            _ => None,
        }
    }

    /// The session the set was calibrated from (the first, for a set over
    /// several).
    pub fn session_id(&self) -> &str {
        match self {
            CalibratedSet::Kinematic(s) => &s.session_id,
            CalibratedSet::HandEye(s) => &s.session_id,
            CalibratedSet::StageCamera(s) => &s.session_id,
        }
    }

    /// The camera intrinsics the set holds, if any (what a later session
    /// may reuse as `camera_calibration_id`).
    pub fn camera(&self) -> Option<&robocal_calib::camera::Intrinsics> {
        match self {
            CalibratedSet::Kinematic(s) => s.camera.as_ref(),
            CalibratedSet::HandEye(s) => Some(&s.camera),
            CalibratedSet::StageCamera(s) => Some(&s.camera),
        }
    }

    /// The identified rows, guess or nominal against identified (none for
    /// a stage camera set).
    pub fn parameter_rows(&self) -> &[super::ParameterReport] {
        match self {
            CalibratedSet::Kinematic(s) => &s.parameters,
            CalibratedSet::HandEye(s) => &s.parameters,
            CalibratedSet::StageCamera(_) => &[],
        }
    }
}

impl<'de> Deserialize<'de> for CalibratedSet {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let mut doc = Map::<String, Value>::deserialize(d)?;
        let kind = match doc.remove(KIND_KEY) {
            None => KINEMATIC.to_string(),
            Some(Value::String(kind)) => kind,
            Some(other) => {
                return Err(D::Error::custom(format!(
                    "`kind` of a parameter set is a string, not {other}"
                )))
            }
        };
        let doc = Value::Object(doc);
        let decoded = match kind.as_str() {
            KINEMATIC => serde_json::from_value(doc).map(CalibratedSet::Kinematic),
            HAND_EYE => serde_json::from_value(doc).map(CalibratedSet::HandEye),
            STAGE_CAMERA => serde_json::from_value(doc).map(CalibratedSet::StageCamera),
            other => {
                return Err(D::Error::custom(format!(
                    "unknown parameter set kind {other:?} (one of {KINEMATIC}, {HAND_EYE}, {STAGE_CAMERA})"
                )))
            }
        };
        decoded.map_err(|e| D::Error::custom(format!("a {kind} parameter set: {e}")))
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    fn kinematic() -> CalibratedSet {
        CalibratedSet::Kinematic(ParameterSet::placeholder("s1"))
    }

    /// Every variant is written with its `kind` and reads back as itself.
    #[test]
    fn a_set_round_trips_with_its_kind() {
        let doc = serde_json::to_value(kinematic()).unwrap();
        assert_eq!(doc[KIND_KEY], KINEMATIC);
        assert_eq!(doc["session_id"], "s1");
        assert!(doc.get("target_to_base").is_some(), "{doc}");
        let back: CalibratedSet = serde_json::from_value(doc).unwrap();
        assert_eq!(back.kind(), KINEMATIC);
        assert_eq!(back.session_id(), "s1");
    }

    /// A row stored before `kind` was written (only kinematic sets were)
    /// reads as a kinematic set; a hand–eye row keeps its variant.
    #[test]
    fn a_set_without_kind_reads_as_kinematic() {
        let mut doc = serde_json::to_value(kinematic()).unwrap();
        doc.as_object_mut().unwrap().remove(KIND_KEY);
        let read: CalibratedSet = serde_json::from_value(doc).unwrap();
        assert!(read.kinematic().is_some());
        let pose = serde_json::to_value(ParameterSet::placeholder("x").world_to_base).unwrap();
        let hand_eye = json!({"kind": "hand_eye", "instrument": "camera", "session_id": "h",
            "target_to_base": pose, "flange_to_camera": pose, "base_to_target": pose,
            "board_scale": 1.0, "camera": {"fx": 1.0, "fy": 1.0, "cx": 0.0, "cy": 0.0,
            "k1": 0.0, "k2": 0.0, "p1": 0.0, "p2": 0.0, "k3": 0.0},
            "camera_mode": "refined", "fixed": [], "parameters": []});
        let read: CalibratedSet = serde_json::from_value(hand_eye).unwrap();
        assert_eq!(read.kind(), HAND_EYE);
        assert!(read.kinematic().is_none());
    }

    /// An unknown kind or a document of the wrong shape is an error that
    /// names the kind, never a default.
    #[test]
    fn a_set_that_does_not_read_says_why() {
        let unknown = json!({"kind": "fixed_camera", "session_id": "s"});
        let e = serde_json::from_value::<CalibratedSet>(unknown).unwrap_err();
        assert!(e.to_string().contains("fixed_camera"), "{e}");
        let broken = json!({"kind": "stage_camera", "session_id": "s"});
        let e = serde_json::from_value::<CalibratedSet>(broken).unwrap_err();
        assert!(e.to_string().contains("stage_camera"), "{e}");
    }
}
