//! A webhook receiver that hangs, and one that answers 500, never slow the
//! API (issue 17, "Bad input"): deliveries run in the outbox loop, off
//! every request's path, with their own timeout and retries.
//!
//! Asserted on completion, not on durations: while the hanging receiver
//! holds its deliveries open (the webhook timeout is longer than the whole
//! test) and the failing one keeps being retried, the API answers reads,
//! writes and a whole calibration job, each under a client timeout far
//! shorter than the hang.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use axum::extract::State;
use axum::http::StatusCode;
use serde_json::{json, Value};

use crate::support::*;

/// The webhook timeout of this test's server: longer than the test, so a
/// hung delivery is still open when the API's answers are checked.
const HANG_TIMEOUT_SECS: u64 = 600;
/// A bound on every wait and on each API request: far under the hang.
const WAIT: Duration = Duration::from_secs(60);
/// Hanging hooks: a few, each holding one delivery open.
const HANGING_HOOKS: usize = 3;
/// Attempts the failing receiver must see: the first and two retries.
const FAILED_ATTEMPTS: usize = 3;

/// Requests that reached a receiver.
#[derive(Clone, Default)]
struct Arrivals(Arc<AtomicUsize>);

async fn hang(State(n): State<Arrivals>) -> StatusCode {
    n.0.fetch_add(1, Ordering::SeqCst);
    std::future::pending::<()>().await;
    StatusCode::OK
}

async fn fail(State(n): State<Arrivals>) -> StatusCode {
    n.0.fetch_add(1, Ordering::SeqCst);
    StatusCode::INTERNAL_SERVER_ERROR
}

/// Serves `handler` on a loopback port; returns the hook URL.
async fn receiver<H, T>(handler: H, arrivals: &Arrivals) -> String
where
    H: axum::handler::Handler<T, Arrivals>,
    T: 'static,
{
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let app = axum::Router::new()
        .route("/hook", axum::routing::post(handler))
        .with_state(arrivals.clone());
    tokio::spawn(async move {
        let _ = axum::serve(listener, app).await;
    });
    format!("http://{addr}/hook")
}

async fn until(what: &str, ok: impl Fn() -> bool) {
    let start = Instant::now();
    while !ok() {
        assert!(start.elapsed() < WAIT, "{what}");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

async fn calibrate(app: &TestApp, client: &reqwest::Client, serial: &str) -> Value {
    let session = app.robot_and_session(serial).await;
    app.add_point_poses(&session, 3, 1).await;
    let job = start_calibration(client, &app.base, &session).await;
    app.wait_job(&job, WAIT, is_finished).await
}

/// Every webhook with its delivery counts.
async fn webhooks(app: &TestApp, client: &reqwest::Client) -> Value {
    let r = client.get(app.url("/v1/webhooks")).send().await.unwrap();
    assert_eq!(r.status(), 200);
    r.json().await.unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hanging_or_failing_receiver_never_slows_the_api() {
    let app = spawn_app_with(|c| {
        c.webhook_timeout_secs = HANG_TIMEOUT_SECS;
        c.webhook_retry_base_ms = 50;
    })
    .await;
    let (hung, failed) = (Arrivals::default(), Arrivals::default());
    let hang_url = receiver(hang, &hung).await;
    let fail_url = receiver(fail, &failed).await;
    for url in std::iter::repeat_n(&hang_url, HANGING_HOOKS).chain([&fail_url]) {
        let r = app
            .post_json(
                "/v1/webhooks",
                &json!({"url": url, "events": ["job.finished"]}),
            )
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    // A bounded client: an API request waiting on a hung delivery would
    // fail here long before the delivery's own timeout.
    let client = reqwest::Client::builder().timeout(WAIT).build().unwrap();

    let first = calibrate(&app, &client, "WH-SLOW-1").await;
    assert_eq!(first["state"], "succeeded", "{first}");
    until("every hanging hook's delivery reached its receiver", || {
        hung.0.load(Ordering::SeqCst) >= HANGING_HOOKS
    })
    .await;
    until(
        "the failing receiver is retried off the request path",
        || failed.0.load(Ordering::SeqCst) >= FAILED_ATTEMPTS,
    )
    .await;

    // The deliveries hang (or keep failing): the API still answers.
    let robots = client.get(app.url("/v1/robots")).send().await.unwrap();
    assert_eq!(robots.status(), 200);
    let hooks = webhooks(&app, &client).await;
    let pending: i64 = hooks["items"]
        .as_array()
        .unwrap_or_else(|| panic!("{hooks}"))
        .iter()
        .map(|h| h["deliveries"]["pending"].as_i64().unwrap_or(0))
        .sum();
    assert_eq!(
        pending as usize,
        HANGING_HOOKS + 1,
        "nothing delivered yet, nothing given up: {hooks}"
    );
    let second = calibrate(&app, &client, "WH-SLOW-2").await;
    assert_eq!(second["state"], "succeeded", "{second}");
    // The hung requests are still open: the answers above came while they hung.
    let hooks = webhooks(&app, &client).await;
    assert!(
        hooks["items"]
            .as_array()
            .unwrap()
            .iter()
            .all(|h| h["deliveries"]["delivered"].as_i64() == Some(0)),
        "{hooks}"
    );
}
