//! Webhooks: bad input, signed delivery of `job.finished` to a local
//! receiver, retries after 500, and delivery across a kill -9 of the sender.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use axum::body::Bytes;
use axum::extract::State;
use axum::http::{HeaderMap, StatusCode};
use hmac::{Hmac, Mac};
use serde_json::{json, Value};
use sha2::Sha256;

use robocal::domain::{ReleaseStatus, Scope};

use super::fleet_page::read_token;
use crate::support::*;

const WAIT: Duration = Duration::from_secs(30);

/// One request the receiver got, and what it answered.
#[derive(Debug, Clone)]
struct Seen {
    event: String,
    delivery: String,
    signature: String,
    body: Vec<u8>,
    answered: u16,
}

/// A local webhook receiver: answers 500 to the first `fail_first`
/// requests, and to all while `fail_all`; 200 otherwise.
#[derive(Clone, Default)]
struct Receiver {
    seen: Arc<Mutex<Vec<Seen>>>,
    fail_first: Arc<AtomicUsize>,
    fail_all: Arc<AtomicBool>,
}

async fn receive(State(rx): State<Receiver>, headers: HeaderMap, body: Bytes) -> StatusCode {
    let failing = rx.fail_all.load(Ordering::SeqCst)
        || rx
            .fail_first
            .fetch_update(Ordering::SeqCst, Ordering::SeqCst, |n| n.checked_sub(1))
            .is_ok();
    let status = if failing {
        StatusCode::INTERNAL_SERVER_ERROR
    } else {
        StatusCode::OK
    };
    let header = |name: &str| {
        headers
            .get(name)
            .and_then(|v| v.to_str().ok())
            .unwrap_or_default()
            .to_string()
    };
    rx.seen.lock().unwrap().push(Seen {
        event: header("x-robocal-event"),
        delivery: header("x-robocal-delivery"),
        signature: header("x-robocal-signature"),
        body: body.to_vec(),
        answered: status.as_u16(),
    });
    status
}

impl Receiver {
    /// Serves on a loopback port; returns the hook URL.
    async fn start(&self) -> String {
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        let app = axum::Router::new()
            .route("/hook", axum::routing::post(receive))
            .with_state(self.clone());
        tokio::spawn(async move {
            let _ = axum::serve(listener, app).await;
        });
        format!("http://{addr}/hook")
    }

    fn seen(&self) -> Vec<Seen> {
        self.seen.lock().unwrap().clone()
    }

    /// Waits until a request was answered 2xx; returns every request so far.
    async fn wait_delivered(&self) -> Vec<Seen> {
        let start = Instant::now();
        loop {
            let seen = self.seen();
            if seen.iter().any(|s| s.answered == 200) {
                return seen;
            }
            assert!(start.elapsed() < WAIT, "no delivery answered 2xx: {seen:?}");
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    }
}

fn verify(secret: &str, s: &Seen) {
    let mut mac = Hmac::<Sha256>::new_from_slice(secret.as_bytes()).unwrap();
    mac.update(&s.body);
    let hex = s
        .signature
        .strip_prefix("sha256=")
        .unwrap_or_else(|| panic!("signature header {:?}", s.signature));
    mac.verify_slice(&hex::decode(hex).unwrap())
        .expect("the signature is the HMAC-SHA256 of the body under the secret");
}

async fn create_hook(c: &reqwest::Client, base: &str, url: &str) -> (String, String) {
    create_hook_for(c, base, url, "job.finished").await
}

async fn create_hook_for(
    c: &reqwest::Client,
    base: &str,
    url: &str,
    event: &str,
) -> (String, String) {
    let r = c
        .post(format!("{base}/v1/webhooks"))
        .json(&json!({ "url": url, "events": [event] }))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let v: Value = r.json().await.unwrap();
    let secret = v["secret"].as_str().unwrap().to_string();
    assert!(secret.starts_with("whsec_"), "{v}");
    (v["id"].as_str().unwrap().to_string(), secret)
}

#[tokio::test]
async fn webhooks_refuse_bad_urls_and_events_and_need_admin() {
    let app = spawn_app().await;
    let field = |v: &Value| {
        v["errors"][0]["field"]
            .as_str()
            .unwrap_or_default()
            .to_string()
    };
    let cases = [
        (
            json!({"url": "ftp://example.com/x", "events": ["job.finished"]}),
            "url",
        ),
        (
            json!({"url": "not a url", "events": ["job.finished"]}),
            "url",
        ),
        (
            json!({"url": app.url("/hook"), "events": ["job.finished"]}),
            "url",
        ),
        (
            json!({"url": "http://user:pw@example.com/", "events": ["job.finished"]}),
            "url",
        ),
        (
            json!({"url": "https://example.com/", "events": ["job.started"]}),
            "events",
        ),
        (
            json!({"url": "https://example.com/", "events": []}),
            "events",
        ),
    ];
    for (body, named) in cases {
        let r = app.post_json("/v1/webhooks", &body).await;
        assert_eq!(r.status(), 422, "{body}");
        let problem: Value = r.json().await.unwrap();
        assert_eq!(field(&problem), named, "{body}: {problem}");
    }
    let (id, _) = create_hook(&app.client, &app.base, "https://hooks.example.com/r").await;
    let list: Value = app.get("/v1/webhooks").await.json().await.unwrap();
    assert_eq!(list["items"][0]["id"], id.as_str());
    assert!(
        list["items"][0].get("secret").is_none(),
        "secrets are shown once"
    );
    assert_eq!(list["items"][0]["deliveries"]["pending"], 0);

    let (write, _) = read_token(&app, Scope::Write).await;
    let (admin, _) = read_token(&app, Scope::Admin).await;
    let r = app
        .client
        .get(app.url("/v1/webhooks"))
        .bearer_auth(&write)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 403, "webhooks need admin");
    let del = |t: String| {
        app.client
            .delete(app.url(&format!("/v1/webhooks/{id}")))
            .bearer_auth(t)
            .send()
    };
    assert_eq!(del(admin.clone()).await.unwrap().status(), 204);
    assert_eq!(del(admin).await.unwrap().status(), 404);
}

