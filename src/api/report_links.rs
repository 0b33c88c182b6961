//! Signed, read-only report links: `POST …/parameter-sets/{version}/report-links`
//! answers a URL that opens that one report (HTML, SVG or JSON) without an
//! `Authorization` header until it expires, so a browser, a mail or a
//! ticket can show the report once tokens are required.
//!
//! The link is `…/parameter-sets/{n}/report.html?expires=UNIX&sig=HMAC`,
//! where the HMAC-SHA256 covers the report's path (version resolved, never
//! `latest`), the set's identity (its creation time: a robot deleted and
//! created again under the serial has new sets, which an old link does not
//! open) and the expiry, under a key kept in the database
//! (`server_secrets`), so every replica of a fleet accepts it. A link stays
//! valid until it expires, also if the token that asked for it is revoked:
//! keep expiries short. Link URLs start with `--public-base-url` when it
//! is set (else with the request's `Host`).

use axum::extract::{Path, State};
use axum::http::{header, HeaderMap, Method, StatusCode, Uri};
use axum::Json;
use base64::Engine;
use hmac::{Hmac, Mac};
use rand::RngCore;
use serde::{Deserialize, Serialize};
use sha2::Sha256;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiError, ApiResult, Problem};
use super::extract::ApiJson;
use super::AppState;
use crate::domain::rfc3339_of_unix_ms;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(create_report_link))
}

/// Name of the signing key in `server_secrets`.
const SECRET_NAME: &str = "report-links";
/// Random bytes of a fresh signing key.
const SECRET_BYTES: usize = 32;
/// Longest link life: a week (a link cannot be revoked).
pub const MAX_LINK_MINUTES: i64 = 7 * 24 * 60;
/// The route that creates links, under a parameter set.
const LINKS_SUFFIX: &str = "/report-links";
/// The report renderings a link opens.
const REPORT_VARIANTS: [&str; 3] = ["/report", "/report.svg", "/report.html"];
/// Query parameters of a link.
const EXPIRES_PARAM: &str = "expires";
const SIG_PARAM: &str = "sig";

type HmacSha256 = Hmac<Sha256>;

#[derive(Debug, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ReportLinkBody {
    /// Minutes the link works, 1 to 10080 (a week).
    #[schema(minimum = 1, maximum = 10080, example = 60)]
    pub expires_in_minutes: i64,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct ReportLink {
    /// The printable HTML report; opens without a header until `expires_at`.
    pub url: String,
    /// The same report as one SVG sheet.
    pub svg_url: String,
    /// The same report as JSON.
    pub json_url: String,
    /// RFC 3339 UTC; the link answers 401 after it.
    pub expires_at: String,
}

/// True for `POST …/report-links`, which needs only `read`.
pub fn is_link_request(method: &Method, path: &str) -> bool {
    *method == Method::POST && path.ends_with(LINKS_SUFFIX)
}

/// The request carries a link signature (it is then judged as a link).
pub fn carries_signature(uri: &Uri) -> bool {
    query_param(uri, SIG_PARAM).is_some()
}

fn query_param<'a>(uri: &'a Uri, name: &str) -> Option<&'a str> {
    uri.query()?
        .split('&')
        .filter_map(|pair| pair.split_once('='))
        .find(|(k, _)| *k == name)
        .map(|(_, v)| v)
}

/// The signature of a link to the report under `set_path`
/// (`/v1/robots/{serial}/parameter-sets/{n}`) of the set created at
/// `set_created_at`, expiring at `expires_unix`.
pub fn sign(secret: &str, set_path: &str, set_created_at: &str, expires_unix: i64) -> String {
    let mac = mac_of(secret, set_path, set_created_at, expires_unix)
        .finalize()
        .into_bytes();
    base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(mac)
}

fn mac_of(secret: &str, set_path: &str, set_created_at: &str, expires_unix: i64) -> HmacSha256 {
    let mut mac =
        HmacSha256::new_from_slice(secret.as_bytes()).expect("HMAC takes keys of any length");
    mac.update(b"robocal report link\n");
    mac.update(set_path.as_bytes());
    mac.update(b"\n");
    mac.update(set_created_at.as_bytes());
    mac.update(b"\n");
    mac.update(expires_unix.to_string().as_bytes());
    mac
}

/// When the set under `set_path` was created (its identity), if it exists.
async fn set_created_at(state: &AppState, set_path: &str) -> ApiResult<Option<String>> {
    let parsed = set_path
        .strip_prefix("/v1/robots/")
        .and_then(|rest| rest.split_once("/parameter-sets/"))
        .and_then(|(serial, v)| v.parse::<i64>().ok().map(|v| (serial, v)));
    let Some((serial, version)) = parsed else {
        return Ok(None);
    };
    let set = state.store.get_parameter_set(serial, Some(version)).await?;
    Ok(set.map(|s| s.created_at))
}

/// The fleet's signing key (created by the first replica that needs one).
pub async fn signing_secret(state: &AppState) -> ApiResult<String> {
    let mut bytes = [0u8; SECRET_BYTES];
    rand::rng().fill_bytes(&mut bytes);
    let fresh = base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(bytes);
    Ok(state.store.server_secret(SECRET_NAME, &fresh).await?)
}

