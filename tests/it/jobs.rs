use std::time::Duration;

use serde_json::{json, Value};

use robocal::domain::{now_unix_ms, JobState, LeaseStatus};
use robocal::schema::job::JobOptions;
use robocal::schema::session::SessionBody;
use robocal::store;
use robocal::store::{JobOutcome, NewJob, NewParameterSet};

use crate::support::*;

const WAIT: Duration = Duration::from_secs(20);

async fn start_job(app: &TestApp, session: &str, body: Option<Value>) -> reqwest::Response {
    let mut req = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/calibrations")));
    if let Some(b) = body {
        req = req.json(&b);
    }
    req.send().await.unwrap()
}

#[tokio::test]
async fn calibration_job_validates_and_succeeds() {
    let app = spawn_app().await;
    let session = app.robot_and_session("J1").await;
    app.add_point_poses(&session, 4, 1).await;
    let r = start_job(&app, &session, None).await;
    assert_eq!(r.status(), 202);
    let location = r.headers()["location"].to_str().unwrap().to_string();
    let accepted: Value = r.json().await.unwrap();
    let job = accepted["job_id"].as_str().unwrap().to_string();
    assert_eq!(location, format!("/v1/jobs/{job}"));
    let done = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    assert_eq!(done["progress"], 1.0);
    assert_eq!(done["result"]["summary"]["calibration_poses"], 4);
    assert_eq!(done["result"]["summary"]["validation_poses"], 1);
    assert_eq!(done["attempts"], 1);
}

/// A calibration that cannot start (2 poses; the validate stage needs 3
/// calibration poses) is refused at the POST with a 422 naming `poses`,
/// not queued to fail later; one more calibration pose and it starts.
#[tokio::test]
async fn too_few_poses_are_a_422_at_the_post_naming_poses() {
    let app = spawn_app().await;
    let session = app.robot_and_session("J2").await;
    app.add_point_poses(&session, 2, 0).await;
    let r = start_job(
        &app,
        &session,
        Some(json!({"validation": {"holdout_fraction": 0.3}})),
    )
    .await;
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], "poses", "{p}");
    let message = p["errors"][0]["message"].as_str().unwrap();
    assert!(message.contains("2 calibration poses"), "{p}");
    let jobs: Value = app.get_ok("/v1/jobs?serial=J2").await;
    assert_eq!(jobs["items"].as_array().unwrap().len(), 0, "{jobs}");
    // Validation poses do not count: 2 cal + 3 val is still refused.
    let more = app.new_session("J2", &session_body()).await;
    app.add_point_poses(&more, 2, 3).await;
    let r = start_job(&app, &more, None).await;
    assert_eq!(r.status(), 422);
    app.add_point_poses(&session, 1, 0).await;
    let r = start_job(
        &app,
        &session,
        Some(json!({"validation": {"holdout_fraction": 0.3}})),
    )
    .await;
    assert_eq!(r.status(), 202, "{}", r.text().await.unwrap());
}

