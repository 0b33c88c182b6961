use async_trait::async_trait;
use serde_json::json;
use sqlx::Row;

use super::results::insert_parameter_set_tx;
use super::{json, SqliteStore};
use crate::domain::{
    new_id, now_rfc3339, ClaimedJob, JobOutcome, JobRecord, JobState, LeaseStatus, NewJob,
    PoseDetection,
};
use crate::store::rows::job;
use crate::store::{JobStore, StoreError, StoreResult};

const COLUMNS: &str = "id, kind, session_id, serial, options, state, stage, progress, attempts,
    max_attempts, error, result, created_at, started_at, finished_at";

#[async_trait]
impl JobStore for SqliteStore {
    async fn enqueue_job(&self, j: &NewJob, max_queued: i64) -> StoreResult<JobRecord> {
        let id = new_id();
        // One statement: the bound check and the insert cannot interleave with
        // another enqueue (SQLite serialises writers).
        let done = sqlx::query(
            "INSERT INTO jobs (id, kind, session_id, serial, options, state, max_attempts, created_at)
             SELECT ?, ?, ?, ?, ?, 'queued', ?, ?
             WHERE (SELECT count(*) FROM jobs WHERE state = 'queued') < ?",
        )
        .bind(&id)
        .bind(&j.kind)
        .bind(&j.session_id)
        .bind(&j.serial)
        .bind(j.options.to_string())
        .bind(j.max_attempts)
        .bind(now_rfc3339())
        .bind(max_queued)
        .execute(&self.pool)
        .await?;
        if done.rows_affected() == 0 {
            return Err(StoreError::QueueFull);
        }
        self.get_job(&id)
            .await?
            .ok_or_else(|| StoreError::Backend("inserted job vanished".into()))
    }

    async fn get_job(&self, id: &str) -> StoreResult<Option<JobRecord>> {
        let row = sqlx::query(&format!("SELECT {COLUMNS} FROM jobs WHERE id = ?"))
            .bind(id)
            .fetch_optional(&self.pool)
            .await?;
        row.as_ref().map(job).transpose()
    }

    async fn cancel_job(&self, id: &str) -> StoreResult<Option<JobRecord>> {
        let row = sqlx::query(&format!(
            "UPDATE jobs SET state = 'cancelled', finished_at = ?, lease_expires_at = NULL
             WHERE id = ? AND state IN ('queued', 'running') RETURNING {COLUMNS}"
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
        let done = sqlx::query(
            "UPDATE jobs SET state = 'failed', finished_at = ?, worker_id = NULL,
               lease_expires_at = NULL,
               error = 'worker lost (lease expired) on attempt ' || attempts || ' of '
                       || max_attempts || coalesce('; last error: ' || error, '')
             WHERE state = 'running' AND lease_expires_at < ? AND attempts >= max_attempts",
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
        let row = sqlx::query(
            "UPDATE jobs SET state = 'running', attempts = attempts + 1, worker_id = ?,
               lease_expires_at = ?, started_at = coalesce(started_at, ?), stage = 'claimed'
             WHERE id = (SELECT id FROM jobs
                         WHERE state = 'queued'
                            OR (state = 'running' AND lease_expires_at < ?
                                AND attempts < max_attempts)
                         ORDER BY id LIMIT 1)
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
            "UPDATE jobs SET lease_expires_at = ?, stage = ?, progress = ?
             WHERE id = ? AND worker_id = ? AND state = 'running'",
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
        let mut tx = self.begin_immediate().await?;
        let held = sqlx::query(
            "SELECT serial, session_id, attempts, max_attempts FROM jobs
             WHERE id = ? AND worker_id = ? AND state = 'running'",
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
            "UPDATE jobs SET state = ?, error = ?, result = ?, finished_at = ?,
               worker_id = NULL, lease_expires_at = NULL,
               progress = CASE WHEN ? = 'succeeded' THEN 1.0 ELSE progress END,
               stage = CASE WHEN ? = 'succeeded' THEN 'done' ELSE stage END
             WHERE id = ?",
        )
        .bind(state)
        .bind(error)
        .bind(result)
        .bind(finished)
        .bind(state)
        .bind(state)
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
        let mut tx = self.begin_immediate().await?;
        let session_id: Option<String> = sqlx::query_scalar(
            "SELECT session_id FROM jobs WHERE id = ? AND worker_id = ? AND state = 'running'",
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
            "UPDATE jobs SET state = 'queued', attempts = max(attempts - 1, 0), worker_id = NULL,
               lease_expires_at = NULL, stage = 'released'
             WHERE id = ? AND worker_id = ? AND state = 'running'",
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
/// inputs shows no stale points from an earlier job).
async fn write_detections_tx(
    tx: &mut sqlx::Transaction<'static, sqlx::Sqlite>,
    session_id: &str,
    detections: &[PoseDetection],
) -> StoreResult<()> {
    sqlx::query("UPDATE poses SET detection = NULL WHERE session_id = ?")
        .bind(session_id)
        .execute(&mut **tx)
        .await?;
    for d in detections {
        sqlx::query("UPDATE poses SET detection = ? WHERE session_id = ? AND id = ?")
            .bind(d.detection.to_string())
            .bind(session_id)
            .bind(&d.pose_id)
            .execute(&mut **tx)
            .await?;
    }
    Ok(())
}

impl SqliteStore {
    async fn lost_or_cancelled(&self, job_id: &str) -> StoreResult<LeaseStatus> {
        let state: Option<String> = sqlx::query_scalar("SELECT state FROM jobs WHERE id = ?")
            .bind(job_id)
            .fetch_optional(&self.pool)
            .await?;
        Ok(match state.as_deref() {
            Some("cancelled") => LeaseStatus::Cancelled,
            _ => LeaseStatus::Lost,
        })
    }
}
