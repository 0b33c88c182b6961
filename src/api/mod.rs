//! The HTTP layer. Every route is listed in [`api_router`]; each resource
//! module owns its handlers and `router()`. Handlers parse, call one store or
//! queue function, and return `Result<_, ApiError>` (mapped in `error.rs`).

use std::sync::atomic::AtomicUsize;
use std::sync::Arc;
use std::time::Instant;

use axum::extract::{DefaultBodyLimit, MatchedPath, Request, State};
use axum::http::{HeaderName, StatusCode};
use axum::middleware::{self, Next};
use axum::response::Response;
use axum::Router;
use tokio::sync::Notify;
use tower_http::catch_panic::CatchPanicLayer;
use tower_http::request_id::{MakeRequestUuid, PropagateRequestIdLayer, SetRequestIdLayer};
use tower_http::trace::{DefaultOnResponse, TraceLayer};
use utoipa::openapi::security::{HttpAuthScheme, HttpBuilder, SecurityScheme};
use utoipa::{Modify, OpenApi};
use utoipa_axum::router::OpenApiRouter;
use utoipa_swagger_ui::SwaggerUi;

use crate::config::ServeConfig;
use crate::jobs::queue::QueuePolicy;
use crate::metrics::Metrics;
use crate::store::DynStore;

pub mod auth;
pub mod body_idle;
pub mod campaign_plans;
pub mod contract;
pub mod controller_query;
pub mod cross_site;
pub mod error;
pub mod export;
pub mod extract;
pub mod fingerprint;
pub mod fleet;
pub mod idempotency;
pub mod job_events;
pub mod jobs;
pub mod lane;
pub mod ndjson;
pub mod nul_guard;
pub mod ops;
pub mod poses;
pub mod problem_fallback;
pub mod release;
pub mod report_links;
pub mod results;
pub mod robots;
pub mod sessions;
pub mod targets;
pub mod token_watch;
pub mod tokens;
pub mod upload;
pub mod webhooks;

/// Seconds a client should wait after a 429 for a full queue.
pub const QUEUE_FULL_RETRY_AFTER_SECS: u64 = 10;

const REQUEST_ID: HeaderName = HeaderName::from_static("x-request-id");

#[derive(Clone)]
pub struct AppState {
    pub store: DynStore,
    pub config: Arc<ServeConfig>,
    pub policy: QueuePolicy,
    pub metrics: Arc<Metrics>,
    /// Wakes an idle worker when a job is enqueued here.
    pub wake: Arc<Notify>,
    pub workers_alive: Arc<AtomicUsize>,
    /// Bounds concurrent image decodes (uploads and jobs share it).
    pub decode_gate: Arc<crate::imaging::DecodeGate>,
    /// The tokens as last read, so open streams end on revocation.
    pub tokens: token_watch::Tokens,
    /// The fleet pages' accuracy per parameter set, read once per set.
    pub fleet_cache: Arc<crate::service::fleet::SummaryCache>,
}

#[derive(OpenApi)]
#[openapi(
    info(
        title = "robocal",
        description = "Robot calibration service: kinematic calibration of industrial robots from a flange camera (dot grid, chessboard, ChArUco or circle boards), a camera on a linear stage or a laser tracker; identified parameters, reports, compensation and exports over REST. Errors are application/problem+json (RFC 9457).",
    ),
    modifiers(&BearerAuth),
    security(("bearer" = []))
)]
struct ApiDoc;

struct BearerAuth;

impl Modify for BearerAuth {
    fn modify(&self, openapi: &mut utoipa::openapi::OpenApi) {
        let components = openapi.components.get_or_insert_with(Default::default);
        components.add_security_scheme(
            "bearer",
            SecurityScheme::Http(HttpBuilder::new().scheme(HttpAuthScheme::Bearer).build()),
        );
    }
}

