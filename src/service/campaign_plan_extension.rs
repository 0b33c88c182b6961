//! The session a campaign plan extends (issue 30, "tell the user what to
//! shoot next"): a camera session of the same robot whose `cal` poses
//! with joints seed the planner, and whose board and camera the request
//! may leave out. Every way the session cannot serve is a 422 naming
//! `extend_session`.

use super::error::{ServiceError, ServiceResult};
use crate::schema::campaign_plan::CampaignPlanBody;
use crate::schema::session::{Instrument, PoseSet};
use crate::store::{DynStore, SessionRecord};

/// The request field naming the session.
pub const FIELD: &str = "extend_session";
/// Poses read per page.
const PAGE: i64 = 1000;

fn invalid(message: impl Into<String>) -> ServiceError {
    ServiceError::invalid(FIELD, message)
}

/// The session `id`, if it is a camera session of robot `serial`.
pub async fn session_to_extend(
    store: &DynStore,
    serial: &str,
    id: &str,
) -> ServiceResult<SessionRecord> {
    let session = store
        .get_session(id)
        .await?
        .ok_or_else(|| invalid(format!("no session {id}")))?;
    if session.serial != serial {
        return Err(invalid(format!(
            "session {id} belongs to another robot, not {serial}"
        )));
    }
    if session.spec.instrument != Instrument::Camera {
        return Err(invalid(format!(
            "session {id} is a {} session: a plan extends a camera campaign",
            session.spec.instrument.as_str()
        )));
    }
    Ok(session)
}

/// The session's board and camera where the request leaves them out (a
/// camera named by neither `camera` nor `camera_calibration_id`).
pub fn fill_from_session(body: &mut CampaignPlanBody, session: &SessionRecord) {
    if body.target.is_none() {
        body.target = session.spec.target.clone();
    }
    if body.camera.is_none() && body.camera_calibration_id.is_none() {
        body.camera = session.spec.camera.clone();
        body.camera_calibration_id = session.spec.camera_calibration_id.clone();
    }
}

/// Joints (rad) of the session's `cal` poses that have them, in upload
/// order; a 422 when there are none (nothing to extend).
pub async fn existing_joints_rad(
    store: &DynStore,
    session: &SessionRecord,
) -> ServiceResult<Vec<Vec<f64>>> {
    let mut joints = Vec::new();
    let mut cursor: Option<String> = None;
    loop {
        let page = store
            .list_poses(&session.id, PAGE, cursor.as_deref())
            .await?;
        joints.extend(
            page.items
                .iter()
                .filter(|p| p.set == PoseSet::Cal && !p.joints_deg.is_empty())
                .map(|p| {
                    p.joints_deg
                        .as_deg()
                        .iter()
                        .map(|d| d.to_radians())
                        .collect()
                }),
        );
        match page.next_cursor {
            Some(c) => cursor = Some(c),
            None => break,
        }
    }
    if joints.is_empty() {
        return Err(invalid(format!(
            "session {} has no cal poses with joints to extend",
            session.id
        )));
    }
    Ok(joints)
}
