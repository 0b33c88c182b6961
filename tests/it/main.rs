//! One integration-test binary: the real server over HTTP, module per area.

mod auth;
mod hostile;
mod idempotency;
mod jobs;
mod openapi;
mod ops;
mod poses;
mod restart;
mod robots;
mod support;
