//! A job's live events (`GET /v1/jobs/{id}/events`, Server-Sent Events):
//! what changed since the last look, read from the job's row, so it works
//! alike on SQLite and PostgreSQL and whichever replica runs the job (the
//! worker writes stage and progress at every heartbeat, `QueuePolicy::heartbeat`).

use std::collections::VecDeque;
use std::time::Duration;

use futures_util::stream::{self, Stream};

use super::error::{ServiceError, ServiceResult};
use crate::store::{DynStore, JobRecord};

/// How often the job's row is read: a quarter of the longest heartbeat
/// (1 s), so every stage a worker publishes is seen.
pub const POLL: Duration = Duration::from_millis(250);

/// One change of a job.
#[derive(Debug, Clone)]
pub enum JobEvent {
    /// The job entered a stage (`claimed`, `validate`, `detect`, …).
    Stage { stage: String, progress: f64 },
    /// The fraction done (0..1) moved.
    Progress {
        stage: Option<String>,
        progress: f64,
    },
    /// The job ended (succeeded, failed, cancelled); the stream ends after it.
    End(Box<JobRecord>),
}

struct Watch {
    store: DynStore,
    id: String,
    first: Option<JobRecord>,
    stage: Option<String>,
    progress: Option<f64>,
    pending: VecDeque<JobEvent>,
    ended: bool,
}

impl Watch {
    /// Queues what changed in `job` since the last look.
    fn compare(&mut self, job: JobRecord) {
        if job.stage != self.stage {
            if let Some(stage) = job.stage.clone() {
                self.pending.push_back(JobEvent::Stage {
                    stage,
                    progress: job.progress,
                });
            }
            self.stage = job.stage.clone();
            self.progress = Some(job.progress);
        }
        if self.progress != Some(job.progress) {
            self.pending.push_back(JobEvent::Progress {
                stage: job.stage.clone(),
                progress: job.progress,
            });
            self.progress = Some(job.progress);
        }
        if job.state.is_terminal() {
            self.ended = true;
            self.pending.push_back(JobEvent::End(Box::new(job)));
        }
    }
}

/// The events of job `id` from now until it ends (404 when there is no
/// such job). The first events state where the job is now.
pub async fn watch(
    store: &DynStore,
    id: &str,
) -> ServiceResult<impl Stream<Item = JobEvent> + Send + 'static> {
    let first = store
        .get_job(id)
        .await?
        .ok_or_else(|| ServiceError::not_found("job", id))?;
    let watch = Watch {
        store: store.clone(),
        id: id.to_string(),
        first: Some(first),
        stage: None,
        progress: None,
        pending: VecDeque::new(),
        ended: false,
    };
    Ok(stream::unfold(watch, |mut w| async move {
        loop {
            if let Some(event) = w.pending.pop_front() {
                return Some((event, w));
            }
            if w.ended {
                return None;
            }
            let job = match w.first.take() {
                Some(job) => job,
                None => {
                    tokio::time::sleep(POLL).await;
                    match w.store.get_job(&w.id).await {
                        Ok(Some(job)) => job,
                        // Deleted with its robot: nothing more will happen.
                        Ok(None) => return None,
                        Err(e) => {
                            tracing::warn!(job_id = %w.id, error = %e, "job events: reading the job failed");
                            continue;
                        }
                    }
                }
            };
            w.compare(job);
        }
    }))
}
