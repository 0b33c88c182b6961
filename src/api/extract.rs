//! Request extractors whose failures are [`ApiError`]s (problem+json naming
//! the field) instead of axum's plain-text rejections.

use axum::body::Bytes;
use axum::extract::{FromRequest, FromRequestParts, Request};
use axum::http::header::CONTENT_TYPE;
use axum::http::request::Parts;
use serde::de::DeserializeOwned;
use serde::Deserialize;

use super::error::ApiError;
use super::AppState;
use crate::domain::{InvalidSerial, JobKind, JobState, Serial};
use crate::store::JobFilter;

/// Default page size of listings.
pub const DEFAULT_LIMIT: i64 = 100;
/// Largest page size.
pub const MAX_LIMIT: i64 = 1000;

/// A JSON body parsed with the failing field's path in the error.
pub struct ApiJson<T>(pub T);

/// Like [`ApiJson`], but an empty body gives `T::default()`.
pub struct OptionalJson<T>(pub T);

impl<T: DeserializeOwned> FromRequest<AppState> for ApiJson<T> {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &AppState) -> Result<Self, ApiError> {
        let bytes = json_bytes(req, state).await?;
        parse_json(&bytes).map(ApiJson)
    }
}

impl<T: DeserializeOwned + Default> FromRequest<AppState> for OptionalJson<T> {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &AppState) -> Result<Self, ApiError> {
        let has_type = req.headers().contains_key(CONTENT_TYPE);
        let bytes = if has_type {
            json_bytes(req, state).await?
        } else {
            read_bytes(req, state).await?
        };
        if bytes.iter().all(|b| b.is_ascii_whitespace()) {
            return Ok(OptionalJson(T::default()));
        }
        if !has_type {
            return Err(ApiError::unsupported_media(
                "send Content-Type: application/json",
            ));
        }
        parse_json(&bytes).map(OptionalJson)
    }
}

pub fn is_json(content_type: Option<&str>) -> bool {
    content_type
        .and_then(|v| v.split(';').next())
        .map(|m| {
            let m = m.trim().to_ascii_lowercase();
            m == "application/json" || (m.starts_with("application/") && m.ends_with("+json"))
        })
        .unwrap_or(false)
}

async fn json_bytes(req: Request, state: &AppState) -> Result<Bytes, ApiError> {
    let ct = req
        .headers()
        .get(CONTENT_TYPE)
        .and_then(|v| v.to_str().ok());
    if !is_json(ct) {
        return Err(ApiError::unsupported_media(
            "expected Content-Type: application/json",
        ));
    }
    read_bytes(req, state).await
}

async fn read_bytes(req: Request, state: &AppState) -> Result<Bytes, ApiError> {
    read_limited(req, state.config.max_json_bytes, "max_json_bytes").await
}

/// Reads a whole (small) body, refusing more than `limit` bytes with a 413
/// naming `limit_name`.
pub async fn read_limited(
    req: Request,
    limit: u64,
    limit_name: &'static str,
) -> Result<Bytes, ApiError> {
    use futures_util::StreamExt;
    if content_length(req.headers()).is_some_and(|n| n > limit) {
        return Err(ApiError::too_large(limit_name, limit));
    }
    let mut stream = req.into_body().into_data_stream();
    let mut buf = Vec::new();
    while let Some(chunk) = stream.next().await {
        let chunk = chunk.map_err(|e| ApiError::malformed("body", format!("reading body: {e}")))?;
        if (buf.len() + chunk.len()) as u64 > limit {
            return Err(ApiError::too_large(limit_name, limit));
        }
        buf.extend_from_slice(&chunk);
    }
    Ok(Bytes::from(buf))
}

pub fn content_length(headers: &axum::http::HeaderMap) -> Option<u64> {
    headers
        .get(axum::http::header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse().ok())
}

/// Parses JSON; syntax errors are 400, type/shape errors and strings with
/// a NUL character 422 naming the field.
pub fn parse_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    if let Some(field) = crate::schema::nul::json_nul_field(bytes) {
        return Err(super::nul_guard::nul_error(field));
    }
    let de = &mut serde_json::Deserializer::from_slice(bytes);
    serde_path_to_error::deserialize(de).map_err(|err| {
        let path = err.path().to_string();
        let inner = err.into_inner();
        let message = strip_position(&inner.to_string());
        // serde_json reports a value of the wrong kind for an enum (a
        // number, a bool, an array) as the syntax error "expected value";
        // if the document itself parses, it is the value that is wrong.
        let wrong_value = inner.classify() == serde_json::error::Category::Syntax
            && message == "expected value"
            && serde_json::from_slice::<serde::de::IgnoredAny>(bytes).is_ok();
        // A fixed-size array (`[x, y, z]`) given too many elements ends in
        // serde_json's "trailing characters" at that field's path: the
        // document parses, the value has the wrong length.
        let too_long = inner.classify() == serde_json::error::Category::Syntax
            && message.starts_with("trailing characters")
            && path != "."
            && serde_json::from_slice::<serde::de::IgnoredAny>(bytes).is_ok();
        match inner.classify() {
            _ if too_long => ApiError::invalid(path, "too many elements for this array"),
            _ if wrong_value => {
                let field = if path == "." { "body".into() } else { path };
                ApiError::invalid(
                    field,
                    "invalid type: expected one of the documented strings",
                )
            }
            serde_json::error::Category::Data => {
                let field = missing_field(&message)
                    .map(|m| {
                        if path == "." {
                            m.to_string()
                        } else {
                            format!("{path}.{m}")
                        }
                    })
                    .unwrap_or_else(|| if path == "." { "body".into() } else { path });
                ApiError::invalid(field, message)
            }
            _ => ApiError::malformed("body", format!("malformed JSON: {message}")),
        }
    })
}

