//! The body timeouts: a request body that sends nothing for
//! `--body-idle-timeout-secs` while its handler waits for it, or that has
//! not averaged `--min-body-bytes-per-sec` once it has been waited for that
//! long (a body trickled a byte at a time restarts no timer), fails the
//! handler's read, and the request is answered 408 (problem+json,
//! `Connection: close`) whatever the handler made of the failed read. Only
//! time spent waiting for the client counts, never the handler's own work
//! between reads, so a slow decode never times a fast client out.

use std::future::Future;
use std::pin::Pin;
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Arc;
use std::task::{Context, Poll};
use std::time::Duration;

use axum::body::{Body, Bytes, HttpBody};
use axum::extract::{Request, State};
use axum::http::{header, HeaderValue, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use http_body::Frame;
use tokio::time::{Instant, Sleep};

use super::error::ApiError;
use super::AppState;

pub async fn layer(State(state): State<AppState>, req: Request, next: Next) -> Response {
    let idle = state.config.body_idle_timeout();
    let min_rate = state.config.min_body_bytes_per_sec;
    let timed_out = Arc::new(AtomicU8::new(IN_TIME));
    let req = req.map(|body| {
        if body.is_end_stream() {
            body
        } else {
            Body::new(IdleBody {
                inner: body,
                idle,
                min_rate,
                sleep: Box::pin(tokio::time::sleep(idle)),
                waiting_since: None,
                waited: Duration::ZERO,
                received: 0,
                timed_out: timed_out.clone(),
            })
        }
    });
    let response = next.run(req).await;
    let detail = match timed_out.load(Ordering::Relaxed) {
        IDLE => format!(
            "the request body sent nothing for {} s (server option --body-idle-timeout-secs)",
            idle.as_secs()
        ),
        TOO_SLOW => format!(
            "the request body arrived slower than {min_rate} bytes/s after {} s \
             (server options --min-body-bytes-per-sec, --body-idle-timeout-secs)",
            idle.as_secs()
        ),
        _ => return response,
    };
    let mut response =
        ApiError::new(StatusCode::REQUEST_TIMEOUT, "body-timeout", detail).into_response();
    response
        .headers_mut()
        .insert(header::CONNECTION, HeaderValue::from_static("close"));
    response
}

/// How a body ended, shared with the layer.
const IN_TIME: u8 = 0;
const IDLE: u8 = 1;
const TOO_SLOW: u8 = 2;

/// A body whose reads fail once the client has been silent for `idle`, or
/// slower than `min_rate` on average after waiting `idle` in all.
struct IdleBody {
    inner: Body,
    idle: Duration,
    min_rate: u64,
    sleep: Pin<Box<Sleep>>,
    /// The handler has been waiting for the client since then (the timer runs).
    waiting_since: Option<Instant>,
    /// Time spent waiting for the client before `waiting_since`.
    waited: Duration,
    received: u64,
    timed_out: Arc<AtomicU8>,
}

impl IdleBody {
    /// Total waiting time at which `received` bytes fall under the minimum rate.
    fn rate_limit(&self) -> Duration {
        self.idle + Duration::from_secs_f64(self.received as f64 / self.min_rate as f64)
    }
}

impl HttpBody for IdleBody {
    type Data = Bytes;
    type Error = axum::Error;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, axum::Error>>> {
        let this = &mut *self;
        if let Poll::Ready(frame) = Pin::new(&mut this.inner).poll_frame(cx) {
            if let Some(since) = this.waiting_since.take() {
                this.waited += since.elapsed();
            }
            if let Some(Ok(data)) = frame.as_ref().map(|f| f.as_ref().map(Frame::data_ref)) {
                this.received += data.map_or(0, |d| d.len() as u64);
            }
            return Poll::Ready(frame);
        }
        let since = match this.waiting_since {
            Some(since) => since,
            None => {
                let now = Instant::now();
                this.waiting_since = Some(now);
                // Whichever comes first: silence, or falling under the rate.
                let slow_at = now + this.rate_limit().saturating_sub(this.waited);
                this.sleep.as_mut().reset((now + this.idle).min(slow_at));
                now
            }
        };
        if this.sleep.as_mut().poll(cx).is_ready() {
            let silent = since.elapsed() >= this.idle;
            let kind = if silent { IDLE } else { TOO_SLOW };
            this.timed_out.store(kind, Ordering::Relaxed);
            return Poll::Ready(Some(Err(axum::Error::new(format!(
                "the request body was {} (limit {} s, {} bytes/s)",
                if silent { "silent" } else { "too slow" },
                this.idle.as_secs(),
                this.min_rate
            )))));
        }
        Poll::Pending
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> http_body::SizeHint {
        self.inner.size_hint()
    }
}
