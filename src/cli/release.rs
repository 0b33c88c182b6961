//! The release workflow from the command line: approve or reject a
//! parameter set, re-check a robot against its approved set, list robots
//! and their sessions, delete a robot, manage webhooks. Each command is one
//! request of the REST contract; the answer is printed as a short line or
//! an aligned table (`--json` prints the server's document as it is).

use reqwest::Method;
use serde_json::{json, Value};

use super::client::{answer_of, Client, ClientError};
use super::command::{Decision, ReleaseCommand, ServerArgs, WebhookCommand};

/// Pause between polls of a re-check's job (`recheck --wait`).
const POLL_INTERVAL: std::time::Duration = std::time::Duration::from_millis(500);

/// Runs one release command; what it prints goes to stdout.
pub async fn run(command: ReleaseCommand) -> Result<(), String> {
    let out = run_on(command).await.map_err(|e| e.to_string())?;
    print!("{out}");
    Ok(())
}

fn client(server: &ServerArgs) -> Result<Client, ClientError> {
    server.client().map_err(ClientError::Local)
}

/// The command's output text.
pub async fn run_on(command: ReleaseCommand) -> Result<String, ClientError> {
    match command {
        ReleaseCommand::Approve(d) => decide(d, "approve").await,
        ReleaseCommand::Reject(d) => decide(d, "reject").await,
        ReleaseCommand::Recheck {
            session,
            wait,
            server,
        } => recheck(&client(&server)?, &session, wait).await,
        ReleaseCommand::Robots { server } => {
            let page: Value = answer_of(
                &client(&server)?
                    .call(Method::GET, "/v1/robots?limit=1000", None)
                    .await?,
            )?;
            Ok(table(
                &["SERIAL", "MODEL", "PRESET", "UPDATED"],
                &page["items"],
                &["serial", "model", "preset", "updated_at"],
            ))
        }
        ReleaseCommand::Sessions { serial, server } => {
            let path = format!("/v1/robots/{serial}/sessions?limit=1000");
            let page: Value = answer_of(&client(&server)?.call(Method::GET, &path, None).await?)?;
            Ok(table(
                &["SESSION", "INSTRUMENT", "POSES", "CREATED", "REGION"],
                &page["items"],
                &["id", "instrument", "pose_count", "created_at", "region"],
            ))
        }
        ReleaseCommand::DeleteRobot { serial, server } => {
            client(&server)?
                .call(Method::DELETE, &format!("/v1/robots/{serial}"), None)
                .await?;
            Ok(format!("robot {serial} deleted\n"))
        }
        ReleaseCommand::Webhooks(command) => webhooks(command).await,
    }
}

async fn decide(d: Decision, verb: &str) -> Result<String, ClientError> {
    let path = format!(
        "/v1/robots/{}/parameter-sets/{}/{verb}",
        d.serial, d.version
    );
    let body = match &d.reason {
        Some(reason) => json!({ "reason": reason }),
        None => json!({}),
    };
    let set: Value = answer_of(
        &client(&d.server)?
            .call(Method::POST, &path, Some(&body))
            .await?,
    )?;
    Ok(format!(
        "{} v{}: {} by {} ({})\n",
        d.serial,
        d.version,
        field(&set["status"]),
        field(&set["status_by"]),
        field(&set["status_reason"])
    ))
}

