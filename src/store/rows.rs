//! Row-to-record mapping shared by the SQLite and PostgreSQL backends: both
//! schemas store JSON documents as TEXT and use the same column names, so
//! only the SQL dialect differs between `sqlite/` and `postgres/`.

use serde_json::Value;
use sqlx::{Decode, Row, Type};

use super::StoreError;
use super::StoreResult;
use crate::domain::{
    ImageMeta, JobKind, JobResult, JobState, JointsDeg, PoseGroup, PoseSet, ReleaseStatus, Scope,
    TokenRecord,
};
use crate::schema::job::JobOptions;
use crate::store::{
    ClaimedJob, JobRecord, ParameterSetRecord, PoseRecord, RobotRecord, SessionRecord,
};

pub fn json(text: &str) -> StoreResult<Value> {
    Ok(serde_json::from_str(text)?)
}

pub fn opt_json(text: Option<&str>) -> StoreResult<Option<Value>> {
    text.map(json).transpose()
}

/// A nullable JSON column read as its typed document.
pub fn opt_typed<T: serde::de::DeserializeOwned>(text: Option<&str>) -> StoreResult<Option<T>> {
    Ok(text.map(serde_json::from_str).transpose()?)
}

/// A result row of either backend, read by column name as one of the few
/// column types the schemas use. The blanket impl below states once what
/// `sqlx` needs to decode them; code reading rows only names this trait.
/// Like `Row::get`, each accessor panics on a missing column or a type the
/// column cannot decode to (a bug in the statement, not bad data).
pub trait Columns: Row {
    fn str(&self, col: &'static str) -> &str;
    fn opt_str(&self, col: &'static str) -> Option<&str>;
    fn string(&self, col: &'static str) -> String;
    fn opt_string(&self, col: &'static str) -> Option<String>;
    fn int(&self, col: &'static str) -> i64;
    fn opt_int(&self, col: &'static str) -> Option<i64>;
    fn real(&self, col: &'static str) -> f64;
    fn opt_real(&self, col: &'static str) -> Option<f64>;
    fn bytes(&self, col: &'static str) -> Vec<u8>;
    fn opt_bytes(&self, col: &'static str) -> Option<Vec<u8>>;
}

impl<R> Columns for R
where
    R: Row,
    &'static str: sqlx::ColumnIndex<R>,
    for<'r> &'r str: Decode<'r, R::Database> + Type<R::Database>,
    for<'r> String: Decode<'r, R::Database> + Type<R::Database>,
    for<'r> i64: Decode<'r, R::Database> + Type<R::Database>,
    for<'r> f64: Decode<'r, R::Database> + Type<R::Database>,
    for<'r> Vec<u8>: Decode<'r, R::Database> + Type<R::Database>,
{
    fn str(&self, col: &'static str) -> &str {
        self.get(col)
    }
    fn opt_str(&self, col: &'static str) -> Option<&str> {
        self.get(col)
    }
    fn string(&self, col: &'static str) -> String {
        self.get(col)
    }
    fn opt_string(&self, col: &'static str) -> Option<String> {
        self.get(col)
    }
    fn int(&self, col: &'static str) -> i64 {
        self.get(col)
    }
    fn opt_int(&self, col: &'static str) -> Option<i64> {
        self.get(col)
    }
    fn real(&self, col: &'static str) -> f64 {
        self.get(col)
    }
    fn opt_real(&self, col: &'static str) -> Option<f64> {
        self.get(col)
    }
    fn bytes(&self, col: &'static str) -> Vec<u8> {
        self.get(col)
    }
    fn opt_bytes(&self, col: &'static str) -> Option<Vec<u8>> {
        self.get(col)
    }
}

pub fn session(row: &impl Columns) -> StoreResult<SessionRecord> {
    Ok(SessionRecord {
        id: row.string("id"),
        serial: row.string("serial"),
        instrument: row.string("instrument"),
        spec: serde_json::from_str(row.str("spec"))?,
        pose_count: row.int("pose_count"),
        created_at: row.string("created_at"),
    })
}

pub fn pose(row: &impl Columns) -> StoreResult<PoseRecord> {
    let image: Option<ImageMeta> = row
        .opt_str("image_meta")
        .map(serde_json::from_str)
        .transpose()?;
    Ok(PoseRecord {
        id: row.string("id"),
        session_id: row.string("session_id"),
        joints_deg: JointsDeg::stored(serde_json::from_str(row.str("joints_deg"))?),
        set: PoseSet::parse(row.str("pose_set")).ok_or_else(|| {
            StoreError::Backend(format!("unknown pose set {:?}", row.str("pose_set")))
        })?,
        image,
        points: serde_json::from_str(row.str("points"))?,
        measured: opt_typed(row.opt_str("measured"))?,
        label: row.opt_string("label"),
        detection: opt_json(row.opt_str("detection"))?,
        image_detection: opt_typed(row.opt_str("image_detection"))?,
        flange_pose: opt_typed(row.opt_str("flange_pose"))?,
        stage_reading: opt_typed(row.opt_str("stage_reading"))?,
        group: row.opt_string("pose_group").map(PoseGroup::stored),
        created_at: row.string("created_at"),
    })
}

pub fn token(row: &impl Columns) -> StoreResult<TokenRecord> {
    let scope = row.str("scope");
    Ok(TokenRecord {
        id: row.string("id"),
        name: row.string("name"),
        scope: Scope::parse(scope)
            .ok_or_else(|| StoreError::Backend(format!("unknown scope {scope:?}")))?,
        created_at: row.string("created_at"),
        expires_ms: row.opt_int("expires_ms"),
        revoked_ms: row.opt_int("revoked_ms"),
        last_used_ms: row.opt_int("last_used_ms"),
    })
}

pub fn robot(row: &impl Columns) -> StoreResult<RobotRecord> {
    Ok(RobotRecord {
        serial: row.string("serial"),
        model: row.string("model"),
        preset: row.opt_string("preset"),
        kinematics: json(row.str("kinematics"))?,
        controller: opt_typed(row.opt_str("controller"))?,
        prior: opt_typed(row.opt_str("prior"))?,
        created_at: row.string("created_at"),
        updated_at: row.string("updated_at"),
    })
}

/// The columns [`job`] reads, for `SELECT` and `RETURNING`.
pub const JOB_COLUMNS: &str =
    "id, kind, session_id, serial, options, state, stage, progress, attempts,
    max_attempts, error, result, created_at, started_at, finished_at";

/// A job's kind, and its options read as that kind's.
fn kind_and_options(row: &impl Columns) -> StoreResult<(JobKind, JobOptions)> {
    let id = row.str("id");
    let kind = JobKind::parse(row.str("kind")).ok_or_else(|| {
        StoreError::Backend(format!("job {id}: unknown kind {:?}", row.str("kind")))
    })?;
    let options = json(row.str("options"))
        .and_then(|doc| Ok(JobOptions::decode(kind, doc)?))
        .map_err(|e| StoreError::Backend(format!("stored options of job {id}: {e}")))?;
    Ok((kind, options))
}

pub fn job(row: &impl Columns) -> StoreResult<JobRecord> {
    let state = row.str("state");
    let (kind, options) = kind_and_options(row)?;
    let result = opt_json(row.opt_str("result"))?
        .map(JobResult::decode)
        .transpose()
        .map_err(|e| StoreError::Backend(format!("stored result of job {}: {e}", row.str("id"))))?;
    Ok(JobRecord {
        id: row.string("id"),
        kind,
        session_id: row.string("session_id"),
        serial: row.string("serial"),
        options,
        state: JobState::parse(state)
            .ok_or_else(|| StoreError::Backend(format!("unknown job state {state:?}")))?,
        stage: row.opt_string("stage"),
        progress: row.real("progress"),
        attempts: row.int("attempts"),
        max_attempts: row.int("max_attempts"),
        error: row.opt_string("error"),
        result,
        created_at: row.string("created_at"),
        started_at: row.opt_string("started_at"),
        finished_at: row.opt_string("finished_at"),
    })
}

pub fn parameter_set(row: &impl Columns) -> StoreResult<ParameterSetRecord> {
    let (serial, version) = (row.string("serial"), row.int("version"));
    let parameters = serde_json::from_str(row.str("parameters")).map_err(|e| {
        StoreError::Backend(format!(
            "stored parameter set {serial}/{version} unreadable: {e}"
        ))
    })?;
    Ok(ParameterSetRecord {
        serial,
        version,
        job_id: row.opt_string("job_id"),
        parameters,
        created_at: row.string("created_at"),
        status: release_status(row.str("status"))?,
        status_reason: row.opt_string("status_reason"),
        status_by: row.opt_string("status_by"),
        status_at: row.opt_string("status_at"),
    })
}

pub fn release_status(s: &str) -> StoreResult<ReleaseStatus> {
    ReleaseStatus::parse(s).ok_or_else(|| StoreError::Backend(format!("unknown status {s:?}")))
}

pub fn claimed_job(row: &impl Columns) -> StoreResult<ClaimedJob> {
    let (kind, options) = kind_and_options(row)?;
    Ok(ClaimedJob {
        id: row.string("id"),
        kind,
        session_id: row.string("session_id"),
        serial: row.string("serial"),
        options,
        attempt: row.int("attempts"),
    })
}
