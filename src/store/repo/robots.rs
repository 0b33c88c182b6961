use async_trait::async_trait;

use super::page_cursor;
use crate::domain::{Page, RobotRecord};
use crate::store::backend::Backend;
use crate::store::rows::robot;
use crate::store::statement::query;
use crate::store::{RobotStore, StoreResult};

const COLUMNS: &str = "serial, model, preset, kinematics, created_at, updated_at";

/// Create-or-replace of a robot (`$1`..`$6` in column order); each backend's
/// [`Backend::upsert_robot`] runs it and tells a creation from a replacement.
pub const UPSERT_ROBOT: &str =
    "INSERT INTO robots (serial, model, preset, kinematics, created_at, updated_at)
     VALUES ($1, $2, $3, $4, $5, $6)
     ON CONFLICT (serial) DO UPDATE SET model = excluded.model,
       preset = excluded.preset, kinematics = excluded.kinematics,
       updated_at = excluded.updated_at";

#[async_trait]
impl<B: Backend> RobotStore for B {
    async fn put_robot(&self, r: &RobotRecord) -> StoreResult<bool> {
        self.upsert_robot(r).await
    }

    async fn get_robot(&self, serial: &str) -> StoreResult<Option<RobotRecord>> {
        let row = query(format!("SELECT {COLUMNS} FROM robots WHERE serial = $1"))
            .bind(serial)
            .fetch_optional(self.pool())
            .await?;
        row.as_ref().map(robot).transpose()
    }

    async fn list_robots(&self, limit: i64, after: Option<&str>) -> StoreResult<Page<RobotRecord>> {
        // On PostgreSQL the key columns are COLLATE "C": byte order, as SQLite
        // sorts, whatever the database locale.
        let rows = query(format!(
            "SELECT {COLUMNS} FROM robots WHERE serial > $1 ORDER BY serial LIMIT $2"
        ))
        .bind(after.unwrap_or(""))
        .bind(limit)
        .fetch_all(self.pool())
        .await?;
        let items = rows.iter().map(robot).collect::<StoreResult<Vec<_>>>()?;
        let next_cursor = page_cursor(&items, limit, |r| r.serial.clone());
        Ok(Page { items, next_cursor })
    }

    async fn delete_robot(&self, serial: &str) -> StoreResult<bool> {
        let deleted = query("DELETE FROM robots WHERE serial = $1")
            .bind(serial)
            .execute(self.pool())
            .await?;
        Ok(deleted > 0)
    }
}
