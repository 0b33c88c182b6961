//! Bearer-token authentication and scope checks, for every `/v1` route and
//! `/metrics` (unless `--public-metrics`). Tokens are random 256-bit
//! strings; only their SHA-256 is stored. Scopes are ordered: `read` <
//! `write` < `admin`. Reads need `read`, writes need `write`, token
//! management and webhooks need `admin` (a webhook sends the service's
//! events to any URL it names, and listing them shows where). A revoked or expired token is refused (401).
//!
//! Anonymous mode: with no token in the database a loopback-bound server
//! serves anonymous requests (the CLI refuses to bind elsewhere without
//! tokens), but only those whose `Host` names the loopback bind, so a web
//! page cannot reach the service through DNS rebinding. A signed report link
//! (`report_links`) opens its one report without a header.
//!
//! Always public: `/healthz`, `/readyz` (probes) and `/docs`,
//! `/openapi.json` (the contract, which holds no data).

use axum::extract::{Request, State};
use axum::http::{header, Method, Uri};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use base64::Engine;
use rand::RngCore;
use sha2::{Digest, Sha256};

use super::error::ApiError;
use super::{report_links, AppState};
use crate::domain::{now_unix_ms, rfc3339_of_unix_ms, Scope, TokenRefusal};

/// Prefix of every token, so a leaked one is recognisable in logs and scanners.
pub const TOKEN_PREFIX: &str = "rbc_";
/// Random bytes per token.
const TOKEN_BYTES: usize = 32;
/// A token's last use is written at most this often: one write a minute per
/// busy token, however many requests it makes.
pub const LAST_USE_INTERVAL_MS: i64 = 60_000;
/// Prometheus scrapes here; needs `read` unless `--public-metrics`.
const METRICS_PATH: &str = "/metrics";
/// Host names that reach a loopback bind without DNS (anonymous mode
/// accepts no others).
const LOOPBACK_HOSTS: [&str; 3] = ["localhost", "127.0.0.1", "[::1]"];

/// Who made the request, for scope checks and idempotency keys.
#[derive(Debug, Clone)]
pub enum Principal {
    Anonymous,
    Token {
        id: String,
        /// The token's name, for the record of who decided what.
        name: String,
        scope: Scope,
    },
    /// A signed, read-only link to one report (no header).
    ReportLink,
}

impl Principal {
    pub fn key(&self) -> String {
        match self {
            Principal::Anonymous => "anonymous".into(),
            Principal::Token { id, .. } => format!("token:{id}"),
            Principal::ReportLink => "report-link".into(),
        }
    }

