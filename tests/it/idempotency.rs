use serde_json::Value;

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

    // The same key on another route is independent.
    let r = c
        .put(app.url("/v1/robots/I2"))
        .header("idempotency-key", "job-1")
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    assert!(r.headers().get("idempotent-replayed").is_none());
}
