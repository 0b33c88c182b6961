//! The reserved lane (`--reserved-connections`): a connection admitted past
//! the cap while every other connection was in a request serves only the
//! probes and authenticated requests, so health checks and token holders
//! still get in while anonymous clients fill the ordinary places.

use axum::extract::Request;
use axum::http::StatusCode;
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::auth::Principal;
use super::error::ApiError;
use crate::listen::registry::{ConnRef, Lane};

/// Seconds a client refused on the reserved lane should wait.
const RESERVED_RETRY_AFTER_SECS: u64 = 1;
/// Paths the reserved lane always serves.
const PROBES: [&str; 2] = ["/healthz", "/readyz"];

/// Runs inside `auth`, which has named the principal by then.
pub async fn layer(req: Request, next: Next) -> Response {
    let reserved = req
        .extensions()
        .get::<ConnRef>()
        .is_some_and(|c| c.lane == Lane::Reserved);
    let allowed = !reserved
        || PROBES.contains(&req.uri().path())
        || matches!(
            req.extensions().get::<Principal>(),
            Some(Principal::Token { .. })
        );
    if allowed {
        return next.run(req).await;
    }
    ApiError {
        retry_after_secs: Some(RESERVED_RETRY_AFTER_SECS),
        ..ApiError::new(
            StatusCode::SERVICE_UNAVAILABLE,
            "too-many-connections",
            "every connection is in a request; this one is reserved for health checks and \
             authenticated requests (server options --max-connections, --reserved-connections); \
             retry later",
        )
    }
    .into_response()
}
