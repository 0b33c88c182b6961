//! Who may see the fleet pages. Without tokens (a loopback-bound server),
//! anyone who reaches the loopback bind by its name, as for the API
//! (`auth::check_loopback_host`). With tokens, a browser signs in once
//! (`POST /login` with a token of any scope) and then holds a session
//! cookie: `token id . expiry . HMAC` under a key kept in the database
//! (`server_secrets`, shared by every replica), `HttpOnly`,
//! `SameSite=Strict`, `Secure` under TLS. The token itself is never put in
//! a cookie or a URL; a revoked or expired token ends its sessions at the
//! next page. The login form carries a nonce that must match its own
//! `SameSite=Strict` cookie (`robocal_login`), so a page on another site
//! cannot sign a browser in under the attacker's token (login CSRF).

use axum::http::{header, HeaderMap, Uri};
use base64::Engine;
use hmac::{Hmac, Mac};
use rand::RngCore;
use sha2::Sha256;

use super::super::auth::{check_loopback_host, hash_token};
use super::super::error::ApiResult;
use super::super::AppState;
use crate::domain::{now_unix_ms, Scope};

/// The session cookie's name.
pub const COOKIE: &str = "robocal_session";
/// How long a session lasts, seconds (a working day and a half).
pub const SESSION_SECS: i64 = 12 * 3600;
/// Name of the session signing key in `server_secrets`.
const SECRET_NAME: &str = "fleet-sessions";
/// Random bytes of a fresh signing key.
const SECRET_BYTES: usize = 32;
/// Longest token accepted by the login form, bytes.
const MAX_TOKEN_BYTES: usize = 256;
/// The login form's nonce cookie, and how long a form stays usable.
pub const LOGIN_COOKIE: &str = "robocal_login";
const LOGIN_FORM_SECS: i64 = 3600;
/// Random bytes of a login nonce.
const NONCE_BYTES: usize = 16;

/// Who is looking at a page.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Viewer {
    /// A server without tokens, reached on its loopback bind.
    Anonymous,
    /// A signed-in browser (it may log out).
    Session,
}

impl Viewer {
    pub fn can_log_out(self) -> bool {
        self == Viewer::Session
    }
}

async fn signing_secret(state: &AppState) -> ApiResult<String> {
    let mut bytes = [0u8; SECRET_BYTES];
    rand::rng().fill_bytes(&mut bytes);
    let fresh = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(bytes);
    Ok(state.store.server_secret(SECRET_NAME, &fresh).await?)
}

fn mac_of(secret: &str, token_id: &str, expires_unix: i64) -> Hmac<Sha256> {
    let mut mac =
        Hmac::<Sha256>::new_from_slice(secret.as_bytes()).expect("HMAC takes keys of any length");
    mac.update(b"robocal fleet session\n");
    mac.update(token_id.as_bytes());
    mac.update(b"\n");
    mac.update(expires_unix.to_string().as_bytes());
    mac
}

/// The cookie's value for token `token_id` until `expires_unix`.
fn session_value(secret: &str, token_id: &str, expires_unix: i64) -> String {
    let sig = mac_of(secret, token_id, expires_unix)
        .finalize()
        .into_bytes();
    format!(
        "{token_id}.{expires_unix}.{}",
        base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(sig)
    )
}

/// The token id a cookie value names, if its signature holds and it has
/// not expired at `now_unix`.
fn verify_value(secret: &str, value: &str, now_unix: i64) -> Option<String> {
    let mut parts = value.rsplitn(3, '.');
    let sig = parts.next()?;
    let expires: i64 = parts.next()?.parse().ok()?;
    let token_id = parts.next()?;
    let sig = base64::engine::general_purpose::URL_SAFE_NO_PAD
        .decode(sig)
        .ok()?;
    mac_of(secret, token_id, expires).verify_slice(&sig).ok()?;
    (expires > now_unix).then(|| token_id.to_string())
}

/// The session cookie's value among the request's cookies.
fn cookie_value(headers: &HeaderMap) -> Option<&str> {
    named_cookie(headers, COOKIE)
}

fn named_cookie<'h>(headers: &'h HeaderMap, wanted: &str) -> Option<&'h str> {
    headers
        .get_all(header::COOKIE)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(';'))
        .filter_map(|pair| pair.trim().split_once('='))
        .find(|(name, _)| *name == wanted)
        .map(|(_, value)| value)
}

