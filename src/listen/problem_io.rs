//! hyper answers requests it cannot parse (bad request line or header
//! syntax: 400; request target over 65534 bytes: 414; head over the read
//! buffer: 431) itself, with an empty body, before the application sees
//! anything, and offers no hook to change that answer. [`ProblemIo`] sits
//! between hyper and the socket and replaces exactly those answers, which the
//! application never produces (its errors always carry a problem+json body),
//! with the same status and a problem+json body, so every error of the
//! service is problem+json.

use std::io;
use std::pin::Pin;
use std::task::{ready, Context, Poll};

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};

use crate::api::error::{Problem, PROBLEM_JSON};

/// A connection's socket with hyper's empty automatic error answers replaced.
pub struct ProblemIo<T> {
    inner: T,
    /// A replacement answer and how much of it has been written.
    pending: Option<(Vec<u8>, usize)>,
    /// The largest request head the server reads, for the 431 message.
    max_head_bytes: usize,
}

impl<T> ProblemIo<T> {
    pub fn new(inner: T, max_head_bytes: usize) -> ProblemIo<T> {
        ProblemIo {
            inner,
            pending: None,
            max_head_bytes,
        }
    }
}

impl<T: AsyncWrite + Unpin> ProblemIo<T> {
    fn poll_pending(&mut self, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        while let Some((bytes, written)) = &mut self.pending {
            if *written == bytes.len() {
                self.pending = None;
                break;
            }
            let n = ready!(Pin::new(&mut self.inner).poll_write(cx, &bytes[*written..]))?;
            if n == 0 {
                return Poll::Ready(Err(io::ErrorKind::WriteZero.into()));
            }
            *written += n;
        }
        Poll::Ready(Ok(()))
    }
}

impl<T: AsyncRead + Unpin> AsyncRead for ProblemIo<T> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_read(cx, buf)
    }
}

impl<T: AsyncWrite + Unpin> AsyncWrite for ProblemIo<T> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        let this = &mut *self;
        ready!(this.poll_pending(cx))?;
        if let Some(replacement) = replacement(buf, this.max_head_bytes) {
            this.pending = Some((replacement, 0));
            // Whatever is not written now is written by the next write or flush.
            let _ = this.poll_pending(cx)?;
            return Poll::Ready(Ok(buf.len()));
        }
        Pin::new(&mut this.inner).poll_write(cx, buf)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        ready!(self.poll_pending(cx))?;
        Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        ready!(self.poll_pending(cx))?;
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

/// The problem+json answer standing for `head` when it is one of hyper's
/// empty automatic error answers.
fn replacement(head: &[u8], max_head_bytes: usize) -> Option<Vec<u8>> {
    let text = std::str::from_utf8(head).ok()?;
    let status_line = text
        .strip_prefix("HTTP/1.1 ")
        .or_else(|| text.strip_prefix("HTTP/1.0 "))?;
    let code: u16 = status_line.get(..3)?.parse().ok()?;
    let (title, detail) = match code {
        400 => (
            "Bad Request",
            "the request is not valid HTTP/1.1 (request line or header syntax)".to_string(),
        ),
        414 => (
            "URI Too Long",
            "the request target is longer than 65534 bytes".to_string(),
        ),
        431 => (
            "Request Header Fields Too Large",
            format!("the request line and headers exceed {max_head_bytes} bytes, or there are over 100 headers"),
        ),
        _ => return None,
    };
    let lower = text.to_ascii_lowercase();
    let empty = lower.contains("\r\ncontent-length: 0\r\n") && lower.ends_with("\r\n\r\n");
    if !empty {
        return None;
    }
    let problem = Problem {
        problem_type: "urn:robocal:problem:malformed-http".into(),
        title: title.into(),
        status: code,
        detail,
        errors: vec![],
        controller: None,
    };
    let body = serde_json::to_vec(&problem).ok()?;
    let mut out = format!(
        "HTTP/1.1 {code} {title}\r\ncontent-type: {PROBLEM_JSON}\r\ncontent-length: {}\r\nconnection: close\r\n\r\n",
        body.len()
    )
    .into_bytes();
    out.extend_from_slice(&body);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_empty_automatic_answers_are_replaced() {
        let auto =
            b"HTTP/1.1 431 Request Header Fields Too Large\r\ncontent-length: 0\r\ndate: x\r\n\r\n";
        let out = String::from_utf8(replacement(auto, 8192).unwrap()).unwrap();
        assert!(out.starts_with("HTTP/1.1 431 "), "{out}");
        assert!(out.contains("application/problem+json"), "{out}");
        assert!(out.contains("\"status\":431"), "{out}");
        let app = b"HTTP/1.1 400 Bad Request\r\ncontent-type: application/problem+json\r\ncontent-length: 90\r\n\r\n";
        assert!(replacement(app, 8192).is_none());
        let ok = b"HTTP/1.1 200 OK\r\ncontent-length: 0\r\n\r\n";
        assert!(replacement(ok, 8192).is_none());
    }
}
