use async_trait::async_trait;

use super::page_cursor;
use crate::domain::{new_id, now_rfc3339, now_unix_ms, ImageMeta, Page, PoseGroup};
use crate::schema::session::SessionBody;
use crate::store::backend::{is_foreign_key_violation, Backend};
use crate::store::rows::{pose, session, Columns};
use crate::store::statement::query;
use crate::store::{
    writer, NewPose, PoseRecord, SessionRecord, SessionStore, StoreError, StoreResult,
};

const SESSION_COLUMNS: &str = "s.id, s.serial, s.instrument, s.spec, s.created_at,
    (SELECT count(*) FROM poses p WHERE p.session_id = s.id) AS pose_count";
const POSE_COLUMNS: &str =
    "id, session_id, joints_deg, pose_set, image_meta, points, measured, label, detection, image_detection, flange_pose, stage_reading, pose_group, created_at";

#[async_trait]
impl<B: Backend> SessionStore for B {
    async fn create_session(
        &self,
        serial: &str,
        instrument: &str,
        spec: &SessionBody,
    ) -> StoreResult<SessionRecord> {
        let id = new_id();
        let created_at = now_rfc3339();
        // A transaction, so a keyed request's key is marked with the insert.
        let mut tx = self.begin_write().await?;
        let inserted = query(
            "INSERT INTO sessions (id, serial, instrument, spec, created_at)
             SELECT $1, serial, $2, $3, $4 FROM robots WHERE serial = $5",
        )
        .bind(&id)
        .bind(instrument)
        .bind(serde_json::to_string(spec)?)
        .bind(&created_at)
        .bind(serial)
        .execute(&mut tx)
        .await;
        match inserted {
            Ok(0) => return Err(StoreError::NotFound("robot")),
            Ok(_) => tx.commit().await?,
            // The robot was deleted between the SELECT and the insert's FK check.
            Err(e) if is_foreign_key_violation(&e) => return Err(StoreError::NotFound("robot")),
            Err(e) => return Err(e.into()),
        }
        Ok(SessionRecord {
            id,
            serial: serial.to_string(),
            instrument: instrument.to_string(),
            spec: spec.clone(),
            pose_count: 0,
            created_at,
        })
    }

    async fn get_session(&self, id: &str) -> StoreResult<Option<SessionRecord>> {
        let row = query(format!(
            "SELECT {SESSION_COLUMNS} FROM sessions s WHERE s.id = $1"
        ))
        .bind(id)
        .fetch_optional(self.pool())
        .await?;
        row.as_ref().map(session).transpose()
    }

    async fn list_sessions(
        &self,
        serial: &str,
        limit: i64,
        after: Option<&str>,
    ) -> StoreResult<Page<SessionRecord>> {
        let rows = query(format!(
            "SELECT {SESSION_COLUMNS} FROM sessions s WHERE s.serial = $1 AND s.id > $2
             ORDER BY s.id LIMIT $3"
        ))
        .bind(serial)
        .bind(after.unwrap_or(""))
        .bind(limit)
        .fetch_all(self.pool())
        .await?;
        let items = rows.iter().map(session).collect::<StoreResult<Vec<_>>>()?;
        let next_cursor = page_cursor(&items, limit, |s| s.id.clone());
        Ok(Page { items, next_cursor })
    }

    async fn put_blob(&self, meta: &ImageMeta, data: &[u8]) -> StoreResult<()> {
        // Two writers storing the same image: the second waits for the
        // first's commit on the primary key, then only renews `touched_ms`.
        query(
            "INSERT INTO blobs (sha256, size_bytes, content_type, data, created_at, touched_ms,
                                stored_by)
             VALUES ($1, $2, $3, $4, $5, $6, $7)
             ON CONFLICT (sha256) DO UPDATE SET touched_ms = excluded.touched_ms,
                                                stored_by = excluded.stored_by",
        )
        .bind(&meta.sha256)
        .bind(meta.size_bytes)
        .bind(&meta.content_type)
        .bind(data)
        .bind(now_rfc3339())
        .bind(now_unix_ms())
        .bind(writer::current())
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn discard_blobs(&self, sha256s: &[String]) -> StoreResult<u64> {
        let mut deleted = 0;
        for sha in sha256s {
            deleted += query(
                "DELETE FROM blobs WHERE sha256 = $1
                 AND NOT EXISTS (SELECT 1 FROM poses WHERE image_sha256 = $1)",
            )
            .bind(sha)
            .execute(self.pool())
            .await?;
        }
        Ok(deleted)
    }

    async fn collect_blobs(&self, touched_before_ms: i64) -> StoreResult<u64> {
        Ok(query(
            "DELETE FROM blobs WHERE touched_ms < $1
             AND NOT EXISTS (SELECT 1 FROM poses WHERE image_sha256 = blobs.sha256)",
        )
        .bind(touched_before_ms)
        .execute(self.pool())
        .await?)
    }