/// A fresh login-form nonce and the `Set-Cookie` value that goes with it.
pub fn login_nonce(state: &AppState) -> (String, String) {
    let mut bytes = [0u8; NONCE_BYTES];
    rand::rng().fill_bytes(&mut bytes);
    let nonce = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(bytes);
    let attributes = cookie_attributes(state).replacen("Path=/", "Path=/login", 1);
    let cookie = format!("{LOGIN_COOKIE}={nonce}; Max-Age={LOGIN_FORM_SECS}; {attributes}");
    (nonce, cookie)
}

/// The form's nonce is the one its browser's login cookie holds.
pub fn login_nonce_matches(headers: &HeaderMap, form_nonce: Option<&str>) -> bool {
    match (named_cookie(headers, LOGIN_COOKIE), form_nonce) {
        (Some(cookie), Some(form)) => !cookie.is_empty() && hash_token(cookie) == hash_token(form),
        _ => false,
    }
}

fn cookie_attributes(state: &AppState) -> &'static str {
    if state.config.tls_enabled() {
        "Path=/; HttpOnly; SameSite=Strict; Secure"
    } else {
        "Path=/; HttpOnly; SameSite=Strict"
    }
}

/// The viewer of a page request, or `None` when it must sign in first.
/// A server without tokens refuses (421) a `Host` that is not its
/// loopback bind, as the API does.
pub async fn viewer(state: &AppState, headers: &HeaderMap, uri: &Uri) -> ApiResult<Option<Viewer>> {
    if state.store.count_tokens().await? == 0 {
        check_loopback_host(state, uri, headers.get(header::HOST))?;
        return Ok(Some(Viewer::Anonymous));
    }
    let Some(value) = cookie_value(headers) else {
        return Ok(None);
    };
    let secret = signing_secret(state).await?;
    let Some(token_id) = verify_value(&secret, value, now_unix_ms() / 1000) else {
        return Ok(None);
    };
    let now = now_unix_ms();
    let usable = state
        .store
        .list_tokens()
        .await?
        .into_iter()
        .any(|t| t.id == token_id && t.check_usable(now).is_ok() && t.scope >= Scope::Read);
    Ok(usable.then_some(Viewer::Session))
}

/// Whether the server asks for a sign-in at all (it has tokens).
pub async fn tokens_required(state: &AppState) -> ApiResult<bool> {
    Ok(state.store.count_tokens().await? > 0)
}

/// Checks a token from the login form: the `Set-Cookie` value of a new
/// session, or why the token is refused.
pub async fn login(state: &AppState, token: &str) -> ApiResult<Result<String, &'static str>> {
    let token = token.trim();
    if token.is_empty() || token.len() > MAX_TOKEN_BYTES {
        return Ok(Err("enter an API token"));
    }
    let Some(record) = state.store.find_token(&hash_token(token)).await? else {
        return Ok(Err("unknown token"));
    };
    if record.check_usable(now_unix_ms()).is_err() {
        return Ok(Err("this token was revoked or has expired"));
    }
    let expires = now_unix_ms() / 1000 + SESSION_SECS;
    let value = session_value(&signing_secret(state).await?, &record.id, expires);
    Ok(Ok(format!(
        "{COOKIE}={value}; Max-Age={SESSION_SECS}; {}",
        cookie_attributes(state)
    )))
}

/// The `Set-Cookie` value that ends the session.
pub fn logout_cookie(state: &AppState) -> String {
    format!("{COOKIE}=; Max-Age=0; {}", cookie_attributes(state))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn session_values_verify_until_they_expire_and_only_unaltered() {
        let v = session_value("k", "tok-1", 1000);
        assert_eq!(verify_value("k", &v, 999).as_deref(), Some("tok-1"));
        assert_eq!(verify_value("k", &v, 1000), None, "expired");
        assert_eq!(verify_value("other", &v, 10), None);
        let forged = v.replacen("tok-1", "tok-2", 1);
        assert_eq!(verify_value("k", &forged, 10), None);
        let later = v.replacen(".1000.", ".9999.", 1);
        assert_eq!(verify_value("k", &later, 10), None);
        assert_eq!(verify_value("k", "garbage", 10), None);
    }

    #[test]
    fn the_session_cookie_is_found_among_others() {
        let mut h = HeaderMap::new();
        h.insert(
            header::COOKIE,
            "a=1; robocal_session=x.2.y; b=3".parse().unwrap(),
        );
        assert_eq!(cookie_value(&h), Some("x.2.y"));
        assert_eq!(cookie_value(&HeaderMap::new()), None);
    }
}
