//! Camera models and calibration (method.md §2–4).

pub mod bias;
pub mod calibrate;
pub mod error;
pub mod leave_out;
pub mod model;
pub mod normal_blocks;
pub mod observations;
pub mod options;
pub mod pose;
pub mod projection_jacobian;
pub mod refine;
pub mod refine_loop;
pub mod sequence;
pub mod tsai;

pub use calibrate::{
    calibrate, CalibrationMode, CalibrationOptions, CameraCalibration, IntrinsicsStdDev,
    OutlierDot, ViewReport,
};
pub use error::CameraError;
pub use model::Intrinsics;
pub use observations::{DotObservation, ImageSize, ViewObservations};
pub use pose::{estimate_pose, PoseEstimate};
pub use refine::StationDistance;
pub use sequence::PaperOptions;
pub use tsai::Stage2Form;