    async fn collect_orphan_blobs(&self) -> StoreResult<u64> {
        let writers: Vec<String> = query(
            "SELECT DISTINCT stored_by FROM blobs WHERE stored_by IS NOT NULL
             AND NOT EXISTS (SELECT 1 FROM poses WHERE image_sha256 = blobs.sha256)",
        )
        .fetch_all(self.pool())
        .await?
        .iter()
        .map(|r| r.string("stored_by"))
        .collect();
        let mut deleted = 0;
        for gone in writers.iter().filter(|w| writer::is_gone(w)) {
            deleted += query(
                "DELETE FROM blobs WHERE stored_by = $1
                 AND NOT EXISTS (SELECT 1 FROM poses WHERE image_sha256 = blobs.sha256)",
            )
            .bind(gone)
            .execute(self.pool())
            .await?;
        }
        Ok(deleted)
    }

    async fn get_blob(&self, sha256: &str) -> StoreResult<Option<Vec<u8>>> {
        let row = query("SELECT data FROM blobs WHERE sha256 = $1")
            .bind(sha256)
            .fetch_optional(self.pool())
            .await?;
        Ok(row.map(|r| r.bytes("data")))
    }

    async fn add_poses(&self, session_id: &str, poses: &[NewPose]) -> StoreResult<Vec<PoseRecord>> {
        let mut tx = self.begin_write().await?;
        // Locks the session row (key share) so it cannot be deleted midway.
        let exists = query(format!(
            "SELECT 1 FROM sessions WHERE id = $1{}",
            B::FOR_KEY_SHARE
        ))
        .bind(session_id)
        .fetch_optional(&mut tx)
        .await?;
        if exists.is_none() {
            return Err(StoreError::NotFound("session"));
        }
        let mut out = Vec::with_capacity(poses.len());
        for p in poses {
            let record = PoseRecord {
                id: new_id(),
                session_id: session_id.to_string(),
                joints_deg: p.joints_deg.clone(),
                set: p.set,
                image: p.image.clone(),
                points: p.points.clone(),
                measured: p.measured.clone(),
                label: p.label.clone(),
                detection: None,
                image_detection: p.image_detection.clone(),
                flange_pose: p.flange_pose.clone(),
                stage_reading: p.stage_reading,
                group: p.group.clone(),
                created_at: now_rfc3339(),
            };
            query(
                "INSERT INTO poses (id, session_id, joints_deg, pose_set, image_sha256,
                   image_meta, points, measured, label, image_detection, flange_pose, stage_reading,
                   pose_group, created_at)
                 VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14)",
            )
            .bind(&record.id)
            .bind(session_id)
            .bind(serde_json::to_string(&record.joints_deg)?)
            .bind(record.set.as_str())
            .bind(record.image.as_ref().map(|i| i.sha256.as_str()))
            .bind(
                record
                    .image
                    .as_ref()
                    .map(serde_json::to_string)
                    .transpose()?,
            )
            .bind(serde_json::to_string(&record.points)?)
            .bind(
                record
                    .measured
                    .as_ref()
                    .map(serde_json::to_string)
                    .transpose()?,
            )
            .bind(record.label.as_deref())
            .bind(
                record
                    .image_detection
                    .as_ref()
                    .map(serde_json::to_string)
                    .transpose()?,
            )
            .bind(
                record
                    .flange_pose
                    .as_ref()
                    .map(serde_json::to_string)
                    .transpose()?,
            )
            .bind(
                record
                    .stage_reading
                    .as_ref()
                    .map(serde_json::to_string)
                    .transpose()?,
            )
            .bind(record.group.as_ref().map(PoseGroup::as_str))
            .bind(&record.created_at)
            .execute(&mut tx)
            .await
            .map_err(|e| match &record.image {
                // The session row is held, so the missing parent is the image.
                Some(image) if is_foreign_key_violation(&e) => StoreError::Conflict(format!(
                    "image {} was removed meanwhile (the robot whose poses named it was \
                     deleted); upload it again",
                    image.sha256
                )),
                _ => e.into(),
            })?;
            out.push(record);
        }
        tx.commit().await?;
        Ok(out)
    }

    async fn get_pose(&self, session_id: &str, pose_id: &str) -> StoreResult<Option<PoseRecord>> {
        let row = query(format!(
            "SELECT {POSE_COLUMNS} FROM poses WHERE session_id = $1 AND id = $2"
        ))
        .bind(session_id)
        .bind(pose_id)
        .fetch_optional(self.pool())
        .await?;
        row.as_ref().map(pose).transpose()
    }

    async fn list_poses(
        &self,
        session_id: &str,
        limit: i64,
        after: Option<&str>,
    ) -> StoreResult<Page<PoseRecord>> {
        let rows = query(format!(
            "SELECT {POSE_COLUMNS} FROM poses WHERE session_id = $1 AND id > $2
             ORDER BY id LIMIT $3"
        ))
        .bind(session_id)
        .bind(after.unwrap_or(""))
        .bind(limit)
        .fetch_all(self.pool())
        .await?;
        let items = rows.iter().map(pose).collect::<StoreResult<Vec<_>>>()?;
        let next_cursor = page_cursor(&items, limit, |p| p.id.clone());
        Ok(Page { items, next_cursor })
    }
}
