//! One integration-test binary: the real server over HTTP, module per area.

mod auth;
mod hostile;
mod hostile_uploads;
mod idempotency;
mod jobs;
mod openapi;
mod ops;
mod poses;
mod restart;
mod robots;
mod store_ops;
pub(crate) mod support;
pub(crate) mod test_db;
