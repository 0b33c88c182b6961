//! The release workflow through the real binary: list robots and
//! sessions, approve and reject with a reason, the jobs table's kind and
//! error columns and filters, webhooks, deleting a robot; a 401 says how
//! to give a token; an upload whose images do not show the session's
//! target says so at once.

use std::process::Output;

use robocal::domain::Scope;
use serde_json::Value;

use crate::fleet_page::{read_token, robot_with_failed_job};
use crate::release_reports::robot_with_decided_sets;
use crate::support::{run_binary, spawn_app, TestApp};

async fn robocal(app: &TestApp, args: &[&str]) -> Output {
    let mut all: Vec<String> = args.iter().map(|a| a.to_string()).collect();
    all.extend(["--url".to_string(), app.base.clone()]);
    tokio::task::spawn_blocking(move || {
        run_binary(&all.iter().map(String::as_str).collect::<Vec<_>>())
    })
    .await
    .unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn ok(out: &Output) -> String {
    assert!(out.status.success(), "stderr: {}", text(&out.stderr));
    text(&out.stdout)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn approve_reject_list_webhooks_and_delete_without_curl() {
    let app = spawn_app().await;
    robot_with_decided_sets(&app, "CLI-R").await;
    let failed = robot_with_failed_job(&app, "CLI-F").await;

    let robots = ok(&robocal(&app, &["robots"]).await);
    assert!(robots.starts_with("SERIAL"), "{robots}");
    assert!(
        robots.contains("CLI-R") && robots.contains("CLI-F"),
        "{robots}"
    );
    let sessions = ok(&robocal(&app, &["sessions", "--serial", "CLI-F"]).await);
    assert!(
        sessions.lines().count() == 2 && sessions.contains("camera"),
        "{sessions}"
    );

    let out = robocal(
        &app,
        &[
            "approve",
            "--serial",
            "CLI-R",
            "--version",
            "3",
            "--reason",
            "seen on the cell",
        ],
    )
    .await;
    assert_eq!(
        ok(&out),
        "CLI-R v3: approved by anonymous (seen on the cell)\n"
    );
    let latest = app.get_ok("/v1/robots/CLI-R/parameter-sets/latest").await;
    assert_eq!(latest["version"], 3);
    let out = robocal(&app, &["reject", "--serial", "CLI-R", "--version", "3"]).await;
    assert!(ok(&out).starts_with("CLI-R v3: rejected by anonymous"));
    let out = robocal(&app, &["reject", "--serial", "CLI-R", "--version", "9"]).await;
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains("version"),
        "{}",
        text(&out.stderr)
    );

    let jobs = ok(&robocal(&app, &["jobs", "--state", "failed"]).await);
    let row = jobs
        .lines()
        .find(|l| l.starts_with(&failed))
        .unwrap_or_else(|| panic!("the failed job, whole id: {jobs}"));
    assert!(
        row.contains("calibration") && row.contains(crate::fleet_page::FAILED_JOB_REASON),
        "{row}"
    );
    let none = ok(&robocal(&app, &["jobs", "--serial", "CLI-R"]).await);
    assert_eq!(none.lines().count(), 1, "a filter by robot: {none}");

    let out = robocal(
        &app,
        &[
            "webhooks",
            "create",
            "http://127.0.0.1:9/hook",
            "--event",
            "job.finished",
        ],
    )
    .await;
    let created = ok(&out);
    assert!(created.contains("signing secret"), "{created}");
    let hooks: Value = app.get_ok("/v1/webhooks").await;
    let id = hooks["items"][0]["id"].as_str().unwrap().to_string();
    let list = ok(&robocal(&app, &["webhooks", "list"]).await);
    assert!(
        list.contains(&id) && list.contains("job.finished"),
        "{list}"
    );
    ok(&robocal(&app, &["webhooks", "delete", &id]).await);
    let hooks: Value = app.get_ok("/v1/webhooks").await;
    assert_eq!(hooks["items"].as_array().unwrap().len(), 0);

    assert_eq!(
        ok(&robocal(&app, &["delete-robot", "--serial", "CLI-F"]).await),
        "robot CLI-F deleted\n"
    );
    assert_eq!(app.get("/v1/robots/CLI-F").await.status(), 404);

    // Once the server has tokens, a request without one says how to give it.
    read_token(&app, Scope::Admin).await;
    let out = robocal(&app, &["robots"]).await;
    assert!(!out.status.success());
    let err = text(&out.stderr);
    assert!(
        err.contains("--token") && err.contains("ROBOCAL_TOKEN"),
        "{err}"
    );
    app.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_upload_whose_images_show_another_board_warns_at_once() {
    let app = spawn_app().await;
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate("irb2400", dir.path(), 3, 1, 5).unwrap();
    // The session says 7x9; the images show the simulator's 9x9 board.
    let path = dir.path().join("campaign.json");
    let mut campaign: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    campaign["session"]["target"]["rows"] = serde_json::json!(7);
    std::fs::write(&path, campaign.to_string()).unwrap();
    let out = robocal(
        &app,
        &["upload", "--serial", "WARN-1", dir.path().to_str().unwrap()],
    )
    .await;
    ok(&out);
    let err = text(&out.stderr);
    assert!(
        err.contains("uploaded 4 poses") && err.contains("(0 images with the target found)"),
        "{err}"
    );
    assert!(
        err.contains("warning: 0 of 4 images show the session's target; 4 say: "),
        "{err}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_failed_upload_names_the_file_and_leaves_no_robot_behind() {
    let app = spawn_app().await;
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate("irb2400", dir.path(), 3, 1, 5).unwrap();
    let entries: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("poses.json")).unwrap())
            .unwrap();
    let name = entries[2]["image"].as_str().unwrap().to_string();
    let image = dir.path().join(&name);
    let bytes = std::fs::read(&image).unwrap();
    std::fs::write(&image, &bytes[..bytes.len() / 2]).unwrap();
    let out = robocal(
        &app,
        &[
            "upload",
            "--serial",
            "DEBRIS-1",
            dir.path().to_str().unwrap(),
        ],
    )
    .await;
    assert!(!out.status.success());
    let err = text(&out.stderr);
    assert!(
        err.contains(&format!("{name}: ")),
        "the file is named: {err}"
    );
    assert!(err.contains("robot DEBRIS-1 removed again"), "{err}");
    assert_eq!(app.get("/v1/robots/DEBRIS-1").await.status(), 404);
}
