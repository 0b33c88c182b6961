//! Bearer-token authentication and scope checks, for every `/v1` route.
//! Tokens are random 256-bit strings; only their SHA-256 is stored. Scopes
//! are ordered: `read` < `write` < `admin`. Reads need `read`, writes need
//! `write`, token management needs `admin`. With no token in the database a
//! loopback-bound server serves anonymous requests (the CLI refuses to bind
//! elsewhere without tokens).

use axum::extract::{Request, State};
use axum::http::{header, Method};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use base64::Engine;
use rand::RngCore;
use sha2::{Digest, Sha256};

use super::error::ApiError;
use super::AppState;
use crate::domain::Scope;

/// Prefix of every token, so a leaked one is recognisable in logs and scanners.
pub const TOKEN_PREFIX: &str = "rbc_";
/// Random bytes per token.
const TOKEN_BYTES: usize = 32;

/// Who made the request, for scope checks and idempotency keys.
#[derive(Debug, Clone)]
pub enum Principal {
    Anonymous,
    Token { id: String, scope: Scope },
}

impl Principal {
    pub fn key(&self) -> String {
        match self {
            Principal::Anonymous => "anonymous".into(),
            Principal::Token { id, .. } => format!("token:{id}"),
        }
    }
}

pub fn generate_token() -> String {
    let mut bytes = [0u8; TOKEN_BYTES];
    rand::rng().fill_bytes(&mut bytes);
    format!(
        "{TOKEN_PREFIX}{}",
        base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(bytes)
    )
}

pub fn hash_token(token: &str) -> String {
    hex::encode(Sha256::digest(token.as_bytes()))
}

/// The scope a request needs.
fn required_scope(method: &Method, path: &str) -> Scope {
    if path.starts_with("/v1/tokens") {
        Scope::Admin
    } else if matches!(*method, Method::GET | Method::HEAD | Method::OPTIONS) {
        Scope::Read
    } else {
        Scope::Write
    }
}

pub async fn layer(State(state): State<AppState>, mut req: Request, next: Next) -> Response {
    if !req.uri().path().starts_with("/v1/") {
        return next.run(req).await;
    }
    let needed = required_scope(req.method(), req.uri().path());
    let header = req
        .headers()
        .get(header::AUTHORIZATION)
        .map(|v| v.to_str().map(str::to_string).unwrap_or_default());
    match authenticate(&state, needed, header).await {
        Ok(principal) => {
            req.extensions_mut().insert(principal);
            next.run(req).await
        }
        Err(e) => e.into_response(),
    }
}

async fn authenticate(
    state: &AppState,
    needed: Scope,
    header: Option<String>,
) -> Result<Principal, ApiError> {
    let Some(header) = header else {
        if state.config.is_loopback() && state.store.count_tokens().await? == 0 {
            return Ok(Principal::Anonymous);
        }
        return Err(ApiError::unauthorized(
            "send Authorization: Bearer <token> (create one with `robocal token create`)",
        ));
    };
    let token = header
        .strip_prefix("Bearer ")
        .map(str::trim)
        .filter(|t| !t.is_empty() && t.len() <= 256)
        .ok_or_else(|| {
            ApiError::unauthorized("the Authorization header must be `Bearer <token>`")
        })?;
    let record = state
        .store
        .find_token(&hash_token(token))
        .await?
        .ok_or_else(|| ApiError::unauthorized("unknown token"))?;
    if record.scope < needed {
        return Err(ApiError::forbidden(format!(
            "this token has scope {:?}; the request needs {:?}",
            record.scope.as_str(),
            needed.as_str()
        )));
    }
    Ok(Principal::Token {
        id: record.id,
        scope: record.scope,
    })
}
