//! The client subcommands (`upload`, `calibrate`, `report`): a cell
//! engineer's view of the service, over [`crate::client`].

use std::io::Write;
use std::path::Path;
use std::time::Duration;

use serde_json::{json, Value};

use crate::campaign;
use crate::client::{Client, ClientError};

/// How often `calibrate --wait` asks for the job's progress.
const POLL_INTERVAL: Duration = Duration::from_millis(250);
/// Width of the terminal progress bar, characters.
const BAR_WIDTH: usize = 30;

/// Zips `poses.json` and the images it names into a temporary file
/// (stored, not deflated: PNG and JPEG are compressed already).
fn zip_campaign(dir: &Path) -> Result<tempfile::NamedTempFile, String> {
    let (_, entries) = campaign::read(dir)?;
    let file = tempfile::NamedTempFile::new().map_err(|e| e.to_string())?;
    let mut zip = zip::ZipWriter::new(file.reopen().map_err(|e| e.to_string())?);
    let stored: zip::write::SimpleFileOptions =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    let mut add = |name: &str| -> Result<(), String> {
        let bytes = std::fs::read(dir.join(name)).map_err(|e| format!("{name}: {e}"))?;
        zip.start_file(name, stored).map_err(|e| e.to_string())?;
        zip.write_all(&bytes).map_err(|e| e.to_string())
    };
    add("poses.json")?;
    for entry in &entries {
        add(&entry.image)?;
    }
    zip.finish().map_err(|e| e.to_string())?;
    Ok(file)
}

/// Creates the robot (from `campaign.json`) and a session, then uploads the
/// campaign as one archive. Returns the session id.
pub async fn upload(client: &Client, serial: &str, dir: &Path) -> Result<String, ClientError> {
    let (file, _) = campaign::read(dir).map_err(ClientError::Local)?;
    client.put_robot(serial, &file.robot).await?;
    let session =
        serde_json::to_value(&file.session).map_err(|e| ClientError::Local(e.to_string()))?;
    let id = client.create_session(serial, &session).await?;
    let archive = zip_campaign(dir).map_err(ClientError::Local)?;
    let answer = client.upload_dataset(&id, archive.path()).await?;
    eprintln!(
        "uploaded {} poses to session {id}",
        answer
            .get("poses_created")
            .and_then(Value::as_u64)
            .unwrap_or(0)
    );
    Ok(id)
}

fn bar(fraction: f64) -> String {
    let filled = ((fraction.clamp(0.0, 1.0)) * BAR_WIDTH as f64).round() as usize;
    format!("[{}{}]", "#".repeat(filled), ".".repeat(BAR_WIDTH - filled))
}

/// Starts a calibration; with `wait`, shows its progress until it ends.
pub async fn calibrate(client: &Client, session: &str, wait: bool) -> Result<Value, ClientError> {
    let job = client.start_calibration(session, &json!({})).await?;
    if !wait {
        return Ok(json!({ "job_id": job }));
    }
    loop {
        let state = client.job(&job).await?;
        let status = state
            .get("state")
            .and_then(Value::as_str)
            .unwrap_or("?")
            .to_string();
        let progress = state.get("progress").and_then(Value::as_f64).unwrap_or(0.0);
        let stage = state.get("stage").and_then(Value::as_str).unwrap_or("");
        eprint!("\r{} {:>3.0}% {stage:<20}", bar(progress), progress * 100.0);
        match status.as_str() {
            "succeeded" => {
                eprintln!();
                return Ok(state);
            }
            "failed" | "cancelled" => {
                eprintln!();
                let error = state
                    .get("error")
                    .and_then(Value::as_str)
                    .unwrap_or(&status);
                return Err(ClientError::Local(format!("job {job} {status}: {error}")));
            }
            _ => tokio::time::sleep(POLL_INTERVAL).await,
        }
    }
}

/// `robocal jobs`: the newest `limit` jobs as a table, newest first.
pub async fn jobs(client: &Client, limit: u32) -> Result<String, ClientError> {
    let page = client.jobs(limit, None).await?;
    let items = page
        .get("items")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    Ok(jobs_table(&items))
}

/// One line per job: id, state, progress, serial, session, creation time.
fn jobs_table(items: &[Value]) -> String {
    let text = |v: &Value, key: &str| {
        v.get(key)
            .and_then(Value::as_str)
            .unwrap_or("-")
            .to_string()
    };
    let mut out = format!(
        "{:<36}  {:<9}  {:>4}  {:<16}  {:<36}  {}\n",
        "JOB", "STATE", "DONE", "SERIAL", "SESSION", "CREATED"
    );
    for job in items {
        let progress = job.get("progress").and_then(Value::as_f64).unwrap_or(0.0);
        out.push_str(&format!(
            "{:<36}  {:<9}  {:>3.0}%  {:<16}  {:<36}  {}\n",
            text(job, "id"),
            text(job, "state"),
            progress * 100.0,
            text(job, "serial"),
            text(job, "session_id"),
            text(job, "created_at"),
        ));
    }
    out
}
