//! The client subcommands (`upload`, `calibrate`, `report`; `forward` and
//! `compensate` in [`evaluate`]): a cell engineer's view of the service,
//! over [`crate::cli::client`].

pub mod campaign;
pub mod client;
pub mod evaluate;
pub mod filter;
pub mod plan;

use std::io::{IsTerminal, Write};
use std::path::Path;
use std::time::Duration;

use serde_json::{json, Value};

use client::{Client, ClientError};

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

/// What `upload` does with the robot of `campaign.json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RobotPolicy {
    /// Create it when the serial is unknown; an existing robot keeps its
    /// kinematics (a campaign must never silently overwrite a robot's
    /// joint table).
    CreateIfMissing,
    /// Replace an existing robot's kinematics with the campaign's.
    Replace,
}

/// Creates the robot (from `campaign.json`) when it does not exist (or
/// replaces it under [`RobotPolicy::Replace`]) and a session, then uploads
/// the campaign as one archive. Returns the session id.
pub async fn upload(
    client: &Client,
    serial: &str,
    dir: &Path,
    robot: RobotPolicy,
) -> Result<String, ClientError> {
    let (file, _) = campaign::read(dir).map_err(ClientError::Local)?;
    let exists = client.get_robot(serial).await?.is_some();
    match (exists, robot) {
        (true, RobotPolicy::CreateIfMissing) => eprintln!(
            "robot {serial} exists: its kinematics are kept (--replace-robot replaces them with the campaign's)"
        ),
        (true, RobotPolicy::Replace) => {
            client.put_robot(serial, &file.robot).await?;
            eprintln!("robot {serial}: kinematics replaced with the campaign's");
        }
        (false, _) => {
            client.put_robot(serial, &file.robot).await?;
            eprintln!("robot {serial} created");
        }
    }
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

/// Refuses a session of another robot: `--serial` names the robot the
/// user means to calibrate, and a pasted session id of another cell must
/// not silently produce a parameter set for that other robot.
async fn check_session_serial(
    client: &Client,
    serial: &str,
    session: &str,
) -> Result<(), ClientError> {
    let found = client.get_session(session).await?;
    match found.get("serial").and_then(Value::as_str) {
        Some(owner) if owner == serial => Ok(()),
        Some(owner) => Err(ClientError::Local(format!(
            "session {session} belongs to robot {owner}, not {serial}"
        ))),
        None => Err(ClientError::Local(format!(
            "the server's session {session} names no robot"
        ))),
    }
}

/// How `calibrate --wait` shows progress: a bar redrawn in place on a
/// terminal; one plain line per change otherwise (logs, CI), never `\r`.
struct Progress {
    terminal: bool,
    last: Option<(String, u32)>,
}

impl Progress {
    fn new(terminal: bool) -> Self {
        Self {
            terminal,
            last: None,
        }
    }

    /// The text to write to stderr for this state, if any.
    fn line(&mut self, fraction: f64, stage: &str) -> Option<String> {
        let percent = (fraction.clamp(0.0, 1.0) * 100.0).round() as u32;
        if self.terminal {
            return Some(format!("\r{} {percent:>3}% {stage:<20}", bar(fraction)));
        }
        let key = (stage.to_string(), percent);
        if self.last.as_ref() == Some(&key) {
            return None;
        }
        self.last = Some(key);
        Some(format!("{percent:>3}% {stage}\n"))
    }

    /// Ends the bar's line (a terminal's bar has no newline yet).
    fn finish(&self) {
        if self.terminal {
            eprintln!();
        }
    }
}

/// Starts a calibration of `serial`'s session; with `wait`, shows its
/// progress until it ends.
pub async fn calibrate(
    client: &Client,
    serial: &str,
    session: &str,
    wait: bool,
) -> Result<Value, ClientError> {
    check_session_serial(client, serial, session).await?;
    let job = client.start_calibration(session, &json!({})).await?;
    if !wait {
        return Ok(json!({ "job_id": job }));
    }
    let mut progress = Progress::new(std::io::stderr().is_terminal());
    loop {
        let state = client.job(&job).await?;
        let status = state
            .get("state")
            .and_then(Value::as_str)
            .unwrap_or("?")
            .to_string();
        let fraction = state.get("progress").and_then(Value::as_f64).unwrap_or(0.0);
        let stage = state.get("stage").and_then(Value::as_str).unwrap_or("");
        if let Some(text) = progress.line(fraction, stage) {
            eprint!("{text}");
        }
        match status.as_str() {
            "succeeded" => {
                progress.finish();
                return Ok(state);
            }
            "failed" | "cancelled" => {
                progress.finish();
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

/// Writes a command's bytes to `out`, or to standard output.
pub fn write_output(out: Option<&std::path::Path>, bytes: &[u8]) -> Result<(), String> {
    match out {
        Some(path) => std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display())),
        None => {
            use std::io::Write;
            std::io::stdout()
                .write_all(bytes)
                .map_err(|e| e.to_string())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_off_a_terminal_is_plain_lines_without_carriage_returns() {
        let mut p = Progress::new(false);
        let mut out = String::new();
        for (f, stage) in [
            (0.0, "detect"),
            (0.0, "detect"),
            (0.5, "camera"),
            (1.0, "report"),
        ] {
            out.extend(p.line(f, stage));
        }
        assert!(!out.contains('\r'), "{out:?}");
        assert_eq!(out, "  0% detect\n 50% camera\n100% report\n");
    }

    #[test]
    fn progress_on_a_terminal_redraws_the_bar_in_place() {
        let mut p = Progress::new(true);
        let line = p.line(0.5, "camera").unwrap();
        assert!(
            line.starts_with('\r') && line.contains(" 50% camera"),
            "{line:?}"
        );
    }
}
