//! robocal: the calibration service. The numerics live in the `robocal-calib`
//! crate (`calib/`), which knows nothing of HTTP, databases or jobs.
//!
//! Data flows one way: an upload lands in [`api`], is validated into the
//! [`schema`] types, and stored through [`store`]; a job row is claimed by
//! [`jobs`], which loads the inputs, calls [`pipeline::run`] on a blocking
//! thread, and stores the outcome.
pub use robocal_calib as calib;

pub mod api;
pub mod cli;
pub mod config;
pub mod domain;
pub mod export;
pub mod housekeeping;
pub mod imaging;
pub mod jobs;
pub mod listen;
pub mod metrics;
pub mod outbox;
pub mod pipeline;
pub mod print;
pub mod report;
pub mod schema;
pub mod server;
pub mod service;
pub mod store;
#[cfg(feature = "testkit")]
pub mod testkit;
