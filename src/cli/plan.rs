//! `robocal plan`: ask the service for a campaign plan (issue 16) and write
//! it as the program the cell runs (or the CSV/JSON a cell script reads);
//! the prediction and the path go to standard error.

use std::path::PathBuf;

use serde_json::Value;

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

fn read_request(path: &PathBuf) -> Result<Value, String> {
    let text = if path.as_os_str() == "-" {
        std::io::read_to_string(std::io::stdin()).map_err(|e| format!("stdin: {e}"))?
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?
    };
    serde_json::from_str(&text).map_err(|e| format!("{}: not JSON: {e}", path.display()))
}

/// One line about the plan for the terminal.
pub fn summary(plan: &Value) -> String {
    let poses = plan["poses"].as_array().map_or(0, Vec::len);
    let p = &plan["predicted"];
    format!(
        "plan {} for {}: {poses} poses ({}), predicted validation error {:.4} mm, condition number {:.1}, path {:.0} deg, model {}",
        plan["id"].as_str().unwrap_or("?"),
        plan["serial"].as_str().unwrap_or("?"),
        plan["purpose"].as_str().unwrap_or("?"),
        p["validation_error_mean_mm"].as_f64().unwrap_or(f64::NAN),
        p["condition_number"].as_f64().unwrap_or(f64::NAN),
        plan["path_length_deg"].as_f64().unwrap_or(f64::NAN),
        plan["model"].as_str().unwrap_or("?"),
    )
}

/// Plan, then fetch the plan in `args.format` and write it.
pub async fn plan(client: &Client, args: &PlanArgs) -> Result<(), String> {
    let body = read_request(&args.request)?;
    let plan = client
        .create_campaign_plan(&args.serial, &body)
        .await
        .map_err(|e| e.to_string())?;
    eprintln!("{}", summary(&plan));
    let id = plan["id"]
        .as_str()
        .ok_or("the server's answer has no `id`")?;
    let bytes = client
        .campaign_plan(&args.serial, id, &args.format)
        .await
        .map_err(|e| e.to_string())?;
    write_output(args.out.as_deref(), &bytes)
}
