//! Robot kinematic model, identification and compensation (method.md §5–8).

pub mod model;
pub mod presets;

pub use model::{choose_conventions, Convention, Joint, KinematicsError, RobotModel};
