use async_trait::async_trait;
use sqlx::Transaction;

use super::detections::write_detections_tx;
use super::job_success::{record_success_tx, Success};
use super::page_cursor;
use super::webhooks::record_event_tx;
use crate::domain::{new_id, now_rfc3339, now_unix_ms, DomainEvent, JobState, LeaseStatus, Page};
use crate::store::backend::{is_foreign_key_violation, Backend};
use crate::store::rows::{claimed_job, job, Columns};
use crate::store::statement::{query, DbRow};
use crate::store::{ClaimedJob, JobFilter, JobOutcome, JobRecord, NewJob, PoseDetection};
use crate::store::{JobStore, StoreError, StoreResult};

use crate::store::rows::JOB_COLUMNS as COLUMNS;

#[async_trait]
impl<B: Backend> JobStore for B {
    async fn enqueue_job(&self, j: &NewJob, max_queued: i64) -> StoreResult<JobRecord> {
        let mut tx = self.begin_write().await?;
        B::serialise_enqueue(&mut tx).await?;
        let row = query(format!(
            "INSERT INTO jobs (id, kind, session_id, serial, options, state, max_attempts,
               created_at)
             SELECT $1, $2, $3, $4, $5, 'queued', $6, $7
             WHERE (SELECT count(*) FROM jobs WHERE state = 'queued') < $8
             RETURNING {COLUMNS}"
        ))
        .bind(new_id())
        .bind(j.options.kind().as_str())
        .bind(&j.session_id)
        .bind(&j.serial)
        .bind(serde_json::to_string(&j.options)?)
        .bind(j.max_attempts)
        .bind(now_rfc3339())
        .bind(max_queued)
        .fetch_optional(&mut tx)
        .await;
        let row = match row {
            Ok(Some(row)) => row,
            Ok(None) => return Err(StoreError::QueueFull),
            Err(e) if is_foreign_key_violation(&e) => return Err(StoreError::NotFound("session")),
            Err(e) => return Err(e.into()),
        };
        let record = job(&row)?;
        // On PostgreSQL the `jobs_claimable` trigger's NOTIFY goes out with this commit.
        tx.commit().await?;
        Ok(record)
    }

    async fn get_job(&self, id: &str) -> StoreResult<Option<JobRecord>> {
        let row = query(format!("SELECT {COLUMNS} FROM jobs WHERE id = $1"))
            .bind(id)
            .fetch_optional(self.pool())
            .await?;
        row.as_ref().map(job).transpose()
    }

    async fn list_jobs(
        &self,
        filter: &JobFilter,
        limit: i64,
        before: Option<&str>,
    ) -> StoreResult<Page<JobRecord>> {
        // Ids are UUIDv7: descending id order is newest first. An empty
        // filter value lets every row through.
        let rows = query(format!(
            "SELECT {COLUMNS} FROM jobs WHERE ($1 = '' OR id < $1)
               AND ($3 = '' OR state = $3) AND ($4 = '' OR serial = $4) AND ($5 = '' OR kind = $5)
             ORDER BY id DESC LIMIT $2"
        ))
        .bind(before.unwrap_or(""))
        .bind(limit)
        .bind(filter.state.map(JobState::as_str).unwrap_or(""))
        .bind(filter.serial.as_deref().unwrap_or(""))
        .bind(filter.kind.map_or("", |k| k.as_str()))
        .fetch_all(self.pool())
        .await?;
        let items = rows.iter().map(job).collect::<StoreResult<Vec<_>>>()?;
        let next_cursor = page_cursor(&items, limit, |j| j.id.clone());
        Ok(Page { items, next_cursor })
    }

    async fn cancel_job(&self, id: &str) -> StoreResult<Option<JobRecord>> {
        let mut tx = self.begin_write().await?;
        let row = query(format!(
            "UPDATE jobs SET state = 'cancelled', finished_at = $1, lease_expires_at = NULL
             WHERE id = $2 AND state IN ('queued', 'running') RETURNING {COLUMNS}"
        ))
        .bind(now_rfc3339())
        .bind(id)
        .fetch_optional(&mut tx)
        .await?;
        if let Some(row) = &row {
            let record = job(row)?;
            record_event_tx::<B>(&mut tx, &finished_event(&record), now_unix_ms()).await?;
            tx.commit().await?;
            return Ok(Some(record));
        }
        drop(tx);
        match row {
            Some(row) => Ok(Some(job(&row)?)),
            None => match self.get_job(id).await? {
                None => Ok(None),
                Some(j) => Err(StoreError::Conflict(format!(
                    "job is already {}",
                    j.state.as_str()
                ))),
            },
        }
    }

    async fn fail_exhausted_jobs(&self, now_ms: i64) -> StoreResult<u64> {
        // SKIP LOCKED: a row another replica is claiming or finishing right
        // now is left to it (and to the next sweep).
        // Every idle worker sweeps at every poll: look before taking the
        // write lock (SQLite has one for the whole database).
        let due = query(
            "SELECT id FROM jobs WHERE state = 'running' AND lease_expires_at < $1
               AND attempts >= max_attempts LIMIT 1",
        )
        .bind(now_ms)
        .fetch_optional(self.pool())
        .await?;
        if due.is_none() {
            return Ok(0);
        }
        let mut tx = self.begin_write().await?;
        let rows = query(format!(
            "UPDATE jobs SET state = 'failed', finished_at = $1, worker_id = NULL,
               lease_expires_at = NULL,
               error = 'worker lost (lease expired) on attempt ' || attempts || ' of '
                       || max_attempts || coalesce('; last error: ' || error, '')
             WHERE id IN (SELECT id FROM jobs
                          WHERE state = 'running' AND lease_expires_at < $2
                            AND attempts >= max_attempts{})
             RETURNING {COLUMNS}",
            B::FOR_UPDATE_SKIP_LOCKED
        ))
        .bind(now_rfc3339())
        .bind(now_ms)
        .fetch_all(&mut tx)
        .await?;
        for row in &rows {
            record_event_tx::<B>(&mut tx, &finished_event(&job(row)?), now_ms).await?;
        }
        tx.commit().await?;
        Ok(rows.len() as u64)
    }

    async fn claim_job(
        &self,
        worker_id: &str,
        now_ms: i64,
        lease_until_ms: i64,
    ) -> StoreResult<Option<ClaimedJob>> {
        // The oldest claimable row not locked by another claimer: replicas
        // never wait on each other and never take the same job. Under READ
        // COMMITTED the row is re-checked after locking, so a job claimed
        // and committed meanwhile is skipped, not taken twice. (SQLite runs
        // the one statement under its database write lock.)
        let row = query(format!(
            "UPDATE jobs SET state = 'running', attempts = attempts + 1, worker_id = $1,
               lease_expires_at = $2, started_at = coalesce(started_at, $3), stage = 'claimed'
             WHERE id = (SELECT id FROM jobs
                         WHERE state = 'queued'
                            OR (state = 'running' AND lease_expires_at < $4
                                AND attempts < max_attempts)
                         ORDER BY id LIMIT 1{})
             RETURNING id, kind, session_id, serial, options, attempts",
            B::FOR_UPDATE_SKIP_LOCKED
        ))
        .bind(worker_id)
        .bind(lease_until_ms)
        .bind(now_rfc3339())
        .bind(now_ms)
        .fetch_optional(self.pool())
        .await?;
        row.as_ref().map(claimed_job).transpose()
    }

    async fn renew_lease(
        &self,
        job_id: &str,
        worker_id: &str,
        lease_until_ms: i64,
        stage: &str,
        progress: f64,
    ) -> StoreResult<LeaseStatus> {
        let renewed = query(
            "UPDATE jobs SET lease_expires_at = $1, stage = $2, progress = $3
             WHERE id = $4 AND worker_id = $5 AND state = 'running'",
        )
        .bind(lease_until_ms)
        .bind(stage)
        .bind(progress)
        .bind(job_id)
        .bind(worker_id)
        .execute(self.pool())
        .await?;
        if renewed > 0 {
            return Ok(LeaseStatus::Held);
        }
        lost_or_cancelled(self, job_id).await
    }

    async fn finish_job(
        &self,
        job_id: &str,
        worker_id: &str,
        outcome: &JobOutcome,
    ) -> StoreResult<LeaseStatus> {
        let mut tx = self.begin_write().await?;
        let Some(held) = lock_held_job::<B>(&mut tx, job_id, worker_id).await? else {
            drop(tx);
            return lost_or_cancelled(self, job_id).await;
        };
        let serial = held.string("serial");
        let attempts = held.int("attempts");
        let max_attempts = held.int("max_attempts");
        let mut version = None;
        let (state, error, result) = match outcome {
            JobOutcome::Succeeded {
                parameter_set,
                summary,
                detections,
                check,
            } => {
                let success = Success {
                    job_id,
                    session_id: held.str("session_id"),
                    serial: &serial,
                    parameter_set: parameter_set.as_ref(),
                    summary,
                    detections,
                    check: check.as_deref(),
                };
                let (result, stored) = record_success_tx::<B>(&mut tx, success).await?;
                version = stored;
                ("succeeded", None, Some(serde_json::to_string(&result)?))
            }
            JobOutcome::Failed { error } => ("failed", Some(error.clone()), None),
            JobOutcome::Retry { error } if attempts < max_attempts => {
                ("queued", Some(error.clone()), None)
            }
            JobOutcome::Retry { error } => (
                "failed",
                Some(format!("{error} (after {attempts} attempts)")),
                None,
            ),
        };
        let finished = (state != "queued").then(now_rfc3339);
        query(
            "UPDATE jobs SET state = $1, error = $2, result = $3, finished_at = $4,
               worker_id = NULL, lease_expires_at = NULL,
               progress = CASE WHEN $1 = 'succeeded' THEN 1.0 ELSE progress END,
               stage = CASE WHEN $1 = 'succeeded' THEN 'done' ELSE stage END
             WHERE id = $5",
        )
        .bind(state)
        .bind(error.clone())
        .bind(result)
        .bind(finished)
        .bind(job_id)
        .execute(&mut tx)
        .await?;
        if state != "queued" {
            let event = DomainEvent::JobFinished {
                job_id: job_id.to_string(),
                kind: held.string("kind"),
                serial,
                session_id: held.string("session_id"),
                state: JobState::parse(state).unwrap_or(JobState::Failed),
                version,
                error,
            };
            record_event_tx::<B>(&mut tx, &event, now_unix_ms()).await?;
        }
        tx.commit().await?;
        Ok(LeaseStatus::Held)
    }

    async fn record_detections(
        &self,
        job_id: &str,
        worker_id: &str,
        detections: &[PoseDetection],
    ) -> StoreResult<LeaseStatus> {
        let mut tx = self.begin_write().await?;
        let Some(held) = lock_held_job::<B>(&mut tx, job_id, worker_id).await? else {
            drop(tx);
            return lost_or_cancelled(self, job_id).await;
        };
        write_detections_tx::<B>(&mut tx, held.str("session_id"), detections).await?;
        tx.commit().await?;
        Ok(LeaseStatus::Held)
    }

    async fn release_job(&self, job_id: &str, worker_id: &str) -> StoreResult<()> {
        query(
            "UPDATE jobs SET state = 'queued',
               attempts = CASE WHEN attempts > 0 THEN attempts - 1 ELSE 0 END,
               worker_id = NULL, lease_expires_at = NULL, stage = 'released'
             WHERE id = $1 AND worker_id = $2 AND state = 'running'",
        )
        .bind(job_id)
        .bind(worker_id)
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn job_counts(&self) -> StoreResult<Vec<(JobState, i64)>> {
        let rows = query("SELECT state, count(*) AS n FROM jobs GROUP BY state")
            .fetch_all(self.pool())
            .await?;
        Ok(JobState::ALL
            .into_iter()
            .map(|st| {
                let n = rows
                    .iter()
                    .find(|r| r.str("state") == st.as_str())
                    .map(|r| r.int("n"))
                    .unwrap_or(0);
                (st, n)
            })
            .collect())
    }
}

