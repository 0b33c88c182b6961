//! What the fleet page shows (`GET /`, `GET /robots/{serial}`): every
//! robot with its current parameter set, that set's accuracy, its last
//! re-check and the jobs in progress. The current set is read exactly as
//! `…/parameter-sets/latest` reads it ([`results::find_parameter_set`]
//! with [`results::LATEST`]), so the page shows whatever `latest` means.

use super::error::{ServiceError, ServiceResult};
use super::fleet_cache::{accuracy_of, accuracy_of_value, SetKey};
pub use super::fleet_cache::{Accuracy, SummaryCache};
use super::results;
use crate::domain::{CheckDoc, ControllerIdentity, JobState, ReleaseStatus, Serial};
use crate::report::Report;
use crate::store::{
    DynStore, FleetRow, JobFilter, JobHead, JobRecord, ParameterSetRecord, SetHead,
};

/// Robots listed on the fleet page (the first, by serial).
pub const MAX_ROBOTS: i64 = 500;
/// Versions listed on a robot's page (the newest).
pub const MAX_VERSIONS: i64 = 50;
/// Jobs listed on a robot's page (the newest).
pub const MAX_ROBOT_JOBS: i64 = 20;
/// Jobs in progress read at once for the fleet page.
const MAX_ACTIVE_JOBS: i64 = 1000;

/// A parameter set as the pages show it.
#[derive(Debug, Clone)]
pub struct SetSummary {
    pub version: i64,
    pub created_at: String,
    pub job_id: Option<String>,
    /// Mean 3-D error at the validation poses, mm, before and after (none
    /// for a set stored without an accuracy report).
    pub accuracy: Option<Accuracy>,
    /// Its release status now, who gave it and why.
    pub status: ReleaseStatus,
    pub status_by: Option<String>,
    pub status_reason: Option<String>,
}

/// The latest re-check of a robot and what it found (`pass`, `drift`,
/// `base_moved`, `controller_changed`).
#[derive(Debug, Clone)]
pub struct CheckSummary {
    pub verdict: String,
    pub at: String,
    /// The version the check judged (`None` for checks stored before the
    /// version was carried): a card must not show a verdict on v1 as if
    /// it were on the current v5.
    pub checked_version: Option<i64>,
}

/// A job that is queued or running.
#[derive(Debug, Clone)]
pub struct JobBrief {
    pub id: String,
    pub serial: String,
    pub kind: String,
    pub state: JobState,
    pub stage: Option<String>,
    pub progress: f64,
    pub created_at: String,
    pub error: Option<String>,
}

/// One row of the fleet page.
#[derive(Debug, Clone)]
pub struct RobotSummary {
    pub serial: String,
    pub model: String,
    /// The robot's controller identity; `None`: none given.
    pub controller: Option<ControllerIdentity>,
    /// What `latest` serves; `None` before the first calibration.
    pub current: Option<SetSummary>,
    /// `None`: never checked.
    pub last_check: Option<CheckSummary>,
    pub jobs_in_progress: Vec<JobBrief>,
    /// The robot's newest job when it failed (a robot whose last job
    /// failed must not look like an untouched one).
    pub last_failed: Option<JobBrief>,
}

/// A robot's own page.
#[derive(Debug, Clone)]
pub struct RobotDetail {
    pub summary: RobotSummary,
    /// Newest first.
    pub versions: Vec<SetSummary>,
    /// Newest first, every state.
    pub recent_jobs: Vec<JobBrief>,
}

impl From<JobRecord> for JobBrief {
    fn from(j: JobRecord) -> JobBrief {
        JobHead::from(j).into()
    }
}

impl From<JobHead> for JobBrief {
    fn from(j: JobHead) -> JobBrief {
        JobBrief {
            id: j.id,
            serial: j.serial,
            kind: j.kind,
            state: j.state,
            stage: j.stage,
            progress: j.progress,
            created_at: j.created_at,
            error: j.error,
        }
    }
}

fn set_key(serial: &str, version: i64, created_at: &str) -> SetKey {
    (serial.to_string(), version, created_at.to_string())
}

