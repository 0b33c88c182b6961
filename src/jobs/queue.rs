//! Queue operations on top of the store: enqueue with a bound, claim with a
//! lease, renew, finish, release. The atomicity lives in the store (one
//! `UPDATE ... RETURNING` claims a job); this module holds the policy.

use std::time::Duration;

use crate::domain::{now_unix_ms, LeaseStatus};
use crate::schema::job::{CalibrationOptions, CheckOptions, JobOptions};
use crate::store::{ClaimedJob, JobOutcome, JobRecord, NewJob, SessionRecord};
use crate::store::{DynStore, StoreResult};

/// Queue policy, from the server configuration.
#[derive(Debug, Clone, Copy)]
pub struct QueuePolicy {
    pub lease: Duration,
    pub max_attempts: i64,
    pub max_queued: i64,
    /// Seconds a client is told to wait when the queue is full.
    pub retry_after_secs: u64,
}

impl QueuePolicy {
    /// How often a worker renews its lease: a third of the lease, at most 1 s,
    /// so progress is visible and a cancel is noticed within a second.
    pub fn heartbeat(&self) -> Duration {
        (self.lease / 3).clamp(Duration::from_millis(50), Duration::from_secs(1))
    }
}

/// Writes a calibration job with its options (one row, one statement).
pub async fn enqueue_calibration(
    store: &DynStore,
    policy: &QueuePolicy,
    session: &SessionRecord,
    options: &CalibrationOptions,
) -> StoreResult<JobRecord> {
    let job = NewJob {
        session_id: session.id.clone(),
        serial: session.serial.clone(),
        options: JobOptions::Calibration(options.clone()),
        max_attempts: policy.max_attempts,
    };
    store.enqueue_job(&job, policy.max_queued).await
}

/// Writes a quick re-check job: no options.
pub async fn enqueue_check(
    store: &DynStore,
    policy: &QueuePolicy,
    session: &SessionRecord,
) -> StoreResult<JobRecord> {
    let job = NewJob {
        session_id: session.id.clone(),
        serial: session.serial.clone(),
        options: JobOptions::Check(CheckOptions::default()),
        max_attempts: policy.max_attempts,
    };
    store.enqueue_job(&job, policy.max_queued).await
}

/// A job held by this worker under a lease.
pub struct Lease {
    pub store: DynStore,
    pub job: ClaimedJob,
    pub worker_id: String,
    pub policy: QueuePolicy,
}

/// Fails jobs whose lease expired with no attempt left, then claims the next job.
pub async fn claim_next(
    store: &DynStore,
    policy: &QueuePolicy,
    worker_id: &str,
) -> StoreResult<Option<Lease>> {
    let now = now_unix_ms();
    let failed = store.fail_exhausted_jobs(now).await?;
    if failed > 0 {
        tracing::warn!(
            failed,
            "jobs failed after their last attempt's lease expired"
        );
    }
    let until = now + policy.lease.as_millis() as i64;
    Ok(store
        .claim_job(worker_id, now, until)
        .await?
        .map(|job| Lease {
            store: store.clone(),
            job,
            worker_id: worker_id.to_string(),
            policy: *policy,
        }))
}

impl Lease {
    pub async fn renew(&self, stage: &str, progress: f64) -> StoreResult<LeaseStatus> {
        let until = now_unix_ms() + self.policy.lease.as_millis() as i64;
        self.store
            .renew_lease(&self.job.id, &self.worker_id, until, stage, progress)
            .await
    }

    pub async fn finish(&self, outcome: &JobOutcome) -> StoreResult<LeaseStatus> {
        self.store
            .finish_job(&self.job.id, &self.worker_id, outcome)
            .await
    }

    /// Back to the queue, attempt not counted (clean shutdown).
    pub async fn release(&self) -> StoreResult<()> {
        self.store.release_job(&self.job.id, &self.worker_id).await
    }
}