/// Checks a headerless request's link: 403 for a link that was altered or
/// names another resource, 401 once it expired.
pub async fn verify(state: &AppState, method: &Method, uri: &Uri) -> ApiResult<()> {
    let refuse = |why: &str| ApiError::forbidden(format!("this report link is not valid: {why}"));
    if !matches!(*method, Method::GET | Method::HEAD) {
        return Err(refuse("a report link only reads"));
    }
    let path = uri.path();
    let set_path = REPORT_VARIANTS
        .iter()
        .find_map(|v| path.strip_suffix(v))
        .ok_or_else(|| refuse("it opens a report, nothing else"))?;
    let expires: i64 = query_param(uri, EXPIRES_PARAM)
        .and_then(|e| e.parse().ok())
        .ok_or_else(|| refuse("`expires` is missing or not a number"))?;
    let sig = query_param(uri, SIG_PARAM)
        .and_then(|s| {
            base64::engine::general_purpose::URL_SAFE_NO_PAD
                .decode(s)
                .ok()
        })
        .ok_or_else(|| refuse("`sig` is not a signature"))?;
    let secret = signing_secret(state).await?;
    let created_at = set_created_at(state, set_path)
        .await?
        .ok_or_else(|| refuse("the parameter set it names no longer exists"))?;
    mac_of(&secret, set_path, &created_at, expires)
        .verify_slice(&sig)
        .map_err(|_| refuse("the signature does not match this report and expiry"))?;
    let now_unix = crate::domain::now_unix_ms() / 1000;
    if expires <= now_unix {
        return Err(ApiError::unauthorized(format!(
            "this report link expired at {}; ask for a new one",
            rfc3339_of_unix_ms(expires.saturating_mul(1000))
        )));
    }
    Ok(())
}

/// A link that opens this parameter set's report without a token.
#[utoipa::path(post, path = "/v1/robots/{serial}/parameter-sets/{version}/report-links", tag = "results",
    params(("serial" = String, Path, description = "Robot serial number"),
           ("version" = String, Path, description = "Version number or `latest` (the link names the resolved version)")),
    request_body = ReportLinkBody,
    responses(
        (status = 201, body = ReportLink, description = "Signed URLs of the report (HTML, SVG, JSON) and their expiry"),
        (status = 401, body = Problem, content_type = "application/problem+json", description = "No valid token"),
        (status = 404, body = Problem, content_type = "application/problem+json", description = "No such parameter set or report"),
        (status = 422, body = Problem, content_type = "application/problem+json", description = "`expires_in_minutes` out of range")))]
async fn create_report_link(
    State(state): State<AppState>,
    Path((serial, version)): Path<(String, String)>,
    headers: HeaderMap,
    ApiJson(body): ApiJson<ReportLinkBody>,
) -> ApiResult<(StatusCode, Json<ReportLink>)> {
    if !(1..=MAX_LINK_MINUTES).contains(&body.expires_in_minutes) {
        return Err(ApiError::invalid(
            "expires_in_minutes",
            format!("1 to {MAX_LINK_MINUTES} minutes"),
        ));
    }
    let set = super::results::find(&state, &serial, &version).await?;
    state
        .store
        .get_report(&set.serial, set.version)
        .await?
        .ok_or_else(|| ApiError::not_found("report", &format!("{serial}/{version}")))?;
    // Serials are A-Z a-z 0-9 - _ . (check_serial): nothing to escape.
    let set_path = format!("/v1/robots/{}/parameter-sets/{}", set.serial, set.version);
    let expires = crate::domain::now_unix_ms() / 1000 + body.expires_in_minutes * 60;
    let sig = sign(
        &signing_secret(&state).await?,
        &set_path,
        &set.created_at,
        expires,
    );
    let base = public_base(&state, &headers);
    let link = |variant: &str| {
        format!("{base}{set_path}{variant}?{EXPIRES_PARAM}={expires}&{SIG_PARAM}={sig}")
    };
    Ok((
        StatusCode::CREATED,
        Json(ReportLink {
            url: link("/report.html"),
            svg_url: link("/report.svg"),
            json_url: link("/report"),
            expires_at: rfc3339_of_unix_ms(expires * 1000),
        }),
    ))
}

/// `--public-base-url` when set; else `scheme://host` as the caller
/// reached this server (its `Host`), else the bind.
fn public_base(state: &AppState, headers: &HeaderMap) -> String {
    if let Some(base) = &state.config.public_base_url {
        return base.trim_end_matches('/').to_string();
    }
    let scheme = if state.config.tls_enabled() {
        "https"
    } else {
        "http"
    };
    let host = headers
        .get(header::HOST)
        .and_then(|h| h.to_str().ok())
        .map(str::to_string)
        .unwrap_or_else(|| state.config.bind.to_string());
    format!("{scheme}://{host}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signature_binds_path_set_and_expiry() {
        let (p1, t) = ("/v1/robots/A/parameter-sets/1", "2026-01-01T00:00:00.000Z");
        let s = sign("k", p1, t, 100);
        assert_eq!(s, sign("k", p1, t, 100));
        assert_ne!(s, sign("k", "/v1/robots/A/parameter-sets/2", t, 100));
        assert_ne!(
            s,
            sign("k", p1, "2026-01-02T00:00:00.000Z", 100),
            "a re-created set"
        );
        assert_ne!(s, sign("k", p1, t, 101));
        assert_ne!(s, sign("other", p1, t, 100));
    }

    #[test]
    fn query_params_are_found_by_name() {
        let uri: Uri = "/x/report?expires=5&sig=abc".parse().unwrap();
        assert_eq!(query_param(&uri, "expires"), Some("5"));
        assert_eq!(query_param(&uri, "sig"), Some("abc"));
        assert!(carries_signature(&uri));
        assert!(!carries_signature(&"/x/report?s=1".parse().unwrap()));
    }
}