/// A set's accuracy from the cache, or read from its report and kept.
async fn accuracy(
    store: &DynStore,
    cache: &SummaryCache,
    set: &ParameterSetRecord,
) -> ServiceResult<Option<Accuracy>> {
    let key = set_key(&set.serial, set.version, &set.created_at);
    if let Some(known) = cache.get(&key) {
        return Ok(known);
    }
    let report = store.get_report(&set.serial, set.version).await?;
    let found = report
        .map(|r| accuracy_of_value(r).map_err(|e| stored_report_error(&set.serial, set.version, e)))
        .transpose()?
        .flatten();
    cache.put(key, found);
    Ok(found)
}

/// A stored report whose figures do not read: an error naming the set, not a blank.
fn stored_report_error(serial: &str, version: i64, e: serde_json::Error) -> ServiceError {
    ServiceError::internal(format!("stored report {serial}/{version}: {e}"))
}

async fn summary_of(
    store: &DynStore,
    cache: &SummaryCache,
    set: &ParameterSetRecord,
) -> ServiceResult<SetSummary> {
    Ok(SetSummary {
        version: set.version,
        created_at: set.created_at.clone(),
        job_id: set.job_id.clone(),
        accuracy: accuracy(store, cache, set).await?,
        status: set.status,
        status_by: set.status_by.clone(),
        status_reason: set.status_reason.clone(),
    })
}

/// The set `latest` names, summarised (`None` when the robot has none).
async fn current_set(
    store: &DynStore,
    cache: &SummaryCache,
    serial: &str,
) -> ServiceResult<Option<SetSummary>> {
    match results::find_parameter_set(store, serial, results::LATEST).await {
        Ok(set) => Ok(Some(summary_of(store, cache, &set).await?)),
        Err(ServiceError::NotFound { .. }) => Ok(None),
        Err(e) => Err(e),
    }
}

/// What a succeeded re-check judged, and when.
fn check_summary(
    check: &CheckDoc,
    created_at: String,
    finished_at: Option<String>,
) -> Option<CheckSummary> {
    Some(CheckSummary {
        verdict: check.verdict.as_str().to_string(),
        at: finished_at.unwrap_or(created_at),
        checked_version: Some(check.checked_version).filter(|v| *v >= 1),
    })
}

/// The robot's last judged quick re-check, if any.
async fn last_check(store: &DynStore, serial: &str) -> ServiceResult<Option<CheckSummary>> {
    let checks = store.list_checks(serial, 1).await?;
    Ok(checks.into_iter().next().and_then(|job| {
        check_summary(
            job.result.as_ref()?.check()?,
            job.created_at,
            job.finished_at,
        )
    }))
}

/// Queued and running jobs (of one robot, or of the whole fleet), oldest first.
async fn active_jobs(store: &DynStore, serial: Option<&str>) -> ServiceResult<Vec<JobBrief>> {
    let mut jobs = Vec::new();
    for state in [JobState::Running, JobState::Queued] {
        let filter = JobFilter {
            state: Some(state),
            serial: serial.map(str::to_string),
            kind: None,
        };
        let page = store.list_jobs(&filter, MAX_ACTIVE_JOBS, None).await?;
        jobs.extend(page.items.into_iter().map(JobBrief::from));
    }
    jobs.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(jobs)
}

/// The robot's newest job, when it failed.
async fn last_failed(store: &DynStore, serial: &str) -> ServiceResult<Option<JobBrief>> {
    let filter = JobFilter {
        serial: Some(serial.to_string()),
        ..JobFilter::default()
    };
    let newest = store
        .list_jobs(&filter, 1, None)
        .await?
        .items
        .into_iter()
        .next();
    Ok(newest
        .filter(|j| j.state == JobState::Failed)
        .map(JobBrief::from))
}