fn missing_field(message: &str) -> Option<&str> {
    let rest = message.strip_prefix("missing field `")?;
    rest.split('`').next()
}

fn strip_position(message: &str) -> String {
    match message.find(" at line ") {
        Some(i) => message[..i].to_string(),
        None => message.to_string(),
    }
}

/// The `{serial}` segment of a robot path, validated once ([`Serial`]): a
/// bad one (`.`, `..`, foreign characters) is a 422 naming `serial`, so no
/// robot can be stored under a name no client can address again.
pub struct SerialPath(pub Serial);

impl<S: Send + Sync> FromRequestParts<S> for SerialPath {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let params = axum::extract::RawPathParams::from_request_parts(parts, state)
            .await
            .map_err(|e| ApiError::malformed("path", e.body_text()))?;
        let raw = params
            .iter()
            .find(|(name, _)| *name == "serial")
            .map(|(_, value)| value)
            .ok_or_else(|| ApiError::internal("route without a {serial} segment"))?;
        Ok(SerialPath(Serial::parse(raw)?))
    }
}

impl From<InvalidSerial> for ApiError {
    fn from(e: InvalidSerial) -> ApiError {
        ApiError::invalid("serial", e.to_string())
    }
}

/// `?limit=&cursor=` of listing endpoints.
#[derive(Debug, Clone)]
pub struct Paging {
    pub limit: i64,
    pub cursor: Option<String>,
}

#[derive(Deserialize)]
struct RawPaging {
    limit: Option<String>,
    cursor: Option<String>,
}

impl<S: Send + Sync> FromRequestParts<S> for Paging {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, _state: &S) -> Result<Self, ApiError> {
        let raw: RawPaging = match parts.uri.query() {
            None => RawPaging {
                limit: None,
                cursor: None,
            },
            Some(q) => serde_urlencoded_like(q)?,
        };
        let limit = match raw.limit {
            None => DEFAULT_LIMIT,
            Some(s) => match s.parse::<i64>() {
                Ok(n) if (1..=MAX_LIMIT).contains(&n) => n,
                _ => {
                    return Err(ApiError::invalid(
                        "limit",
                        format!("an integer 1 to {MAX_LIMIT}"),
                    ))
                }
            },
        };
        if raw.cursor.as_ref().is_some_and(|c| c.len() > 200) {
            return Err(ApiError::invalid("cursor", "too long"));
        }
        Ok(Paging {
            limit,
            cursor: raw.cursor.filter(|c| !c.is_empty()),
        })
    }
}

fn serde_urlencoded_like(query: &str) -> Result<RawPaging, ApiError> {
    query_of::<RawPaging>(query)
}

/// The query string read into `T` (unknown parameters ignored).
pub(crate) fn query_of<T: DeserializeOwned>(query: &str) -> Result<T, ApiError> {
    let uri: axum::http::Uri = format!("/?{query}")
        .parse()
        .map_err(|_| ApiError::malformed("query", "unreadable query string"))?;
    axum::extract::Query::<T>::try_from_uri(&uri)
        .map(|q| q.0)
        .map_err(|e| ApiError::malformed("query", e.body_text()))
}

/// `?state=&serial=&kind=` of `GET /v1/jobs`, each checked (422 naming it).
#[derive(Debug, Clone)]
pub struct JobQuery(pub JobFilter);

#[derive(Deserialize)]
struct RawJobQuery {
    state: Option<String>,
    serial: Option<String>,
    kind: Option<String>,
}

impl<S: Send + Sync> FromRequestParts<S> for JobQuery {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, _state: &S) -> Result<Self, ApiError> {
        let raw = match parts.uri.query() {
            None => RawJobQuery {
                state: None,
                serial: None,
                kind: None,
            },
            Some(q) => query_of::<RawJobQuery>(q)?,
        };
        let state = match raw.state.as_deref() {
            None | Some("") => None,
            Some(s) => Some(JobState::parse(s).ok_or_else(|| {
                let all: Vec<&str> = JobState::ALL.iter().map(|s| s.as_str()).collect();
                ApiError::invalid("state", format!("one of {}", all.join(", ")))
            })?),
        };
        let serial = match raw.serial.as_deref() {
            None | Some("") => None,
            Some(s) => Some(
                Serial::parse(s)
                    .map_err(|e| ApiError::invalid("serial", e.to_string()))?
                    .to_string(),
            ),
        };
        let kind = match raw.kind.as_deref() {
            None | Some("") => None,
            Some(k) => Some(JobKind::parse(k).ok_or_else(|| {
                ApiError::invalid("kind", format!("one of {}", JobKind::names()))
            })?),
        };
        Ok(JobQuery(JobFilter {
            state,
            serial,
            kind,
        }))
    }
}
