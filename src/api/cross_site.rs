//! Cross-site writes are refused in every mode (anonymous mode included,
//! where any web page the operator visits could otherwise post to the
//! loopback service): a state-changing request whose `Sec-Fetch-Site` says
//! `cross-site`, or whose `Origin` is `null` or names another host than the
//! request's `Host`, is answered 403. Programs (the CLI, curl, scripts)
//! send neither header and are not affected. And a write to `/v1/` may not
//! carry a body of the types a cross-site HTML form sends without asking
//! (`application/x-www-form-urlencoded`, `text/plain`): 415.

use axum::extract::Request;
use axum::http::{header, HeaderMap, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::error::ApiError;

const SEC_FETCH_SITE: &str = "sec-fetch-site";
/// Body types a form on another site can post without a CORS preflight.
const FORM_TYPES: [&str; 2] = ["application/x-www-form-urlencoded", "text/plain"];

pub async fn layer(req: Request, next: Next) -> Response {
    let writes = !matches!(
        *req.method(),
        Method::GET | Method::HEAD | Method::OPTIONS | Method::TRACE
    );
    if writes {
        if let Err(e) = check_site(req.headers(), req.uri().authority().map(|a| a.as_str())) {
            return e.into_response();
        }
        if req.uri().path().starts_with("/v1/") {
            if let Err(e) = check_body_type(req.headers()) {
                return e.into_response();
            }
        }
    }
    next.run(req).await
}

fn cross_site(detail: String) -> ApiError {
    ApiError::new(StatusCode::FORBIDDEN, "cross-site", detail)
}

/// The request comes from this site, or from no web page at all.
fn check_site(headers: &HeaderMap, target_authority: Option<&str>) -> Result<(), ApiError> {
    let site = headers.get(SEC_FETCH_SITE).and_then(|v| v.to_str().ok());
    if site.is_some_and(|s| s.eq_ignore_ascii_case("cross-site")) {
        return Err(cross_site(
            "a state-changing request from another site (Sec-Fetch-Site: cross-site) is refused"
                .into(),
        ));
    }
    if site.is_some_and(|s| s.eq_ignore_ascii_case("same-origin") || s.eq_ignore_ascii_case("none"))
    {
        return Ok(());
    }
    let Some(origin) = headers.get(header::ORIGIN) else {
        return Ok(());
    };
    let origin = origin.to_str().unwrap_or("null").trim();
    let host = target_authority.or_else(|| headers.get(header::HOST).and_then(|v| v.to_str().ok()));
    match (origin_authority(origin), host) {
        (Some((scheme, authority)), Some(host))
            if normalise(&authority, scheme) == normalise(host, scheme) =>
        {
            Ok(())
        }
        _ => Err(cross_site(format!(
            "a state-changing request from origin {origin:?} to host {:?} is refused \
             (Origin must name this service)",
            host.unwrap_or_default()
        ))),
    }
}

/// `scheme://authority` of an `Origin` value (`None` for `null` or junk).
fn origin_authority(origin: &str) -> Option<(&'static str, String)> {
    let (scheme, rest) = origin.split_once("://")?;
    let scheme = match scheme.to_ascii_lowercase().as_str() {
        "http" => "http",
        "https" => "https",
        _ => return None,
    };
    (!rest.is_empty() && !rest.contains('/')).then(|| (scheme, rest.to_string()))
}

/// `host[:port]` in lower case without the scheme's default port.
fn normalise(authority: &str, scheme: &str) -> String {
    let lower = authority.to_ascii_lowercase();
    let default = if scheme == "https" { ":443" } else { ":80" };
    lower
        .strip_suffix(default)
        .map(str::to_string)
        .unwrap_or(lower)
}

fn check_body_type(headers: &HeaderMap) -> Result<(), ApiError> {
    let Some(ct) = headers.get(header::CONTENT_TYPE) else {
        return Ok(());
    };
    let media = ct
        .to_str()
        .unwrap_or("")
        .split(';')
        .next()
        .unwrap_or("")
        .trim()
        .to_ascii_lowercase();
    if FORM_TYPES.contains(&media.as_str()) {
        return Err(ApiError::unsupported_media(format!(
            "Content-Type {media} is not accepted on the API: send application/json \
             (or the upload's own type)"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use axum::http::HeaderValue;

    fn headers(pairs: &[(&'static str, &'static str)]) -> HeaderMap {
        let mut h = HeaderMap::new();
        for (k, v) in pairs {
            h.insert(*k, HeaderValue::from_static(v));
        }
        h
    }

    #[test]
    fn same_origin_and_headerless_pass_other_sites_do_not() {
        let ok = |pairs| check_site(&headers(pairs), None).is_ok();
        assert!(ok(&[("host", "127.0.0.1:8080")]));
        assert!(ok(&[
            ("host", "127.0.0.1:8080"),
            ("origin", "http://127.0.0.1:8080")
        ]));
        assert!(ok(&[
            ("host", "robocal.example"),
            ("origin", "https://robocal.example:443")
        ]));
        assert!(ok(&[
            ("host", "x"),
            ("sec-fetch-site", "same-origin"),
            ("origin", "http://y")
        ]));
        assert!(!ok(&[
            ("host", "127.0.0.1:8080"),
            ("origin", "http://evil.example")
        ]));
        assert!(!ok(&[("host", "127.0.0.1:8080"), ("origin", "null")]));
        assert!(!ok(&[
            ("host", "127.0.0.1:8080"),
            ("sec-fetch-site", "cross-site")
        ]));
        assert!(!ok(&[
            ("host", "127.0.0.1:8080"),
            ("origin", "http://127.0.0.1:8081")
        ]));
    }
}
