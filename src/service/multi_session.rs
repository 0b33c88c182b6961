//! Starting a calibration over several sessions of one robot (issue 18,
//! the paper's regions, section 5): every session is one placement of the
//! board; the job fits one kinematic model and hand–eye, one
//! `target_to_base` per session and shared camera intrinsics. A list of
//! one session is today's local calibration of that session.

use super::error::{ServiceError, ServiceResult};
use crate::jobs::queue::{enqueue_calibration, QueuePolicy};
use crate::schema::job::CalibrationOptions;
use crate::schema::session::Instrument;
use crate::schema::FieldError;
use crate::store::{DynStore, JobRecord, SessionRecord};

/// The field the session list is named by in problems.
const FIELD: &str = "sessions";

fn invalid(field: &str, message: String) -> ServiceError {
    ServiceError::Invalid(vec![FieldError::new(field, message)])
}

/// Queues the calibration of `options.sessions`, all of robot `serial`:
/// 422 naming `sessions` (the message says which entry, `[i]`) when the
/// list is empty, repeats a session, or names one that does not exist or
/// belongs to another robot.
pub async fn start_robot_calibration(
    store: &DynStore,
    policy: &QueuePolicy,
    serial: &str,
    options: &CalibrationOptions,
) -> ServiceResult<JobRecord> {
    options.check()?;
    let records = sessions_of(store, serial, &options.sessions).await?;
    if let [one] = records.as_slice() {
        let local = CalibrationOptions {
            sessions: Vec::new(),
            ..options.clone()
        };
        return super::checks::start_calibration(store, policy, one, &local).await;
    }
    check_multi(&records, options)?;
    Ok(enqueue_calibration(store, policy, &records[0], options).await?)
}

/// The named sessions, in the order given, each checked to exist and to be
/// the robot's.
async fn sessions_of(
    store: &DynStore,
    serial: &str,
    ids: &[String],
) -> ServiceResult<Vec<SessionRecord>> {
    if ids.is_empty() {
        return Err(invalid(FIELD, "must name at least one session".into()));
    }
    let mut records: Vec<SessionRecord> = Vec::with_capacity(ids.len());
    for (i, id) in ids.iter().enumerate() {
        if ids[..i].contains(id) {
            return Err(invalid(
                FIELD,
                format!("[{i}]: session {id} is named twice"),
            ));
        }
        let session = store
            .get_session(id)
            .await?
            .ok_or_else(|| invalid(FIELD, format!("[{i}]: session {id} does not exist")))?;
        if session.serial != serial {
            return Err(invalid(
                FIELD,
                format!(
                    "[{i}]: session {id} belongs to robot {}, not {serial}: one job calibrates one robot",
                    session.serial
                ),
            ));
        }
        records.push(session);
    }
    Ok(records)
}

/// What a fit over several board placements needs: camera sessions with
/// joints (the shared intrinsics and the per-session boards are fitted on
/// the image points), a full scope and the joint refinement.
fn check_multi(records: &[SessionRecord], options: &CalibrationOptions) -> ServiceResult<()> {
    for (i, s) in records.iter().enumerate() {
        if s.spec.instrument != Instrument::Camera {
            return Err(invalid(
                FIELD,
                format!(
                    "[{i}]: session {} is a {} session: several sessions are fitted together on their camera images only",
                    s.id,
                    s.spec.instrument.as_str()
                ),
            ));
        }
    }
    let refused = |field: &str, why: &str| Err(invalid(field, why.to_string()));
    if !options.scope.is_full() {
        return refused("scope", "a calibration over several sessions is a full one");
    }
    if !options.joint_refinement || !options.refine_intrinsics {
        return refused(
            "joint_refinement",
            "several sessions are fitted together by the joint refinement on the image points (with the intrinsics refined)",
        );
    }
    if options.non_geometric == Some(true) {
        return refused(
            "non_geometric",
            "a calibration over several sessions identifies geometry only",
        );
    }
    Ok(())
}
