//! The one error type of the HTTP layer and its mapping to
//! `application/problem+json` (RFC 9457), with `errors: [{field, message}]`
//! naming every invalid field. Every handler returns `Result<_, ApiError>`;
//! this file is the only place a status code is chosen for a failure.

use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use utoipa::ToSchema;

use crate::domain::ControllerMismatch;
use crate::schema::FieldError;
use crate::service::ServiceError;
use crate::store::StoreError;

pub const PROBLEM_JSON: &str = "application/problem+json";

#[derive(Debug)]
pub struct ApiError {
    pub status: StatusCode,
    /// Short machine-readable slug, becomes the problem `type`.
    pub slug: &'static str,
    pub detail: String,
    pub errors: Vec<FieldError>,
    pub retry_after_secs: Option<u64>,
    /// A controller mismatch's two identities (409).
    pub controller: Option<Box<ControllerMismatch>>,
}

/// The problem document, as served.
#[derive(Debug, Serialize, ToSchema)]
pub struct Problem {
    #[serde(rename = "type")]
    pub problem_type: String,
    pub title: String,
    pub status: u16,
    pub detail: String,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<FieldError>,
    /// On a controller mismatch (409): the identity the request expected
    /// and the one recorded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub controller: Option<ControllerMismatch>,
}

impl ApiError {
    pub fn new(status: StatusCode, slug: &'static str, detail: impl Into<String>) -> ApiError {
        ApiError {
            status,
            slug,
            detail: detail.into(),
            errors: vec![],
            retry_after_secs: None,
            controller: None,
        }
    }

    fn with_field(mut self, field: impl Into<String>, message: impl Into<String>) -> ApiError {
        self.errors.push(FieldError::new(field, message));
        self
    }

    /// 422: the document parsed but its values are wrong.
    pub fn validation(errors: Vec<FieldError>) -> ApiError {
        let detail = match errors.first() {
            Some(e) if errors.len() == 1 => format!("{}: {}", e.field, e.message),
            _ => format!("{} fields are invalid", errors.len()),
        };
        ApiError {
            errors,
            ..ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "validation", detail)
        }
    }

    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> ApiError {
        ApiError::validation(vec![FieldError::new(field, message)])
    }

    /// 400: the request cannot be read at all (malformed JSON, multipart, zip).
    pub fn malformed(field: impl Into<String>, message: impl Into<String>) -> ApiError {
        let (field, message) = (field.into(), message.into());
        ApiError::new(
            StatusCode::BAD_REQUEST,
            "malformed",
            format!("{field}: {message}"),
        )
        .with_field(field, message)
    }

    pub fn not_found(what: &str, id: &str) -> ApiError {
        ApiError::new(
            StatusCode::NOT_FOUND,
            "not-found",
            format!("{what} {id:?} not found"),
        )
    }

    /// 404 for a reference inside the body: names the field that holds it.
    pub fn not_found_field(field: &str, message: impl Into<String>) -> ApiError {
        let error = FieldError::new(field, message);
        ApiError {
            errors: vec![error.clone()],
            ..ApiError::new(
                StatusCode::NOT_FOUND,
                "not-found",
                format!("{}: {}", error.field, error.message),
            )
        }
    }

    pub fn conflict(detail: impl Into<String>) -> ApiError {
        ApiError::new(StatusCode::CONFLICT, "conflict", detail)
    }

    /// 413 naming the limit that was exceeded and how to raise it.
    pub fn too_large(limit: &'static str, bytes: u64) -> ApiError {
        let flag = limit.replace('_', "-");
        ApiError::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            "too-large",
            format!("the upload exceeds {limit} = {bytes} bytes (server option --{flag})"),
        )
        .with_field(limit, format!("limit is {bytes} bytes"))
    }

    /// 413 for a multipart part over its fixed size limit.
    pub fn part_too_large(part: &str, bytes: u64) -> ApiError {
        ApiError::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            "too-large",
            format!("the part {part:?} exceeds its limit of {bytes} bytes"),
        )
        .with_field(part, format!("at most {bytes} bytes"))
    }

    pub fn unsupported_media(detail: impl Into<String>) -> ApiError {
        ApiError::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "unsupported-media-type",
            detail,
        )
    }

    pub fn unauthorized(detail: impl Into<String>) -> ApiError {
        ApiError::new(StatusCode::UNAUTHORIZED, "unauthorized", detail)
    }

    pub fn forbidden(detail: impl Into<String>) -> ApiError {
        ApiError::new(StatusCode::FORBIDDEN, "forbidden", detail)
    }

    /// 421: the request names a host this service does not answer for.
    pub fn misdirected(detail: impl Into<String>) -> ApiError {
        ApiError::new(
            StatusCode::MISDIRECTED_REQUEST,
            "misdirected-request",
            detail,
        )
    }

    pub fn queue_full(retry_after_secs: u64) -> ApiError {
        ApiError {
            retry_after_secs: Some(retry_after_secs),
            ..ApiError::new(
                StatusCode::TOO_MANY_REQUESTS,
                "queue-full",
                "the job queue is full; retry later (see Retry-After)",
            )
        }
    }

    /// 500: logged with its cause; the client sees no internals.
    pub fn internal(cause: impl std::fmt::Display) -> ApiError {
        tracing::error!(error = %cause, "internal error");
        ApiError::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "internal",
            "internal error; see the server log",
        )
    }
}

