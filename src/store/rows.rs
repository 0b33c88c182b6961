//! Row-to-record mapping shared by the SQLite and PostgreSQL backends: both
//! schemas store JSON documents as TEXT and use the same column names, so
//! only the SQL dialect differs between `sqlite/` and `postgres/`.

use serde_json::Value;
use sqlx::{ColumnIndex, Decode, Row, Type};

use super::StoreError;
use super::StoreResult;
use crate::domain::{
    ImageMeta, JobRecord, JobState, ParameterSetRecord, PoseRecord, RobotRecord, Scope,
    SessionRecord, TokenRecord,
};

pub fn json(text: &str) -> StoreResult<Value> {
    Ok(serde_json::from_str(text)?)
}

pub fn opt_json(text: Option<String>) -> StoreResult<Option<Value>> {
    text.map(|t| json(&t)).transpose()
}

pub fn session<'r, R>(row: &'r R) -> StoreResult<SessionRecord>
where
    R: Row,
    &'static str: ColumnIndex<R>,
    String: Decode<'r, R::Database> + Type<R::Database>,
    &'r str: Decode<'r, R::Database> + Type<R::Database>,
    i64: Decode<'r, R::Database> + Type<R::Database>,
{
    Ok(SessionRecord {
        id: row.get("id"),
        serial: row.get("serial"),
        instrument: row.get("instrument"),
        spec: json(row.get::<&str, _>("spec"))?,
        pose_count: row.get("pose_count"),
        created_at: row.get("created_at"),
    })
}

pub fn pose<'r, R>(row: &'r R) -> StoreResult<PoseRecord>
where
    R: Row,
    &'static str: ColumnIndex<R>,
    String: Decode<'r, R::Database> + Type<R::Database>,
    &'r str: Decode<'r, R::Database> + Type<R::Database>,
{
    let image: Option<ImageMeta> = row
        .get::<Option<&str>, _>("image_meta")
        .map(serde_json::from_str)
        .transpose()?;
    Ok(PoseRecord {
        id: row.get("id"),
        session_id: row.get("session_id"),
        joints_deg: serde_json::from_str(row.get::<&str, _>("joints_deg"))?,
        set: row.get("pose_set"),
        image,
        points: json(row.get::<&str, _>("points"))?,
        measured: opt_json(row.get("measured"))?,
        detection: opt_json(row.get("detection"))?,
        created_at: row.get("created_at"),
    })
}

pub fn token<'r, R>(row: &'r R) -> StoreResult<TokenRecord>
where
    R: Row,
    &'static str: ColumnIndex<R>,
    String: Decode<'r, R::Database> + Type<R::Database>,
    &'r str: Decode<'r, R::Database> + Type<R::Database>,
    i64: Decode<'r, R::Database> + Type<R::Database>,
    f64: Decode<'r, R::Database> + Type<R::Database>,
{
    let scope: String = row.get("scope");
    Ok(TokenRecord {
        id: row.get("id"),
        name: row.get("name"),
        scope: Scope::parse(&scope)
            .ok_or_else(|| StoreError::Backend(format!("unknown scope {scope:?}")))?,
        created_at: row.get("created_at"),
    })
}

pub fn robot<'r, R>(row: &'r R) -> StoreResult<RobotRecord>
where
    R: Row,
    &'static str: ColumnIndex<R>,
    String: Decode<'r, R::Database> + Type<R::Database>,
    &'r str: Decode<'r, R::Database> + Type<R::Database>,
    i64: Decode<'r, R::Database> + Type<R::Database>,
    f64: Decode<'r, R::Database> + Type<R::Database>,
{
    Ok(RobotRecord {
        serial: row.get("serial"),
        model: row.get("model"),
        preset: row.get("preset"),
        kinematics: json(row.get::<&str, _>("kinematics"))?,
        created_at: row.get("created_at"),
        updated_at: row.get("updated_at"),
    })
}

pub fn job<'r, R>(row: &'r R) -> StoreResult<JobRecord>
where
    R: Row,
    &'static str: ColumnIndex<R>,
    String: Decode<'r, R::Database> + Type<R::Database>,
    &'r str: Decode<'r, R::Database> + Type<R::Database>,
    i64: Decode<'r, R::Database> + Type<R::Database>,
    f64: Decode<'r, R::Database> + Type<R::Database>,
{
    let state: String = row.get("state");
    Ok(JobRecord {
        id: row.get("id"),
        kind: row.get("kind"),
        session_id: row.get("session_id"),
        serial: row.get("serial"),
        options: json(row.get::<&str, _>("options"))?,
        state: JobState::parse(&state)
            .ok_or_else(|| StoreError::Backend(format!("unknown job state {state:?}")))?,
        stage: row.get("stage"),
        progress: row.get("progress"),
        attempts: row.get("attempts"),
        max_attempts: row.get("max_attempts"),
        error: row.get("error"),
        result: opt_json(row.get("result"))?,
        created_at: row.get("created_at"),
        started_at: row.get("started_at"),
        finished_at: row.get("finished_at"),
    })
}

pub fn parameter_set<'r, R>(row: &'r R) -> StoreResult<ParameterSetRecord>
where
    R: Row,
    &'static str: ColumnIndex<R>,
    String: Decode<'r, R::Database> + Type<R::Database>,
    &'r str: Decode<'r, R::Database> + Type<R::Database>,
    i64: Decode<'r, R::Database> + Type<R::Database>,
    f64: Decode<'r, R::Database> + Type<R::Database>,
{
    Ok(ParameterSetRecord {
        serial: row.get("serial"),
        version: row.get("version"),
        job_id: row.get("job_id"),
        parameters: json(row.get::<&str, _>("parameters"))?,
        created_at: row.get("created_at"),
    })
}
