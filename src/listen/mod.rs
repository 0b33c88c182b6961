//! The HTTP/1.1 listener, in place of `axum::serve` (which offers no
//! settings): a header-read timeout (`--header-timeout-secs`, also the
//! keep-alive idle limit), a bounded request head, the connection table
//! ([`registry`]: a cap that displaces idle connections, a reserved lane,
//! per-address limits, event streams counted apart; a connection refused
//! is answered 503 and closed), hyper's own parse-error answers as
//! problem+json ([`problem_io`]), and a graceful shutdown that lets
//! requests in flight finish.

use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::watch;

use crate::api::error::{Problem, PROBLEM_JSON};

pub mod problem_io;
pub mod registry;
pub mod tls;
pub mod tracked;

use problem_io::ProblemIo;
use registry::{ConnLimits, ConnRef, Refusal, Registry};
use tracked::Tracked;

/// Largest request head (request line and headers), bytes; over it the
/// answer is 431. Above hyper's fixed 65534-byte limit of the request
/// target, so a long target gets its own 414.
pub const MAX_HEAD_BYTES: usize = 80 * 1024;
/// A failing `accept` (out of file descriptors) is retried after this pause.
const ACCEPT_ERROR_PAUSE: Duration = Duration::from_millis(100);
/// How long a refused connection is read from (and discarded) after its 503,
/// so the client reads the answer instead of a reset.
const REFUSAL_LINGER: Duration = Duration::from_millis(500);
const REFUSAL_DRAIN_BYTES: usize = 64 * 1024;
/// `Retry-After` of the 503 for a connection over the cap, seconds.
const REFUSAL_RETRY_AFTER_SECS: u64 = 1;

#[derive(Debug, Clone, Copy)]
pub struct Limits {
    pub header_timeout: Duration,
    pub connections: ConnLimits,
}

/// Serves `app` until `shutdown` turns true, then stops accepting, lets the
/// connections finish their requests in flight, and returns.
pub async fn serve(
    listener: TcpListener,
    app: Router,
    limits: Limits,
    tls: Option<Arc<rustls::ServerConfig>>,
    mut shutdown: watch::Receiver<bool>,
) {
    let acceptor = tls.map(tokio_rustls::TlsAcceptor::from);
    let registry = Registry::new(limits.connections);
    // Every connection task holds a receiver; `closed()` waits for them all.
    let (open_tx, open_rx) = watch::channel(());
    loop {
        let (stream, peer) = tokio::select! {
            accepted = listener.accept() => match accepted {
                Ok(pair) => pair,
                Err(e) => {
                    tracing::warn!(error = %e, "accept failed");
                    tokio::time::sleep(ACCEPT_ERROR_PAUSE).await;
                    continue;
                }
            },
            _ = stopped(&mut shutdown) => break,
        };
        let conn = match registry.admit(peer.ip()) {
            Ok(conn) => conn,
            Err(refusal) => {
                // Over TLS a plain-text 503 would be noise to the client: close.
                if acceptor.is_none() {
                    tokio::spawn(refuse(stream, refusal, limits.connections));
                }
                continue;
            }
        };
        let service = Tracked::new(app.clone(), conn.clone());
        let stop = shutdown.clone();
        let open = open_rx.clone();
        let acceptor = acceptor.clone();
        tokio::spawn(async move {
            match acceptor {
                None => serve_connection(stream, service, &conn, limits, stop).await,
                Some(acceptor) => {
                    // The handshake counts against the header timeout: a
                    // client that stalls in it is dropped like a slow head.
                    match tokio::time::timeout(limits.header_timeout, acceptor.accept(stream)).await
                    {
                        Ok(Ok(tls)) => serve_connection(tls, service, &conn, limits, stop).await,
                        Ok(Err(e)) => tracing::debug!(error = %e, "TLS handshake failed"),
                        Err(_) => tracing::debug!("TLS handshake timed out"),
                    }
                }
            }
            conn.leave();
            drop(open);
        });
    }
    drop(open_rx);
    open_tx.closed().await;
}

/// One connection, plain or TLS, until it closes or the server stops.
async fn serve_connection<S>(
    stream: S,
    service: Tracked,
    conn: &ConnRef,
    limits: Limits,
    mut stop: watch::Receiver<bool>,
) where
    S: AsyncRead + AsyncWrite + Unpin + Send + 'static,
{
    let io = TokioIo::new(ProblemIo::new(stream, MAX_HEAD_BYTES));
    let mut builder = hyper::server::conn::http1::Builder::new();
    builder
        .timer(TokioTimer::new())
        .header_read_timeout(limits.header_timeout)
        .max_header_size(MAX_HEAD_BYTES)
        // One buffer per write, so ProblemIo sees hyper's answers whole.
        .writev(false);
    let conn_ref = conn;
    let conn = builder.serve_connection(io, service);
    tokio::pin!(conn);
    let mut stopping = false;
    loop {
        tokio::select! {
            result = conn.as_mut() => {
                if let Err(e) = result {
                    tracing::debug!(error = %e, "connection ended with an error");
                }
                break;
            }
            _ = stopped(&mut stop), if !stopping => {
                stopping = true;
                conn.as_mut().graceful_shutdown();
            }
            // Displaced by a newer connection while idle: closed outright
            // (a request that started meanwhile still finishes).
            _ = conn_ref.evict.notified(), if !stopping => {
                if conn_ref.is_idle() {
                    break;
                }
                stopping = true;
                conn.as_mut().graceful_shutdown();
            }
        }
    }
}

/// Resolves once `shutdown` is (or has been) set; also if its sender is gone.
async fn stopped(shutdown: &mut watch::Receiver<bool>) {
    let _ = shutdown.wait_for(|stop| *stop).await;
}

/// Answers a refused connection with 503 problem+json and closes it.
async fn refuse(mut stream: TcpStream, refusal: Refusal, limits: ConnLimits) {
    let detail = match refusal {
        Refusal::PerAddress => format!(
            "this client address holds its maximum of {} connections \
             (server option --max-connections-per-address); retry later",
            limits.max_per_address
        ),
        Refusal::Full => format!(
            "the server holds its maximum of {} connections, all in requests \
             (server options --max-connections, --reserved-connections); retry later",
            limits.max_connections + limits.reserved_connections
        ),
    };
    let problem = Problem {
        problem_type: "urn:robocal:problem:too-many-connections".into(),
        title: "Service Unavailable".into(),
        status: 503,
        detail,
        errors: vec![],
        controller: None,
    };
    let body = serde_json::to_vec(&problem).unwrap_or_default();
    let head = format!(
        "HTTP/1.1 503 Service Unavailable\r\ncontent-type: {PROBLEM_JSON}\r\n\
         content-length: {}\r\nretry-after: {REFUSAL_RETRY_AFTER_SECS}\r\nconnection: close\r\n\r\n",
        body.len()
    );
    let answer = async {
        stream.write_all(head.as_bytes()).await?;
        stream.write_all(&body).await?;
        stream.shutdown().await?;
        let mut sink = vec![0u8; REFUSAL_DRAIN_BYTES];
        let _ = stream.read(&mut sink).await;
        Ok::<(), std::io::Error>(())
    };
    let _ = tokio::time::timeout(REFUSAL_LINGER, answer).await;
}
