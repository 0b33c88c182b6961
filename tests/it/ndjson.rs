//! Streamed answers (issue "Deploy the result": a 10,000-target request
//! streams): `compensate` and `filter` with `Accept: application/x-ndjson`
//! answer one JSON line per target, in order, read here line by line as
//! they arrive, and equal to the whole answer, per-target errors included
//! by index; a bad field is still a 422 problem+json before any line.

use futures_util::StreamExt;
use rand::{rngs::StdRng, SeedableRng};
use serde_json::{json, Value};

use crate::compensate::{forward, stored_model, target_of};
use crate::support::*;

/// More targets than two chunks of the stream (`STREAM_CHUNK_TARGETS` is 200).
const TARGETS: usize = 450;
/// A target nothing reaches, at this index.
const FAR_INDEX: usize = 211;

/// The lines of a streamed answer, parsed as each arrives.
pub(crate) async fn lines(r: reqwest::Response) -> Vec<Value> {
    assert_eq!(r.status(), 200);
    assert_eq!(r.headers()["content-type"], "application/x-ndjson");
    let mut stream = r.bytes_stream();
    let (mut pending, mut lines) = (Vec::new(), Vec::new());
    while let Some(chunk) = stream.next().await {
        pending.extend_from_slice(&chunk.unwrap());
        while let Some(end) = pending.iter().position(|&b| b == b'\n') {
            let line: Vec<u8> = pending.drain(..=end).collect();
            lines.push(serde_json::from_slice(&line).unwrap());
        }
    }
    assert!(pending.is_empty(), "the stream ended mid-line");
    lines
}

pub(crate) async fn post_ndjson(app: &TestApp, path: &str, body: &Value) -> reqwest::Response {
    app.client
        .post(app.url(path))
        .header("accept", "application/x-ndjson")
        .json(body)
        .send()
        .await
        .unwrap()
}

/// Each line against the whole answer's columns: `index` in order, the
/// error where `errors` names the index, the same numbers elsewhere.
fn assert_same(streamed: &[Value], whole: &Value, columns: &[(&str, &str)]) {
    assert_eq!(streamed.len(), TARGETS);
    let errors = whole["errors"].as_array().unwrap();
    for (i, line) in streamed.iter().enumerate() {
        assert_eq!(line["index"], i, "{line}");
        match errors.iter().find(|e| e["index"] == i) {
            Some(e) => assert_eq!(line["error"], e["message"], "{line}"),
            None => {
                assert!(line.get("error").is_none(), "{line}");
                for (line_field, column) in columns {
                    assert_eq!(
                        line[line_field], whole[column][i],
                        "target {i} {line_field}"
                    );
                }
            }
        }
    }
}

#[tokio::test]
async fn streamed_answers_equal_the_whole_answers_line_by_line() {
    let app = spawn_app().await;
    let serial = "NDJSON-1";
    let (model, seed) = stored_model(&app, "irb2400", serial).await;
    let mut rng = StdRng::seed_from_u64(17);
    let mut joints = Vec::new();
    while joints.len() < TARGETS {
        joints.extend(crate::compensate::spread_joints(&model, &mut rng));
    }
    joints.truncate(TARGETS);
    let poses = forward(&app, serial, &joints).await;
    let mut targets: Vec<Value> = (0..TARGETS)
        .map(|i| target_of(&poses["poses"][i]["camera_in_target"]))
        .collect();
    targets[FAR_INDEX] =
        json!({"translation_mm": [9000.0, 0.0, 0.0], "rotation_deg": [0.0, 0.0, 0.0]});
    let set = format!("/v1/robots/{serial}/parameter-sets/1");

    let body = json!({"targets": targets, "seed_joints_deg": seed});
    let whole: Value = app
        .post_json(&format!("{set}/compensate"), &body)
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(
        whole["errors"][0]["index"], FAR_INDEX,
        "{}",
        whole["errors"]
    );
    let streamed = lines(post_ndjson(&app, &format!("{set}/compensate"), &body).await).await;
    assert!(streamed[FAR_INDEX]["error"].is_string());
    assert_same(
        &streamed,
        &whole,
        &[
            ("joints_deg", "joints_deg"),
            ("residual_mm", "residual_mm"),
            ("start", "start"),
            ("configuration", "configuration"),
        ],
    );

    let tool = json!({"translation_mm": [0.0, 0.0, 120.0], "rotation_deg": [0.0, 0.0, 0.0]});
    let body = json!({"targets": targets, "tool": tool, "seed_joints_deg": seed});
    let whole: Value = app
        .post_json(&format!("{set}/filter"), &body)
        .await
        .json()
        .await
        .unwrap();
    let streamed = lines(post_ndjson(&app, &format!("{set}/filter"), &body).await).await;
    assert!(streamed[FAR_INDEX]["error"].is_string());
    assert_same(
        &streamed,
        &whole,
        &[
            ("nominal_target", "nominal_targets"),
            ("joints_deg", "joints_deg"),
            ("residual_mm", "residual_mm"),
        ],
    );

    // A bad field is refused whole, before any line: problem+json naming it.
    let bad_seed = json!({"targets": targets, "seed_joints_deg": [0.0, 1.0]});
    let r = post_ndjson(&app, &format!("{set}/compensate"), &bad_seed).await;
    assert_eq!(r.status(), 422);
    assert_eq!(r.headers()["content-type"], "application/problem+json");
    let problem: Value = r.json().await.unwrap();
    assert_eq!(
        problem["errors"][0]["field"], "seed_joints_deg",
        "{problem}"
    );
    // A target that is not a number (JSON has no NaN) is named by its index.
    let mut nan = targets.clone();
    nan[3] = json!({"translation_mm": ["NaN", 0.0, 0.0], "rotation_deg": [0.0, 0.0, 0.0]});
    let body = json!({"targets": nan, "tool": tool});
    let r = post_ndjson(&app, &format!("{set}/filter"), &body).await;
    assert_eq!(r.status(), 422);
    let problem: Value = r.json().await.unwrap();
    let field = problem["errors"][0]["field"].as_str().unwrap();
    assert!(field.starts_with("targets[3]"), "{problem}");
    app.shutdown().await;
}
