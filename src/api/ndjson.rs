//! Answers streamed as newline-delimited JSON (`Accept:
//! application/x-ndjson`, api.md "Results"): `compensate` and `filter` send
//! one line per target as they are solved, so a 10,000-target answer is
//! never held in memory whole (issue "Deploy the result", Speed).

use std::convert::Infallible;

use axum::body::{Body, Bytes};
use axum::http::{header, HeaderMap, HeaderValue};
use axum::response::{IntoResponse, Response};
use futures_util::{Stream, StreamExt};

/// The media type of a streamed answer: one JSON document per line.
pub const NDJSON: &str = "application/x-ndjson";

/// Whether the client asked for the streamed answer (`Accept` names
/// `application/x-ndjson`); any other `Accept` gets the one JSON document.
pub fn wanted(headers: &HeaderMap) -> bool {
    headers
        .get_all(header::ACCEPT)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(','))
        .any(|media| media.split(';').next().unwrap_or("").trim() == NDJSON)
}

/// A `200` whose body is the lines as they come.
pub fn response<S>(lines: S) -> Response
where
    S: Stream<Item = Vec<u8>> + Send + 'static,
{
    let body = Body::from_stream(lines.map(|chunk| Ok::<_, Infallible>(Bytes::from(chunk))));
    (
        [(header::CONTENT_TYPE, HeaderValue::from_static(NDJSON))],
        body,
    )
        .into_response()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn accept(value: &str) -> HeaderMap {
        let mut headers = HeaderMap::new();
        headers.insert(header::ACCEPT, HeaderValue::from_str(value).unwrap());
        headers
    }

    #[test]
    fn only_an_accept_naming_ndjson_streams() {
        assert!(wanted(&accept("application/x-ndjson")));
        assert!(wanted(&accept(
            "application/problem+json, application/x-ndjson;q=0.9"
        )));
        assert!(!wanted(&accept("application/json")));
        assert!(!wanted(&accept("*/*")));
        assert!(!wanted(&HeaderMap::new()));
    }
}