impl From<StoreError> for ApiError {
    fn from(e: StoreError) -> ApiError {
        match e {
            StoreError::NotFound(what) => ApiError::new(
                StatusCode::NOT_FOUND,
                "not-found",
                format!("{what} not found"),
            ),
            StoreError::Conflict(detail) => ApiError::conflict(detail),
            StoreError::QueueFull => ApiError::queue_full(crate::api::QUEUE_FULL_RETRY_AFTER_SECS),
            StoreError::Backend(_) => ApiError::internal(e),
        }
    }
}

/// The service layer's errors, mapped to problem+json here and nowhere else.
impl From<ServiceError> for ApiError {
    fn from(e: ServiceError) -> ApiError {
        match e {
            ServiceError::NotFound { what, id } => ApiError::not_found(what, &id),
            ServiceError::NotFoundField { field, message } => {
                ApiError::not_found_field(field, message)
            }
            ServiceError::Invalid(errors) => ApiError::validation(errors),
            ServiceError::Malformed { field, message } => ApiError::malformed(field, message),
            ServiceError::TooLarge { limit, bytes } => ApiError::too_large(limit, bytes),
            ServiceError::Conflict(detail) => ApiError::conflict(detail),
            ServiceError::ConflictField { field, message } => {
                ApiError::conflict(format!("{field}: {message}")).with_field(field, message)
            }
            ServiceError::ControllerMismatch { what, mismatch } => {
                let message = mismatch.message(what);
                ApiError {
                    controller: Some(mismatch),
                    ..ApiError::conflict(format!("controller: {message}"))
                        .with_field("controller", message)
                }
            }
            ServiceError::Store(e) => e.into(),
            ServiceError::Internal(cause) => ApiError::internal(cause),
        }
    }
}

impl From<Vec<FieldError>> for ApiError {
    fn from(errors: Vec<FieldError>) -> ApiError {
        ApiError::validation(errors)
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let title = self
            .status
            .canonical_reason()
            .unwrap_or("Error")
            .to_string();
        let problem = Problem {
            problem_type: format!("urn:robocal:problem:{}", self.slug),
            title,
            status: self.status.as_u16(),
            detail: self.detail,
            errors: self.errors,
            controller: self.controller.map(|m| *m),
        };
        let body = serde_json::to_vec(&problem).unwrap_or_default();
        let mut response = (self.status, body).into_response();
        let headers = response.headers_mut();
        headers.insert(header::CONTENT_TYPE, HeaderValue::from_static(PROBLEM_JSON));
        if let Some(secs) = self.retry_after_secs {
            headers.insert(header::RETRY_AFTER, HeaderValue::from(secs));
        }
        if self.status == StatusCode::UNAUTHORIZED {
            headers.insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
        }
        response
    }
}

pub type ApiResult<T> = Result<T, ApiError>;