/// `job.finished` of a job that ended outside a worker (cancelled, or
/// failed once its last lease expired).
fn finished_event(j: &JobRecord) -> DomainEvent {
    DomainEvent::JobFinished {
        job_id: j.id.clone(),
        kind: j.kind.as_str().to_string(),
        serial: j.serial.clone(),
        session_id: j.session_id.clone(),
        state: j.state,
        version: None,
        error: j.error.clone(),
    }
}

/// The job's row, locked, if `worker_id` still holds its lease. A
/// concurrent reclaim (lease expired) or cancel waits for this transaction,
/// or won first, and then this worker no longer matches and writes nothing.
async fn lock_held_job<B: Backend>(
    tx: &mut Transaction<'static, B::Db>,
    job_id: &str,
    worker_id: &str,
) -> StoreResult<Option<DbRow<B::Db>>> {
    Ok(query(format!(
        "SELECT serial, session_id, kind, attempts, max_attempts FROM jobs
         WHERE id = $1 AND worker_id = $2 AND state = 'running'{}",
        B::FOR_UPDATE
    ))
    .bind(job_id)
    .bind(worker_id)
    .fetch_optional(tx)
    .await?)
}

/// Why a worker's write matched no row: the job was cancelled, or its lease
/// went to another worker (or the job is gone).
async fn lost_or_cancelled<B: Backend>(store: &B, job_id: &str) -> StoreResult<LeaseStatus> {
    let row = query("SELECT state FROM jobs WHERE id = $1")
        .bind(job_id)
        .fetch_optional(store.pool())
        .await?;
    Ok(match row.as_ref().map(|r| r.str("state")) {
        Some("cancelled") => LeaseStatus::Cancelled,
        _ => LeaseStatus::Lost,
    })
}
