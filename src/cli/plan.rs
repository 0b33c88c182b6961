//! `robocal plan`: ask the service for a campaign plan (issue 16) and write
//! it as the program the cell runs (or the CSV/JSON a cell script reads);
//! the prediction and the path go to standard error.

use std::path::PathBuf;

use serde::de::IgnoredAny;
use serde::Deserialize;

use super::client::Client;
use super::write_output;
use crate::export::campaign_program::ProgramFormat;

#[derive(Debug, Clone, clap::Args)]
pub struct PlanArgs {
    /// Robot serial number.
    #[arg(long)]
    pub serial: String,
    /// The request document (`-` reads stdin): `{"target", "camera",
    /// "flange_to_camera_guess", "target_to_base_guess", "poses", ...}` as
    /// `POST /v1/robots/{serial}/campaign-plans` takes it.
    #[arg(long)]
    pub request: PathBuf,
    /// What to write: `json`, `csv`, `urscript`, `rapid` or `krl`.
    #[arg(long, default_value = "json", value_parser = ProgramFormat::NAMES)]
    pub format: String,
    /// Output file (standard output when absent).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The request as the user wrote it (the server checks it), once it is
/// known to be JSON.
fn read_request(path: &PathBuf) -> Result<String, String> {
    let text = if path.as_os_str() == "-" {
        std::io::read_to_string(std::io::stdin()).map_err(|e| format!("stdin: {e}"))?
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?
    };
    serde_json::from_str::<IgnoredAny>(&text)
        .map_err(|e| format!("{}: not JSON: {e}", path.display()))?;
    Ok(text)
}

/// The fields of the plan document the terminal line shows.
#[derive(Debug, Default, Deserialize)]
pub struct PlanSummary {
    pub id: Option<String>,
    pub serial: Option<String>,
    #[serde(default)]
    pub poses: Vec<IgnoredAny>,
    pub purpose: Option<String>,
    #[serde(default)]
    pub predicted: Predicted,
    pub path_length_deg: Option<f64>,
    pub model: Option<String>,
}

/// What the plan predicts.
#[derive(Debug, Default, Deserialize)]
pub struct Predicted {
    pub validation_error_mean_mm: Option<f64>,
    pub condition_number: Option<f64>,
    /// An extension's session alone (`extend_session`).
    pub existing: Option<Existing>,
}

/// What the extended session is predicted to achieve alone.
#[derive(Debug, Default, Deserialize)]
pub struct Existing {
    pub poses: Option<usize>,
    pub validation_error_mean_mm: Option<f64>,
    pub gain_mm: Option<f64>,
}

/// One line about the plan for the terminal.
pub fn summary(plan: &PlanSummary) -> String {
    let text = |v: &Option<String>| v.clone().unwrap_or_else(|| "?".into());
    let p = &plan.predicted;
    let extension = p.existing.as_ref().map_or(String::new(), |e| {
        format!(
            "; the session's {} poses alone {:.4} mm, gain {:.4} mm",
            e.poses.unwrap_or(0),
            e.validation_error_mean_mm.unwrap_or(f64::NAN),
            e.gain_mm.unwrap_or(f64::NAN)
        )
    });
    format!(
        "plan {} for {}: {} poses ({}), predicted validation error {:.4} mm, condition number {:.1}, path {:.0} deg, model {}{extension}",
        text(&plan.id),
        text(&plan.serial),
        plan.poses.len(),
        text(&plan.purpose),
        p.validation_error_mean_mm.unwrap_or(f64::NAN),
        p.condition_number.unwrap_or(f64::NAN),
        plan.path_length_deg.unwrap_or(f64::NAN),
        text(&plan.model),
    )
}

/// Plan, then fetch the plan in `args.format` and write it.
pub async fn plan(client: &Client, args: &PlanArgs) -> Result<(), String> {
    let body = read_request(&args.request)?;
    let plan: PlanSummary = client
        .create_campaign_plan(&args.serial, body)
        .await
        .map_err(|e| e.to_string())?;
    eprintln!("{}", summary(&plan));
    let id = plan
        .id
        .as_deref()
        .ok_or("the server's answer has no `id`")?;
    let bytes = client
        .campaign_plan(&args.serial, id, &args.format)
        .await
        .map_err(|e| e.to_string())?;
    write_output(args.out.as_deref(), &bytes)
}
