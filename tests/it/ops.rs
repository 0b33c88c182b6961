use serde_json::Value;

use crate::support::*;

#[tokio::test]
async fn health_readiness_metrics_docs() {
    let app = spawn_app().await;
    assert_eq!(app.get("/healthz").await.status(), 200);
    let ready: Value = app.get("/readyz").await.json().await.unwrap();
    assert_eq!(ready["status"], "ready");
    assert_eq!(ready["workers"], 2);
    let session = app.robot_and_session("O1").await;
    app.add_point_poses(&session, 3, 1).await;
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/calibrations")))
        .send()
        .await
        .unwrap();
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    app.wait_job(&job, std::time::Duration::from_secs(20), is_finished)
        .await;
    let r = app.get("/metrics").await;
    assert!(r.headers()["content-type"]
        .to_str()
        .unwrap()
        .starts_with("text/plain"));
    let text = r.text().await.unwrap();
    assert!(text.contains("robocal_queue_depth 0"), "{text}");
    assert!(
        text.contains("robocal_jobs{state=\"succeeded\"} 1"),
        "{text}"
    );
    assert!(text.contains("robocal_http_request_duration_seconds_bucket{method=\"PUT\",route=\"/v1/robots/{serial}\",status=\"201\",le=\"+Inf\"} 1"), "{text}");
    let r = app.get("/healthz").await;
    assert!(
        r.headers().contains_key("x-request-id"),
        "every response carries a request id"
    );
    let docs = app.get("/docs/").await;
    assert_eq!(docs.status(), 200);
    assert!(docs.text().await.unwrap().contains("swagger"));
    let spec: Value = app.get("/openapi.json").await.json().await.unwrap();
    assert!(spec["paths"]["/v1/robots/{serial}"]["put"].is_object());
}
