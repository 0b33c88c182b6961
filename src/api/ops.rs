//! Operations: `/healthz` (process up), `/readyz` (database answers and
//! workers run), `/metrics` (Prometheus text). No authentication.

use std::fmt::Write;
use std::sync::atomic::Ordering;

use axum::extract::State;
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::Serialize;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::ApiResult;
use super::AppState;
use crate::domain::JobState;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(healthz))
        .routes(routes!(readyz))
        .routes(routes!(metrics))
}

#[derive(Debug, Serialize, ToSchema)]
pub struct Health {
    pub status: String,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct Readiness {
    pub status: String,
    pub database: String,
    pub workers: usize,
}

/// The process is up.
#[utoipa::path(get, path = "/healthz", tag = "ops", security(()), responses((status = 200, description = "The process is alive", body = Health)))]
async fn healthz() -> Json<Health> {
    Json(Health {
        status: "ok".into(),
    })
}

/// The database answers and the workers run (503 otherwise).
#[utoipa::path(get, path = "/readyz", tag = "ops", security(()),
    responses((status = 200, description = "The database answers and at least one worker runs", body = Readiness), (status = 503, description = "Not ready: the database or the workers are down (the body says which)", body = Readiness)))]
async fn readyz(State(state): State<AppState>) -> Response {
    let database = match state.store.ping().await {
        Ok(()) => "ok".to_string(),
        Err(e) => format!("error: {e}"),
    };
    let workers = state.workers_alive.load(Ordering::SeqCst);
    let ready = database == "ok" && workers > 0;
    let status = if ready {
        StatusCode::OK
    } else {
        StatusCode::SERVICE_UNAVAILABLE
    };
    let body = Readiness {
        status: if ready { "ready" } else { "not ready" }.into(),
        database,
        workers,
    };
    (status, Json(body)).into_response()
}

/// Prometheus text: queue depth, jobs by state, request latency histograms.
#[utoipa::path(get, path = "/metrics", tag = "ops", security(()),
    responses((status = 200, description = "Prometheus text format", content_type = "text/plain")))]
async fn metrics(State(state): State<AppState>) -> ApiResult<Response> {
    let counts = state.store.job_counts().await?;
    let mut out = String::new();
    let queued = counts
        .iter()
        .find(|(s, _)| *s == JobState::Queued)
        .map(|(_, n)| *n)
        .unwrap_or(0);
    out.push_str("# HELP robocal_queue_depth Jobs waiting to be claimed.\n");
    out.push_str("# TYPE robocal_queue_depth gauge\n");
    let _ = writeln!(out, "robocal_queue_depth {queued}");
    out.push_str("# HELP robocal_jobs Jobs by state.\n# TYPE robocal_jobs gauge\n");
    for (st, n) in &counts {
        let _ = writeln!(out, "robocal_jobs{{state=\"{}\"}} {n}", st.as_str());
    }
    out.push_str("# HELP robocal_workers_alive Worker loops running in this process.\n");
    out.push_str("# TYPE robocal_workers_alive gauge\n");
    let _ = writeln!(
        out,
        "robocal_workers_alive {}",
        state.workers_alive.load(Ordering::SeqCst)
    );
    state.metrics.render(&mut out);
    Ok((
        [(
            header::CONTENT_TYPE,
            "text/plain; version=0.0.4; charset=utf-8",
        )],
        out,
    )
        .into_response())
}
