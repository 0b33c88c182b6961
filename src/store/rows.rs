//! Row-to-record mapping shared by the SQLite and PostgreSQL backends: both
//! schemas store JSON documents as TEXT and use the same column names, so
//! only the SQL dialect differs between `sqlite/` and `postgres/`.

use serde_json::Value;
use sqlx::{ColumnIndex, Decode, Row, Type};

use super::StoreResult;
use crate::domain::{ImageMeta, PoseRecord, SessionRecord};

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
        created_at: row.get("created_at"),
    })
}
