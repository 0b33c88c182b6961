//! What a succeeded job writes in the transaction that ends it: the final
//! detections, its parameter set with the release gate's decision (and
//! `set.approved` in the outbox when the gate approved it), a re-check's
//! verdict (and `check.finished`). The job's `result` document is built
//! here, once.

use sqlx::Transaction;

use super::detections::write_detections_tx;
use super::results::insert_parameter_set_tx;
use super::webhooks::record_event_tx;
use crate::domain::{
    now_unix_ms, CalibrationResult, CheckDoc, DomainEvent, JobResult, JobSummary, ReleaseStatus,
    GATE_ACTOR,
};
use crate::store::backend::Backend;
use crate::store::{NewParameterSet, PoseDetection, StoreResult};

/// A succeeded job, as `finish_job` received it.
pub(super) struct Success<'a> {
    pub job_id: &'a str,
    pub session_id: &'a str,
    pub serial: &'a str,
    pub parameter_set: Option<&'a NewParameterSet>,
    pub summary: &'a JobSummary,
    pub detections: &'a [PoseDetection],
    pub check: Option<&'a CheckDoc>,
}

/// Writes `s` in `tx`; returns the job's `result` and the version stored.
pub(super) async fn record_success_tx<B: Backend>(
    tx: &mut Transaction<'static, B::Db>,
    s: Success<'_>,
) -> StoreResult<(JobResult, Option<i64>)> {
    if !s.detections.is_empty() {
        write_detections_tx::<B>(tx, s.session_id, s.detections).await?;
    }
    let mut result = CalibrationResult {
        summary: s.summary.clone(),
        ..CalibrationResult::default()
    };
    let mut version = None;
    if let Some(set) = s.parameter_set {
        let stored = insert_parameter_set_tx::<B>(tx, s.serial, Some(s.job_id), set).await?;
        version = Some(stored);
        result.serial = Some(s.serial.to_string());
        result.version = Some(stored);
        result.status = Some(set.release.status);
        result.status_reason = set.release.reason.clone();
        if set.release.status == ReleaseStatus::Approved {
            let event = DomainEvent::SetApproved {
                serial: s.serial.to_string(),
                version: stored,
                approved_by: GATE_ACTOR.to_string(),
            };
            record_event_tx::<B>(tx, &event, now_unix_ms()).await?;
        }
    }
    if let Some(check) = s.check {
        let event = DomainEvent::CheckFinished {
            job_id: s.job_id.to_string(),
            serial: s.serial.to_string(),
            verdict: check.verdict.as_str().to_string(),
            version: check.checked_version,
        };
        record_event_tx::<B>(tx, &event, now_unix_ms()).await?;
    }
    Ok((JobResult::new(result, s.check.cloned()), version))
}