/// Every robot (the first [`MAX_ROBOTS`] by serial) with what it runs
/// now: one statement for the robots with their current set, re-check and
/// newest job, one per job state for the jobs in progress, and the
/// current sets' reports only when a set is new to `cache`.
pub async fn fleet(store: &DynStore, cache: &SummaryCache) -> ServiceResult<Vec<RobotSummary>> {
    let rows = store.fleet_rows(MAX_ROBOTS).await?;
    let unknown = rows
        .iter()
        .filter_map(|r| r.current.as_ref().map(|s| (r, s)))
        .any(|(r, s)| {
            cache
                .get(&set_key(&r.serial, s.version, &s.created_at))
                .is_none()
        });
    if unknown {
        let mut reported = std::collections::HashSet::new();
        for current in store.fleet_reports(MAX_ROBOTS).await? {
            let key = set_key(&current.serial, current.version, &current.set_created_at);
            reported.insert(key.clone());
            let found = accuracy_of(&current.report)
                .map_err(|e| stored_report_error(&current.serial, current.version, e))?;
            cache.put(key, found);
        }
        for (r, s) in rows
            .iter()
            .filter_map(|r| r.current.as_ref().map(|s| (r, s)))
        {
            let key = set_key(&r.serial, s.version, &s.created_at);
            if !reported.contains(&key) {
                cache.put(key, None);
            }
        }
    }
    let active = active_jobs(store, None).await?;
    rows.into_iter()
        .map(|row| robot_summary(row, cache, &active))
        .collect()
}

/// A fleet row with its cached accuracy and its jobs in progress.
fn robot_summary(
    row: FleetRow,
    cache: &SummaryCache,
    active: &[JobBrief],
) -> ServiceResult<RobotSummary> {
    let last_check = row.last_check.and_then(|head| {
        let check = head.result.as_ref()?.check()?;
        check_summary(check, head.created_at, head.finished_at)
    });
    let current = row.current.map(|set: SetHead| SetSummary {
        accuracy: cache
            .get(&set_key(&row.serial, set.version, &set.created_at))
            .flatten(),
        version: set.version,
        created_at: set.created_at,
        job_id: set.job_id,
        status: set.status,
        status_by: set.status_by,
        status_reason: set.status_reason,
    });
    Ok(RobotSummary {
        current,
        last_check,
        last_failed: row
            .newest_job
            .filter(|j| j.state == JobState::Failed)
            .map(JobBrief::from),
        jobs_in_progress: active
            .iter()
            .filter(|j| j.serial == row.serial)
            .cloned()
            .collect(),
        serial: row.serial,
        model: row.model,
        controller: row.controller,
    })
}

/// A robot's page: its current set, every version (the newest
/// [`MAX_VERSIONS`]) and its recent jobs; 404 for an unknown serial.
pub async fn robot(
    store: &DynStore,
    cache: &SummaryCache,
    serial: &str,
) -> ServiceResult<RobotDetail> {
    let serial =
        Serial::parse(serial).map_err(|e| ServiceError::invalid("serial", e.to_string()))?;
    let robot = store
        .get_robot(&serial)
        .await?
        .ok_or_else(|| ServiceError::not_found("robot", &serial))?;
    let mut versions = Vec::new();
    for set in store
        .list_parameter_sets(&serial, MAX_VERSIONS, None)
        .await?
        .items
    {
        versions.push(summary_of(store, cache, &set).await?);
    }
    let filter = JobFilter {
        serial: Some(serial.to_string()),
        ..JobFilter::default()
    };
    let recent_jobs = store
        .list_jobs(&filter, MAX_ROBOT_JOBS, None)
        .await?
        .items
        .into_iter()
        .map(JobBrief::from)
        .collect();
    Ok(RobotDetail {
        summary: RobotSummary {
            current: current_set(store, cache, &serial).await?,
            last_check: last_check(store, &serial).await?,
            last_failed: last_failed(store, &serial).await?,
            jobs_in_progress: active_jobs(store, Some(&serial)).await?,
            serial: robot.serial,
            model: robot.model,
            controller: robot.controller,
        },
        versions,
        recent_jobs,
    })
}

/// The accuracy report of version `version` of robot `serial`, with the
/// set's identity and current release status as `/v1/…/report.html` shows
/// it (404 when absent, 409 when the set holds no report to draw).
pub async fn report(store: &DynStore, serial: &str, version: i64) -> ServiceResult<Report> {
    super::report_view::typed_report(store, serial, &version.to_string()).await
}
