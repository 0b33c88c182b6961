//! A raw HTTP/1.1 client over TCP, for what reqwest will not send or wait
//! for: broken request heads, slow and silent clients, many idle connections.

use std::time::Duration;

use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// A parsed answer: status, lower-cased head, body.
#[derive(Debug)]
pub struct RawResponse {
    pub status: u16,
    pub head: String,
    pub body: Vec<u8>,
}

impl RawResponse {
    pub fn header(&self, name: &str) -> Option<String> {
        let prefix = format!("{}:", name.to_ascii_lowercase());
        self.head
            .lines()
            .find_map(|l| l.strip_prefix(&prefix).map(|v| v.trim().to_string()))
    }

    /// The body as a problem document; panics unless the answer is problem+json.
    pub fn problem(&self) -> Value {
        assert_eq!(
            self.header("content-type").as_deref(),
            Some("application/problem+json"),
            "{} {}",
            self.head,
            String::from_utf8_lossy(&self.body)
        );
        let problem: Value = serde_json::from_slice(&self.body).unwrap();
        assert_eq!(problem["status"], self.status, "{problem}");
        problem
    }
}

pub fn addr_of(base: &str) -> String {
    base.trim_start_matches("http://").to_string()
}

pub async fn connect(base: &str) -> TcpStream {
    TcpStream::connect(addr_of(base)).await.unwrap()
}

/// Reads one answer (head and `content-length` body) within `wait`.
pub async fn read_response(stream: &mut TcpStream, wait: Duration) -> Option<RawResponse> {
    let read = async {
        let mut buf = Vec::new();
        let mut chunk = [0u8; 8192];
        loop {
            if let Some(end) = find(&buf, b"\r\n\r\n") {
                let head = String::from_utf8_lossy(&buf[..end]).to_ascii_lowercase();
                let length: usize = head
                    .lines()
                    .find_map(|l| l.strip_prefix("content-length:"))
                    .map(|v| v.trim().parse().unwrap())
                    .unwrap_or(0);
                if buf.len() >= end + 4 + length {
                    let status = head[9..12].parse().unwrap();
                    let body = buf[end + 4..end + 4 + length].to_vec();
                    return Some(RawResponse { status, head, body });
                }
            }
            match stream.read(&mut chunk).await {
                Ok(0) | Err(_) => return None,
                Ok(n) => buf.extend_from_slice(&chunk[..n]),
            }
        }
    };
    tokio::time::timeout(wait, read).await.ok().flatten()
}

/// Sends `request` on a new connection and reads the answer.
pub async fn exchange(base: &str, request: &[u8]) -> RawResponse {
    let mut stream = connect(base).await;
    stream.write_all(request).await.unwrap();
    read_response(&mut stream, Duration::from_secs(10))
        .await
        .unwrap_or_else(|| {
            panic!(
                "no answer to {:?}",
                String::from_utf8_lossy(&request[..request.len().min(200)])
            )
        })
}

/// Whether the server closed the connection within `wait` (EOF or reset),
/// reading and ignoring anything it sends first.
pub async fn closed_within(stream: &mut TcpStream, wait: Duration) -> bool {
    let drain = async {
        let mut chunk = [0u8; 1024];
        loop {
            match stream.read(&mut chunk).await {
                Ok(0) | Err(_) => return,
                Ok(_) => {}
            }
        }
    };
    tokio::time::timeout(wait, drain).await.is_ok()
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}
