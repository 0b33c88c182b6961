//! A stage session's layout checked before its job is queued (issue 18):
//! every sequence needs at least four stage positions that are not all on
//! one line, or the stage's axes cannot be fitted
//! (`robocal_calib::stage::layout`). Refused up front with a 422 naming the
//! field, rather than a job that can only fail.

use nalgebra::Vector3;
use robocal_calib::stage::layout::check_stage_positions;

use super::error::{ServiceError, ServiceResult};
use crate::store::{DynStore, SessionRecord};

/// Poses read per page.
const PAGE: i64 = 1000;

/// 422 naming `sequence` or `stage_position_mm` when the session's stage
/// readings cannot fix the stage's axes.
pub async fn check(store: &DynStore, session: &SessionRecord) -> ServiceResult<()> {
    let mut readings = Vec::new();
    let mut cursor = None;
    loop {
        let page = store
            .list_poses(&session.id, PAGE, cursor.as_deref())
            .await?;
        readings.extend(
            page.items
                .iter()
                .filter_map(|p| p.stage_reading)
                .map(|r| (r.sequence, Vector3::from(r.stage_position_mm))),
        );
        match page.next_cursor {
            Some(c) => cursor = Some(c),
            None => break,
        }
    }
    check_stage_positions(&readings)
        .map(|_| ())
        .map_err(|e| ServiceError::invalid(e.field(), e.to_string()))
}
