//! `Idempotency-Key` on writes: the first request with a key runs and its
//! response is stored with the request's fingerprint (method, path, body
//! digest: `fingerprint.rs`), per principal and key. A retry of the same
//! request gets the stored response (`Idempotent-Replayed: true`) and changes
//! nothing; the key sent with a different request is a 422. A key whose first
//! request is still running answers 409; the running request holds the key
//! under a lease it renews, so a key whose process died frees itself.
//! Responses that a retry may improve on (5xx, 429) are not stored, nor
//! responses to requests whose body was not read to its end. Every writing
//! transaction of a keyed request marks its key in that transaction
//! (`store::write_guard`): a key whose server died after the write
//! committed is answered 409 `idempotent-request-done`, never run again.

use std::future::Future;
use std::time::Duration;

use axum::body::Body;
use axum::extract::{Request, State};
use axum::http::{HeaderName, HeaderValue, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::auth::Principal;
use super::error::ApiError;
use super::fingerprint::{digest_body, BodyRead, BodyTap, DigestError, Fingerprinter};
use super::AppState;
use crate::domain::{new_id, now_unix_ms, IdempotencyClaim, IdempotencyScope, StoredResponse};
use crate::store::write_guard;

pub const HEADER: &str = "idempotency-key";
const MAX_KEY_LEN: usize = 255;
/// Largest response body kept for replay.
const MAX_STORED_BODY: usize = 16 * 1024 * 1024;
/// Response headers worth replaying.
const KEPT_HEADERS: [&str; 3] = ["content-type", "location", "retry-after"];
/// Shortest lease on a key in flight: renewals cost a write each, and a
/// lease lapsing under a slow database would let a retry run twice.
const MIN_LEASE: Duration = Duration::from_secs(5);
/// Renewals of the key's lease per lease length, so one late renewal does not lose it.
const LEASE_RENEWALS: u32 = 3;
const MIN_RENEW_INTERVAL: Duration = Duration::from_millis(100);
/// What is read of a body its handler left unread, to see it end (a
/// multipart epilogue); a larger remainder leaves the answer unstored.
const MAX_DRAIN_BYTES: usize = 64 * 1024;
const MAX_DRAIN_WAIT: Duration = Duration::from_secs(1);

pub async fn layer(State(state): State<AppState>, req: Request, next: Next) -> Response {
    let is_write = matches!(
        *req.method(),
        Method::POST | Method::PUT | Method::PATCH | Method::DELETE
    );
    let key = req.headers().get(HEADER).cloned();
    let (true, Some(key)) = (is_write, key) else {
        return next.run(req).await;
    };
    let key = match key.to_str() {
        Ok(k)
            if !k.is_empty()
                && k.len() <= MAX_KEY_LEN
                && k.bytes().all(|b| b.is_ascii_graphic()) =>
        {
            k.to_string()
        }
        _ => {
            return ApiError::invalid(
                "Idempotency-Key",
                format!("1 to {MAX_KEY_LEN} printable ASCII characters"),
            )
            .into_response()
        }
    };
    let principal = req
        .extensions()
        .get::<Principal>()
        .map(Principal::key)
        .unwrap_or_else(|| "anonymous".into());
    let scope = IdempotencyScope {
        principal,
        method: req.method().to_string(),
        path: req.uri().path().to_string(),
        key,
        holder: new_id(),
    };
    let lease = state.config.lease().max(MIN_LEASE);
    let (parts, body) = req.into_parts();
    let fingerprint = Fingerprinter::new(&parts);
    match state
        .store
        .claim_idempotency(&scope, lease_until(lease))
        .await
    {
        Err(e) => ApiError::from(e).into_response(),
        Ok(IdempotencyClaim::InFlight) => ApiError::conflict(format!(
            "a request with this Idempotency-Key is still running (if its server died, \
             the key is free again within {} s)",
            lease.as_secs()
        ))
        .into_response(),
        Ok(IdempotencyClaim::Lost) => ApiError::new(
            StatusCode::CONFLICT,
            "idempotent-request-done",
            "the request with this Idempotency-Key was carried out, but its server stopped \
             before storing the answer; it is not run again: read the resource to see the result",
        )
        .into_response(),
        Ok(IdempotencyClaim::OtherRequest { method, path }) => {
            reused(format!("it was used for {method} {path}")).into_response()
        }
        Ok(IdempotencyClaim::Done {
            fingerprint: None,
            response,
        }) => replay(response),
        Ok(IdempotencyClaim::Done {
            fingerprint: Some(expected),
            response,
        }) => {
            let limit = state.config.max_archive_bytes;
            match digest_body(body, fingerprint, limit).await {
                Ok(actual) if actual == expected => replay(response),
                Ok(_) => {
                    reused("it was used for a request with another body".into()).into_response()
                }
                Err(DigestError::TooLarge) => {
                    ApiError::too_large("max_archive_bytes", limit).into_response()
                }
                Err(DigestError::Read(e)) => {
                    ApiError::malformed("body", format!("reading body: {e}")).into_response()
                }
            }
        }
        Ok(IdempotencyClaim::Fresh) => {
            let tap = BodyTap::new(body, fingerprint);
            let req = Request::from_parts(parts, tap.body());
            // Every writing transaction of the request marks the key (crash safety).
            let run = write_guard::guarded(scope.clone(), next.run(req));
            let response = run_holding_lease(&state, &scope, lease, run).await;
            if state.config.test_crash_before_idempotent_answer {
                tracing::warn!("test hook: aborting before the idempotent answer is stored");
                std::process::abort();
            }
            let read = tap.finish(MAX_DRAIN_BYTES, MAX_DRAIN_WAIT).await;
            record(&state, &scope, read, response).await
        }
    }
}

/// 422 for a key that belongs to another request.
fn reused(why: String) -> ApiError {
    ApiError::invalid(
        "Idempotency-Key",
        format!("{why}; a key identifies one request: send a new key for a new request"),
    )
}

fn lease_until(lease: Duration) -> i64 {
    now_unix_ms() + lease.as_millis() as i64
}

/// Runs the request while renewing the key's lease, so the key stays held
/// as long as this process works on it, and no longer if the process dies.
async fn run_holding_lease(
    state: &AppState,
    scope: &IdempotencyScope,
    lease: Duration,
    run: impl Future<Output = Response>,
) -> Response {
    let every = (lease / LEASE_RENEWALS).max(MIN_RENEW_INTERVAL);
    let mut tick = tokio::time::interval_at(tokio::time::Instant::now() + every, every);
    tokio::pin!(run);
    loop {
        tokio::select! {
            response = &mut run => return response,
            _ = tick.tick() => {
                if let Err(e) = state.store.renew_idempotency(scope, lease_until(lease)).await {
                    tracing::warn!(error = %e, "renewing an Idempotency-Key lease failed");
                }
            }
        }
    }
}

async fn record(
    state: &AppState,
    scope: &IdempotencyScope,
    read: BodyRead,
    response: Response,
) -> Response {
    let status = response.status();
    let retryable = status.is_server_error() || status == StatusCode::TOO_MANY_REQUESTS;
    // Only an answer to the whole request is its answer: one to a body cut
    // short (client gone, idle timeout) would refuse the full retry. A
    // success that left some body unread did act, so it is kept (without a
    // fingerprint, the body being unknown).
    let fingerprint = match read {
        _ if retryable => None,
        BodyRead::Complete(f) => Some(Some(f)),
        BodyRead::Incomplete if status.is_success() => Some(None),
        BodyRead::Incomplete | BodyRead::Failed => None,
    };
    let (parts, body) = response.into_parts();
    let bytes = match axum::body::to_bytes(body, MAX_STORED_BODY).await {
        Ok(b) => b,
        Err(e) => {
            let _ = state.store.abandon_idempotency(scope).await;
            return ApiError::internal(format!("buffering response: {e}")).into_response();
        }
    };
    let outcome = if let Some(fingerprint) = fingerprint {
        let headers = KEPT_HEADERS
            .iter()
            .filter_map(|h| {
                parts
                    .headers
                    .get(*h)
                    .and_then(|v| v.to_str().ok())
                    .map(|v| (h.to_string(), v.to_string()))
            })
            .collect();
        let stored = StoredResponse {
            status: status.as_u16(),
            headers,
            body: bytes.to_vec(),
        };
        state
            .store
            .complete_idempotency(scope, fingerprint.as_deref(), &stored)
            .await
    } else {
        state.store.abandon_idempotency(scope).await
    };
    if let Err(e) = outcome {
        tracing::error!(error = %e, "storing the idempotent response failed");
    }
    Response::from_parts(parts, Body::from(bytes))
}

fn replay(stored: StoredResponse) -> Response {
    let mut response = Response::new(Body::from(stored.body));
    *response.status_mut() = StatusCode::from_u16(stored.status).unwrap_or(StatusCode::OK);
    let headers = response.headers_mut();
    for (name, value) in stored.headers {
        if let (Ok(n), Ok(v)) = (HeaderName::try_from(name), HeaderValue::try_from(value)) {
            headers.insert(n, v);
        }
    }
    headers.insert("idempotent-replayed", HeaderValue::from_static("true"));
    response
}
