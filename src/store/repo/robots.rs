use async_trait::async_trait;

use super::page_cursor;
use crate::domain::{ControllerChange, ControllerIdentity, Page};
use crate::store::backend::Backend;
use crate::store::rows::{robot, Columns};
use crate::store::statement::query;
use crate::store::RobotRecord;
use crate::store::{RobotStore, SessionStore, StoreError, StoreResult};

const COLUMNS: &str =
    "serial, model, preset, kinematics, controller, prior, created_at, updated_at";

/// Create-or-replace of a robot (`$1`..`$7` in the insert's order; the
/// controller identity is left as it was: `set_robot_controller` writes it
/// with its history); each backend's
/// [`Backend::upsert_robot`] runs it and tells a creation from a replacement.
pub const UPSERT_ROBOT: &str =
    "INSERT INTO robots (serial, model, preset, kinematics, created_at, updated_at, prior)
     VALUES ($1, $2, $3, $4, $5, $6, $7)
     ON CONFLICT (serial) DO UPDATE SET model = excluded.model,
       preset = excluded.preset, kinematics = excluded.kinematics,
       updated_at = excluded.updated_at, prior = excluded.prior";

/// The robot's prior as its column stores it (JSON text, NULL for none).
pub fn prior_text(r: &RobotRecord) -> StoreResult<Option<String>> {
    r.prior
        .as_ref()
        .map(serde_json::to_string)
        .transpose()
        .map_err(|e| StoreError::Backend(format!("robot prior: {e}")))
}

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
        let mut tx = self.begin_write().await?;
        let images: Vec<String> = query(
            "SELECT DISTINCT p.image_sha256 AS sha256 FROM poses p
             JOIN sessions s ON s.id = p.session_id
             WHERE s.serial = $1 AND p.image_sha256 IS NOT NULL",
        )
        .bind(serial)
        .fetch_all(&mut tx)
        .await?
        .iter()
        .map(|r| r.string("sha256"))
        .collect();
        // Jobs first, as `finish_job` locks them (job, then poses, then the
        // version counter): the same order, so the two cannot deadlock, and
        // a job finishing after this commit finds its lease gone and writes
        // nothing.
        query("DELETE FROM jobs WHERE session_id IN (SELECT id FROM sessions WHERE serial = $1)")
            .bind(serial)
            .execute(&mut tx)
            .await?;
        // Sessions and poses go with the robot (ON DELETE CASCADE).
        let deleted = query("DELETE FROM robots WHERE serial = $1")
            .bind(serial)
            .execute(&mut tx)
            .await?;
        // Parameter sets name the serial, not the robot row: without this a
        // robot re-created under the serial would serve them as its own.
        query("DELETE FROM parameter_sets WHERE serial = $1")
            .bind(serial)
            .execute(&mut tx)
            .await?;
        if let Some(forget) = B::FORGET_VERSIONS {
            query(forget).bind(serial).execute(&mut tx).await?;
        }
        tx.commit().await?;
        // Best effort after the commit: an image another upload is about to
        // attach may be refused by the database here; the periodic
        // collection takes whatever this leaves.
        if let Err(e) = self.discard_blobs(&images).await {
            tracing::warn!(error = %e, serial, "images of the deleted robot left for the periodic collection");
        }
        // The file shrinks now, not at the next sweep (best effort too).
        if let Err(e) = Backend::reclaim_space(self).await {
            tracing::warn!(error = %e, "space of the deleted robot left for the next sweep");
        }
        Ok(deleted > 0)
    }

    async fn set_robot_controller(
        &self,
        serial: &str,
        controller: Option<&ControllerIdentity>,
        at: &str,
    ) -> StoreResult<bool> {
        let mut tx = self.begin_write().await?;
        let row = query(format!(
            "SELECT controller FROM robots WHERE serial = $1{}",
            B::FOR_UPDATE
        ))
        .bind(serial)
        .fetch_optional(&mut tx)
        .await?
        .ok_or(StoreError::NotFound("robot"))?;
        let before: Option<ControllerIdentity> = row
            .opt_str("controller")
            .map(serde_json::from_str)
            .transpose()?;
        if before.as_ref() == controller {
            return Ok(false);
        }
        let text = |c: Option<&ControllerIdentity>| c.map(serde_json::to_string).transpose();
        let (from, to) = (text(before.as_ref())?, text(controller)?);
        query("UPDATE robots SET controller = $1 WHERE serial = $2")
            .bind(to.as_deref())
            .bind(serial)
            .execute(&mut tx)
            .await?;
        query(
            "INSERT INTO robot_controller_changes (serial, seq, from_controller, to_controller, changed_at)
             VALUES ($1, (SELECT COALESCE(MAX(seq), 0) + 1 FROM robot_controller_changes WHERE serial = $1),
                     $2, $3, $4)",
        )
        .bind(serial)
        .bind(from.as_deref())
        .bind(to.as_deref())
        .bind(at)
        .execute(&mut tx)
        .await?;
        tx.commit().await?;
        Ok(true)
    }

    async fn list_controller_changes(&self, serial: &str) -> StoreResult<Vec<ControllerChange>> {
        let rows = query(
            "SELECT from_controller, to_controller, changed_at FROM robot_controller_changes
             WHERE serial = $1 ORDER BY seq",
        )
        .bind(serial)
        .fetch_all(self.pool())
        .await?;
        let typed = |t: Option<&str>| -> StoreResult<Option<ControllerIdentity>> {
            Ok(t.map(serde_json::from_str).transpose()?)
        };
        rows.iter()
            .map(|r| {
                Ok(ControllerChange {
                    from: typed(r.opt_str("from_controller"))?,
                    to: typed(r.opt_str("to_controller"))?,
                    changed_at: r.string("changed_at"),
                })
            })
            .collect()
    }
}
