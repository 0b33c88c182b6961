//! What measures the robot: a camera on the flange, a laser tracker, or a
//! camera on a translation stage; and what a tracker measured at each pose.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The session's instrument.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Instrument {
    #[default]
    Camera,
    Tracker,
    /// A camera on a linear stage (paper section 4): poses are
    /// images with the stage's reading, and the job calibrates and assesses
    /// the camera itself (no robot is identified).
    Stage,
}

impl Instrument {
    pub fn as_str(self) -> &'static str {
        match self {
            Instrument::Camera => "camera",
            Instrument::Tracker => "tracker",
            Instrument::Stage => "stage",
        }
    }

    /// The value of the sessions table's `instrument` column: the sensor.
    /// Its 0001 CHECK allows `camera` and `tracker`, and SQLite relaxes a
    /// CHECK only by rebuilding the table, whose DROP would cascade into
    /// every pose; a stage session's sensor is its camera, and its served
    /// and typed `instrument` (the stored spec) stays `stage`.
    pub fn column(self) -> &'static str {
        match self {
            Instrument::Camera | Instrument::Stage => "camera",
            Instrument::Tracker => "tracker",
        }
    }

    /// Whether the session's poses carry images of a board.
    pub fn has_camera(self) -> bool {
        matches!(self, Instrument::Camera | Instrument::Stage)
    }
}

/// What a tracker measured: the probe's full `pose`, or its `position`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Measurement {
    Pose,
    Position,
}

impl Measurement {
    pub fn as_str(self) -> &'static str {
        match self {
            Measurement::Pose => "pose",
            Measurement::Position => "position",
        }
    }
}
