//! Pure, synchronous numerics of robocal (see `docs/method.md` at the repository root).
//!
//! This crate never imports HTTP, database or job code: plain functions on
//! plain types; degenerate input returns an error, never a panic. Frames are
//! named `a_to_b` = the pose of frame b expressed in frame a
//! (`p_a = a_to_b * p_b`), lengths are millimetres, angles radians inside the
//! numerics unless a name says `_deg`.

pub mod arrow;
pub mod bound;
pub mod camera;
pub mod chi_square;
pub mod covariance;
pub mod geometry;
pub mod handeye;
pub mod kinematics;
pub mod normal_matrix;
pub mod plan;
pub mod schur;
pub mod sim;
pub mod solver;
pub mod stage;
pub mod stats;
pub mod vision;
