use async_trait::async_trait;
use serde_json::Value;
use sqlx::Transaction;

use super::page_cursor;
use super::release::record_decision_tx;
use crate::domain::{now_rfc3339, Page, GATE_ACTOR};
use crate::store::backend::Backend;
use crate::store::rows::{json, parameter_set, Columns};
use crate::store::statement::query;
use crate::store::{NewParameterSet, ParameterSetRecord};
use crate::store::{ResultStore, StoreResult};

/// Inserts the serial's next version inside the caller's writing
/// transaction. The backend's `NEXT_VERSION` hands out 1, 2, 3... with no
/// duplicate and no gap under concurrent writers (see each backend).
pub(super) async fn insert_parameter_set_tx<B: Backend>(
    tx: &mut Transaction<'static, B::Db>,
    serial: &str,
    job_id: Option<&str>,
    set: &NewParameterSet,
) -> StoreResult<i64> {
    let version = query(B::NEXT_VERSION)
        .bind(serial)
        .fetch_one(&mut *tx)
        .await?
        .int("version");
    let now = now_rfc3339();
    let release = &set.release;
    query(
        "INSERT INTO parameter_sets (serial, version, job_id, parameters, created_at,
           status, status_reason, status_by, status_at)
         VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $5)",
    )
    .bind(serial)
    .bind(version)
    .bind(job_id)
    .bind(serde_json::to_string(&set.parameters)?)
    .bind(&now)
    .bind(release.status.as_str())
    .bind(release.reason.as_deref())
    .bind(GATE_ACTOR)
    .execute(&mut *tx)
    .await?;
    record_decision_tx::<B>(tx, serial, version, release, GATE_ACTOR, &now).await?;
    query("INSERT INTO reports (serial, version, report) VALUES ($1, $2, $3)")
        .bind(serial)
        .bind(version)
        .bind(set.report.to_string())
        .execute(&mut *tx)
        .await?;
    Ok(version)
}

#[async_trait]
impl<B: Backend> ResultStore for B {
    async fn insert_parameter_set(
        &self,
        serial: &str,
        job_id: Option<&str>,
        set: &NewParameterSet,
    ) -> StoreResult<i64> {
        let mut tx = self.begin_write().await?;
        let version = insert_parameter_set_tx::<B>(&mut tx, serial, job_id, set).await?;
        tx.commit().await?;
        Ok(version)
    }

    async fn list_parameter_sets(
        &self,
        serial: &str,
        limit: i64,
        before_version: Option<i64>,
    ) -> StoreResult<Page<ParameterSetRecord>> {
        let rows = query(
            "SELECT serial, version, job_id, parameters, created_at,
                    status, status_reason, status_by, status_at FROM parameter_sets
             WHERE serial = $1 AND version < $2 ORDER BY version DESC LIMIT $3",
        )
        .bind(serial)
        .bind(before_version.unwrap_or(i64::MAX))
        .bind(limit)
        .fetch_all(self.pool())
        .await?;
        let items = rows
            .iter()
            .map(parameter_set)
            .collect::<StoreResult<Vec<_>>>()?;
        let next_cursor = page_cursor(&items, limit, |p| p.version.to_string());
        Ok(Page { items, next_cursor })
    }

    async fn get_parameter_set(
        &self,
        serial: &str,
        version: Option<i64>,
    ) -> StoreResult<Option<ParameterSetRecord>> {
        let row = query(
            "SELECT serial, version, job_id, parameters, created_at,
                    status, status_reason, status_by, status_at FROM parameter_sets
             WHERE serial = $1
               AND (CAST($2 AS BIGINT) IS NULL AND status = 'approved' OR version = $2)
             ORDER BY version DESC LIMIT 1",
        )
        .bind(serial)
        .bind(version)
        .fetch_optional(self.pool())
        .await?;
        row.as_ref().map(parameter_set).transpose()
    }

    async fn get_report(&self, serial: &str, version: i64) -> StoreResult<Option<Value>> {
        let row = query("SELECT report FROM reports WHERE serial = $1 AND version = $2")
            .bind(serial)
            .bind(version)
            .fetch_optional(self.pool())
            .await?;
        row.as_ref().map(|r| json(r.str("report"))).transpose()
    }
}
