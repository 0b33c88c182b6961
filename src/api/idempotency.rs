//! `Idempotency-Key` on writes: the first request with a key runs and its
//! response is stored (per principal, method, path and key); a replay gets the
//! stored response (`Idempotent-Replayed: true`) and changes nothing. A key
//! whose first request is still running answers 409. Responses that a retry
//! may improve on (5xx, 429) are not stored.

use axum::body::Body;
use axum::extract::{Request, State};
use axum::http::{HeaderName, HeaderValue, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::auth::Principal;
use super::error::ApiError;
use super::AppState;
use crate::domain::{IdempotencyClaim, IdempotencyScope, StoredResponse};

pub const HEADER: &str = "idempotency-key";
const MAX_KEY_LEN: usize = 255;
/// Largest response body kept for replay.
const MAX_STORED_BODY: usize = 16 * 1024 * 1024;
/// Response headers worth replaying.
const KEPT_HEADERS: [&str; 3] = ["content-type", "location", "retry-after"];

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
    };
    match state.store.claim_idempotency(&scope).await {
        Err(e) => ApiError::from(e).into_response(),
        Ok(IdempotencyClaim::InFlight) => {
            ApiError::conflict("a request with this Idempotency-Key is still running")
                .into_response()
        }
        Ok(IdempotencyClaim::Replay(stored)) => replay(stored),
        Ok(IdempotencyClaim::Fresh) => {
            let response = next.run(req).await;
            record(&state, &scope, response).await
        }
    }
}

async fn record(state: &AppState, scope: &IdempotencyScope, response: Response) -> Response {
    let status = response.status();
    let keep = !(status.is_server_error() || status == StatusCode::TOO_MANY_REQUESTS);
    let (parts, body) = response.into_parts();
    let bytes = match axum::body::to_bytes(body, MAX_STORED_BODY).await {
        Ok(b) => b,
        Err(e) => {
            let _ = state.store.abandon_idempotency(scope).await;
            return ApiError::internal(format!("buffering response: {e}")).into_response();
        }
    };
    let outcome = if keep {
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
        state.store.complete_idempotency(scope, &stored).await
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
