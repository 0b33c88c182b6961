//! Header-read and body-idle timeouts and the connection cap, with raw
//! clients that send slowly or nothing (short limits configured here).

use std::time::{Duration, Instant};

use tokio::io::{AsyncReadExt, AsyncWriteExt};

use crate::raw_http::*;
use crate::support::*;

/// Longest the server may take to act on a 1 s limit.
const GRACE: Duration = Duration::from_secs(4);

#[tokio::test]
async fn a_partial_request_head_is_dropped_after_the_header_timeout() {
    let app = spawn_app_with(|c| c.header_timeout_secs = 1).await;
    let mut slow = connect(&app.base).await;
    slow.write_all(
        format!(
            "GET /healthz HTTP/1.1\r\nHost: {}\r\nX-Slow: ",
            crate::raw_http::addr_of(&app.base)
        )
        .as_bytes(),
    )
    .await
    .unwrap();
    let start = Instant::now();
    assert!(
        closed_within(&mut slow, GRACE).await,
        "partial head held open"
    );
    assert!(start.elapsed() >= Duration::from_millis(900));
    // A silent connection (slowloris opening) is dropped as well.
    let mut silent = connect(&app.base).await;
    assert!(
        closed_within(&mut silent, GRACE).await,
        "silent connection held open"
    );
    // And normal requests are still served.
    assert_eq!(app.get("/healthz").await.status(), 200);
}

#[tokio::test]
async fn a_body_that_stops_sending_is_answered_408() {
    let app = spawn_app_with(|c| c.body_idle_timeout_secs = 1).await;
    let body = serde_json::to_vec(&robot_body()).unwrap();
    let mut trickle = connect(&app.base).await;
    let head = format!(
        "PUT /v1/robots/T1 HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len(), host = crate::raw_http::addr_of(&app.base));
    trickle.write_all(head.as_bytes()).await.unwrap();
    trickle.write_all(&body[..10]).await.unwrap();
    let start = Instant::now();
    let answer = read_response(&mut trickle, GRACE)
        .await
        .expect("an answer before the grace period");
    assert!(start.elapsed() >= Duration::from_millis(900));
    assert_eq!(answer.status, 408, "{answer:?}");
    let problem = answer.problem();
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("--body-idle-timeout-secs"),
        "{problem}"
    );
    assert!(closed_within(&mut trickle, GRACE).await);
    // Nothing was created.
    assert_eq!(app.get("/v1/robots/T1").await.status(), 404);
}

#[tokio::test]
async fn a_slow_but_steady_body_is_not_timed_out() {
    // Above the minimum rate (100 bytes/s), never silent for a second.
    let app = spawn_app_with(|c| {
        c.body_idle_timeout_secs = 1;
        c.min_body_bytes_per_sec = 100;
    })
    .await;
    let body = serde_json::to_vec(&robot_body()).unwrap();
    let mut slow = connect(&app.base).await;
    let head = format!(
        "PUT /v1/robots/T2 HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len(), host = crate::raw_http::addr_of(&app.base));
    slow.write_all(head.as_bytes()).await.unwrap();
    let thirds = body.len() / 3;
    for part in [
        &body[..thirds],
        &body[thirds..2 * thirds],
        &body[2 * thirds..],
    ] {
        tokio::time::sleep(Duration::from_millis(600)).await;
        slow.write_all(part).await.unwrap();
    }
    let answer = read_response(&mut slow, GRACE).await.expect("an answer");
    assert_eq!(answer.status, 201, "{answer:?}");
}

#[tokio::test]
async fn a_body_trickled_under_the_minimum_rate_is_answered_408() {
    // Before the rate, every byte restarted the idle timer: a body at one
    // byte a second held its connection forever.
    let app = spawn_app_with(|c| {
        c.body_idle_timeout_secs = 1;
        c.min_body_bytes_per_sec = 100;
    })
    .await;
    let mut trickle = connect(&app.base).await;
    let head = format!(
        "PUT /v1/robots/T3 HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\nContent-Length: 10000\r\n\r\n",
        host = crate::raw_http::addr_of(&app.base));
    trickle.write_all(head.as_bytes()).await.unwrap();
    let start = Instant::now();
    let (mut reader, mut writer) = trickle.into_split();
    let sender = tokio::spawn(async move {
        loop {
            tokio::time::sleep(Duration::from_millis(200)).await;
            if writer.write_all(b" ").await.is_err() {
                break;
            }
        }
    });
    let mut answer = Vec::new();
    let _ = tokio::time::timeout(GRACE, reader.read_to_end(&mut answer)).await;
    sender.abort();
    let text = String::from_utf8_lossy(&answer).to_string();
    assert!(start.elapsed() >= Duration::from_millis(900));
    assert!(text.starts_with("HTTP/1.1 408 "), "{text:?}");
    assert!(text.contains("--min-body-bytes-per-sec"), "{text}");
    assert_eq!(app.get("/v1/robots/T3").await.status(), 404);
}
