//! Hand–eye and board from controller flange poses (issue 14, method.md §4
//! and §6 **beyond**): the camera intrinsics, `flange_to_camera` and
//! `target_to_base` fitted jointly as one bundle on image points, with the
//! flange poses `base_to_flange` taken as given (no kinematics), and poses
//! whose robot data contradict their image screened out.
//!
//! Stages: per-image PnP and a robust AX = XB ([`start`]) only start the
//! fit; [`bundle`] is the least-squares problem; [`screen`] finds the
//! lying poses by the consensus of per-pose board estimates and then by
//! residual screening with re-fit; [`calibrate`] joins them.

pub mod bundle;
pub mod bundle_model;
mod bundle_problem;
pub mod calibrate;
pub mod error;
pub mod noise;
pub mod redundancy;
pub mod result;
pub mod robust;
pub mod screen;
pub mod start;
pub mod view;

pub use calibrate::{calibrate_flange, FlangeOptions};
pub use error::HandEyeError;
pub use result::{FlangeCalibration, PoseSigma, PoseVerdict};
pub use screen::screen_joint_poses;
pub use view::FlangeView;

#[cfg(test)]
mod calibrate_tests;
#[cfg(test)]
mod real_data_tests;
#[cfg(test)]
mod screen_tests;
#[cfg(test)]
mod test_campaign;
