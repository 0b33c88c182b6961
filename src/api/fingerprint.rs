//! The fingerprint of a request under an `Idempotency-Key`: SHA-256 over its
//! method, path and query, media type and body, so a key reused for a
//! different request is told apart from a retry. The body is hashed as the
//! handler streams it ([`BodyTap`]), never buffered; a multipart body is
//! hashed with its boundary blanked out, because a client library draws a new
//! random boundary for every attempt of the same form.

use std::pin::Pin;
use std::sync::{Arc, Mutex, PoisonError};
use std::task::{ready, Context, Poll};
use std::time::Duration;

use axum::body::{Body, Bytes, HttpBody};
use axum::http::header::CONTENT_TYPE;
use axum::http::request::Parts;
use http_body::Frame;
use sha2::{Digest, Sha256};

/// What stands for every occurrence of the multipart boundary in the hash.
const BOUNDARY_TOKEN: &[u8] = b"\0boundary\0";

/// Streaming SHA-256 of one request.
pub struct Fingerprinter {
    hasher: Sha256,
    /// The multipart boundary, when the body is multipart.
    boundary: Option<Vec<u8>>,
    /// Tail of the body not hashed yet: it may hold the start of a boundary.
    pending: Vec<u8>,
}

impl Fingerprinter {
    pub fn new(parts: &Parts) -> Fingerprinter {
        let content_type = parts
            .headers
            .get(CONTENT_TYPE)
            .and_then(|v| v.to_str().ok())
            .unwrap_or("");
        let mut params = content_type.split(';');
        let media = params.next().unwrap_or("").trim().to_ascii_lowercase();
        let boundary = if media.starts_with("multipart/") {
            params
                .filter_map(|p| p.trim().split_once('='))
                .find(|(k, _)| k.trim().eq_ignore_ascii_case("boundary"))
                .map(|(_, v)| v.trim().trim_matches('"').as_bytes().to_vec())
                .filter(|b| !b.is_empty())
        } else {
            None
        };
        let mut hasher = Sha256::new();
        let target = parts
            .uri
            .path_and_query()
            .map(|p| p.as_str())
            .unwrap_or("/");
        for field in [parts.method.as_str(), target, &media] {
            hasher.update(field.as_bytes());
            hasher.update([0]);
        }
        Fingerprinter {
            hasher,
            boundary,
            pending: Vec::new(),
        }
    }

    pub fn update(&mut self, chunk: &[u8]) {
        let Some(boundary) = &self.boundary else {
            self.hasher.update(chunk);
            return;
        };
        self.pending.extend_from_slice(chunk);
        let mut start = 0;
        while let Some(i) = memchr::memmem::find(&self.pending[start..], boundary) {
            self.hasher.update(&self.pending[start..start + i]);
            self.hasher.update(BOUNDARY_TOKEN);
            start += i + boundary.len();
        }
        // The last boundary.len() - 1 bytes may be the start of a boundary.
        let keep_from = start.max(self.pending.len().saturating_sub(boundary.len() - 1));
        self.hasher.update(&self.pending[start..keep_from]);
        self.pending.drain(..keep_from);
    }

    /// The fingerprint, hex.
    pub fn finish(mut self) -> String {
        self.hasher.update(&self.pending);
        hex::encode(self.hasher.finalize())
    }
}

/// How far the body of a request under a key was read.
pub enum BodyRead {
    /// To its end: the request's fingerprint.
    Complete(String),
    /// Not to its end (the handler answered without reading it all).
    Incomplete,
    /// Reading it failed (the client went away, timed out or sent garbage).
    Failed,
}

struct Tap {
    body: Option<Body>,
    fingerprint: Option<Fingerprinter>,
    state: TapState,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum TapState {
    Reading,
    Complete,
    Failed,
}

/// Fingerprints a request body while the handler reads it. The handler gets
/// [`BodyTap::body`]; afterwards [`BodyTap::finish`] says how far it was read.
#[derive(Clone)]
pub struct BodyTap(Arc<Mutex<Tap>>);

impl BodyTap {
    pub fn new(body: Body, fingerprint: Fingerprinter) -> BodyTap {
        let state = if body.is_end_stream() {
            TapState::Complete
        } else {
            TapState::Reading
        };
        BodyTap(Arc::new(Mutex::new(Tap {
            body: Some(body),
            fingerprint: Some(fingerprint),
            state,
        })))
    }

    /// The body to hand to the handler.
    pub fn body(&self) -> Body {
        Body::new(TapBody(self.0.clone()))
    }

