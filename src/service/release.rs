//! The release gate as a person uses it (issue 17): approve or reject a
//! parameter set (recorded with who and when), a robot's history (approved
//! versions with each parameter's change in σ units, who decided what, the
//! re-checks' verdicts) and a side-by-side comparison of two versions.

use serde::Serialize;
use utoipa::ToSchema;

use super::error::{ServiceError, ServiceResult};
use crate::domain::{CheckDoc, ControllerChange, Decision, Release, ReleaseStatus};
use crate::report::ParameterReport;
use crate::store::{DynStore, ParameterSetRecord};

/// Re-checks listed in a history, newest first.
const HISTORY_CHECKS: i64 = 100;
/// Parameter sets read per store call while collecting a history.
const PAGE: i64 = 500;

/// A version number (no `latest`: a decision names one set).
fn parse_version(version: &str) -> ServiceResult<i64> {
    match version.parse::<i64>() {
        Ok(v) if v >= 1 => Ok(v),
        _ => Err(ServiceError::invalid("version", "a positive integer")),
    }
}

async fn require_robot(store: &DynStore, serial: &str) -> ServiceResult<()> {
    match store.get_robot(serial).await? {
        Some(_) => Ok(()),
        None => Err(ServiceError::not_found("robot", serial)),
    }
}

/// Gives set `serial`/`version` `status`, decided by `actor`: 404 naming
/// `version` when the robot has no such set (a version of another robot).
pub async fn decide(
    store: &DynStore,
    serial: &str,
    version: &str,
    status: ReleaseStatus,
    actor: &str,
    reason: Option<String>,
) -> ServiceResult<ParameterSetRecord> {
    let v = parse_version(version)?;
    require_robot(store, serial).await?;
    let release = Release {
        status,
        reason: reason.or_else(|| Some(format!("{} by {actor}", status.as_str()))),
    };
    store
        .set_release(serial, v, &release, actor)
        .await?
        .ok_or_else(|| ServiceError::NotFoundField {
            field: "version",
            message: format!("robot {serial} has no parameter set {v}"),
        })
}

/// One parameter's change between two sets.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ParameterChange {
    pub name: String,
    pub unit: String,
    pub from: f64,
    pub to: f64,
    /// `to - from`.
    pub change: f64,
    /// The change over the combined standard deviation of both sets,
    /// `sqrt(σ_from² + σ_to²)`; `null` when neither states one.
    pub sigmas: Option<f64>,
}

/// The kinematic parameters' changes from `old` to `new` (the frames'
/// rows are corrections relative to each job's own "before" and are not
/// comparable across sets).
pub fn changes(old: &[ParameterReport], new: &[ParameterReport]) -> Vec<ParameterChange> {
    new.iter()
        .filter(|p| !p.name.contains('.'))
        .filter_map(|p| {
            let o = old.iter().find(|o| o.name == p.name)?;
            let change = p.identified - o.identified;
            let sigma = (o.std.powi(2) + p.std.powi(2)).sqrt();
            Some(ParameterChange {
                name: p.name.clone(),
                unit: p.unit.clone(),
                from: o.identified,
                to: p.identified,
                change,
                sigmas: (sigma > 0.0).then(|| change / sigma),
            })
        })
        .collect()
}

/// The identified rows of a stored set (empty for a set without them).
fn rows(record: &ParameterSetRecord) -> Vec<ParameterReport> {
    record.parameters.parameter_rows().to_vec()
}

/// One approved version in a history.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct HistoryVersion {
    pub version: i64,
    pub created_at: String,
    pub job_id: Option<String>,
    /// Who approved it (`gate`, a token, `anonymous`; `null` for sets
    /// approved by the migration that introduced the gate) and when.
    pub approved_by: Option<String>,
    pub approved_at: Option<String>,
    pub reason: Option<String>,
    /// Each kinematic parameter's change from the previous approved version.
    pub changes: Vec<ParameterChange>,
}

