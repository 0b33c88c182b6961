//! What every controller export says about itself in its header comment
//! (issue 34): which set, which version, whether it was approved, and the
//! controller it was measured on, so a file found on a controller names
//! its origin.

use serde::Serialize;

use crate::domain::{ControllerIdentity, ReleaseStatus};

/// The set an export was written from.
#[derive(Debug, Clone, Serialize)]
pub struct ExportHeader {
    pub serial: String,
    pub version: i64,
    /// `approved`, `candidate` or `rejected` when the export was written.
    pub status: ReleaseStatus,
    /// The controller identity the set inherited from its session; `None`
    /// when none was recorded.
    pub controller: Option<ControllerIdentity>,
}

impl ExportHeader {
    /// The header's lines, without comment marks.
    pub fn lines(&self, format: &str) -> Vec<String> {
        let status = match self.status {
            ReleaseStatus::Approved => "approved".to_string(),
            other => format!("{} (NOT approved)", other.as_str()),
        };
        let controller = self
            .controller
            .as_ref()
            .map(ControllerIdentity::describe)
            .unwrap_or_else(|| "none recorded".into());
        vec![
            format!("robocal {format} export of robot {}", self.serial),
            format!("parameter set: {}/{}", self.serial, self.version),
            format!("version: {}", self.version),
            format!("status: {status}"),
            format!("controller: {controller}"),
        ]
    }

    /// The header as comment lines opened by `mark` (`#`, `;`, `!`).
    pub fn comment(&self, format: &str, mark: &str) -> String {
        self.lines(format)
            .iter()
            .map(|l| format!("{mark} {}\n", one_line(l)))
            .collect()
    }
}

/// A value on one comment line: line breaks in user text would end the
/// comment and start a statement on the controller.
pub fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}
