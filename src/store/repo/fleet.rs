//! The fleet page's read: every robot of a page with the set `latest`
//! serves, its last judged re-check and its newest job, in one statement
//! whatever the fleet's size (index lookups per robot inside the database,
//! not a round trip per robot), and the reports of those sets in a second
//! one that the service runs only for sets it has not summarised yet.

use async_trait::async_trait;

use crate::domain::{ControllerIdentity, JobKind, JobResult, JobState, ReleaseStatus};
use crate::store::backend::Backend;
use crate::store::rows::{opt_json, opt_typed, release_status, Columns};
use crate::store::statement::query;
use crate::store::{FleetStore, StoreError, StoreResult};

/// A page of robots by serial, with the approved set each serves: the
/// rule of `get_parameter_set(serial, None)` (the newest approved).
const PAGE_WITH_CURRENT: &str = "
    WITH page AS (SELECT serial, model, controller FROM robots ORDER BY serial LIMIT $1)
    SELECT p.serial, p.model, p.controller,
           ps.version AS set_version, ps.job_id AS set_job_id, ps.created_at AS set_created_at,
           ps.status AS set_status, ps.status_reason AS set_status_reason,
           ps.status_by AS set_status_by";
const CURRENT_JOIN: &str = "
    FROM page p
    LEFT JOIN parameter_sets ps ON ps.serial = p.serial AND ps.version =
        (SELECT MAX(a.version) FROM parameter_sets a
          WHERE a.serial = p.serial AND a.status = 'approved')";

/// The set a robot's `latest` serves, without its parameters.
#[derive(Debug, Clone)]
pub struct SetHead {
    pub version: i64,
    pub job_id: Option<String>,
    /// Also the set's identity: a re-created robot's version 1 is another set.
    pub created_at: String,
    pub status: ReleaseStatus,
    pub status_reason: Option<String>,
    pub status_by: Option<String>,
}

/// A succeeded re-check job: its result and times.
#[derive(Debug, Clone)]
pub struct CheckHead {
    pub result: Option<JobResult>,
    pub created_at: String,
    pub finished_at: Option<String>,
}

/// A job as the fleet page shows it (no options, no result).
#[derive(Debug, Clone)]
pub struct JobHead {
    pub id: String,
    pub serial: String,
    pub kind: String,
    pub state: JobState,
    pub stage: Option<String>,
    pub progress: f64,
    pub created_at: String,
    pub error: Option<String>,
}

/// A whole job as the fleet page shows it.
impl From<crate::store::JobRecord> for JobHead {
    fn from(j: crate::store::JobRecord) -> JobHead {
        JobHead {
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

/// One robot of the fleet page.
#[derive(Debug, Clone)]
pub struct FleetRow {
    pub serial: String,
    pub model: String,
    pub controller: Option<ControllerIdentity>,
    pub current: Option<SetHead>,
    pub last_check: Option<CheckHead>,
    pub newest_job: Option<JobHead>,
}

/// The report text of a robot's current set, with the set's identity.
#[derive(Debug, Clone)]
pub struct CurrentReport {
    pub serial: String,
    pub version: i64,
    pub set_created_at: String,
    pub report: String,
}

fn set_head(row: &impl Columns) -> StoreResult<Option<SetHead>> {
    let Some(version) = row.opt_int("set_version") else {
        return Ok(None);
    };
    Ok(Some(SetHead {
        version,
        job_id: row.opt_string("set_job_id"),
        created_at: row.string("set_created_at"),
        status: release_status(row.str("set_status"))?,
        status_reason: row.opt_string("set_status_reason"),
        status_by: row.opt_string("set_status_by"),
    }))
}

fn job_head(row: &impl Columns, serial: &str) -> StoreResult<Option<JobHead>> {
    let Some(id) = row.opt_string("job_id") else {
        return Ok(None);
    };
    let state = row.str("job_state");
    Ok(Some(JobHead {
        id,
        serial: serial.to_string(),
        kind: row.string("job_kind"),
        state: JobState::parse(state)
            .ok_or_else(|| StoreError::Backend(format!("unknown job state {state:?}")))?,
        stage: row.opt_string("job_stage"),
        progress: row.opt_real("job_progress").unwrap_or(0.0),
        created_at: row.string("job_created_at"),
        error: row.opt_string("job_error"),
    }))
}

fn fleet_row(row: &impl Columns) -> StoreResult<FleetRow> {
    let serial = row.string("serial");
    let last_check = match row.opt_string("check_created_at") {
        None => None,
        Some(created_at) => Some(CheckHead {
            result: opt_json(row.opt_str("check_result"))?
                .map(JobResult::decode)
                .transpose()
                .map_err(|e| {
                    StoreError::Backend(format!("stored re-check result of {serial}: {e}"))
                })?,
            created_at,
            finished_at: row.opt_string("check_finished_at"),
        }),
    };
    Ok(FleetRow {
        model: row.string("model"),
        controller: opt_typed(row.opt_str("controller"))?,
        current: set_head(row)?,
        last_check,
        newest_job: job_head(row, &serial)?,
        serial,
    })
}

#[async_trait]
impl<B: Backend> FleetStore for B {
    async fn fleet_rows(&self, limit: i64) -> StoreResult<Vec<FleetRow>> {
        let sql = format!(
            "{PAGE_WITH_CURRENT},
                ck.result AS check_result, ck.created_at AS check_created_at,
                ck.finished_at AS check_finished_at,
                nj.id AS job_id, nj.kind AS job_kind, nj.state AS job_state,
                nj.stage AS job_stage, nj.progress AS job_progress,
                nj.created_at AS job_created_at, nj.error AS job_error
             {CURRENT_JOIN}
             LEFT JOIN jobs ck ON ck.id =
                (SELECT c.id FROM jobs c WHERE c.serial = p.serial AND c.kind = $2
                   AND c.state = 'succeeded' ORDER BY c.id DESC LIMIT 1)
             LEFT JOIN jobs nj ON nj.id =
                (SELECT n.id FROM jobs n WHERE n.serial = p.serial ORDER BY n.id DESC LIMIT 1)
             ORDER BY p.serial"
        );
        let rows = query(sql)
            .bind(limit)
            .bind(JobKind::Check.as_str())
            .fetch_all(self.pool())
            .await?;
        rows.iter().map(fleet_row).collect()
    }

    async fn fleet_reports(&self, limit: i64) -> StoreResult<Vec<CurrentReport>> {
        let sql = format!(
            "{PAGE_WITH_CURRENT}, r.report
             {CURRENT_JOIN}
             JOIN reports r ON r.serial = ps.serial AND r.version = ps.version"
        );
        let rows = query(sql).bind(limit).fetch_all(self.pool()).await?;
        Ok(rows
            .iter()
            .map(|row| CurrentReport {
                serial: row.string("serial"),
                version: row.int("set_version"),
                set_created_at: row.string("set_created_at"),
                report: row.string("report"),
            })
            .collect())
    }
}