/// A finished re-check in a history.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct HistoryCheck {
    pub job_id: String,
    pub session_id: String,
    pub finished_at: Option<String>,
    pub check: CheckDoc,
}

/// `GET /v1/robots/{serial}/history`.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct History {
    pub serial: String,
    /// Approved versions, oldest first.
    pub approved: Vec<HistoryVersion>,
    /// Every status decision on the robot's sets, oldest first.
    pub decisions: Vec<Decision>,
    /// Re-checks, newest first (at most 100).
    pub checks: Vec<HistoryCheck>,
    /// Every change of the robot's controller identity, oldest
    /// first: from, to, when.
    pub controller_changes: Vec<ControllerChange>,
}

/// Every parameter set of the serial, oldest first.
async fn all_sets(store: &DynStore, serial: &str) -> ServiceResult<Vec<ParameterSetRecord>> {
    let mut sets = Vec::new();
    let mut before = None;
    loop {
        let page = store.list_parameter_sets(serial, PAGE, before).await?;
        before = page.items.last().map(|s| s.version);
        sets.extend(page.items);
        if page.next_cursor.is_none() {
            break;
        }
    }
    sets.reverse();
    Ok(sets)
}

pub async fn history(store: &DynStore, serial: &str) -> ServiceResult<History> {
    require_robot(store, serial).await?;
    let sets = all_sets(store, serial).await?;
    let mut approved = Vec::new();
    let mut previous: Option<Vec<ParameterReport>> = None;
    for set in sets.iter().filter(|s| s.status == ReleaseStatus::Approved) {
        let now = rows(set);
        approved.push(HistoryVersion {
            version: set.version,
            created_at: set.created_at.clone(),
            job_id: set.job_id.clone(),
            approved_by: set.status_by.clone(),
            approved_at: set.status_at.clone(),
            reason: set.status_reason.clone(),
            changes: previous
                .as_ref()
                .map(|p| changes(p, &now))
                .unwrap_or_default(),
        });
        previous = Some(now);
    }
    let checks = store
        .list_checks(serial, HISTORY_CHECKS)
        .await?
        .into_iter()
        .filter_map(|job| {
            let check = job.result?.check()?.clone();
            Some(HistoryCheck {
                job_id: job.id,
                session_id: job.session_id,
                finished_at: job.finished_at,
                check,
            })
        })
        .collect();
    Ok(History {
        serial: serial.to_string(),
        approved,
        decisions: store.list_decisions(serial).await?,
        checks,
        controller_changes: store.list_controller_changes(serial).await?,
    })
}

/// A report's side-by-side comparison with another version of the robot.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Comparison {
    /// The version compared with.
    pub version: i64,
    pub status: ReleaseStatus,
    /// Mean 3-D validation error of that version's own report (mm; each
    /// on its own session's validation poses).
    pub mean_mm: Option<f64>,
    /// This report's parameters against that version's: `from` is the
    /// other version, `to` this one.
    pub changes: Vec<ParameterChange>,
}

/// The comparison of `this` with version `other` of the same robot (404
/// naming `compare` when there is none).
pub async fn compare(
    store: &DynStore,
    this: &ParameterSetRecord,
    other: &str,
) -> ServiceResult<Comparison> {
    let v = other
        .parse::<i64>()
        .ok()
        .filter(|v| *v >= 1)
        .ok_or_else(|| ServiceError::invalid("compare", "a positive version number"))?;
    let record = store
        .get_parameter_set(&this.serial, Some(v))
        .await?
        .ok_or_else(|| ServiceError::NotFoundField {
            field: "compare",
            message: format!("robot {} has no parameter set {v}", this.serial),
        })?;
    let mean_mm = store
        .get_report(&this.serial, v)
        .await?
        .and_then(|r| r.pointer("/after/mean_mm").and_then(|m| m.as_f64()));
    Ok(Comparison {
        version: v,
        status: record.status,
        mean_mm,
        changes: changes(&rows(&record), &rows(this)),
    })
}
