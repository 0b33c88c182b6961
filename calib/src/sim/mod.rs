//! Simulator: target images and whole campaigns with known truth.

pub mod camera_step;
/// Camera campaigns with and without non-geometric terms (issue 19).
pub mod camera_terms;
pub mod campaign;
pub mod campaign_io;
/// The simulated campaign kinds the bound benchmark judges the fit on.
pub mod campaign_kinds;
pub mod campaign_spec;
/// A camera job's default identification, from calib.
pub mod default_job;
pub mod experiment;
pub mod experiment_error;
/// Campaigns shot in configuration groups (weakly excited links).
pub mod grouped_campaign;
pub mod oracle;
/// Planned campaigns: plan requests, images at planned joints, a job on them (issue 16).
pub mod planned;
/// Views as point observations (no image): camera-calibration tests.
pub mod point_views;
pub mod render;
/// ChArUco boards through the same camera (issue 14).
pub mod render_charuco;
/// Chessboards through the same camera (issue 14).
pub mod render_chessboard;
/// Circle boards: symmetric dot grids and OpenCV's asymmetric grid.
pub mod render_circles;
pub mod rendered_camera;
/// The paper's stage accuracy test (section 4; issue 18).
pub mod stage_campaign;
pub mod start_model;
/// Laser-tracker campaigns with optional non-geometric errors (issue 19).
pub mod tracker_campaign;
/// The true robot of a camera campaign: perturbed kinematics, true joints.
pub mod true_robot;
/// Board placement and tilt of simulated campaigns (point views).
pub mod view_layout;
/// What a simulated camera campaign is made of.
pub mod view_spec;
/// Random board views for rendering: detector tests and benchmarks.
pub mod views;