    /// Who this is in a record of decisions (a parameter set's approval):
    /// `token:{id} ({name})`, or `anonymous`.
    pub fn actor(&self) -> String {
        match self {
            Principal::Token { id, name, .. } => format!("token:{id} ({name})"),
            other => other.key(),
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

/// The scope a request needs; `None` for the public routes.
fn required_scope(public_metrics: bool, method: &Method, path: &str) -> Option<Scope> {
    if path == METRICS_PATH {
        return (!public_metrics).then_some(Scope::Read);
    }
    if !path.starts_with("/v1/") {
        return None;
    }
    let reads = matches!(*method, Method::GET | Method::HEAD | Method::OPTIONS);
    Some(
        if path.starts_with("/v1/tokens") || path.starts_with("/v1/webhooks") {
            Scope::Admin
        } else if reads || report_links::is_link_request(method, path) {
            Scope::Read
        } else {
            Scope::Write
        },
    )
}

pub async fn layer(State(state): State<AppState>, mut req: Request, next: Next) -> Response {
    let Some(needed) = required_scope(state.config.public_metrics, req.method(), req.uri().path())
    else {
        return next.run(req).await;
    };
    let header = req
        .headers()
        .get(header::AUTHORIZATION)
        .map(|v| v.to_str().map(str::to_string).unwrap_or_default());
    let result = match header {
        Some(header) => authenticate_token(&state, needed, &header).await,
        None => {
            let (method, uri) = (req.method().clone(), req.uri().clone());
            let host = req.headers().get(header::HOST).cloned();
            authenticate_headerless(&state, &method, &uri, host.as_ref()).await
        }
    };
    match result {
        Ok(principal) => {
            req.extensions_mut().insert(principal);
            next.run(req).await
        }
        Err(e) => e.into_response(),
    }
}

/// No `Authorization`: a signed report link, or anonymous mode.
async fn authenticate_headerless(
    state: &AppState,
    method: &Method,
    uri: &Uri,
    host: Option<&header::HeaderValue>,
) -> Result<Principal, ApiError> {
    if report_links::carries_signature(uri) {
        report_links::verify(state, method, uri).await?;
        return Ok(Principal::ReportLink);
    }
    if state.config.is_loopback() && state.store.count_tokens().await? == 0 {
        check_loopback_host(state, uri, host)?;
        return Ok(Principal::Anonymous);
    }
    Err(ApiError::unauthorized(
        "send Authorization: Bearer <token> (create one with `robocal token create`)",
    ))
}

/// Anonymous mode answers only requests addressed to the loopback bind by
/// name or address (`localhost`, `127.0.0.1`, `[::1]` with the bound port):
/// a page loaded from elsewhere whose DNS name was rebound to 127.0.0.1
/// still sends its own name as `Host`.
pub(crate) fn check_loopback_host(
    state: &AppState,
    uri: &Uri,
    host: Option<&header::HeaderValue>,
) -> Result<(), ApiError> {
    let authority = request_authority(uri, host);
    let port = state.config.bind.port();
    let bound_ip = state.config.bind.ip().to_string();
    if let Some(authority) = authority.as_deref() {
        if host_is_loopback_bind(authority, &bound_ip, port, state.config.tls_enabled()) {
            return Ok(());
        }
    }
    tracing::warn!(host = ?authority, "anonymous request refused: Host is not the loopback bind");
    Err(ApiError::misdirected(format!(
        "without tokens this service answers only requests to localhost:{port} or \
         127.0.0.1:{port}, not to host {:?} (create a token with `robocal token create` \
         to serve other names)",
        authority.unwrap_or_default()
    )))
}

/// The target's authority: the absolute-form URI's, else the `Host` header.
fn request_authority(uri: &Uri, host: Option<&header::HeaderValue>) -> Option<String> {
    if let Some(authority) = uri.authority() {
        return Some(authority.as_str().to_string());
    }
    host.and_then(|h| h.to_str().ok()).map(str::to_string)
}

/// `authority` is `name[:port]` with a loopback name (or the bound address)
/// and the bound port; no port only when the bound one is the scheme's default.
fn host_is_loopback_bind(authority: &str, bound_ip: &str, port: u16, tls: bool) -> bool {
    let authority = authority.to_ascii_lowercase();
    let (name, given_port) = match authority.rsplit_once(':') {
        // `[::1]` alone has colons inside the brackets only.
        Some((name, p)) if !p.contains(']') => (name.to_string(), p.parse::<u16>().ok()),
        _ => (authority.clone(), None),
    };
    let default_port = if tls { 443 } else { 80 };
    let port_ok = match given_port {
        Some(p) => p == port,
        None => !authority.ends_with(':') && port == default_port,
    };
    let bracketed = format!("[{bound_ip}]");
    let name_ok = LOOPBACK_HOSTS.contains(&name.as_str()) || name == bound_ip || name == bracketed;
    port_ok && name_ok
}

async fn authenticate_token(
    state: &AppState,
    needed: Scope,
    header: &str,
) -> Result<Principal, ApiError> {
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
    let now = now_unix_ms();
    match record.check_usable(now) {
        Ok(()) => {}
        Err(TokenRefusal::Revoked) => {
            return Err(ApiError::unauthorized(format!(
                "token {} was revoked",
                record.id
            )))
        }
        Err(TokenRefusal::Expired) => {
            return Err(ApiError::unauthorized(format!(
                "token {} expired at {}",
                record.id,
                rfc3339_of_unix_ms(record.expires_ms.unwrap_or_default())
            )))
        }
    }
    if record.scope < needed {
        return Err(ApiError::forbidden(format!(
            "this token has scope {:?}; the request needs {:?}",
            record.scope.as_str(),
            needed.as_str()
        )));
    }
    if record
        .last_used_ms
        .is_none_or(|t| now - t >= LAST_USE_INTERVAL_MS)
    {
        // Off the request's path: a busy database delays the record, not the answer.
        let store = state.store.clone();
        let id = record.id.clone();
        tokio::spawn(async move {
            if let Err(e) = store.touch_token(&id, now, LAST_USE_INTERVAL_MS).await {
                tracing::debug!(error = %e, token = %id, "last use not recorded");
            }
        });
    }
    Ok(Principal::Token {
        id: record.id,
        name: record.name,
        scope: record.scope,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loopback_hosts_with_the_bound_port_only() {
        let ok = |a: &str| host_is_loopback_bind(a, "127.0.0.1", 8080, false);
        assert!(ok("127.0.0.1:8080"));
        assert!(ok("localhost:8080"));
        assert!(ok("LOCALHOST:8080"));
        assert!(ok("[::1]:8080"));
        assert!(!ok("127.0.0.1:8081"));
        assert!(!ok("evil.example:8080"));
        assert!(!ok("localhost.evil.example:8080"));
        assert!(!ok("127.0.0.1"), "no port means 80");
        assert!(!ok("localhost:"));
        assert!(!ok("[::1]"));
        assert!(host_is_loopback_bind("localhost", "127.0.0.1", 80, false));
        assert!(host_is_loopback_bind("[::1]", "::1", 443, true));
        assert!(host_is_loopback_bind("127.0.0.2:9", "127.0.0.2", 9, false));
    }

    #[test]
    fn metrics_scope_follows_the_flag() {
        assert_eq!(
            required_scope(false, &Method::GET, "/metrics"),
            Some(Scope::Read)
        );
        assert_eq!(required_scope(true, &Method::GET, "/metrics"), None);
        assert_eq!(required_scope(false, &Method::GET, "/docs/"), None);
        assert_eq!(required_scope(false, &Method::GET, "/healthz"), None);
        assert_eq!(
            required_scope(false, &Method::DELETE, "/v1/tokens/x"),
            Some(Scope::Admin)
        );
    }
}
