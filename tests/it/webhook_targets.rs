//! Where webhooks may point (issue 32, item 9): cloud metadata, link-local
//! and internal addresses, and the service itself (also spelled
//! `[::ffff:127.0.0.1]` or `localhost.`) are refused when the webhook is
//! created; and every delivery resolves its host and checks the addresses,
//! so a name that resolves to an internal address is never called.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use serde_json::{json, Value};

use robocal::store::{self, WebhookRecord};

use crate::support::*;

const WAIT: Duration = Duration::from_secs(30);

/// A loopback listener that counts the connections it gets.
async fn counting_receiver() -> (u16, Arc<AtomicUsize>) {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let port = listener.local_addr().unwrap().port();
    let count = Arc::new(AtomicUsize::new(0));
    let seen = count.clone();
    tokio::spawn(async move {
        while let Ok((_stream, _)) = listener.accept().await {
            seen.fetch_add(1, Ordering::SeqCst);
        }
    });
    (port, count)
}

#[tokio::test]
async fn internal_and_metadata_receivers_are_refused_at_creation_and_delivery() {
    let app = spawn_app_with(|c| {
        c.webhook_allow_networks = vec![];
        c.webhook_retry_base_ms = 600_000;
    })
    .await;
    let (rx_port, connections) = counting_receiver().await;
    let own_port = app.base.rsplit(':').next().unwrap().to_string();
    for url in [
        "http://169.254.169.254/latest/meta-data/".to_string(),
        "http://[fe80::1]/hook".to_string(),
        "http://100.100.100.200/".to_string(),
        format!("http://[::ffff:127.0.0.1]:{own_port}/v1/robots"),
        format!("http://localhost.:{own_port}/v1/robots"),
        format!("http://127.0.0.1:{rx_port}/hook"),
        "http://10.0.0.5/hook".to_string(),
    ] {
        let r = app
            .post_json(
                "/v1/webhooks",
                &json!({"url": url, "events": ["job.finished"]}),
            )
            .await;
        assert_eq!(r.status(), 422, "{url}");
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], "url", "{problem}");
    }

    // A name is checked when it is resolved, at delivery: `localhost`
    // resolves to loopback, which this server does not allow.
    let s = store::connect(&app.database_url).await.unwrap();
    s.create_webhook(&WebhookRecord {
        id: "wh-internal".into(),
        url: format!("http://localhost:{rx_port}/hook"),
        events: vec!["job.finished".into()],
        secret: "whsec_test".into(),
        created_at: "2026-01-01T00:00:00Z".into(),
    })
    .await
    .unwrap();
    let session = app.robot_and_session("WT-1").await;
    app.add_point_poses(&session, 3, 1).await;
    let job = start_calibration(&app.client, &app.base, &session).await;
    let done = wait_job_at(&app.client, &app.base, &job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    // The attempt is made (and fails) without a connection to the receiver.
    let start = Instant::now();
    loop {
        let hook = app.get_ok("/v1/webhooks/wh-internal").await;
        let counts = &hook["deliveries"];
        assert_eq!(counts["delivered"], 0, "{hook}");
        if counts["pending"].as_i64().unwrap() >= 1 && start.elapsed() > Duration::from_secs(2) {
            break;
        }
        assert!(start.elapsed() < WAIT, "{hook}");
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
    assert_eq!(
        connections.load(Ordering::SeqCst),
        0,
        "the receiver was called"
    );
}
