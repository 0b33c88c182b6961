//! The client subcommands (`upload`, `calibrate`, `report`; `forward` and
//! `compensate` in [`evaluate`]): a cell engineer's view of the service,
//! over [`crate::cli::client`].

pub mod campaign;
pub mod client;
mod client_error;
pub mod command;
pub mod evaluate;
pub mod evaluate_docs;
pub mod filter;
mod job_summary;
mod jobs;
pub use jobs::{jobs, JobFilters};
pub mod plan;
pub mod release;
mod sim_board;

use std::io::{IsTerminal, Write};
use std::path::Path;
use std::time::Duration;

use serde::{Deserialize, Serialize};

use client::{answer_of, Client, ClientError};

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

/// `campaign.json` of a campaign zipped as the dataset upload takes it
/// (`poses.json` and the images, with `campaign.json` beside them; the
/// service ignores entries its manifest does not name).
fn campaign_in_zip(path: &Path) -> Result<campaign::CampaignFile, String> {
    let name = campaign::CAMPAIGN_FILE;
    let file = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut zip = zip::ZipArchive::new(file)
        .map_err(|e| format!("{}: not a zip archive: {e}", path.display()))?;
    let entry = zip
        .by_name(name)
        .map_err(|e| format!("{}: {name}: {e}", path.display()))?;
    serde_json::from_reader(entry).map_err(|e| format!("{}: {name}: {e}", path.display()))
}

/// Creates the robot (from `campaign.json`) when it does not exist (or
/// replaces it under [`RobotPolicy::Replace`]) and a session, then uploads
/// the campaign as one archive. `campaign` is a campaign directory, or a
/// zip of one (sent as is). Its poses carry joints or, for a hand–eye
/// campaign, the controller's flange poses. Returns the session id.
pub async fn upload(
    client: &Client,
    serial: &str,
    campaign: &Path,
    robot: RobotPolicy,
) -> Result<String, ClientError> {
    let zipped = campaign.is_file();
    let file = if zipped {
        campaign_in_zip(campaign)
    } else {
        campaign::read(campaign).map(|(file, _)| file)
    }
    .map_err(ClientError::Local)?;
    let exists = client.robot_exists(serial).await?;
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
    let sent = async {
        let id = client.create_session(serial, &file.session).await?;
        let answer = if zipped {
            client.upload_dataset(&id, campaign).await?
        } else {
            let archive = zip_campaign(campaign).map_err(ClientError::Local)?;
            client.upload_dataset(&id, archive.path()).await?
        };
        Ok::<_, ClientError>((id, answer))
    }
    .await;
    let (id, answer) = match sent {
        Ok(sent) => sent,
        // A robot this upload created goes again with its empty session:
        // a failed upload leaves nothing behind.
        Err(e) if !exists => {
            let path = format!("/v1/robots/{serial}");
            if client
                .call(reqwest::Method::DELETE, &path, None)
                .await
                .is_ok()
            {
                eprintln!("robot {serial} removed again: the upload failed");
            }
            return Err(e);
        }
        Err(e) => return Err(e),
    };
    let found = answer.detected_points.iter().filter(|n| **n > 0).count();
    eprintln!(
        "uploaded {} poses to session {id} ({found} images with the target found)",
        answer.poses_created
    );
    for warning in &answer.warnings {
        eprintln!("warning: {warning}");
    }
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
    let found: SessionOwner = client.get_session(session).await?;
    match found.serial.as_deref() {
        Some(owner) if owner == serial => Ok(()),
        Some(owner) => Err(ClientError::Local(format!(
            "session {session} belongs to robot {owner}, not {serial}"
        ))),
        None => Err(ClientError::Local(format!(
            "the server's session {session} names no robot"
        ))),
    }
}

/// The robot a session belongs to.
#[derive(Debug, Deserialize)]
struct SessionOwner {
    serial: Option<String>,
}

/// Where a job is, as `calibrate --wait` follows it.
#[derive(Debug, Deserialize)]
struct JobProgress {
    state: Option<String>,
    #[serde(default)]
    progress: f64,
    stage: Option<String>,
    error: Option<String>,
}

/// What `calibrate` did: queued a job, or (with `--wait`) saw it succeed.
#[derive(Debug, Clone, PartialEq)]
pub enum Calibration {
    Started {
        job_id: String,
    },
    /// The finished job's document as the server wrote it.
    Succeeded {
        job_id: String,
        job: String,
    },
}

/// What `calibrate` prints without `--wait`.
#[derive(Serialize)]
struct Started<'a> {
    job_id: &'a str,
}

impl Calibration {
    pub fn job_id(&self) -> &str {
        match self {
            Calibration::Started { job_id } | Calibration::Succeeded { job_id, .. } => job_id,
        }
    }

    /// The JSON `calibrate --json` prints: `{"job_id": …}`, or the
    /// finished job's whole document as the server wrote it.
    pub fn json(&self) -> String {
        match self {
            Calibration::Started { job_id } => {
                serde_json::to_string(&Started { job_id }).unwrap_or_default()
            }
            Calibration::Succeeded { job, .. } => job.clone(),
        }
    }
}

/// `{"job_id": …}`, or the finished job's document.
impl std::fmt::Display for Calibration {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Calibration::Started { job_id } => {
                let text =
                    serde_json::to_string(&Started { job_id }).map_err(|_| std::fmt::Error)?;
                f.write_str(&text)
            }
            Calibration::Succeeded { job_id, job } => {
                f.write_str(&job_summary::summary_of(job_id, job))
            }
        }
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
) -> Result<Calibration, ClientError> {
    check_session_serial(client, serial, session).await?;
    let job_id = client.start_calibration(session, &NoOptions {}).await?;
    if !wait {
        return Ok(Calibration::Started { job_id });
    }
    let mut progress = Progress::new(std::io::stderr().is_terminal());
    loop {
        let text = client.job(&job_id).await?;
        let state: JobProgress = answer_of(&text)?;
        let status = state.state.as_deref().unwrap_or("?");
        if let Some(line) = progress.line(state.progress, state.stage.as_deref().unwrap_or("")) {
            eprint!("{line}");
        }
        match status {
            "succeeded" => {
                progress.finish();
                return Ok(Calibration::Succeeded { job_id, job: text });
            }
            "failed" | "cancelled" => {
                progress.finish();
                let error = state.error.as_deref().unwrap_or(status);
                return Err(ClientError::Local(format!(
                    "job {job_id} {status}: {error}"
                )));
            }
            _ => tokio::time::sleep(POLL_INTERVAL).await,
        }
    }
}

/// The request body of a calibration with the server's default options.
#[derive(Serialize)]
struct NoOptions {}

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
