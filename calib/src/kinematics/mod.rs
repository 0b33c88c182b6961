//! Robot kinematic model, identification and compensation (method.md §5–8).

pub mod config_groups;
pub mod filter;
pub mod identifiability;
pub mod identify;
pub mod identify_error;
pub mod identify_options;
pub mod ik;
pub mod ik_branches;
#[cfg(test)]
mod ik_branches_tests;
#[cfg(test)]
mod ik_limits_tests;
mod ik_newton;
#[cfg(test)]
mod ik_proptests;
mod ik_seeds;
#[cfg(test)]
mod ik_tests;
mod image_fit;
pub mod image_information;
pub mod image_pose;
pub mod image_term_selection;
#[cfg(test)]
mod image_test_campaign;
pub mod initial;
pub mod jacobian;
pub mod joint_covariance;
pub mod joint_refine;
mod ladder_terms;
pub mod measurement;
pub mod model;
pub mod model_ladder;
pub mod nongeometric;
pub mod params;
mod pose_fit;
pub mod pose_map;
pub mod position_ladder;
pub mod presets;
pub mod prior;
pub mod projection;
pub mod recheck;
pub mod refined_terms;
pub mod regions;
mod term_cv;
mod term_elimination;
mod term_fit;
pub mod term_model;
pub mod term_range;
pub mod term_report;
pub mod term_selection;
pub mod term_uncertainty;
pub mod term_validate;
pub mod tracker_csv;
pub mod tracker_pose;
pub mod uncertainty;
pub mod weights;

pub use model::{choose_conventions, Convention, Joint, KinematicsError, RobotModel};
pub use params::{CalibratedModel, Instrument, ParamKind, ParamLayout};
