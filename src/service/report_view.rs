//! A parameter set's accuracy report as every rendering shows it: the
//! stored report (written by the pipeline, which cannot know the set's
//! version number, date or later decisions) with the set's identity and
//! its *current* release status filled in. The JSON, SVG and HTML forms
//! under `/v1/…/report*` and the fleet page's `/robots/{serial}/reports/{v}`
//! all read it here, so a report never contradicts the set's status.

use serde_json::{Map, Value};

use super::error::{ServiceError, ServiceResult};
use super::results;
use crate::report::Report;
use crate::store::{DynStore, ParameterSetRecord};

/// The report of set `version` (`latest` allowed) of robot `serial` as
/// JSON, with identity and release status; 404 when there is none.
pub async fn report_json(store: &DynStore, serial: &str, version: &str) -> ServiceResult<Value> {
    let set = results::find_parameter_set(store, serial, version).await?;
    let mut report = store
        .get_report(&set.serial, set.version)
        .await?
        .ok_or_else(|| ServiceError::not_found("report", &format!("{serial}/{version}")))?;
    if let Some(obj) = report.as_object_mut() {
        fill_identity(obj, &set);
    }
    Ok(report)
}

/// The same report typed for drawing (409 when the set holds no report
/// a renderer can draw).
pub async fn typed_report(store: &DynStore, serial: &str, version: &str) -> ServiceResult<Report> {
    serde_json::from_value(report_json(store, serial, version).await?).map_err(|_| {
        ServiceError::Conflict("this parameter set has no accuracy report to draw".into())
    })
}

fn fill_identity(obj: &mut Map<String, Value>, set: &ParameterSetRecord) {
    let opt = |v: &Option<String>| v.clone().map(Value::from).unwrap_or(Value::Null);
    obj.insert("serial".into(), Value::from(set.serial.clone()));
    obj.insert("version".into(), Value::from(set.version));
    obj.insert(
        "job_id".into(),
        Value::from(set.job_id.clone().unwrap_or_default()),
    );
    obj.insert("created_at".into(), Value::from(set.created_at.clone()));
    obj.insert("status".into(), Value::from(set.status.as_str()));
    obj.insert("status_reason".into(), opt(&set.status_reason));
    obj.insert("status_by".into(), opt(&set.status_by));
    obj.insert("status_at".into(), opt(&set.status_at));
}
