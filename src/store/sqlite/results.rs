use async_trait::async_trait;
use serde_json::Value;
use sqlx::{Sqlite, Transaction};

use super::{json, SqliteStore};
use crate::domain::{now_rfc3339, NewParameterSet, Page, ParameterSetRecord};
use crate::store::rows::parameter_set;
use crate::store::{ResultStore, StoreResult};

/// Inserts the serial's next version inside the caller's (immediate) transaction.
pub(super) async fn insert_parameter_set_tx(
    tx: &mut Transaction<'static, Sqlite>,
    serial: &str,
    job_id: Option<&str>,
    set: &NewParameterSet,
) -> StoreResult<i64> {
    let version: i64 = sqlx::query_scalar(
        "INSERT INTO parameter_sets (serial, version, job_id, parameters, created_at)
         SELECT ?, coalesce(max(version), 0) + 1, ?, ?, ? FROM parameter_sets WHERE serial = ?
         RETURNING version",
    )
    .bind(serial)
    .bind(job_id)
    .bind(set.parameters.to_string())
    .bind(now_rfc3339())
    .bind(serial)
    .fetch_one(&mut **tx)
    .await?;
    sqlx::query("INSERT INTO reports (serial, version, report) VALUES (?, ?, ?)")
        .bind(serial)
        .bind(version)
        .bind(set.report.to_string())
        .execute(&mut **tx)
        .await?;
    Ok(version)
}

#[async_trait]
impl ResultStore for SqliteStore {
    async fn insert_parameter_set(
        &self,
        serial: &str,
        job_id: Option<&str>,
        set: &NewParameterSet,
    ) -> StoreResult<i64> {
        let mut tx = self.begin_immediate().await?;
        let version = insert_parameter_set_tx(&mut tx, serial, job_id, set).await?;
        tx.commit().await?;
        Ok(version)
    }

    async fn list_parameter_sets(
        &self,
        serial: &str,
        limit: i64,
        before_version: Option<i64>,
    ) -> StoreResult<Page<ParameterSetRecord>> {
        let rows = sqlx::query(
            "SELECT serial, version, job_id, parameters, created_at FROM parameter_sets
             WHERE serial = ? AND version < ? ORDER BY version DESC LIMIT ?",
        )
        .bind(serial)
        .bind(before_version.unwrap_or(i64::MAX))
        .bind(limit)
        .fetch_all(&self.pool)
        .await?;
        let items = rows
            .iter()
            .map(parameter_set)
            .collect::<StoreResult<Vec<_>>>()?;
        let next_cursor = if items.len() as i64 == limit {
            items.last().map(|p| p.version.to_string())
        } else {
            None
        };
        Ok(Page { items, next_cursor })
    }

    async fn get_parameter_set(
        &self,
        serial: &str,
        version: Option<i64>,
    ) -> StoreResult<Option<ParameterSetRecord>> {
        let row = sqlx::query(
            "SELECT serial, version, job_id, parameters, created_at FROM parameter_sets
             WHERE serial = ? AND (? IS NULL OR version = ?) ORDER BY version DESC LIMIT 1",
        )
        .bind(serial)
        .bind(version)
        .bind(version)
        .fetch_optional(&self.pool)
        .await?;
        row.as_ref().map(parameter_set).transpose()
    }

    async fn get_report(&self, serial: &str, version: i64) -> StoreResult<Option<Value>> {
        let text: Option<String> =
            sqlx::query_scalar("SELECT report FROM reports WHERE serial = ? AND version = ?")
                .bind(serial)
                .bind(version)
                .fetch_optional(&self.pool)
                .await?;
        text.map(|t| json(&t)).transpose()
    }
}
