//! The fleet pages (issue 17): `GET /` (every robot: current parameter
//! set and its age, accuracy, last re-check, jobs in progress),
//! `GET /robots/{serial}` (its versions and jobs) and
//! `GET /robots/{serial}/reports/{version}` (a version's HTML report),
//! server-rendered, self-contained HTML; with `GET`/`POST /login` and
//! `POST /logout` when the server has tokens (`access.rs`). These routes
//! are for people, so they stay out of the OpenAPI document.

use axum::body::Body;
use axum::extract::{Path, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use serde::Deserialize;

use super::error::{ApiError, ApiResult};
use super::extract::query_of;
use super::AppState;
use crate::domain::now_unix_ms;
use crate::report::render_html;
use crate::service::{fleet, ServiceError};

mod access;
mod frame;
mod pages;

pub use access::COOKIE;
pub use pages::NO_CHECKS;

/// Largest login form body, bytes.
const MAX_FORM_BYTES: usize = 4096;
/// Pages load nothing from anywhere: inline style, inline SVG, no script.
const CONTENT_SECURITY_POLICY: &str =
    "default-src 'none'; style-src 'unsafe-inline'; img-src data:; form-action 'self'; frame-ancestors 'none'";

pub fn router() -> Router<AppState> {
    Router::new()
        .route("/", get(fleet_page))
        .route("/robots/{serial}", get(robot_page))
        .route("/robots/{serial}/reports/{version}", get(report_page))
        .route("/login", get(login_form).post(login))
        .route("/logout", post(logout))
}

/// An HTML answer that no cache keeps (the pages show private data).
fn html(status: StatusCode, body: String) -> Response {
    let mut r = (status, body).into_response();
    let h = r.headers_mut();
    h.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("text/html; charset=utf-8"),
    );
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    h.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(CONTENT_SECURITY_POLICY),
    );
    r
}

fn see_other(to: &'static str) -> Response {
    (StatusCode::SEE_OTHER, [(header::LOCATION, to)]).into_response()
}

/// A 404 page for what the service did not find; other errors stay problem+json.
fn page_error(e: ServiceError, logout: bool) -> ApiResult<Response> {
    match e {
        ServiceError::NotFound { what, id } => Ok(html(
            StatusCode::NOT_FOUND,
            frame::message_page("Not found", &format!("There is no {what} {id}."), logout),
        )),
        e => Err(ApiError::from(e)),
    }
}

async fn fleet_page(
    State(state): State<AppState>,
    headers: HeaderMap,
    uri: Uri,
) -> ApiResult<Response> {
    let Some(viewer) = access::viewer(&state, &headers, &uri).await? else {
        return Ok(see_other("/login"));
    };
    let robots = fleet::fleet(&state.store, &state.fleet_cache).await?;
    Ok(html(
        StatusCode::OK,
        pages::fleet_page(&robots, now_unix_ms(), viewer.can_log_out()),
    ))
}

async fn robot_page(
    State(state): State<AppState>,
    Path(serial): Path<String>,
    headers: HeaderMap,
    uri: Uri,
) -> ApiResult<Response> {
    let Some(viewer) = access::viewer(&state, &headers, &uri).await? else {
        return Ok(see_other("/login"));
    };
    match fleet::robot(&state.store, &state.fleet_cache, &serial).await {
        Ok(detail) => Ok(html(
            StatusCode::OK,
            pages::robot_page(&detail, now_unix_ms(), viewer.can_log_out()),
        )),
        Err(ServiceError::Invalid(_)) => page_error(
            ServiceError::not_found("robot", &serial),
            viewer.can_log_out(),
        ),
        Err(e) => page_error(e, viewer.can_log_out()),
    }
}

async fn report_page(
    State(state): State<AppState>,
    Path((serial, version)): Path<(String, String)>,
    headers: HeaderMap,
    uri: Uri,
) -> ApiResult<Response> {
    let Some(viewer) = access::viewer(&state, &headers, &uri).await? else {
        return Ok(see_other("/login"));
    };
    let found = match version.parse::<i64>() {
        Ok(v) if v >= 1 => fleet::report(&state.store, &serial, v).await,
        _ => Err(ServiceError::not_found(
            "report",
            &format!("{serial}/{version}"),
        )),
    };
    match found {
        Ok(report) => Ok(html(StatusCode::OK, render_html(&report))),
        Err(e) => page_error(e, viewer.can_log_out()),
    }
}

async fn login_form(State(state): State<AppState>) -> ApiResult<Response> {
    if !access::tokens_required(&state).await? {
        return Ok(see_other("/"));
    }
    Ok(login_page(&state, StatusCode::OK, None))
}

/// The login form with a fresh nonce and its cookie.
fn login_page(state: &AppState, status: StatusCode, error: Option<&str>) -> Response {
    let (nonce, cookie) = access::login_nonce(state);
    let mut r = html(status, frame::login_page(error, &nonce));
    if let Ok(v) = HeaderValue::from_str(&cookie) {
        r.headers_mut().insert(header::SET_COOKIE, v);
    }
    r
}

#[derive(Deserialize)]
struct LoginForm {
    token: Option<String>,
    /// The form's nonce, matched against its cookie (login CSRF).
    nonce: Option<String>,
}

/// `token=…&nonce=…` (form-encoded): a session cookie and back to the
/// fleet, or the form again (401; 403 without the form's nonce) saying why.
async fn login(
    State(state): State<AppState>,
    headers: HeaderMap,
    body: Body,
) -> ApiResult<Response> {
    if !access::tokens_required(&state).await? {
        return Ok(see_other("/"));
    }
    let bytes = axum::body::to_bytes(body, MAX_FORM_BYTES)
        .await
        .map_err(|_| ApiError::malformed("token", "the login form is too large"))?;
    let text = String::from_utf8_lossy(&bytes);
    let form: LoginForm = query_of(&text)?;
    if !access::login_nonce_matches(&headers, form.nonce.as_deref()) {
        return Ok(login_page(
            &state,
            StatusCode::FORBIDDEN,
            Some("this sign-in form expired or was not sent from this site: sign in again"),
        ));
    }
    match access::login(&state, form.token.as_deref().unwrap_or("")).await? {
        Ok(cookie) => {
            let mut r = see_other("/");
            if let Ok(v) = HeaderValue::from_str(&cookie) {
                r.headers_mut().insert(header::SET_COOKIE, v);
            }
            Ok(r)
        }
        Err(why) => Ok(login_page(&state, StatusCode::UNAUTHORIZED, Some(why))),
    }
}

async fn logout(State(state): State<AppState>) -> Response {
    let mut r = see_other("/login");
    if let Ok(v) = HeaderValue::from_str(&access::logout_cookie(&state)) {
        r.headers_mut().insert(header::SET_COOKIE, v);
    }
    r
}
