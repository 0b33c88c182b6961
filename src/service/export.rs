//! A parameter set exported for the controller or the off-line programming
//! tool (issue "Deploy the result"): URDF, `dh-json`, CSV.

use super::error::{ServiceError, ServiceResult};
use super::results::{find_parameter_set, refuse_hand_eye, typed};
use crate::export::table::{dh_table, write_csv};
use crate::export::urdf::write_urdf;
use crate::export::ExportFormat;
use crate::report::IdentifiabilityReport;
use crate::store::DynStore;

/// An export's bytes and how to serve them.
pub struct Exported {
    pub content_type: &'static str,
    /// A file name for `Content-Disposition`.
    pub file_name: String,
    pub body: Vec<u8>,
}

/// Parameter set `version` of `serial` in `format` (`urdf`, `dh-json`, `csv`).
pub async fn export(
    store: &DynStore,
    serial: &str,
    version: &str,
    format: &str,
) -> ServiceResult<Exported> {
    let format = ExportFormat::parse(format).ok_or_else(|| {
        ServiceError::invalid(
            "format",
            format!("must be one of {}", ExportFormat::NAMES.join(", ")),
        )
    })?;
    let record = find_parameter_set(store, serial, version).await?;
    refuse_hand_eye(&record)?;
    let set = typed(&record)?;
    let stem = format!("{serial}-v{}", record.version);
    let (body, extension) = match format {
        ExportFormat::Urdf => {
            let model = set.model().map_err(ServiceError::internal)?;
            (
                write_urdf(serial, &model, set.frame_names(), set.terms.as_ref()).into_bytes(),
                "urdf",
            )
        }
        ExportFormat::DhJson | ExportFormat::Csv => {
            let report = store.get_report(serial, record.version).await?;
            let identifiability: Option<IdentifiabilityReport> = report
                .as_ref()
                .and_then(|r| r.get("identifiability"))
                .and_then(|v| serde_json::from_value(v.clone()).ok());
            let table = dh_table(serial, record.version, &set, identifiability.as_ref());
            match format {
                ExportFormat::Csv => (write_csv(&table).into_bytes(), "csv"),
                _ => (
                    serde_json::to_vec_pretty(&table).map_err(ServiceError::internal)?,
                    "json",
                ),
            }
        }
    };
    Ok(Exported {
        content_type: format.content_type(),
        file_name: format!("{stem}.{extension}"),
        body,
    })
}
