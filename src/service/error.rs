//! The one error of the service layer. It says what went wrong in the
//! service's terms (which field, which resource, which limit); `api/error.rs`
//! turns it into problem+json in one place.

use crate::domain::ControllerMismatch;
use crate::schema::FieldError;
use crate::store::StoreError;

#[derive(Debug, thiserror::Error)]
pub enum ServiceError {
    /// No such resource (`what` and the id the client gave): 404.
    #[error("{what} {id:?} not found")]
    NotFound { what: &'static str, id: String },
    /// A reference inside the request names nothing: 404 naming the field.
    #[error("{field}: {message}")]
    NotFoundField {
        field: &'static str,
        message: String,
    },
    /// The request parsed but its values are wrong: 422.
    #[error("invalid input")]
    Invalid(Vec<FieldError>),
    /// The request cannot be read at all (zip, manifest): 400.
    #[error("{field}: {message}")]
    Malformed { field: String, message: String },
    /// A configured size limit was exceeded: 413.
    #[error("{limit} exceeded")]
    TooLarge { limit: &'static str, bytes: u64 },
    /// The resource exists but cannot serve this request: 409.
    #[error("{0}")]
    Conflict(String),
    /// The state of what a field names forbids the request: 409 naming it.
    #[error("{field}: {message}")]
    ConflictField {
        field: &'static str,
        message: String,
    },
    /// The request expected another controller than the one the set (or
    /// robot) records: 409 naming `controller`, both identities
    /// in the problem's `controller` member. `what` names the recorder.
    #[error("controller mismatch")]
    ControllerMismatch {
        what: &'static str,
        mismatch: Box<ControllerMismatch>,
    },
    #[error(transparent)]
    Store(#[from] StoreError),
    /// A fault of the service itself (a task that died, a stored document
    /// that no longer parses): 500, the cause logged.
    #[error("{0}")]
    Internal(String),
}

impl ServiceError {
    /// One invalid field.
    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> ServiceError {
        ServiceError::Invalid(vec![FieldError::new(field, message)])
    }

    pub fn not_found(what: &'static str, id: &str) -> ServiceError {
        ServiceError::NotFound {
            what,
            id: id.to_string(),
        }
    }

    pub fn internal(cause: impl std::fmt::Display) -> ServiceError {
        ServiceError::Internal(cause.to_string())
    }
}

impl ServiceError {
    /// `check_controller`'s refusal of a call on `what` (`the parameter set`).
    pub fn controller(what: &'static str) -> impl FnOnce(Box<ControllerMismatch>) -> ServiceError {
        move |mismatch| ServiceError::ControllerMismatch { what, mismatch }
    }
}

impl From<Vec<FieldError>> for ServiceError {
    fn from(errors: Vec<FieldError>) -> ServiceError {
        ServiceError::Invalid(errors)
    }
}

pub type ServiceResult<T> = Result<T, ServiceError>;