/// Every route of the service.
fn api_router() -> OpenApiRouter<AppState> {
    OpenApiRouter::with_openapi(ApiDoc::openapi())
        .merge(ops::router())
        .merge(robots::router())
        .merge(sessions::router())
        .merge(poses::router())
        .merge(upload::router())
        .merge(jobs::router())
        .merge(job_events::router())
        .merge(webhooks::router())
        .merge(results::router())
        .merge(release::router())
        .merge(export::router())
        .merge(report_links::router())
        .merge(tokens::router())
        .merge(targets::router())
        .merge(campaign_plans::router())
}

/// The routes and their OpenAPI document with the shared failure answers.
fn router_and_doc() -> (Router<AppState>, utoipa::openapi::OpenApi) {
    let (router, mut doc) = api_router().split_for_parts();
    contract::add_shared_responses(&mut doc);
    (router, doc)
}

/// The OpenAPI document (`robocal openapi`, `/openapi.json`).
pub fn openapi() -> utoipa::openapi::OpenApi {
    router_and_doc().1
}

/// The complete application: routes, docs, auth, idempotency, tracing, metrics.
pub fn app(state: AppState) -> Router {
    let (router, doc) = router_and_doc();
    let router = router
        .merge(SwaggerUi::new("/docs").url("/openapi.json", doc))
        .merge(fleet::router())
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .layer(middleware::from_fn_with_state(
            state.clone(),
            idempotency::layer,
        ))
        // Outside idempotency: a body that timed out is a failed read there.
        .layer(middleware::from_fn_with_state(
            state.clone(),
            body_idle::layer,
        ))
        // Inside auth: the reserved lane serves authenticated requests.
        .layer(middleware::from_fn(lane::layer))
        .layer(middleware::from_fn_with_state(state.clone(), auth::layer))
        // Before auth: ids and cursors with NUL never reach the database.
        .layer(middleware::from_fn(nul_guard::layer))
        // Before auth: a cross-site write is refused whoever it claims to be.
        .layer(middleware::from_fn(cross_site::layer))
        .layer(middleware::from_fn_with_state(state.clone(), observe))
        .layer(middleware::from_fn(problem_fallback::layer))
        // Uploads stream with their own limits; JSON bodies are limited by the extractors.
        .layer(DefaultBodyLimit::disable())
        .with_state(state);
    router
        .layer(CatchPanicLayer::custom(|_| {
            axum::response::IntoResponse::into_response(error::ApiError::internal("handler panicked"))
        }))
        .layer(
            TraceLayer::new_for_http()
                .on_response(DefaultOnResponse::new().level(tracing::Level::INFO))
                .make_span_with(|req: &Request| {
                let id = req
                    .headers()
                    .get(&REQUEST_ID)
                    .and_then(|v| v.to_str().ok())
                    .unwrap_or("-");
                tracing::info_span!("request", request_id = %id, method = %req.method(), uri = %req.uri())
            }),
        )
        .layer(PropagateRequestIdLayer::new(REQUEST_ID))
        .layer(SetRequestIdLayer::new(REQUEST_ID, MakeRequestUuid))
}

/// Records the request's latency under its route template.
async fn observe(State(state): State<AppState>, req: Request, next: Next) -> Response {
    let start = Instant::now();
    let method = req.method().to_string();
    let route = req
        .extensions()
        .get::<MatchedPath>()
        .map(|p| p.as_str().to_string())
        .unwrap_or_else(|| "unmatched".into());
    let response = next.run(req).await;
    state
        .metrics
        .observe(&method, &route, response.status().as_u16(), start.elapsed());
    response
}

async fn not_found(req: Request) -> error::ApiError {
    error::ApiError::new(
        StatusCode::NOT_FOUND,
        "not-found",
        format!("no route {} {}", req.method(), req.uri().path()),
    )
}

async fn method_not_allowed(req: Request) -> error::ApiError {
    error::ApiError::new(
        StatusCode::METHOD_NOT_ALLOWED,
        "method-not-allowed",
        format!("{} is not allowed on {}", req.method(), req.uri().path()),
    )
}

/// The OpenAPI document as committed in `openapi/openapi.json`.
pub fn openapi_json() -> String {
    openapi()
        .to_pretty_json()
        .unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
}
