//! The release gate's records (issue 17): a parameter set's status changes,
//! each logged with who and when, and the finished re-checks of a robot.

use async_trait::async_trait;
use sqlx::Transaction;

use super::webhooks::record_event_tx;
use crate::domain::{
    now_rfc3339, now_unix_ms, Decision, DomainEvent, JobKind, Release, ReleaseStatus,
};
use crate::store::backend::Backend;
use crate::store::rows::{job, parameter_set, release_status, Columns, JOB_COLUMNS};
use crate::store::statement::query;
use crate::store::{JobRecord, ParameterSetRecord, ReleaseStore, StoreResult};

/// Appends one decision to the set's log inside the caller's transaction.
pub(super) async fn record_decision_tx<B: Backend>(
    tx: &mut Transaction<'static, B::Db>,
    serial: &str,
    version: i64,
    release: &Release,
    actor: &str,
    at: &str,
) -> StoreResult<()> {
    let seq = query(
        "SELECT COALESCE(MAX(seq), 0) + 1 AS seq FROM parameter_set_decisions
         WHERE serial = $1 AND version = $2",
    )
    .bind(serial)
    .bind(version)
    .fetch_one(&mut *tx)
    .await?
    .int("seq");
    query(
        "INSERT INTO parameter_set_decisions
           (serial, version, seq, status, reason, decided_by, decided_at)
         VALUES ($1, $2, $3, $4, $5, $6, $7)",
    )
    .bind(serial)
    .bind(version)
    .bind(seq)
    .bind(release.status.as_str())
    .bind(release.reason.as_deref())
    .bind(actor)
    .bind(at)
    .execute(&mut *tx)
    .await?;
    Ok(())
}

#[async_trait]
impl<B: Backend> ReleaseStore for B {
    async fn set_release(
        &self,
        serial: &str,
        version: i64,
        release: &Release,
        actor: &str,
    ) -> StoreResult<Option<ParameterSetRecord>> {
        let mut tx = self.begin_write().await?;
        let found = query(format!(
            "SELECT version FROM parameter_sets WHERE serial = $1 AND version = $2{}",
            B::FOR_UPDATE
        ))
        .bind(serial)
        .bind(version)
        .fetch_optional(&mut tx)
        .await?;
        if found.is_none() {
            return Ok(None);
        }
        let now = now_rfc3339();
        query(
            "UPDATE parameter_sets SET status = $1, status_reason = $2, status_by = $3,
               status_at = $4 WHERE serial = $5 AND version = $6",
        )
        .bind(release.status.as_str())
        .bind(release.reason.as_deref())
        .bind(actor)
        .bind(&now)
        .bind(serial)
        .bind(version)
        .execute(&mut tx)
        .await?;
        record_decision_tx::<B>(&mut tx, serial, version, release, actor, &now).await?;
        if release.status == ReleaseStatus::Approved {
            let event = DomainEvent::SetApproved {
                serial: serial.to_string(),
                version,
                approved_by: actor.to_string(),
            };
            record_event_tx::<B>(&mut tx, &event, now_unix_ms()).await?;
        }
        let row = query(
            "SELECT serial, version, job_id, parameters, created_at,
                    status, status_reason, status_by, status_at FROM parameter_sets
             WHERE serial = $1 AND version = $2",
        )
        .bind(serial)
        .bind(version)
        .fetch_one(&mut tx)
        .await?;
        tx.commit().await?;
        parameter_set(&row).map(Some)
    }

    async fn list_decisions(&self, serial: &str) -> StoreResult<Vec<Decision>> {
        let rows = query(
            "SELECT version, status, reason, decided_by, decided_at FROM parameter_set_decisions
             WHERE serial = $1 ORDER BY decided_at, version, seq",
        )
        .bind(serial)
        .fetch_all(self.pool())
        .await?;
        rows.iter()
            .map(|r| {
                Ok(Decision {
                    version: r.int("version"),
                    status: release_status(r.str("status"))?,
                    reason: r.opt_string("reason"),
                    decided_by: r.string("decided_by"),
                    decided_at: r.string("decided_at"),
                })
            })
            .collect()
    }

    async fn list_checks(&self, serial: &str, limit: i64) -> StoreResult<Vec<JobRecord>> {
        let rows = query(format!(
            "SELECT {} FROM jobs WHERE serial = $1 AND kind = $2 AND state = 'succeeded'
             ORDER BY id DESC LIMIT $3",
            JOB_COLUMNS
        ))
        .bind(serial)
        .bind(JobKind::Check.as_str())
        .bind(limit)
        .fetch_all(self.pool())
        .await?;
        rows.iter().map(job).collect()
    }
}
