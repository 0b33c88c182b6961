//! One integration-test binary: the real server over HTTP, module per area.

pub(crate) mod accuracy;
pub(crate) mod auth;
pub(crate) mod camera_reuse;
pub(crate) mod e2e;
pub(crate) mod e2e_points;
pub(crate) mod hostile;
pub(crate) mod hostile_uploads;
pub(crate) mod http_errors;
pub(crate) mod idempotency;
pub(crate) mod job_list;
pub(crate) mod jobs;
pub(crate) mod openapi;
pub(crate) mod ops;
pub(crate) mod poses;
pub(crate) mod raw_http;
pub(crate) mod restart;
pub(crate) mod robots;
pub(crate) mod store_ops;
pub(crate) mod support;
pub(crate) mod test_db;
pub(crate) mod timeouts;
