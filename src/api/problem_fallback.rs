//! The last line of the error contract: an error response that did not come
//! from [`ApiError`] (an axum extractor's plain-text rejection, such as a
//! path segment that is not UTF-8) is rewritten as problem+json with the
//! same status, its text kept as `detail`.

use axum::extract::Request;
use axum::http::{header, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::error::{ApiError, PROBLEM_JSON};

/// Longest rejection text kept as the problem's detail.
const MAX_DETAIL_BYTES: usize = 1024;

pub async fn layer(req: Request, next: Next) -> Response {
    let response = next.run(req).await;
    let status = response.status();
    let is_problem = response
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(PROBLEM_JSON.as_bytes()));
    // The fleet pages answer their own errors as HTML, for a person.
    let is_html = response
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(b"text/html"));
    if !(status.is_client_error() || status.is_server_error()) || is_problem || is_html {
        return response;
    }
    let text = match axum::body::to_bytes(response.into_body(), 64 * MAX_DETAIL_BYTES).await {
        Ok(bytes) => String::from_utf8_lossy(&bytes).trim().to_string(),
        Err(_) => String::new(),
    };
    let mut detail: String = text.chars().take(MAX_DETAIL_BYTES).collect();
    if detail.is_empty() {
        detail = status.canonical_reason().unwrap_or("error").to_string();
    }
    let error = if status == StatusCode::BAD_REQUEST {
        ApiError::malformed(named_field(&detail).unwrap_or("request"), detail.clone())
    } else if status.is_server_error() {
        ApiError::internal(detail)
    } else {
        ApiError::new(status, "rejected", detail)
    };
    error.into_response()
}

/// The parameter an axum rejection names in backquotes ("Invalid UTF-8 in `id`").
fn named_field(text: &str) -> Option<&str> {
    let (_, rest) = text.split_once(" in `")?;
    rest.split('`').next().filter(|f| !f.is_empty())
}
