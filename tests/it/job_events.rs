//! `GET /v1/jobs/{id}/events` (Server-Sent Events) and the filters of
//! `GET /v1/jobs`.

use std::time::Duration;

use futures_util::StreamExt;
use serde_json::Value;

use crate::support::*;

const WAIT: Duration = Duration::from_secs(30);

/// The `(event, data)` pairs of an SSE stream read to its end.
async fn read_events(r: reqwest::Response) -> Vec<(String, Value)> {
    let mut text = String::new();
    let mut body = r.bytes_stream();
    let read = async {
        while let Some(chunk) = body.next().await {
            text.push_str(&String::from_utf8_lossy(&chunk.unwrap()));
        }
    };
    tokio::time::timeout(WAIT, read)
        .await
        .expect("the stream ends when the job ends");
    text.split("\n\n")
        .filter_map(|block| {
            let mut name = None;
            let mut data = None;
            for line in block.lines() {
                if let Some(n) = line.strip_prefix("event:") {
                    name = Some(n.trim().to_string());
                } else if let Some(d) = line.strip_prefix("data:") {
                    data = Some(serde_json::from_str(d.trim()).unwrap());
                }
            }
            Some((name?, data?))
        })
        .collect()
}

#[tokio::test]
async fn job_events_stream_stages_progress_and_end_then_close() {
    // 4 poses × 500 ms: a few heartbeats of visible progress.
    let app = spawn_app_with(|c| c.test_stage_delay_ms = 500).await;
    let session = app.robot_and_session("EV-1").await;
    app.add_point_poses(&session, 3, 1).await;
    let job = start_calibration(&app.client, &app.base, &session).await;

    let r = app.get(&format!("/v1/jobs/{job}/events")).await;
    assert_eq!(r.status(), 200);
    assert!(r.headers()["content-type"]
        .to_str()
        .unwrap()
        .starts_with("text/event-stream"));
    let events = read_events(r).await;
    let names: Vec<&str> = events.iter().map(|(n, _)| n.as_str()).collect();
    assert!(names.contains(&"stage"), "{names:?}");
    assert!(names.contains(&"progress"), "{names:?}");
    assert_eq!(names.last(), Some(&"end"), "{names:?}");
    assert_eq!(names.iter().filter(|n| **n == "end").count(), 1);
    let stages: Vec<&str> = events
        .iter()
        .filter(|(n, _)| n == "stage")
        .map(|(_, d)| d["stage"].as_str().unwrap())
        .collect();
    assert!(stages.contains(&"validate"), "{stages:?}");
    let progress: Vec<f64> = events
        .iter()
        .filter(|(n, _)| n == "progress")
        .map(|(_, d)| d["progress"].as_f64().unwrap())
        .collect();
    assert!(
        progress.iter().any(|p| *p > 0.0 && *p < 1.0),
        "{progress:?}"
    );
    let (_, end) = events.last().unwrap();
    assert_eq!(end["id"], job.as_str());
    assert_eq!(end["state"], "succeeded", "{end}");

    // A finished job's stream answers its end at once.
    let again = read_events(app.get(&format!("/v1/jobs/{job}/events")).await).await;
    assert_eq!(again.last().unwrap().0, "end");

    let missing = app.get("/v1/jobs/nope/events").await;
    assert_eq!(missing.status(), 404);
}

#[tokio::test]
async fn jobs_filter_by_state_serial_and_kind_with_paging() {
    let app = spawn_app().await;
    let a = app.robot_and_session("FLT-A").await;
    let b = app.robot_and_session("FLT-B").await;
    app.add_point_poses(&a, 3, 1).await;
    app.add_point_poses(&b, 3, 1).await;
    let a_jobs = [
        start_calibration(&app.client, &app.base, &a).await,
        start_calibration(&app.client, &app.base, &a).await,
    ];
    let b_job = start_calibration(&app.client, &app.base, &b).await;
    for j in a_jobs.iter().chain([&b_job]) {
        app.wait_job(j, WAIT, is_finished).await;
    }
    let ids = |v: &Value| -> Vec<String> {
        v["items"]
            .as_array()
            .unwrap()
            .iter()
            .map(|j| j["id"].as_str().unwrap().to_string())
            .collect()
    };
    let get = |q: &str| {
        let url = app.url(&format!("/v1/jobs?{q}"));
        let c = app.client.clone();
        async move { c.get(url).send().await.unwrap() }
    };
    let only_a: Value = get("serial=FLT-A").await.json().await.unwrap();
    assert_eq!(ids(&only_a), [a_jobs[1].clone(), a_jobs[0].clone()]);
    let page1: Value = get("serial=FLT-A&limit=1").await.json().await.unwrap();
    assert_eq!(ids(&page1), [a_jobs[1].clone()]);
    let cursor = page1["next_cursor"].as_str().unwrap();
    let page2: Value = get(&format!("serial=FLT-A&limit=1&cursor={cursor}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(ids(&page2), [a_jobs[0].clone()]);
    let succeeded: Value = get("state=succeeded&kind=calibration")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(ids(&succeeded).len(), 3);
    let queued: Value = get("state=queued").await.json().await.unwrap();
    assert!(ids(&queued).is_empty());
    let b_done: Value = get("state=succeeded&serial=FLT-B")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(ids(&b_done), [b_job]);

    for (q, field) in [
        ("state=done", "state"),
        ("kind=bake", "kind"),
        ("serial=..", "serial"),
        ("serial=a%20b", "serial"),
    ] {
        let r = get(q).await;
        assert_eq!(r.status(), 422, "{q}");
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], field, "{q}: {problem}");
    }
}

/// Issue 32, item 7: a stream stayed open 72 s after its token was revoked.
#[tokio::test]
async fn revoking_the_token_ends_its_open_streams_within_a_second() {
    let app = spawn_app_with(|c| c.test_stage_delay_ms = 10_000).await;
    let session = app.robot_and_session("EV-R").await;
    app.add_point_poses(&session, 3, 1).await;
    let job = start_calibration(&app.client, &app.base, &session).await;
    let token = crate::tokens::stored_token(&app, robocal::domain::Scope::Read, None).await;
    let r = app
        .client
        .get(app.url(&format!("/v1/jobs/{job}/events")))
        .bearer_auth(&token)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 200);
    let mut body = r.bytes_stream();
    // The first events arrive; the job runs on for tens of seconds.
    assert!(body.next().await.is_some());
    let s = robocal::store::connect(&app.database_url).await.unwrap();
    let id = s
        .list_tokens()
        .await
        .unwrap()
        .into_iter()
        .find(|t| t.name == "test")
        .unwrap()
        .id;
    s.revoke_token(&id).await.unwrap();
    let revoked = std::time::Instant::now();
    let drained = tokio::time::timeout(Duration::from_secs(5), async {
        while let Some(chunk) = body.next().await {
            if chunk.is_err() {
                break;
            }
        }
    })
    .await;
    assert!(drained.is_ok(), "the stream stayed open after revocation");
    let took = revoked.elapsed();
    // The job itself runs 4 × 10 s: the stream did not end with it.
    assert!(took < Duration::from_millis(1500), "closed after {took:?}");
}
