//! `robocal jobs`: the newest jobs as a table (whole ids, kind, state,
//! robot, session, why a job failed), filtered as `GET /v1/jobs` filters.

use serde::Deserialize;

use super::client::{Client, ClientError};

/// The fields of `GET /v1/jobs` that `robocal jobs` shows.
#[derive(Debug, Default, Deserialize)]
struct JobPage {
    #[serde(default)]
    items: Vec<JobLine>,
}

#[derive(Debug, Default, Deserialize)]
struct JobLine {
    id: Option<String>,
    kind: Option<String>,
    state: Option<String>,
    #[serde(default)]
    progress: f64,
    serial: Option<String>,
    session_id: Option<String>,
    created_at: Option<String>,
    error: Option<String>,
}

/// `robocal jobs`' filters, as `GET /v1/jobs` takes them.
#[derive(Debug, Default, Clone, clap::Args)]
pub struct JobFilters {
    /// Only this robot's jobs.
    #[arg(long)]
    pub serial: Option<String>,
    /// Only jobs in this state.
    #[arg(long, value_parser = ["queued", "running", "succeeded", "failed", "cancelled"])]
    pub state: Option<String>,
    /// Only jobs of this kind (`calibration`, `check`).
    #[arg(long)]
    pub kind: Option<String>,
}

/// `robocal jobs`: the newest `limit` jobs (of `filters`) as a table, newest first.
pub async fn jobs(
    client: &Client,
    limit: u32,
    filters: &JobFilters,
) -> Result<String, ClientError> {
    let query: Vec<(&str, String)> = [
        ("serial", &filters.serial),
        ("state", &filters.state),
        ("kind", &filters.kind),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.clone().map(|v| (k, v)))
    .collect();
    let page: JobPage = client.jobs(limit, None, &query).await?;
    Ok(jobs_table(&page.items))
}

/// One line per job: id (whole), kind, state, progress, serial, session,
/// creation time, and why a job failed.
fn jobs_table(items: &[JobLine]) -> String {
    let text = |v: &Option<String>| v.as_deref().unwrap_or("-").to_string();
    let mut out = format!(
        "{:<36}  {:<11}  {:<9}  {:>4}  {:<16}  {:<36}  {:<24}  {}\n",
        "JOB", "KIND", "STATE", "DONE", "SERIAL", "SESSION", "CREATED", "ERROR"
    );
    for job in items {
        let error = job
            .error
            .as_deref()
            .unwrap_or("")
            .replace(['\n', '\r'], " ");
        out.push_str(&format!(
            "{:<36}  {:<11}  {:<9}  {:>3.0}%  {:<16}  {:<36}  {:<24}  {}\n",
            text(&job.id),
            text(&job.kind),
            text(&job.state),
            job.progress * 100.0,
            text(&job.serial),
            text(&job.session_id),
            text(&job.created_at),
            error,
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_jobs_table_shows_kind_and_why_a_job_failed() {
        let table = jobs_table(&[JobLine {
            id: Some("0193-a".into()),
            kind: Some("check".into()),
            state: Some("failed".into()),
            error: Some("robot R has no approved set\nto check".into()),
            ..JobLine::default()
        }]);
        let mut lines = table.lines();
        let head = lines.next().unwrap();
        assert!(head.contains("KIND") && head.ends_with("ERROR"), "{head}");
        let row = lines.next().unwrap();
        assert!(row.starts_with("0193-a"), "{row}");
        assert!(
            row.contains("  check  ") && row.ends_with("robot R has no approved set to check"),
            "{row}"
        );
    }
}
