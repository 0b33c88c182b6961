//! A parameter set in the forms controllers and off-line programming tools
//! read (issue "Deploy the result"): URDF, the identified table as JSON
//! and CSV. Pure writers over the typed parameter set and its report.

pub mod campaign_program;
pub mod table;
pub mod urdf;

use serde::Deserialize;

/// `?format=` of `GET …/parameter-sets/{version}/export`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
pub enum ExportFormat {
    #[serde(rename = "urdf")]
    Urdf,
    #[serde(rename = "dh-json")]
    DhJson,
    #[serde(rename = "csv")]
    Csv,
}

impl ExportFormat {
    /// The accepted names, for the 422 that refuses another.
    pub const NAMES: [&'static str; 3] = ["urdf", "dh-json", "csv"];

    pub fn parse(name: &str) -> Option<ExportFormat> {
        match name {
            "urdf" => Some(ExportFormat::Urdf),
            "dh-json" => Some(ExportFormat::DhJson),
            "csv" => Some(ExportFormat::Csv),
            _ => None,
        }
    }

    pub fn content_type(self) -> &'static str {
        match self {
            ExportFormat::Urdf => "application/xml",
            ExportFormat::DhJson => "application/json",
            ExportFormat::Csv => "text/csv",
        }
    }
}
