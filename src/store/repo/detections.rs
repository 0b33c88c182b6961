//! The image points a job measured, written to its session's poses.

use sqlx::Transaction;

use crate::store::backend::Backend;
use crate::store::statement::query;
use crate::store::{PoseDetection, StoreResult};

/// Replaces every pose's detection document of a session: the listed poses
/// get theirs, the others none (a pose uploaded after the job loaded its
/// inputs shows no stale points from an earlier job). Two jobs of one
/// session writing at once serialise on the rows: each write is whole.
pub async fn write_detections_tx<B: Backend>(
    tx: &mut Transaction<'static, B::Db>,
    session_id: &str,
    detections: &[PoseDetection],
) -> StoreResult<()> {
    query("UPDATE poses SET detection = NULL WHERE session_id = $1")
        .bind(session_id)
        .execute(&mut *tx)
        .await?;
    for d in detections {
        // A pose detected for the first time by this job keeps what the
        // detector found, so later jobs need not decode its image again.
        query(
            "UPDATE poses SET detection = $1, image_detection = COALESCE(image_detection, $2)
             WHERE session_id = $3 AND id = $4",
        )
        .bind(serde_json::to_string(&d.detection)?)
        .bind(
            d.image_detection
                .as_ref()
                .map(serde_json::to_string)
                .transpose()?,
        )
        .bind(session_id)
        .bind(&d.pose_id)
        .execute(&mut *tx)
        .await?;
    }
    Ok(())
}