async fn recheck(client: &Client, session: &str, wait: bool) -> Result<String, ClientError> {
    let path = format!("/v1/sessions/{session}/checks");
    let accepted: Value = answer_of(&client.call(Method::POST, &path, Some(&json!({}))).await?)?;
    let job_id = field(&accepted["job_id"]);
    if !wait {
        return Ok(format!("{job_id}\n"));
    }
    loop {
        let job: Value = answer_of(&client.job(&job_id).await?)?;
        match job["state"].as_str() {
            Some("succeeded") => {
                let r = &job["result"];
                return Ok(format!(
                    "check {job_id}: {} against {}: mean {} mm, expected {} mm, p = {}\n",
                    field(&r["verdict"]),
                    field(&r["checked_against"]),
                    number(&r["mean_mm"]),
                    number(&r["expected_mean_mm"]),
                    number(&r["p_value"])
                ));
            }
            Some(state @ ("failed" | "cancelled")) => {
                return Err(ClientError::Local(format!(
                    "check {job_id} {state}: {}",
                    field(&job["error"])
                )))
            }
            _ => tokio::time::sleep(POLL_INTERVAL).await,
        }
    }
}

async fn webhooks(command: WebhookCommand) -> Result<String, ClientError> {
    match command {
        WebhookCommand::List { server } => {
            let page: Value = answer_of(
                &client(&server)?
                    .call(Method::GET, "/v1/webhooks", None)
                    .await?,
            )?;
            Ok(table(
                &["WEBHOOK", "URL", "EVENTS", "CREATED"],
                &page["items"],
                &["id", "url", "events", "created_at"],
            ))
        }
        WebhookCommand::Create {
            hook_url,
            events,
            server,
        } => {
            let body = json!({ "url": hook_url, "events": events });
            let hook: Value = answer_of(
                &client(&server)?
                    .call(Method::POST, "/v1/webhooks", Some(&body))
                    .await?,
            )?;
            Ok(format!(
                "webhook {} created; its signing secret (shown once): {}\n",
                field(&hook["id"]),
                field(&hook["secret"])
            ))
        }
        WebhookCommand::Delete { id, server } => {
            client(&server)?
                .call(Method::DELETE, &format!("/v1/webhooks/{id}"), None)
                .await?;
            Ok(format!("webhook {id} deleted\n"))
        }
    }
}

/// A JSON value as one cell: strings as they are, lists joined, `-` for none.
fn field(v: &Value) -> String {
    match v {
        Value::Null => "-".into(),
        Value::String(s) => s.replace(['\n', '\r'], " "),
        Value::Array(items) => items.iter().map(field).collect::<Vec<_>>().join(","),
        other => other.to_string(),
    }
}

/// A number with four significant digits, `-` when absent.
fn number(v: &Value) -> String {
    v.as_f64()
        .map_or_else(|| "-".into(), |x| crate::report::format::significant(x, 4))
}

/// Rows of `items` as aligned columns (`keys` read from each item).
fn table(heads: &[&str], items: &Value, keys: &[&str]) -> String {
    let rows: Vec<Vec<String>> = items
        .as_array()
        .map(|a| {
            a.iter()
                .map(|item| keys.iter().map(|k| field(&item[*k])).collect())
                .collect()
        })
        .unwrap_or_default();
    let widths: Vec<usize> = (0..heads.len())
        .map(|i| {
            rows.iter()
                .map(|r| r[i].chars().count())
                .chain([heads[i].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: Vec<String>| {
        let mut text = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:<w$}"))
            .collect::<Vec<_>>()
            .join("  ");
        text.truncate(text.trim_end().len());
        text.push('\n');
        text
    };
    let mut out = line(heads.iter().map(|h| h.to_string()).collect());
    for row in rows {
        out.push_str(&line(row));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_align_and_show_missing_cells_as_dashes() {
        let items = json!([
            {"serial": "IRB-001", "model": "IRB 2400", "preset": "irb2400"},
            {"serial": "R", "model": "UR10e", "preset": null, "updated_at": "2026"}
        ]);
        let t = table(
            &["SERIAL", "MODEL", "PRESET", "UPDATED"],
            &items,
            &["serial", "model", "preset", "updated_at"],
        );
        assert_eq!(
            t,
            "SERIAL   MODEL     PRESET   UPDATED\n\
             IRB-001  IRB 2400  irb2400  -\n\
             R        UR10e     -        2026\n"
        );
    }
}
