//! `GET /v1/jobs/{id}/events`: a job's stage, progress and end as
//! Server-Sent Events (`text/event-stream`); the stream ends with the job.

use std::convert::Infallible;

use axum::extract::{Path, State};
use axum::response::sse::{Event, KeepAlive, Sse};
use futures_util::{Stream, StreamExt};
use serde_json::json;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiResult, Problem};
use super::jobs::JobOut;
use super::AppState;
use crate::service::job_events::{self, JobEvent};

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
              (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn job_events(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Sse<impl Stream<Item = Result<Event, Infallible>>>> {
    let events = job_events::watch(&state.store, &id).await?;
    Ok(Sse::new(events.map(|e| Ok(sse_event(e)))).keep_alive(KeepAlive::default()))
}

fn sse_event(event: JobEvent) -> Event {
    let (name, data) = match event {
        JobEvent::Stage { stage, progress } => {
            ("stage", json!({ "stage": stage, "progress": progress }))
        }
        JobEvent::Progress { stage, progress } => {
            ("progress", json!({ "stage": stage, "progress": progress }))
        }
        JobEvent::End(job) => (
            "end",
            serde_json::to_value(JobOut::from(*job)).unwrap_or_default(),
        ),
    };
    Event::default().event(name).data(data.to_string())
}
