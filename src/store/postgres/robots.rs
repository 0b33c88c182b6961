use async_trait::async_trait;

use super::PgStore;
use crate::domain::{Page, RobotRecord};
use crate::store::rows::robot;
use crate::store::{RobotStore, StoreResult};

const COLUMNS: &str = "serial, model, preset, kinematics, created_at, updated_at";

#[async_trait]
impl RobotStore for PgStore {
    async fn put_robot(&self, r: &RobotRecord) -> StoreResult<bool> {
        // One statement; `xmax = 0` is true only for a freshly inserted row,
        // so two replicas creating the same serial at once answer 201 once.
        let inserted: bool = sqlx::query_scalar(
            "INSERT INTO robots (serial, model, preset, kinematics, created_at, updated_at)
             VALUES ($1, $2, $3, $4, $5, $6)
             ON CONFLICT (serial) DO UPDATE SET model = excluded.model,
               preset = excluded.preset, kinematics = excluded.kinematics,
               updated_at = excluded.updated_at
             RETURNING (xmax = 0)",
        )
        .bind(&r.serial)
        .bind(&r.model)
        .bind(&r.preset)
        .bind(r.kinematics.to_string())
        .bind(&r.created_at)
        .bind(&r.updated_at)
        .fetch_one(&self.pool)
        .await?;
        Ok(inserted)
    }

    async fn get_robot(&self, serial: &str) -> StoreResult<Option<RobotRecord>> {
        let row = sqlx::query(&format!("SELECT {COLUMNS} FROM robots WHERE serial = $1"))
            .bind(serial)
            .fetch_optional(&self.pool)
            .await?;
        row.as_ref().map(robot).transpose()
    }

    async fn list_robots(&self, limit: i64, after: Option<&str>) -> StoreResult<Page<RobotRecord>> {
        // COLLATE "C": byte order, as SQLite sorts, whatever the database locale.
        let rows = sqlx::query(&format!(
            "SELECT {COLUMNS} FROM robots WHERE serial > $1
             ORDER BY serial LIMIT $2"
        ))
        .bind(after.unwrap_or(""))
        .bind(limit)
        .fetch_all(&self.pool)
        .await?;
        let items = rows.iter().map(robot).collect::<StoreResult<Vec<_>>>()?;
        let next_cursor = page_cursor(&items, limit, |r| r.serial.clone());
        Ok(Page { items, next_cursor })
    }

    async fn delete_robot(&self, serial: &str) -> StoreResult<bool> {
        let done = sqlx::query("DELETE FROM robots WHERE serial = $1")
            .bind(serial)
            .execute(&self.pool)
            .await?;
        Ok(done.rows_affected() > 0)
    }
}

/// The cursor of a full page is its last key; a short page is the last one.
pub(super) fn page_cursor<T>(
    items: &[T],
    limit: i64,
    key: impl Fn(&T) -> String,
) -> Option<String> {
    if items.len() as i64 == limit {
        items.last().map(key)
    } else {
        None
    }
}