#[tokio::test]
async fn job_finished_is_delivered_signed_and_retried_after_500() {
    let app = spawn_app_with(|c| c.webhook_retry_base_ms = 100).await;
    let rx = Receiver::default();
    rx.fail_first.store(2, Ordering::SeqCst);
    let url = rx.start().await;
    let (hook, secret) = create_hook(&app.client, &app.base, &url).await;

    let session = app.robot_and_session("WH-1").await;
    app.add_point_poses(&session, 3, 1).await;
    let job = start_calibration(&app.client, &app.base, &session).await;
    let done = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");

    let seen = rx.wait_delivered().await;
    assert_eq!(
        seen.iter().map(|s| s.answered).collect::<Vec<_>>(),
        [500, 500, 200],
        "two failures, then delivered once"
    );
    for s in &seen {
        verify(&secret, s);
        assert_eq!(s.event, "job.finished");
        assert_eq!(s.delivery, seen[0].delivery, "one event id on every retry");
        assert_eq!(s.body, seen[0].body);
    }
    let body: Value = serde_json::from_slice(&seen[0].body).unwrap();
    assert_eq!(body["type"], "job.finished");
    assert_eq!(body["id"], seen[0].delivery.as_str());
    assert_eq!(body["data"]["job_id"], job.as_str());
    assert_eq!(body["data"]["serial"], "WH-1");
    assert_eq!(body["data"]["state"], "succeeded");

    let start = Instant::now();
    loop {
        let v: Value = app
            .get(&format!("/v1/webhooks/{hook}"))
            .await
            .json()
            .await
            .unwrap();
        if v["deliveries"]["delivered"] == 1 {
            assert_eq!(v["deliveries"]["pending"], 0, "{v}");
            break;
        }
        assert!(start.elapsed() < WAIT, "{v}");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

#[tokio::test]
async fn set_approved_is_delivered_when_a_person_approves() {
    let app = spawn_app().await;
    let rx = Receiver::default();
    let url = rx.start().await;
    let (_, secret) = create_hook_for(&app.client, &app.base, &url, "set.approved").await;
    app.robot_and_session("WH-3").await;
    let store = robocal::store::connect(&app.database_url).await.unwrap();
    store
        .insert_parameter_set(
            "WH-3",
            None,
            &super::release_gate::set(1.0, ReleaseStatus::Candidate),
        )
        .await
        .unwrap();
    let r = app
        .post_json("/v1/robots/WH-3/parameter-sets/1/approve", &json!({}))
        .await;
    assert_eq!(r.status(), 200);
    let seen = rx.wait_delivered().await;
    assert_eq!(seen.len(), 1, "{seen:?}");
    verify(&secret, &seen[0]);
    let body: Value = serde_json::from_slice(&seen[0].body).unwrap();
    assert_eq!(body["type"], "set.approved", "{body}");
    assert_eq!(body["data"]["serial"], "WH-3");
    assert_eq!(body["data"]["version"], 1);
    assert_eq!(body["data"]["approved_by"], "anonymous");
}

#[tokio::test]
async fn webhook_events_survive_kill_9_of_the_sender() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let args = [
        "--database-url",
        &db,
        "--bind",
        "127.0.0.1:0",
        "--workers",
        "1",
        "--lease-secs",
        "1",
        "--poll-ms",
        "50",
        "--webhook-retry-base-ms",
        "100",
        // A delivery killed in flight is sent again after its claim (2 timeouts).
        "--webhook-timeout-secs",
        "1",
        // The test's receiver listens on loopback.
        "--webhook-allow-networks",
        "127.0.0.0/8",
    ];
    let rx = Receiver::default();
    rx.fail_all.store(true, Ordering::SeqCst);
    let url = rx.start().await;
    let c = reqwest::Client::new();
    let mut first = spawn_binary(&args, &[]);
    let (_, secret) = create_hook(&c, &first.base, &url).await;
    let (session, _, _) = robot_with_session(&c, &first.base, "WH-K9", 7, "cal").await;
    let job = start_calibration(&c, &first.base, &session).await;
    let done = wait_job_at(&c, &first.base, &job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    // The receiver is down (500) while the sender dies without any cleanup.
    let start = Instant::now();
    while rx.seen().is_empty() {
        assert!(start.elapsed() < WAIT, "no delivery attempt");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    first.child.kill().unwrap();
    first.child.wait().unwrap();

    rx.fail_all.store(false, Ordering::SeqCst);
    let mut second = spawn_binary(&args, &[]);
    let seen = rx.wait_delivered().await;
    let delivered = seen.iter().find(|s| s.answered == 200).unwrap();
    verify(&secret, delivered);
    let body: Value = serde_json::from_slice(&delivered.body).unwrap();
    assert_eq!(body["data"]["job_id"], job.as_str());
    assert!(seen.iter().all(|s| s.delivery == delivered.delivery));
    second.child.kill().unwrap();
    second.child.wait().unwrap();
}
