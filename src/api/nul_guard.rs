//! No string with a NUL character gets past the edge: PostgreSQL cannot
//! store one in text (it answered 500), SQLite would store what no other
//! tool reads back. Path parameters and query parameters are checked here,
//! before any handler, and answered 422 naming the parameter; JSON bodies
//! are checked where they are parsed (`schema::nul::json_nul_field`).

use super::error::ApiError;
use axum::extract::{MatchedPath, Request};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use crate::schema::nul::NUL_MESSAGE;

pub async fn layer(req: Request, next: Next) -> Response {
    let template = req.extensions().get::<MatchedPath>().map(|m| m.as_str());
    if let Some(field) = path_nul_field(req.uri().path(), template) {
        return ApiError::invalid(field, NUL_MESSAGE).into_response();
    }
    if let Some(field) = req.uri().query().and_then(query_nul_field) {
        return ApiError::invalid(field, NUL_MESSAGE).into_response();
    }
    next.run(req).await
}

/// The 422 for a JSON body holding a NUL in the string at `field`.
pub fn nul_error(field: String) -> ApiError {
    ApiError::invalid(field, NUL_MESSAGE)
}

fn decodes_to_nul(text: &str) -> bool {
    percent_decoded(text).contains(&0)
}

/// The path parameter (named after the route's template) holding a NUL.
fn path_nul_field(path: &str, template: Option<&str>) -> Option<String> {
    if !path.contains("%00") && !path.contains('\0') {
        return None;
    }
    let names: Vec<&str> = template.map(|t| t.split('/').collect()).unwrap_or_default();
    path.split('/').enumerate().find_map(|(i, segment)| {
        decodes_to_nul(segment).then(|| {
            names
                .get(i)
                .and_then(|n| n.strip_prefix('{'))
                .and_then(|n| n.strip_suffix('}'))
                .unwrap_or("path")
                .to_string()
        })
    })
}

/// The query parameter whose name or value holds a NUL.
fn query_nul_field(query: &str) -> Option<String> {
    query.split('&').find_map(|pair| {
        let (name, value) = pair.split_once('=').unwrap_or((pair, ""));
        (decodes_to_nul(name) || decodes_to_nul(value)).then(|| {
            let name = String::from_utf8_lossy(&percent_decoded(name)).replace('\0', "");
            if name.is_empty() {
                "query".to_string()
            } else {
                name
            }
        })
    })
}

/// `%XX` decoded (`+` left as it is: only NUL matters here).
fn percent_decoded(text: &str) -> Vec<u8> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                i += 3;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schema::nul::json_nul_field;

    #[test]
    fn nul_is_found_and_named_wherever_it_is() {
        assert_eq!(
            path_nul_field("/v1/jobs/ab%00c", Some("/v1/jobs/{id}")).as_deref(),
            Some("id")
        );
        assert_eq!(path_nul_field("/v1/jobs/abc", Some("/v1/jobs/{id}")), None);
        assert_eq!(
            query_nul_field("limit=5&cursor=x%00").as_deref(),
            Some("cursor")
        );
        assert_eq!(query_nul_field("limit=5"), None);
        assert_eq!(
            json_nul_field(br#"{"name":"ok","tags":[{"x":"a\u0000"}]}"#).as_deref(),
            Some("tags[0].x")
        );
        assert_eq!(
            json_nul_field(br#"{"name":"a\\u0000"}"#),
            None,
            "an escaped backslash"
        );
        assert_eq!(json_nul_field(br#"{"model":"r"}"#), None);
    }
}
