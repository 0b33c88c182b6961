//! `GET /v1/jobs` (newest first, cursor paging) and `robocal jobs`.

use serde_json::Value;

use crate::support::*;

async fn start_jobs(app: &TestApp, session: &str, n: usize) -> Vec<String> {
    let mut ids = Vec::new();
    for _ in 0..n {
        let r = app
            .client
            .post(app.url(&format!("/v1/sessions/{session}/calibrations")))
            .send()
            .await
            .unwrap();
        assert_eq!(r.status(), 202);
        let body: Value = r.json().await.unwrap();
        ids.push(body["job_id"].as_str().unwrap().to_string());
    }
    ids
}

fn ids_of(page: &Value) -> Vec<String> {
    page["items"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["id"].as_str().unwrap().to_string())
        .collect()
}

#[tokio::test]
async fn jobs_are_listed_newest_first_with_cursor_paging() {
    let app = spawn_app().await;
    let empty: Value = app.get("/v1/jobs").await.json().await.unwrap();
    assert_eq!(empty["items"].as_array().unwrap().len(), 0);
    assert!(empty["next_cursor"].is_null());

    let session = app.robot_and_session("JL1").await;
    app.add_point_poses(&session, 3, 1).await;
    let started = start_jobs(&app, &session, 3).await;
    let newest_first: Vec<String> = started.iter().rev().cloned().collect();

    let r = app.get("/v1/jobs?limit=2").await;
    assert_eq!(r.status(), 200);
    let first: Value = r.json().await.unwrap();
    assert_eq!(ids_of(&first), newest_first[..2]);
    assert_eq!(first["items"][0]["session_id"], session.as_str());
    assert_eq!(first["items"][0]["serial"], "JL1");
    let cursor = first["next_cursor"]
        .as_str()
        .expect("a full page has a cursor");
    let second: Value = app
        .get(&format!("/v1/jobs?limit=2&cursor={cursor}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(ids_of(&second), newest_first[2..]);
    assert!(second["next_cursor"].is_null(), "{second}");

    let all: Value = app.get("/v1/jobs").await.json().await.unwrap();
    assert_eq!(ids_of(&all), newest_first);

    let bad = app.get("/v1/jobs?limit=0").await;
    assert_eq!(bad.status(), 422);
    let problem: Value = bad.json().await.unwrap();
    assert_eq!(problem["errors"][0]["field"], "limit");
}

#[tokio::test]
async fn robocal_jobs_prints_the_newest_jobs() {
    let app = spawn_app().await;
    let session = app.robot_and_session("JL2").await;
    app.add_point_poses(&session, 3, 1).await;
    let started = start_jobs(&app, &session, 3).await;
    let base = app.base.clone();
    let out =
        tokio::task::spawn_blocking(move || run_binary(&["jobs", "--url", &base, "--limit", "2"]))
            .await
            .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.contains(&started[2]), "{stdout}");
    assert!(stdout.contains(&started[1]), "{stdout}");
    assert!(!stdout.contains(&started[0]), "only the 2 newest: {stdout}");
    assert!(stdout.contains("JL2"), "{stdout}");
}
