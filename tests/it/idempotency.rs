use std::time::{Duration, Instant};

use serde_json::Value;
use tokio::io::AsyncWriteExt;

use crate::raw_http::connect;
use crate::support::*;

#[tokio::test]
async fn replayed_writes_return_the_stored_response_and_create_nothing() {
    let app = spawn_app().await;
    let session = app.robot_and_session("I1").await;
    app.add_point_poses(&session, 3, 1).await;
    let c = &app.client;
    let post = |key: &str| {
        c.post(app.url(&format!("/v1/sessions/{session}/calibrations")))
            .header("idempotency-key", key.to_string())
            .send()
    };
    let first = post("job-1").await.unwrap();
    assert_eq!(first.status(), 202);
    let location = first.headers()["location"].clone();
    let first: Value = first.json().await.unwrap();
    let again = post("job-1").await.unwrap();
    assert_eq!(again.status(), 202);
    assert_eq!(again.headers()["location"], location);
    assert_eq!(again.headers()["idempotent-replayed"], "true");
    let again: Value = again.json().await.unwrap();
    assert_eq!(
        again["job_id"], first["job_id"],
        "the same job, not a new one"
    );

    // A new key makes a new job.
    let other: Value = post("job-2").await.unwrap().json().await.unwrap();
    assert_ne!(other["job_id"], first["job_id"]);

    // Pose creation: replay creates no second pose.
    let pose = point_pose(9, "cal");
    let p1: Value = c
        .post(app.url(&format!("/v1/sessions/{session}/poses")))
        .header("idempotency-key", "pose-9")
        .json(&pose)
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let p2: Value = c
        .post(app.url(&format!("/v1/sessions/{session}/poses")))
        .header("idempotency-key", "pose-9")
        .json(&pose)
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    assert_eq!(p1["id"], p2["id"]);
    let s: Value = app
        .get(&format!("/v1/sessions/{session}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(s["pose_count"], 5);

    // A key names one request: the same key on another route is refused.
    let r = c
        .put(app.url("/v1/robots/I2"))
        .header("idempotency-key", "job-1")
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 422);
    let problem: Value = r.json().await.unwrap();
    assert_eq!(
        problem["errors"][0]["field"], "Idempotency-Key",
        "{problem}"
    );
    assert_eq!(app.get("/v1/robots/I2").await.status(), 404);
}

#[tokio::test]
async fn a_key_reused_with_another_body_is_422_and_creates_nothing() {
    let app = spawn_app().await;
    let session = app.robot_and_session("I3").await;
    let c = &app.client;
    let post = |pose: Value| {
        c.post(app.url(&format!("/v1/sessions/{session}/poses")))
            .header("idempotency-key", "pose-a")
            .json(&pose)
            .send()
    };
    let first = post(point_pose(1, "cal")).await.unwrap();
    assert_eq!(first.status(), 201);
    let first: Value = first.json().await.unwrap();
    let other = post(point_pose(2, "val")).await.unwrap();
    assert_eq!(other.status(), 422);
    assert!(other.headers().get("idempotent-replayed").is_none());
    let problem: Value = other.json().await.unwrap();
    assert_eq!(
        problem["errors"][0]["field"], "Idempotency-Key",
        "{problem}"
    );
    // The real retry still replays.
    let again = post(point_pose(1, "cal")).await.unwrap();
    assert_eq!(again.status(), 201);
    assert_eq!(again.headers()["idempotent-replayed"], "true");
    let again: Value = again.json().await.unwrap();
    assert_eq!(again["id"], first["id"]);
    let s: Value = app
        .get(&format!("/v1/sessions/{session}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(s["pose_count"], 1);
}

#[tokio::test]
async fn a_multipart_retry_with_a_new_boundary_replays_and_another_image_is_422() {
    let app = spawn_app().await;
    let session = app.robot_and_session("I4").await;
    let url = app.url(&format!("/v1/sessions/{session}/poses"));
    let send = |image: Vec<u8>| {
        // reqwest draws a new random boundary for every form.
        let form = reqwest::multipart::Form::new()
            .text("joints_deg", "[1,2,3,4,5,6]")
            .part("image", image_part(image, "a.png"));
        app.client
            .post(&url)
            .header("idempotency-key", "upload-1")
            .multipart(form)
            .send()
    };
    let image = png(CAMERA_W, CAMERA_H, 7);
    let first = send(image.clone()).await.unwrap();
    assert_eq!(first.status(), 201);
    let first: Value = first.json().await.unwrap();
    let retry = send(image).await.unwrap();
    assert_eq!(retry.status(), 201);
    assert_eq!(retry.headers()["idempotent-replayed"], "true");
    let retry: Value = retry.json().await.unwrap();
    assert_eq!(retry["id"], first["id"]);
    let other = send(png(CAMERA_W, CAMERA_H, 8)).await.unwrap();
    assert_eq!(other.status(), 422);
}

/// Retries `send` while the key is still held by the dropped request.
async fn until_not_in_flight(
    send: impl Fn() -> reqwest::RequestBuilder,
    wait: Duration,
) -> reqwest::Response {
    let deadline = Instant::now() + wait;
    loop {
        let r = send().send().await.unwrap();
        if r.status() != 409 || Instant::now() > deadline {
            return r;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

#[tokio::test]
async fn a_client_that_drops_mid_upload_does_not_poison_its_key() {
    let app = spawn_app().await;
    let body = serde_json::to_vec(&robot_body()).unwrap();
    let mut dropped = connect(&app.base).await;
    let head = format!(
        "PUT /v1/robots/I5 HTTP/1.1\r\nHost: {host}\r\nIdempotency-Key: robot-i5\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len(),
        host = crate::raw_http::addr_of(&app.base)
    );
    dropped.write_all(head.as_bytes()).await.unwrap();
    dropped.write_all(&body[..body.len() / 2]).await.unwrap();
    tokio::time::sleep(Duration::from_millis(300)).await;
    drop(dropped);

    let full = || {
        app.client
            .put(app.url("/v1/robots/I5"))
            .header("idempotency-key", "robot-i5")
            .json(&robot_body())
    };
    let r = until_not_in_flight(full, Duration::from_secs(5)).await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    assert!(r.headers().get("idempotent-replayed").is_none());
    assert_eq!(app.get("/v1/robots/I5").await.status(), 200);
}
