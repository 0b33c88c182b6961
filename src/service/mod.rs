//! The service layer, between [`crate::api`] (HTTP) and [`crate::store`]
//! (SQL): what the service does with a request once it is parsed. Functions
//! here take the store and typed inputs and answer typed outputs or a
//! [`ServiceError`]; they know neither HTTP nor SQL. Handlers parse, call
//! one function of this module and map its error in one place
//! (`api/error.rs`).

pub mod camera_reuse;
pub mod campaign_plan_doc;
pub mod campaign_plan_extension;
pub mod campaign_plan_inputs;
pub mod campaign_plan_noise;
pub mod campaign_plans;
pub mod checks;
pub mod compensate;
pub mod dataset;
pub mod dataset_intake;
pub mod dataset_warning;
pub mod error;
pub mod evaluate;
pub mod events;
pub mod export;
pub mod filter;
pub mod fleet;
mod fleet_cache;
pub mod images;
pub mod intake;
pub mod release;

pub mod job_events;
pub mod multi_session;
pub mod report_camera;
pub mod report_view;
pub mod results;
pub mod stage_layout;
pub mod staged_images;
pub mod target_stream;
pub mod uncertainty;
pub mod webhooks;
pub mod zip_names;

pub use error::{ServiceError, ServiceResult};
