use async_trait::async_trait;
use serde_json::Value;
use sqlx::{Postgres, Transaction};

use super::{json, PgStore};
use crate::domain::{now_rfc3339, NewParameterSet, Page, ParameterSetRecord};
use crate::store::rows::parameter_set;
use crate::store::{ResultStore, StoreResult};

/// Inserts the serial's next version inside the caller's transaction.
///
/// The version comes from the serial's counter row, bumped by an upsert:
/// the row lock it takes makes concurrent writers (any replica) wait for
/// each other's commit, so versions are 1, 2, 3... with no duplicate, and a
/// transaction that rolls back takes its bump with it (no gap).
pub(super) async fn insert_parameter_set_tx(
    tx: &mut Transaction<'static, Postgres>,
    serial: &str,
    job_id: Option<&str>,
    set: &NewParameterSet,
) -> StoreResult<i64> {
    let version: i64 = sqlx::query_scalar(
        "INSERT INTO parameter_set_counters (serial, last_version) VALUES ($1, 1)
         ON CONFLICT (serial) DO UPDATE
           SET last_version = parameter_set_counters.last_version + 1
         RETURNING last_version",
    )
    .bind(serial)
    .fetch_one(&mut **tx)
    .await?;
    sqlx::query(
        "INSERT INTO parameter_sets (serial, version, job_id, parameters, created_at)
         VALUES ($1, $2, $3, $4, $5)",
    )
    .bind(serial)
    .bind(version)
    .bind(job_id)
    .bind(set.parameters.to_string())
    .bind(now_rfc3339())
    .execute(&mut **tx)
    .await?;
    sqlx::query("INSERT INTO reports (serial, version, report) VALUES ($1, $2, $3)")
        .bind(serial)
        .bind(version)
        .bind(set.report.to_string())
        .execute(&mut **tx)
        .await?;
    Ok(version)
}

#[async_trait]
impl ResultStore for PgStore {
    async fn insert_parameter_set(
        &self,
        serial: &str,
        job_id: Option<&str>,
        set: &NewParameterSet,
    ) -> StoreResult<i64> {
        let mut tx = self.pool.begin().await?;
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
             WHERE serial = $1 AND version < $2 ORDER BY version DESC LIMIT $3",
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
             WHERE serial = $1 AND ($2::BIGINT IS NULL OR version = $2)
             ORDER BY version DESC LIMIT 1",
        )
        .bind(serial)
        .bind(version)
        .fetch_optional(&self.pool)
        .await?;
        row.as_ref().map(parameter_set).transpose()
    }

    async fn get_report(&self, serial: &str, version: i64) -> StoreResult<Option<Value>> {
        let text: Option<String> =
            sqlx::query_scalar("SELECT report FROM reports WHERE serial = $1 AND version = $2")
                .bind(serial)
                .bind(version)
                .fetch_optional(&self.pool)
                .await?;
        text.map(|t| json(&t)).transpose()
    }
}
