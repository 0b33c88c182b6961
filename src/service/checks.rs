//! Starting jobs that hold the robot's latest approved set (issue 17): a
//! quick re-check of a short session, and a calibration whose `scope` is
//! partial (`base`, `hand_eye`). Both refuse up front (409 naming the
//! field) when the robot has no approved set, instead of queueing a job
//! that can only fail.

use super::error::{ServiceError, ServiceResult};
use super::results::typed;
use crate::domain::{check_controller, ControllerIdentity};
use crate::jobs::queue::{enqueue_calibration, enqueue_check, QueuePolicy};
use crate::schema::job::CalibrationOptions;
use crate::store::{DynStore, JobRecord, SessionRecord};

/// 409 naming `field` when `serial` has no approved parameter set.
async fn require_approved(
    store: &DynStore,
    serial: &str,
    field: &'static str,
) -> ServiceResult<()> {
    if store.get_parameter_set(serial, None).await?.is_some() {
        return Ok(());
    }
    Err(ServiceError::ConflictField {
        field,
        message: format!(
            "robot {serial} has no approved parameter set to hold: calibrate it in full, or \
             approve a set (POST /v1/robots/{serial}/parameter-sets/{{version}}/approve)"
        ),
    })
}

/// Calibration poses read per page while counting them.
const POSE_PAGE: i64 = 100;

/// 422 naming `poses` when the session has fewer calibration poses than
/// the job's validate stage needs (`pipeline::MIN_CALIBRATION_POSES`): a
/// job that can only fail is refused at the POST, not queued. Reads pages
/// only until enough are counted.
async fn require_calibration_poses(store: &DynStore, session: &SessionRecord) -> ServiceResult<()> {
    let needed = crate::pipeline::MIN_CALIBRATION_POSES;
    let (mut cal, mut after) = (0, None::<String>);
    loop {
        let page = store
            .list_poses(&session.id, POSE_PAGE, after.as_deref())
            .await?;
        cal += page
            .items
            .iter()
            .filter(|p| p.set == crate::schema::session::PoseSet::Cal)
            .count();
        match page.next_cursor {
            Some(next) if cal < needed => after = Some(next),
            _ => break,
        }
    }
    if cal >= needed {
        return Ok(());
    }
    Err(ServiceError::invalid(
        "poses",
        format!(
            "session {} has {cal} calibration poses (of {} poses); a calibration needs at least {needed}: upload more poses with set \"cal\" first",
            session.id, session.pose_count
        ),
    ))
}

/// Queues a calibration; a partial scope needs an approved set.
pub async fn start_calibration(
    store: &DynStore,
    policy: &QueuePolicy,
    session: &SessionRecord,
    options: &CalibrationOptions,
) -> ServiceResult<JobRecord> {
    options.check()?;
    if !options.sessions.is_empty() {
        return Err(ServiceError::Invalid(vec![crate::schema::FieldError::new(
            "sessions",
            format!(
                "a session's calibration is its own: name several sessions in POST /v1/robots/{}/calibrations",
                session.serial
            ),
        )]));
    }
    if session.spec.instrument == crate::schema::session::Instrument::Stage {
        super::stage_layout::check(store, session).await?;
    }
    if !options.scope.is_full() {
        require_approved(store, &session.serial, "scope").await?;
    }
    require_calibration_poses(store, session).await?;
    Ok(enqueue_calibration(store, policy, session, options).await?)
}

/// Queues a quick re-check of the session against the robot's latest
/// approved set (409 naming `serial` when it has none; 409 naming
/// `controller` when the caller expects another controller than the set's).
pub async fn start_check(
    store: &DynStore,
    policy: &QueuePolicy,
    session: &SessionRecord,
    expect_controller: Option<&ControllerIdentity>,
) -> ServiceResult<JobRecord> {
    require_approved(store, &session.serial, "serial").await?;
    if expect_controller.is_some() {
        let approved = store.get_parameter_set(&session.serial, None).await?;
        let recorded = approved
            .as_ref()
            .and_then(|r| typed(r).ok())
            .and_then(|set| set.controller);
        check_controller(expect_controller, recorded.as_ref())
            .map_err(ServiceError::controller("the approved parameter set"))?;
    }
    Ok(enqueue_check(store, policy, session).await?)
}