    /// Reads what the handler left of the body, up to `max_bytes` and for at
    /// most `max_wait` (a trailing multipart epilogue, not a whole upload),
    /// and says how far the body was read.
    pub async fn finish(self, max_bytes: usize, max_wait: Duration) -> BodyRead {
        let mut rest = TapBody(self.0.clone());
        let drain = async {
            let mut drained = 0usize;
            while drained <= max_bytes {
                match std::future::poll_fn(|cx| Pin::new(&mut rest).poll_frame(cx)).await {
                    Some(Ok(frame)) => {
                        drained += frame.data_ref().map_or(0, Bytes::len);
                    }
                    _ => break,
                }
            }
        };
        let _ = tokio::time::timeout(max_wait, drain).await;
        let mut tap = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        match tap.state {
            TapState::Complete => match tap.fingerprint.take() {
                Some(f) => BodyRead::Complete(f.finish()),
                None => BodyRead::Failed,
            },
            TapState::Reading => BodyRead::Incomplete,
            TapState::Failed => BodyRead::Failed,
        }
    }
}

struct TapBody(Arc<Mutex<Tap>>);

impl HttpBody for TapBody {
    type Data = Bytes;
    type Error = axum::Error;

    fn poll_frame(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, axum::Error>>> {
        let mut guard = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        let tap = &mut *guard;
        let Some(body) = tap.body.as_mut() else {
            return Poll::Ready(None);
        };
        let polled = ready!(Pin::new(&mut *body).poll_frame(cx));
        match &polled {
            Some(Ok(frame)) => {
                if let (Some(data), Some(f)) = (frame.data_ref(), tap.fingerprint.as_mut()) {
                    f.update(data);
                }
                if body.is_end_stream() {
                    tap.state = TapState::Complete;
                }
            }
            Some(Err(_)) => {
                tap.state = TapState::Failed;
                tap.body = None;
            }
            None => {
                if tap.state == TapState::Reading {
                    tap.state = TapState::Complete;
                }
                tap.body = None;
            }
        }
        Poll::Ready(polled)
    }

    fn is_end_stream(&self) -> bool {
        let tap = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        tap.body.as_ref().is_none_or(|b| b.is_end_stream())
    }

    fn size_hint(&self) -> http_body::SizeHint {
        let tap = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        tap.body
            .as_ref()
            .map_or_else(|| http_body::SizeHint::with_exact(0), |b| b.size_hint())
    }
}

/// Fingerprints a whole body that no handler reads (a replay is checked
/// against the stored request); `None` when it cannot be read to its end
/// within `max_bytes`.
pub async fn digest_body(
    body: Body,
    mut fingerprint: Fingerprinter,
    max_bytes: u64,
) -> Result<String, DigestError> {
    use futures_util::StreamExt;
    let mut stream = body.into_data_stream();
    let mut total = 0u64;
    while let Some(chunk) = stream.next().await {
        let chunk = chunk.map_err(|e| DigestError::Read(e.to_string()))?;
        total += chunk.len() as u64;
        if total > max_bytes {
            return Err(DigestError::TooLarge);
        }
        fingerprint.update(&chunk);
    }
    Ok(fingerprint.finish())
}

#[derive(Debug)]
pub enum DigestError {
    Read(String),
    TooLarge,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parts(content_type: &str) -> Parts {
        let (parts, _) = axum::http::Request::post("/v1/x?a=1")
            .header(CONTENT_TYPE, content_type)
            .body(())
            .unwrap()
            .into_parts();
        parts
    }

    fn digest(content_type: &str, chunks: &[&[u8]]) -> String {
        let mut f = Fingerprinter::new(&parts(content_type));
        for c in chunks {
            f.update(c);
        }
        f.finish()
    }

    #[test]
    fn multipart_boundaries_do_not_change_the_fingerprint_however_chunked() {
        let body = |b: &str| format!("--{b}\r\nname=x\r\n\r\n123\r\n--{b}--\r\n").into_bytes();
        let a = body("AAAA1111");
        let b = body("bbbbbbbbbbbbbbbbbbbbbbbb");
        let whole = digest("multipart/form-data; boundary=AAAA1111", &[&a]);
        let split = digest(
            "multipart/form-data; boundary=\"bbbbbbbbbbbbbbbbbbbbbbbb\"",
            &[&b[..5], &b[5..7], &b[7..30], &b[30..]],
        );
        assert_eq!(whole, split);
        let other = body("AAAA1111")
            .iter()
            .map(|&c| if c == b'3' { b'4' } else { c })
            .collect::<Vec<_>>();
        assert_ne!(
            whole,
            digest("multipart/form-data; boundary=AAAA1111", &[&other])
        );
    }

    #[test]
    fn bodies_media_types_and_targets_change_the_fingerprint() {
        let json = digest("application/json", &[b"{\"a\":1}"]);
        assert_eq!(json, digest("application/json", &[b"{\"a\"", b":1}"]));
        assert_ne!(json, digest("application/json", &[b"{\"a\":2}"]));
        assert_ne!(json, digest("text/plain", &[b"{\"a\":1}"]));
    }
}
