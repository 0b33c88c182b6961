//! Per-target answers of `compensate` and `filter`: a target that cannot be
//! answered is named by its index while the others are answered (issue
//! "Deploy the result", Bad input), and the whole answer can be streamed as
//! one JSON line per target (`Accept: application/x-ndjson`, api.md
//! "Results") so that a 10,000-target request does not hold its answer in
//! memory.

use futures_util::stream::{self, Stream};
use serde::Serialize;
use tokio::sync::mpsc;
use utoipa::ToSchema;

/// Targets solved and serialised per message of the stream: large enough
/// that the channel costs nothing next to the inverse kinematics (~25 µs a
/// target, BENCHMARKS.md "IK"), small enough that a chunk's bytes (~0.5 kB
/// a target) stay near 100 kB.
pub const STREAM_CHUNK_TARGETS: usize = 200;
/// Chunks waiting for a slow client before the solving thread pauses: the
/// memory of a streamed answer is bounded by this, not by its length.
pub const STREAM_CHANNEL_CHUNKS: usize = 4;

/// One target that could not be answered; the others are still answered.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TargetError {
    /// Index into `targets`.
    pub index: usize,
    pub message: String,
}

/// One line of a streamed answer: the target's index and either its
/// answer (the fields of `T`) or `error`.
#[derive(Debug, Clone, Serialize)]
pub struct TargetLine<T> {
    pub index: usize,
    #[serde(flatten)]
    pub outcome: TargetOutcome<T>,
}

/// A target's answer, or why it has none.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum TargetOutcome<T> {
    Answered(T),
    Failed { error: String },
}

impl<T> TargetLine<T> {
    pub fn of(index: usize, outcome: Result<T, String>) -> Self {
        TargetLine {
            index,
            outcome: match outcome {
                Ok(answer) => TargetOutcome::Answered(answer),
                Err(error) => TargetOutcome::Failed { error },
            },
        }
    }
}

/// The answers of targets `0..count`, one JSON line each in index order,
/// solved `STREAM_CHUNK_TARGETS` at a time on a blocking thread and handed
/// over through a channel of `STREAM_CHANNEL_CHUNKS`: the solver waits for
/// the client, and stops when the client goes away. The request must have
/// been checked whole before (a bad field is a 422, never a line).
pub fn ndjson<T, F>(count: usize, answer: F) -> impl Stream<Item = Vec<u8>>
where
    T: Serialize,
    F: Fn(usize) -> Result<T, String> + Send + 'static,
{
    let (sender, receiver) = mpsc::channel::<Vec<u8>>(STREAM_CHANNEL_CHUNKS);
    tokio::task::spawn_blocking(move || {
        for first in (0..count).step_by(STREAM_CHUNK_TARGETS) {
            let mut chunk = Vec::new();
            for index in first..count.min(first + STREAM_CHUNK_TARGETS) {
                let line = TargetLine::of(index, answer(index));
                // Plain structs of numbers and strings: writing to memory cannot fail.
                if serde_json::to_writer(&mut chunk, &line).is_err() {
                    tracing::error!(index, "a streamed target's answer did not serialise");
                    return;
                }
                chunk.push(b'\n');
            }
            if sender.blocking_send(chunk).is_err() {
                return; // the client went away
            }
        }
    });
    stream::unfold(receiver, |mut receiver| async move {
        receiver.recv().await.map(|chunk| (chunk, receiver))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use futures_util::StreamExt;

    #[tokio::test]
    async fn lines_come_in_index_order_with_errors_inline() {
        let count = 2 * STREAM_CHUNK_TARGETS + 3;
        let chunks: Vec<Vec<u8>> = ndjson(count, |i| {
            if i % 7 == 3 {
                Err(format!("target {i} out of reach"))
            } else {
                Ok(serde_json::json!({ "residual_mm": i as f64 }))
            }
        })
        .collect()
        .await;
        assert_eq!(chunks.len(), 3);
        let text = String::from_utf8(chunks.concat()).unwrap();
        let lines: Vec<serde_json::Value> = text
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(lines.len(), count);
        for (i, line) in lines.iter().enumerate() {
            assert_eq!(line["index"], i);
            if i % 7 == 3 {
                assert_eq!(line["error"], format!("target {i} out of reach"));
                assert!(line.get("residual_mm").is_none());
            } else {
                assert_eq!(line["residual_mm"], i as f64);
                assert!(line.get("error").is_none());
            }
        }
    }
}
