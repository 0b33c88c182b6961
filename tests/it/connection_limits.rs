//! The connection table with small limits: idle connections displaced at
//! the cap, busy ones refused, the reserved lane, per-address limits, and
//! event streams counted apart.

use std::net::SocketAddr;
use std::time::Duration;

use robocal::domain::Scope;
use robocal::listen::registry::DISPLACE_GRACE;
use serde_json::Value;
use tokio::io::AsyncWriteExt;
use tokio::net::{TcpSocket, TcpStream};

use crate::raw_http::*;
use crate::support::*;
use crate::tokens::stored_token;

const WAIT: Duration = Duration::from_secs(4);
/// Time for the server to accept a connection just opened.
const SETTLE: Duration = Duration::from_millis(200);

fn healthz(base: &str) -> Vec<u8> {
    format!("GET /healthz HTTP/1.1\r\nHost: {}\r\n\r\n", addr_of(base)).into_bytes()
}

/// A request whose body never comes: it keeps its connection in a request.
async fn busy_connection(base: &str, token: Option<&str>) -> TcpStream {
    let mut s = connect(base).await;
    let auth = token.map_or(String::new(), |t| format!("Authorization: Bearer {t}\r\n"));
    s.write_all(
        format!(
            "PUT /v1/robots/B HTTP/1.1\r\nHost: {}\r\n{auth}Content-Type: application/json\r\nContent-Length: 100\r\n\r\n{{",
            addr_of(base)
        )
        .as_bytes(),
    )
    .await
    .unwrap();
    s
}

async fn connect_from(base: &str, last_octet: u8) -> TcpStream {
    let socket = TcpSocket::new_v4().unwrap();
    socket
        .bind(SocketAddr::from(([127, 0, 0, last_octet], 0)))
        .unwrap();
    socket
        .connect(addr_of(base).parse().unwrap())
        .await
        .unwrap()
}

async fn ask(stream: &mut TcpStream, request: &[u8]) -> RawResponse {
    stream.write_all(request).await.unwrap();
    read_response(stream, WAIT).await.expect("an answer")
}

#[tokio::test]
async fn at_the_cap_idle_connections_make_room_and_busy_ones_do_not() {
    let app = spawn_app_with(|c| {
        c.max_connections = 2;
        c.reserved_connections = 0;
    })
    .await;
    // Two idle connections fill the cap; a third displaces the older one
    // (before, it was refused 503 while they sat there).
    let mut idle = vec![connect(&app.base).await];
    tokio::time::sleep(SETTLE).await;
    idle.push(connect(&app.base).await);
    // Past the grace a new connection has for its first request.
    tokio::time::sleep(DISPLACE_GRACE).await;
    let mut third = connect(&app.base).await;
    assert_eq!(ask(&mut third, &healthz(&app.base)).await.status, 200);
    assert!(closed_within(&mut idle[0], WAIT).await, "oldest idle kept");
    drop(idle);
    drop(third);
    tokio::time::sleep(SETTLE).await;
    // Two connections in requests are never displaced: a third is refused.
    let _busy = [
        busy_connection(&app.base, None).await,
        busy_connection(&app.base, None).await,
    ];
    tokio::time::sleep(SETTLE).await;
    let refused = exchange(&app.base, &healthz(&app.base)).await;
    assert_eq!(refused.status, 503, "{refused:?}");
    assert!(refused.header("retry-after").is_some());
    let problem = refused.problem();
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("--max-connections"),
        "{problem}"
    );
}

#[tokio::test]
async fn the_reserved_lane_serves_probes_and_tokens_only() {
    let app = spawn_app_with(|c| {
        c.max_connections = 1;
        c.reserved_connections = 1;
    })
    .await;
    let token = stored_token(&app, Scope::Write, None).await;
    let _busy = busy_connection(&app.base, Some(&token)).await;
    tokio::time::sleep(SETTLE).await;
    let mut reserved = connect(&app.base).await;
    assert_eq!(ask(&mut reserved, &healthz(&app.base)).await.status, 200);
    let authed = format!(
        "GET /v1/robots HTTP/1.1\r\nHost: {}\r\nAuthorization: Bearer {token}\r\n\r\n",
        addr_of(&app.base)
    );
    assert_eq!(ask(&mut reserved, authed.as_bytes()).await.status, 200);
    let public = format!(
        "GET /openapi.json HTTP/1.1\r\nHost: {}\r\n\r\n",
        addr_of(&app.base)
    );
    let refused = ask(&mut reserved, public.as_bytes()).await;
    assert_eq!(refused.status, 503, "{refused:?}");
    assert!(refused.problem()["detail"]
        .as_str()
        .unwrap()
        .contains("--reserved-connections"));
}

#[tokio::test]
async fn one_address_holds_at_most_its_share() {
    let app = spawn_app_with(|c| c.max_connections_per_address = 2).await;
    let _held = [
        connect_from(&app.base, 2).await,
        connect_from(&app.base, 2).await,
    ];
    tokio::time::sleep(SETTLE).await;
    let mut over = connect_from(&app.base, 2).await;
    let refused = ask(&mut over, &healthz(&app.base)).await;
    assert_eq!(refused.status, 503, "{refused:?}");
    assert!(refused.problem()["detail"]
        .as_str()
        .unwrap()
        .contains("--max-connections-per-address"));
    let mut other = connect_from(&app.base, 3).await;
    assert_eq!(ask(&mut other, &healthz(&app.base)).await.status, 200);
}

#[tokio::test]
async fn event_streams_are_counted_apart_and_limited_per_address() {
    let app = spawn_app_with(|c| {
        c.test_stage_delay_ms = 10_000;
        c.max_connections = 1;
        c.reserved_connections = 0;
        c.max_event_streams_per_address = 1;
    })
    .await;
    let session = app.robot_and_session("S1").await;
    app.add_point_poses(&session, 3, 1).await;
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/calibrations")))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 202);
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let events = format!(
        "GET /v1/jobs/{job}/events HTTP/1.1\r\nHost: {}\r\n\r\n",
        addr_of(&app.base)
    );
    // The test client's keep-alive connection may now be displaced.
    tokio::time::sleep(DISPLACE_GRACE).await;
    let mut stream = connect(&app.base).await;
    stream.write_all(events.as_bytes()).await.unwrap();
    tokio::time::sleep(SETTLE).await;
    // The stream left the one connection place: a request still gets in
    // (it used to be refused 503) and is not displaced by the next.
    let mut second = connect(&app.base).await;
    let over = ask(&mut second, events.as_bytes()).await;
    assert_eq!(over.status, 429, "{over:?}");
    assert!(over.problem()["detail"]
        .as_str()
        .unwrap()
        .contains("--max-event-streams-per-address"));
    assert!(!closed_within(&mut stream, SETTLE).await, "stream closed");
}
