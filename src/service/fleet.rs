//! What the fleet page shows (`GET /`, `GET /robots/{serial}`): every
//! robot with its current parameter set, that set's accuracy, its last
//! re-check and the jobs in progress. The current set is read exactly as
//! `…/parameter-sets/latest` reads it ([`results::find_parameter_set`]
//! with [`results::LATEST`]), so the page shows whatever `latest` means.

use serde::Deserialize;

use super::error::{ServiceError, ServiceResult};
use super::results;
use crate::domain::{ControllerIdentity, JobState, ReleaseStatus, Serial};
use crate::report::{AccuracySummary, Report};
use crate::store::{DynStore, JobFilter, JobRecord, ParameterSetRecord};

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

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accuracy {
    pub validation_poses: usize,
    pub before_mean_mm: f64,
    pub after_mean_mm: f64,
    /// A hand–eye set's reprojection RMS (px): such a set identified no
    /// kinematics, so its before and after are the same model and the
    /// pages show what it measured instead.
    pub hand_eye_rms_px: Option<f64>,
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

/// The key of a report's validation figures after calibration.
const AFTER_KEY: &str = "after";

/// The report's validation statistics, read without the rest of it.
#[derive(Deserialize)]
struct ReportAccuracy {
    before: AccuracySummary,
    after: AccuracySummary,
    #[serde(default)]
    hand_eye: Option<HandEyeFit>,
}

/// The part of a report's hand–eye section the pages show.
#[derive(Deserialize)]
struct HandEyeFit {
    reprojection_rms_px: f64,
}

impl From<JobRecord> for JobBrief {
    fn from(j: JobRecord) -> JobBrief {
        JobBrief {
            id: j.id,
            serial: j.serial,
            kind: j.kind.as_str().into(),
            state: j.state,
            stage: j.stage,
            progress: j.progress,
            created_at: j.created_at,
            error: j.error,
        }
    }
}

async fn summary_of(store: &DynStore, set: &ParameterSetRecord) -> ServiceResult<SetSummary> {
    let report = store.get_report(&set.serial, set.version).await?;
    // A report without validation figures (a test marker) shows none; one
    // whose figures do not read is an error, not a blank.
    let accuracy = report
        .filter(|r| r.get(AFTER_KEY).is_some())
        .map(serde_json::from_value::<ReportAccuracy>)
        .transpose()
        .map_err(|e| {
            ServiceError::internal(format!("stored report {}/{}: {e}", set.serial, set.version))
        })?
        .map(|r| Accuracy {
            validation_poses: r.after.norm.n,
            before_mean_mm: r.before.norm.mean_mm,
            after_mean_mm: r.after.norm.mean_mm,
            hand_eye_rms_px: r.hand_eye.map(|h| h.reprojection_rms_px),
        });
    Ok(SetSummary {
        version: set.version,
        created_at: set.created_at.clone(),
        job_id: set.job_id.clone(),
        accuracy,
        status: set.status,
        status_by: set.status_by.clone(),
        status_reason: set.status_reason.clone(),
    })
}

/// The set `latest` names, summarised (`None` when the robot has none).
async fn current_set(store: &DynStore, serial: &str) -> ServiceResult<Option<SetSummary>> {
    match results::find_parameter_set(store, serial, results::LATEST).await {
        Ok(set) => Ok(Some(summary_of(store, &set).await?)),
        Err(ServiceError::NotFound { .. }) => Ok(None),
        Err(e) => Err(e),
    }
}

/// The robot's last judged quick re-check, if any.
async fn last_check(store: &DynStore, serial: &str) -> ServiceResult<Option<CheckSummary>> {
    let checks = store.list_checks(serial, 1).await?;
    Ok(checks.into_iter().next().and_then(|job| {
        let check = job.result.as_ref()?.check()?;
        let verdict = check.verdict.as_str().to_string();
        let checked_version = Some(check.checked_version).filter(|v| *v >= 1);
        Some(CheckSummary {
            verdict,
            at: job.finished_at.unwrap_or(job.created_at),
            checked_version,
        })
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

/// Every robot (the first [`MAX_ROBOTS`] by serial) with what it runs now.
pub async fn fleet(store: &DynStore) -> ServiceResult<Vec<RobotSummary>> {
    let robots = store.list_robots(MAX_ROBOTS, None).await?.items;
    let active = active_jobs(store, None).await?;
    let mut rows = Vec::with_capacity(robots.len());
    for robot in robots {
        rows.push(RobotSummary {
            current: current_set(store, &robot.serial).await?,
            last_check: last_check(store, &robot.serial).await?,
            last_failed: last_failed(store, &robot.serial).await?,
            jobs_in_progress: active
                .iter()
                .filter(|j| j.serial == robot.serial)
                .cloned()
                .collect(),
            serial: robot.serial,
            model: robot.model,
            controller: robot.controller,
        });
    }
    Ok(rows)
}

/// A robot's page: its current set, every version (the newest
/// [`MAX_VERSIONS`]) and its recent jobs; 404 for an unknown serial.
pub async fn robot(store: &DynStore, serial: &str) -> ServiceResult<RobotDetail> {
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
        versions.push(summary_of(store, &set).await?);
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
            current: current_set(store, &serial).await?,
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