#[tokio::test]
async fn running_job_reports_progress_and_can_be_cancelled() {
    let app = spawn_app_with(|c| c.test_stage_delay_ms = 500).await;
    let session = app.robot_and_session("J3").await;
    app.add_point_poses(&session, 5, 1).await;
    let job = start_job(&app, &session, None)
        .await
        .json::<Value>()
        .await
        .unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let running = app
        .wait_job(&job, WAIT, |v| {
            v["state"] == "running" && v["progress"].as_f64().unwrap() > 0.0
        })
        .await;
    assert_eq!(running["stage"], "validate");
    let r = app
        .client
        .delete(app.url(&format!("/v1/jobs/{job}")))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 200);
    assert_eq!(r.json::<Value>().await.unwrap()["state"], "cancelled");
    // The worker notices and stops; the state stays cancelled.
    tokio::time::sleep(Duration::from_millis(800)).await;
    let after: Value = app
        .get(&format!("/v1/jobs/{job}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(after["state"], "cancelled");
    assert!(after["result"].is_null());
    // Cancelling again is a conflict; an unknown job is 404.
    let again = app
        .client
        .delete(app.url(&format!("/v1/jobs/{job}")))
        .send()
        .await
        .unwrap();
    assert_eq!(again.status(), 409);
    let r = app
        .client
        .delete(app.url("/v1/jobs/nope"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 404);
}

#[tokio::test]
async fn full_queue_answers_429_and_loses_nothing_accepted() {
    let app = spawn_app_with(|c| {
        c.workers = Some(1);
        c.max_queued = 2;
        c.test_stage_delay_ms = 300;
    })
    .await;
    let session = app.robot_and_session("Q1").await;
    app.add_point_poses(&session, 3, 1).await;
    let (mut accepted, mut refused) = (vec![], 0);
    for _ in 0..8 {
        let r = start_job(&app, &session, None).await;
        match r.status().as_u16() {
            202 => accepted.push(
                r.json::<Value>().await.unwrap()["job_id"]
                    .as_str()
                    .unwrap()
                    .to_string(),
            ),
            429 => {
                let retry: u64 = r.headers()["retry-after"]
                    .to_str()
                    .unwrap()
                    .parse()
                    .unwrap();
                assert!(retry > 0);
                assert_eq!(r.headers()["content-type"], "application/problem+json");
                refused += 1;
            }
            other => panic!("unexpected {other}"),
        }
    }
    // At most 2 queued + 1 running while the 8 requests arrive (a job takes >1 s).
    assert!(
        refused >= 3,
        "the queue bound must refuse: {refused} refused"
    );
    assert!(accepted.len() >= 2 && accepted.len() + refused == 8);
    for job in &accepted {
        let done = app.wait_job(job, WAIT, is_finished).await;
        assert_eq!(done["state"], "succeeded", "{done}");
    }
}

#[tokio::test]
async fn shutdown_releases_running_job_without_counting_the_attempt() {
    let app = spawn_app_with(|c| {
        c.test_stage_delay_ms = 2000;
        c.shutdown_grace_secs = 0;
    })
    .await;
    let session = app.robot_and_session("R1").await;
    app.add_point_poses(&session, 3, 1).await;
    let job = start_job(&app, &session, None)
        .await
        .json::<Value>()
        .await
        .unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    app.wait_job(&job, WAIT, |v| v["state"] == "running").await;
    let url = app.database_url.clone();
    let started = std::time::Instant::now();
    let _dir = app.shutdown().await;
    assert!(
        started.elapsed() < Duration::from_secs(5),
        "shutdown is prompt"
    );
    let store = store::connect(&url).await.unwrap();
    let j = store.get_job(&job).await.unwrap().unwrap();
    assert_eq!(j.state, JobState::Queued);
    assert_eq!(j.attempts, 0);
}

#[tokio::test]
async fn queue_reclaims_expired_leases_until_max_attempts() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let s = store::connect(&db).await.unwrap();
    let app_like = robocal::store::RobotRecord {
        serial: "X".into(),
        model: "m".into(),
        preset: None,
        kinematics: json!({"joints": []}),
        controller: None,
        prior: None,
        created_at: "t".into(),
        updated_at: "t".into(),
    };
    s.put_robot(&app_like).await.unwrap();
    let session = s
        .create_session("X", "camera", &SessionBody::default())
        .await
        .unwrap();
    let job = s
        .enqueue_job(
            &NewJob {
                session_id: session.id,
                serial: "X".into(),
                options: JobOptions::Calibration(Default::default()),
                max_attempts: 2,
            },
            10,
        )
        .await
        .unwrap();
    let now = now_unix_ms();
    // Worker A claims with a lease that is already over (as if killed).
    let a = s.claim_job("A", now, now - 1).await.unwrap().unwrap();
    assert_eq!((a.id.as_str(), a.attempt), (job.id.as_str(), 1));
    // Worker B reclaims it; A's late writes are refused.
    let b = s.claim_job("B", now, now - 1).await.unwrap().unwrap();
    assert_eq!(b.attempt, 2);
    assert_eq!(
        s.renew_lease(&job.id, "A", now + 1000, "x", 0.5)
            .await
            .unwrap(),
        LeaseStatus::Lost
    );
    let outcome = JobOutcome::Succeeded {
        parameter_set: None,
        summary: Default::default(),
        detections: vec![],
        check: None,
    };
    assert_eq!(
        s.finish_job(&job.id, "A", &outcome).await.unwrap(),
        LeaseStatus::Lost
    );
    // No attempt left: nobody can claim it, and the sweep fails it.
    assert!(s.claim_job("C", now, now + 1000).await.unwrap().is_none());
    assert_eq!(s.fail_exhausted_jobs(now).await.unwrap(), 1);
    let failed = s.get_job(&job.id).await.unwrap().unwrap();
    assert_eq!(failed.state, JobState::Failed);
    assert!(failed.error.unwrap().contains("attempt 2 of 2"));

    // A job that succeeds with a parameter set stores it as the serial's next
    // version in the transaction that finishes the job.
    let session = s
        .create_session("X", "camera", &SessionBody::default())
        .await
        .unwrap();
    let new = NewJob {
        session_id: session.id,
        serial: "X".into(),
        options: JobOptions::Calibration(Default::default()),
        max_attempts: 3,
    };
    let job = s.enqueue_job(&new, 10).await.unwrap();
    let w = s.claim_job("W", now, now + 60_000).await.unwrap().unwrap();
    assert_eq!(w.id, job.id);
    let outcome = JobOutcome::Succeeded {
        parameter_set: Some(NewParameterSet::approved(
            placeholder_set("p1"),
            json!({"r": 2}),
        )),
        summary: Default::default(),
        detections: vec![],
        check: None,
    };
    assert_eq!(
        s.finish_job(&job.id, "W", &outcome).await.unwrap(),
        LeaseStatus::Held
    );
    let done = s.get_job(&job.id).await.unwrap().unwrap();
    assert_eq!(done.state, JobState::Succeeded);
    let result = done.result.unwrap();
    let stored = result.calibration();
    assert_eq!(
        (stored.serial.as_deref(), stored.version),
        (Some("X"), Some(1))
    );
    assert_eq!(s.get_report("X", 1).await.unwrap().unwrap()["r"], 2);

    // A retryable failure requeues while attempts remain.
    let session = s
        .create_session("X", "camera", &SessionBody::default())
        .await
        .unwrap();
    let new = NewJob {
        session_id: session.id,
        serial: "X".into(),
        options: JobOptions::Calibration(Default::default()),
        max_attempts: 2,
    };
    let job = s.enqueue_job(&new, 10).await.unwrap();
    s.claim_job("W", now, now + 60_000).await.unwrap().unwrap();
    let retry = JobOutcome::Retry {
        error: "flaky".into(),
    };
    s.finish_job(&job.id, "W", &retry).await.unwrap();
    assert_eq!(
        s.get_job(&job.id).await.unwrap().unwrap().state,
        JobState::Queued
    );
    s.claim_job("W", now, now + 60_000).await.unwrap().unwrap();
    s.finish_job(&job.id, "W", &retry).await.unwrap();
    let j = s.get_job(&job.id).await.unwrap().unwrap();
    assert_eq!(j.state, JobState::Failed);
    assert!(j.error.unwrap().contains("after 2 attempts"));
}

#[tokio::test]
async fn parameter_sets_are_versioned_per_serial_and_served() {
    let app = spawn_app().await;
    let session = app.robot_and_session("V1").await;
    app.robot_and_session("V2").await;
    let s = store::connect(&app.database_url).await.unwrap();
    let _ = session;
    let set = |k: f64| {
        NewParameterSet::approved(
            placeholder_set(&format!("k{k}")),
            json!({"after": {"rms_mm": k}}),
        )
    };
    assert_eq!(
        s.insert_parameter_set("V1", None, &set(1.0)).await.unwrap(),
        1
    );
    assert_eq!(
        s.insert_parameter_set("V2", None, &set(5.0)).await.unwrap(),
        1
    );
    assert_eq!(
        s.insert_parameter_set("V1", None, &set(2.0)).await.unwrap(),
        2
    );
    let list: Value = app
        .get("/v1/robots/V1/parameter-sets")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(list["items"][0]["version"], 2, "newest first");
    assert_eq!(list["items"][1]["session_id"], "k1");
    assert_eq!(list["items"][1]["kind"], "kinematic");
    let latest: Value = app
        .get("/v1/robots/V1/parameter-sets/latest")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(latest["version"], 2);
    let report: Value = app
        .get("/v1/robots/V1/parameter-sets/1/report")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(report["after"]["rms_mm"], 1.0);
    assert_eq!(
        app.get("/v1/robots/V1/parameter-sets/9").await.status(),
        404
    );
}
