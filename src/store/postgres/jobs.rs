use async_trait::async_trait;
use serde_json::json;
use sqlx::Row;

use super::results::insert_parameter_set_tx;
use super::{json, PgStore};
use crate::domain::{
    new_id, now_rfc3339, ClaimedJob, JobOutcome, JobRecord, JobState, LeaseStatus, NewJob,
    PoseDetection,
};
use crate::store::rows::job;
use crate::store::{JobStore, StoreError, StoreResult};

const COLUMNS: &str = "id, kind, session_id, serial, options, state, stage, progress, attempts,
    max_attempts, error, result, created_at, started_at, finished_at";

/// Advisory lock key serialising enqueues (the `--max-queued` bound is a
/// count-then-insert, which READ COMMITTED alone would let replicas overrun).
const ENQUEUE_LOCK: i64 = 0x726f_626f_6361_6c01; // "robocal" + 1

#[async_trait]
impl JobStore for PgStore {
    async fn enqueue_job(&self, j: &NewJob, max_queued: i64) -> StoreResult<JobRecord> {
        let id = new_id();
        let mut tx = self.pool.begin().await?;
        sqlx::query("SELECT pg_advisory_xact_lock($1)")
            .bind(ENQUEUE_LOCK)
            .execute(&mut *tx)
            .await?;
        let row = sqlx::query(&format!(
            "INSERT INTO jobs (id, kind, session_id, serial, options, state, max_attempts, created_at)
             SELECT $1, $2, $3, $4, $5, 'queued', $6, $7
             WHERE (SELECT count(*) FROM jobs WHERE state = 'queued') < $8
             RETURNING {COLUMNS}"
        ))
        .bind(&id)
        .bind(&j.kind)
        .bind(&j.session_id)
        .bind(&j.serial)
        .bind(j.options.to_string())
        .bind(j.max_attempts)
        .bind(now_rfc3339())
        .bind(max_queued)
        .fetch_optional(&mut *tx)
        .await;
        let row = match row {
            Ok(Some(row)) => row,
            Ok(None) => return Err(StoreError::QueueFull),
            Err(e) if super::is_foreign_key_violation(&e) => {
                return Err(StoreError::NotFound("session"))
            }
            Err(e) => return Err(e.into()),
        };
        let record = job(&row)?;
        // The `jobs_claimable` trigger's NOTIFY goes out with this commit.
        tx.commit().await?;
        Ok(record)
    }

    async fn get_job(&self, id: &str) -> StoreResult<Option<JobRecord>> {
        let row = sqlx::query(&format!("SELECT {COLUMNS} FROM jobs WHERE id = $1"))
            .bind(id)
            .fetch_optional(&self.pool)
            .await?;
        row.as_ref().map(job).transpose()
    }

    async fn cancel_job(&self, id: &str) -> StoreResult<Option<JobRecord>> {
        let row = sqlx::query(&format!(
            "UPDATE jobs SET state = 'cancelled', finished_at = $1, lease_expires_at = NULL
             WHERE id = $2 AND state IN ('queued', 'running') RETURNING {COLUMNS}"
        ))
        .bind(now_rfc3339())
        .bind(id)
        .fetch_optional(&self.pool)
        .await?;
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
        let done = sqlx::query(
            "UPDATE jobs SET state = 'failed', finished_at = $1, worker_id = NULL,
               lease_expires_at = NULL,
               error = 'worker lost (lease expired) on attempt ' || attempts || ' of '
                       || max_attempts || coalesce('; last error: ' || error, '')
             WHERE id IN (SELECT id FROM jobs
                          WHERE state = 'running' AND lease_expires_at < $2
                            AND attempts >= max_attempts
                          FOR UPDATE SKIP LOCKED)",
        )
        .bind(now_rfc3339())
        .bind(now_ms)
        .execute(&self.pool)
        .await?;
        Ok(done.rows_affected())
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
        // and committed meanwhile is skipped, not taken twice.
        let row = sqlx::query(
            "UPDATE jobs SET state = 'running', attempts = attempts + 1, worker_id = $1,
               lease_expires_at = $2, started_at = coalesce(started_at, $3), stage = 'claimed'
             WHERE id = (SELECT id FROM jobs
                         WHERE state = 'queued'
                            OR (state = 'running' AND lease_expires_at < $4
                                AND attempts < max_attempts)
                         ORDER BY id LIMIT 1
                         FOR UPDATE SKIP LOCKED)
             RETURNING id, session_id, serial, options, attempts",
        )
        .bind(worker_id)
        .bind(lease_until_ms)
        .bind(now_rfc3339())
        .bind(now_ms)
        .fetch_optional(&self.pool)
        .await?;
        row.map(|row| {
            Ok(ClaimedJob {
                id: row.get("id"),
                session_id: row.get("session_id"),
                serial: row.get("serial"),
                options: json(row.get::<&str, _>("options"))?,
                attempt: row.get("attempts"),
            })
        })
        .transpose()
    }

    async fn renew_lease(
        &self,
        job_id: &str,
        worker_id: &str,
        lease_until_ms: i64,
        stage: &str,
        progress: f64,
    ) -> StoreResult<LeaseStatus> {
        let done = sqlx::query(
            "UPDATE jobs SET lease_expires_at = $1, stage = $2, progress = $3
             WHERE id = $4 AND worker_id = $5 AND state = 'running'",
        )
        .bind(lease_until_ms)
        .bind(stage)
        .bind(progress)
        .bind(job_id)
        .bind(worker_id)
        .execute(&self.pool)
        .await?;
        if done.rows_affected() > 0 {
            return Ok(LeaseStatus::Held);
        }
        self.lost_or_cancelled(job_id).await
    }

