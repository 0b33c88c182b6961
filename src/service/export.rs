//! A parameter set exported for the controller or the off-line programming
//! tool (issue "Deploy the result", issue 34): URDF, `dh-json`, CSV, and
//! the controllers' own forms (`ur-kinematics`, `dh-table`, `krl-frames`,
//! `rapid-frames`), each naming the set, its status and its controller.

use super::error::{ServiceError, ServiceResult};
use super::results::{find_parameter_set, refuse_hand_eye, typed};
use crate::domain::{check_controller, ControllerIdentity, ParameterSet};
use crate::export::controller_table::{controller_table, write_ini};
use crate::export::header::ExportHeader;
use crate::export::table::{dh_table, write_csv};
use crate::export::ur_kinematics::{ur_kinematics, write_ur_yaml};
use crate::export::urdf::write_urdf;
use crate::export::vendor_frames::{write_krl, write_rapid};
use crate::export::ExportFormat;
use crate::report::IdentifiabilityReport;
use crate::store::{DynStore, ParameterSetRecord};

/// An export's bytes and how to serve them.
pub struct Exported {
    pub content_type: &'static str,
    /// A file name for `Content-Disposition`.
    pub file_name: String,
    pub body: Vec<u8>,
}

/// What the caller asked for.
pub struct ExportRequest<'a> {
    /// `?format=` (`None`: not given, a 422 naming it).
    pub format: Option<&'a str>,
    /// `Accept: application/json` (`dh-table` then answers JSON).
    pub json: bool,
    /// The controller the caller expects the set to be for (409 otherwise).
    pub expect_controller: Option<ControllerIdentity>,
}

/// Parameter set `version` of `serial` in the requested format.
pub async fn export(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: ExportRequest<'_>,
) -> ServiceResult<Exported> {
    let accepted = || format!("must be one of {}", ExportFormat::NAMES.join(", "));
    let name = request
        .format
        .ok_or_else(|| ServiceError::invalid("format", format!("required: {}", accepted())))?;
    let format =
        ExportFormat::parse(name).ok_or_else(|| ServiceError::invalid("format", accepted()))?;
    let record = find_parameter_set(store, serial, version).await?;
    refuse_hand_eye(&record)?;
    let set = typed(&record)?;
    check_controller(request.expect_controller.as_ref(), set.controller.as_ref())
        .map_err(ServiceError::controller("the parameter set"))?;
    let stem = format!("{serial}-v{}", record.version);
    let header = ExportHeader {
        serial: serial.to_string(),
        version: record.version,
        status: record.status,
        controller: set.controller.clone(),
    };
    let (body, extension, content_type) = match format {
        ExportFormat::Urdf => {
            let model = set.model().map_err(ServiceError::internal)?;
            let urdf = write_urdf(serial, &model, set.frame_names(), set.terms.as_ref());
            (urdf.into_bytes(), "urdf", format.content_type())
        }
        ExportFormat::DhJson | ExportFormat::Csv => {
            table_export(store, serial, &record, &set, format).await?
        }
        ExportFormat::UrKinematics => {
            let model = set.model().map_err(ServiceError::internal)?;
            let terms: Vec<String> = set
                .terms
                .iter()
                .flat_map(|t| t.terms.iter().map(|k| k.name.clone()))
                .collect();
            let k = ur_kinematics(&model.robot, &terms)
                .map_err(|e| ServiceError::invalid("format", e.to_string()))?;
            let yaml = write_ur_yaml(&header, &k);
            (yaml.into_bytes(), "yaml", format.content_type())
        }
        ExportFormat::DhTable => {
            let table = controller_table(header, &set.kinematics);
            if request.json {
                let body = serde_json::to_vec_pretty(&table).map_err(ServiceError::internal)?;
                (body, "json", "application/json")
            } else {
                (write_ini(&table).into_bytes(), "ini", format.content_type())
            }
        }
        ExportFormat::KrlFrames | ExportFormat::RapidFrames => {
            let model = set.model().map_err(ServiceError::internal)?;
            let (base, tool) = (&model.world_to_base, &model.flange_to_tool);
            if format == ExportFormat::KrlFrames {
                let text = write_krl(&header, set.frame_names(), base, tool);
                (text.into_bytes(), "dat", format.content_type())
            } else {
                let text = write_rapid(&header, set.frame_names(), base, tool);
                (text.into_bytes(), "mod", format.content_type())
            }
        }
    };
    let file_name = match format {
        ExportFormat::Urdf | ExportFormat::DhJson | ExportFormat::Csv => {
            format!("{stem}.{extension}")
        }
        _ => format!("{stem}-{}.{extension}", format.name()),
    };
    Ok(Exported {
        content_type,
        file_name,
        body,
    })
}

/// `dh-json` or `csv`: the identified table with σ and the report's
/// reasons for held parameters.
async fn table_export(
    store: &DynStore,
    serial: &str,
    record: &ParameterSetRecord,
    set: &ParameterSet,
    format: ExportFormat,
) -> ServiceResult<(Vec<u8>, &'static str, &'static str)> {
    let report = store.get_report(serial, record.version).await?;
    let identifiability: Option<IdentifiabilityReport> = report
        .as_ref()
        .and_then(|r| r.get("identifiability"))
        .map(|v| serde_json::from_value(v.clone()))
        .transpose()
        .map_err(|e| {
            ServiceError::internal(format!(
                "identifiability of stored report {serial}/{}: {e}",
                record.version
            ))
        })?;
    let table = dh_table(serial, record.version, set, identifiability.as_ref());
    Ok(match format {
        ExportFormat::Csv => (write_csv(&table).into_bytes(), "csv", format.content_type()),
        _ => (
            serde_json::to_vec_pretty(&table).map_err(ServiceError::internal)?,
            "json",
            format.content_type(),
        ),
    })
}
