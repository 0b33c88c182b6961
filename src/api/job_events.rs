//! `GET /v1/jobs/{id}/events`: a job's stage, progress and end as
//! Server-Sent Events (`text/event-stream`); the stream ends with the job,
//! or within a second of its token's revocation or expiry. Open streams are
//! counted apart from connections (`listen::registry`).

use std::convert::Infallible;

use axum::extract::{Path, State};
use axum::http::StatusCode;
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::Extension;
use futures_util::future::BoxFuture;
use futures_util::{Stream, StreamExt};
use serde_json::json;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::auth::Principal;
use super::error::{ApiError, ApiResult, Problem};
use super::jobs::JobOut;
use super::token_watch;
use super::AppState;
use crate::listen::registry::{ConnRef, Refusal, StreamGuard};
use crate::service::job_events::{self, JobEvent};

/// Seconds a client refused a stream should wait.
const STREAM_RETRY_AFTER_SECS: u64 = 5;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(job_events))
}

/// The job's events as they happen: `stage` (`{"stage","progress"}`) when
/// it enters a stage, `progress` (`{"stage","progress"}`, 0..1) as it
/// advances, and `end` (the job, as `GET /v1/jobs/{id}` answers it) when it
/// succeeded, failed or was cancelled; the stream closes after `end`. The
/// first events say where the job is when the stream opens (a finished
/// job answers its `end` at once).
#[utoipa::path(get, path = "/v1/jobs/{id}/events", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses((status = 200, description = "Server-Sent Events: `stage`, `progress`, then `end` with the job", content_type = "text/event-stream", body = crate::schema::job::JobEventFrame),
              (status = 404, body = Problem, content_type = "application/problem+json"),
              (status = 429, description = "This client address holds its maximum of event streams (`--max-event-streams-per-address`)", body = Problem, content_type = "application/problem+json"),
              (status = 503, description = "The server holds its maximum of event streams (`--max-event-streams`), or of connections", body = Problem, content_type = "application/problem+json")))]
async fn job_events(
    State(state): State<AppState>,
    conn: Option<Extension<ConnRef>>,
    principal: Option<Extension<Principal>>,
    Path(id): Path<String>,
) -> ApiResult<Sse<impl Stream<Item = Result<Event, Infallible>>>> {
    let place = conn.map(|Extension(c)| stream_place(&c)).transpose()?;
    let events = job_events::watch(&state.store, &id).await?;
    // A stream opened with a token ends once the token is revoked or expires.
    let revoked: BoxFuture<'static, ()> = match principal {
        Some(Extension(Principal::Token { id, .. })) => {
            Box::pin(token_watch::unusable(state.tokens.clone(), id))
        }
        _ => Box::pin(futures_util::future::pending()),
    };
    Ok(Sse::new(events.take_until(revoked).map(move |e| {
        // The stream holds its place until it ends or the client goes.
        let _place: &Option<StreamGuard> = &place;
        Ok(sse_event(e))
    }))
    .keep_alive(KeepAlive::default()))
}

/// Moves the connection from the connection count to the stream count.
fn stream_place(conn: &ConnRef) -> Result<StreamGuard, ApiError> {
    conn.open_stream().map_err(|refusal| {
        let (status, detail) = match refusal {
            Refusal::PerAddress => (
                StatusCode::TOO_MANY_REQUESTS,
                "this client address holds its maximum of event streams \
                 (server option --max-event-streams-per-address)",
            ),
            Refusal::Full => (
                StatusCode::SERVICE_UNAVAILABLE,
                "the server holds its maximum of event streams (server option --max-event-streams)",
            ),
        };
        ApiError {
            retry_after_secs: Some(STREAM_RETRY_AFTER_SECS),
            ..ApiError::new(status, "too-many-streams", detail)
        }
    })
}

fn sse_event(event: JobEvent) -> Event {
    let (name, data) = match event {
        JobEvent::Stage { stage, progress } => {
            ("stage", json!({ "stage": stage, "progress": progress }))
        }
        JobEvent::Progress { stage, progress } => {
            ("progress", json!({ "stage": stage, "progress": progress }))
        }
        JobEvent::End(job) => {
            // A job document that does not serialise ends the stream with
            // the reason, not with an empty `end`.
            return Event::default()
                .event("end")
                .json_data(JobOut::from(*job))
                .unwrap_or_else(|e| Event::default().event("error").data(e.to_string()));
        }
    };
    Event::default().event(name).data(data.to_string())
}