    async fn finish_job(
        &self,
        job_id: &str,
        worker_id: &str,
        outcome: &JobOutcome,
    ) -> StoreResult<LeaseStatus> {
        let mut tx = self.pool.begin().await?;
        // Row lock: a concurrent reclaim (lease expired) or cancel waits, and
        // if it won first this worker no longer matches and writes nothing.
        let held = sqlx::query(
            "SELECT serial, session_id, attempts, max_attempts FROM jobs
             WHERE id = $1 AND worker_id = $2 AND state = 'running' FOR UPDATE",
        )
        .bind(job_id)
        .bind(worker_id)
        .fetch_optional(&mut *tx)
        .await?;
        let Some(held) = held else {
            drop(tx);
            return self.lost_or_cancelled(job_id).await;
        };
        let serial: String = held.get("serial");
        let attempts: i64 = held.get("attempts");
        let max_attempts: i64 = held.get("max_attempts");
        let now = now_rfc3339();
        let (state, error, result) = match outcome {
            JobOutcome::Succeeded {
                parameter_set,
                summary,
                detections,
            } => {
                if !detections.is_empty() {
                    let session_id: String = held.get("session_id");
                    write_detections_tx(&mut tx, &session_id, detections).await?;
                }
                let mut result = json!({ "summary": summary });
                if let Some(set) = parameter_set {
                    let version =
                        insert_parameter_set_tx(&mut tx, &serial, Some(job_id), set).await?;
                    result["serial"] = json!(serial);
                    result["version"] = json!(version);
                }
                ("succeeded", None, Some(result.to_string()))
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
        let finished = (state != "queued").then_some(now);
        sqlx::query(
            "UPDATE jobs SET state = $1, error = $2, result = $3, finished_at = $4,
               worker_id = NULL, lease_expires_at = NULL,
               progress = CASE WHEN $1 = 'succeeded' THEN 1.0 ELSE progress END,
               stage = CASE WHEN $1 = 'succeeded' THEN 'done' ELSE stage END
             WHERE id = $5",
        )
        .bind(state)
        .bind(error)
        .bind(result)
        .bind(finished)
        .bind(job_id)
        .execute(&mut *tx)
        .await?;
        tx.commit().await?;
        Ok(LeaseStatus::Held)
    }

    async fn record_detections(
        &self,
        job_id: &str,
        worker_id: &str,
        detections: &[PoseDetection],
    ) -> StoreResult<LeaseStatus> {
        let mut tx = self.pool.begin().await?;
        // Row lock, as in `finish_job`: a reclaim or cancel racing this
        // write waits, or wins and this worker writes nothing.
        let session_id: Option<String> = sqlx::query_scalar(
            "SELECT session_id FROM jobs
             WHERE id = $1 AND worker_id = $2 AND state = 'running' FOR UPDATE",
        )
        .bind(job_id)
        .bind(worker_id)
        .fetch_optional(&mut *tx)
        .await?;
        let Some(session_id) = session_id else {
            drop(tx);
            return self.lost_or_cancelled(job_id).await;
        };
        write_detections_tx(&mut tx, &session_id, detections).await?;
        tx.commit().await?;
        Ok(LeaseStatus::Held)
    }

    async fn release_job(&self, job_id: &str, worker_id: &str) -> StoreResult<()> {
        sqlx::query(
            "UPDATE jobs SET state = 'queued', attempts = greatest(attempts - 1, 0),
               worker_id = NULL, lease_expires_at = NULL, stage = 'released'
             WHERE id = $1 AND worker_id = $2 AND state = 'running'",
        )
        .bind(job_id)
        .bind(worker_id)
        .execute(&self.pool)
        .await?;
        Ok(())
    }

    async fn job_counts(&self) -> StoreResult<Vec<(JobState, i64)>> {
        let rows = sqlx::query("SELECT state, count(*) AS n FROM jobs GROUP BY state")
            .fetch_all(&self.pool)
            .await?;
        Ok(JobState::ALL
            .into_iter()
            .map(|st| {
                let n = rows
                    .iter()
                    .find(|r| r.get::<&str, _>("state") == st.as_str())
                    .map(|r| r.get::<i64, _>("n"))
                    .unwrap_or(0);
                (st, n)
            })
            .collect())
    }
}

/// Replaces every pose's detection document of a session: the listed poses
/// get theirs, the others none (a pose uploaded after the job loaded its
/// inputs shows no stale points from an earlier job). Two jobs of one
/// session writing at once serialise on the rows: each write is whole.
async fn write_detections_tx(
    tx: &mut sqlx::Transaction<'static, sqlx::Postgres>,
    session_id: &str,
    detections: &[PoseDetection],
) -> StoreResult<()> {
    sqlx::query("UPDATE poses SET detection = NULL WHERE session_id = $1")
        .bind(session_id)
        .execute(&mut **tx)
        .await?;
    for d in detections {
        sqlx::query("UPDATE poses SET detection = $1 WHERE session_id = $2 AND id = $3")
            .bind(d.detection.to_string())
            .bind(session_id)
            .bind(&d.pose_id)
            .execute(&mut **tx)
            .await?;
    }
    Ok(())
}

impl PgStore {
    async fn lost_or_cancelled(&self, job_id: &str) -> StoreResult<LeaseStatus> {
        let state: Option<String> = sqlx::query_scalar("SELECT state FROM jobs WHERE id = $1")
            .bind(job_id)
            .fetch_optional(&self.pool)
            .await?;
        Ok(match state.as_deref() {
            Some("cancelled") => LeaseStatus::Cancelled,
            _ => LeaseStatus::Lost,
        })
    }
}
