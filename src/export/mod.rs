//! A parameter set in the forms controllers and off-line programming tools
//! read (issue "Deploy the result", issue 34): URDF, the identified table
//! as JSON and CSV, and the controllers' own forms: a Universal Robots
//! `kinematics.yaml`, the corrected DH table with β, KUKA KRL and ABB
//! RAPID frames. Pure writers over the typed parameter set and its report.

pub mod campaign_program;
pub mod controller_table;
pub mod header;
pub mod table;
pub mod ur_kinematics;
pub mod urdf;
pub mod vendor_frames;

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
    #[serde(rename = "ur-kinematics")]
    UrKinematics,
    #[serde(rename = "dh-table")]
    DhTable,
    #[serde(rename = "krl-frames")]
    KrlFrames,
    #[serde(rename = "rapid-frames")]
    RapidFrames,
}

impl ExportFormat {
    pub const ALL: [ExportFormat; 7] = [
        ExportFormat::Urdf,
        ExportFormat::DhJson,
        ExportFormat::Csv,
        ExportFormat::UrKinematics,
        ExportFormat::DhTable,
        ExportFormat::KrlFrames,
        ExportFormat::RapidFrames,
    ];
    /// The accepted names, for the 422 that refuses another.
    pub const NAMES: [&'static str; 7] = [
        "urdf",
        "dh-json",
        "csv",
        "ur-kinematics",
        "dh-table",
        "krl-frames",
        "rapid-frames",
    ];

    pub fn name(self) -> &'static str {
        let i = Self::ALL.iter().position(|f| *f == self).unwrap_or(0);
        Self::NAMES[i]
    }

    pub fn parse(name: &str) -> Option<ExportFormat> {
        Self::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Self::ALL[i])
    }

    /// The media type served (`dh-table` as text; JSON when asked, see
    /// `service::export`).
    pub fn content_type(self) -> &'static str {
        match self {
            ExportFormat::Urdf => "application/xml",
            ExportFormat::DhJson => "application/json",
            ExportFormat::Csv => "text/csv",
            ExportFormat::UrKinematics => "application/yaml",
            ExportFormat::DhTable | ExportFormat::KrlFrames | ExportFormat::RapidFrames => {
                "text/plain; charset=utf-8"
            }
        }
    }
}
