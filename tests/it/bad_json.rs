//! Property test of the HTTP edge (issue 13): whatever JSON a client sends
//! to a route that takes a JSON body, the answer is never a 5xx, and every
//! refusal is `application/problem+json`. Two kinds of bodies: arbitrary
//! JSON values (objects keyed by the contract's own field names, so they get
//! past the outer shape checks), and valid bodies with one value replaced by
//! an arbitrary one or one key removed.

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, TestRunner};
use serde_json::{Map, Value};

use crate::support::*;

/// Bodies per route and kind: enough to reach every field, a few seconds.
const CASES: usize = 40;
/// Field names of the contract, used as object keys and string values.
const WORDS: &[&str] = &[
    "model",
    "preset",
    "kinematics",
    "joints",
    "type",
    "a_mm",
    "alpha_deg",
    "d_mm",
    "theta_offset_deg",
    "beta_deg",
    "min_deg",
    "max_deg",
    "convention",
    "instrument",
    "target",
    "kind",
    "rows",
    "cols",
    "pitch_mm",
    "dot_diameter_mm",
    "camera",
    "width",
    "height",
    "pixel_size_um",
    "nominal_focal_mm",
    "joints_deg",
    "set",
    "cal",
    "val",
    "image_points",
    "row",
    "col",
    "x",
    "y",
    "measured_position_mm",
    "measured_pose",
    "translation_mm",
    "rotation_deg",
    "matrix",
    "label",
    "targets",
    "tool",
    "seed_joints_deg",
    "options",
    "validation",
    "holdout_fraction",
    "camera_calibration_id",
    "revolute",
    "dots",
    "charuco",
];

fn number() -> impl Strategy<Value = Value> {
    prop_oneof![
        any::<i64>().prop_map(Value::from),
        any::<u64>().prop_map(Value::from),
        any::<f64>()
            .prop_filter("JSON has no NaN or infinity", |f| f.is_finite())
            .prop_map(Value::from),
        prop::sample::select(vec![
            0.0, -0.0, 1.0, -1.0, 1e308, -1e308, 5e-324, 720.5, 1e9
        ])
        .prop_map(Value::from),
    ]
}

fn word() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(WORDS).prop_map(String::from),
        "\\PC{0,12}",
    ]
}

fn any_json() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        number(),
        word().prop_map(Value::String),
    ];
    leaf.prop_recursive(4, 64, 8, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..8).prop_map(Value::Array),
            prop::collection::btree_map(word(), inner, 0..8)
                .prop_map(|m| Value::Object(m.into_iter().collect::<Map<_, _>>())),
        ]
    })
}

/// Every path (object keys, array indices) inside `v`, the root included.
fn paths(v: &Value, at: &mut Vec<Vec<PathStep>>, here: Vec<PathStep>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let mut p = here.clone();
                p.push(PathStep::Key(k.clone()));
                paths(x, at, p);
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                let mut p = here.clone();
                p.push(PathStep::Index(i));
                paths(x, at, p);
            }
        }
        _ => {}
    }
    at.push(here);
}

#[derive(Debug, Clone)]
enum PathStep {
    Key(String),
    Index(usize),
}

/// `valid` with the value at one of its paths replaced by `with`, or
/// (`remove`) that key taken out.
fn mutated(valid: &Value, pick: prop::sample::Index, with: Value, remove: bool) -> Value {
    let mut all = Vec::new();
    paths(valid, &mut all, Vec::new());
    let path = pick.get(&all).clone();
    let mut out = valid.clone();
    let Some((last, parents)) = path.split_last() else {
        return with;
    };
    let mut node = &mut out;
    for step in parents {
        node = match step {
            PathStep::Key(k) => &mut node[k.as_str()],
            PathStep::Index(i) => &mut node[*i],
        };
    }
    match (last, node) {
        (PathStep::Key(k), Value::Object(m)) if remove => {
            m.remove(k);
        }
        (PathStep::Key(k), node) => node[k.as_str()] = with,
        (PathStep::Index(i), node) => node[*i] = with,
    }
    out
}

/// Sends `CASES` bodies from `strategy` to `path` by `method`; each answer
/// must be below 500, and a problem+json document when it is a refusal.
/// Returns how many were refused (4xx).
async fn probe(
    app: &TestApp,
    method: reqwest::Method,
    path: &str,
    strategy: impl Strategy<Value = Value>,
) -> usize {
    let mut runner = TestRunner::new(Config::default());
    let mut refused = 0;
    for _ in 0..CASES {
        let body = strategy.new_tree(&mut runner).unwrap().current();
        let r = app
            .client
            .request(method.clone(), app.url(path))
            .json(&body)
            .send()
            .await
            .unwrap();
        let status = r.status();
        let content_type = r
            .headers()
            .get(reqwest::header::CONTENT_TYPE)
            .and_then(|v| v.to_str().ok())
            .unwrap_or("")
            .to_string();
        let text = r.text().await.unwrap();
        assert!(
            status.as_u16() < 500,
            "{method} {path} answered {status} to {body}: {text}"
        );
        if !status.is_success() {
            refused += 1;
            assert!(
                content_type.starts_with("application/problem+json"),
                "{method} {path} answered {status} as {content_type:?} to {body}: {text}"
            );
            let problem: Value = serde_json::from_str(&text).unwrap_or_else(|e| {
                panic!("{method} {path}: problem is not JSON ({e}) for {body}: {text}")
            });
            assert_eq!(problem["status"], status.as_u16(), "{problem}");
        }
    }
    refused
}

/// Arbitrary bodies, then mutations of `valid`, to one route.
async fn probe_route(app: &TestApp, method: reqwest::Method, path: &str, valid: Value) {
    let refused = probe(app, method.clone(), path, any_json()).await;
    // An arbitrary value is (all but) never a valid body: the route refused
    // them, rather than the probe having tested nothing.
    assert!(
        refused + 2 >= CASES,
        "{path}: only {refused} of {CASES} refused"
    );
    let mutations = (any::<prop::sample::Index>(), any_json(), any::<bool>())
        .prop_map(move |(pick, with, remove)| mutated(&valid, pick, with, remove));
    probe(app, method, path, mutations).await;
}

#[tokio::test]
async fn arbitrary_json_bodies_get_problem_json_never_a_5xx() {
    let app = spawn_app().await;
    let session = app.robot_and_session("BADJSON").await;
    app.add_point_poses(&session, 1, 0).await;
    probe_route(
        &app,
        reqwest::Method::PUT,
        "/v1/robots/BADJSON-2",
        robot_body(),
    )
    .await;
    probe_route(
        &app,
        reqwest::Method::POST,
        "/v1/robots/BADJSON/sessions",
        session_body(),
    )
    .await;
    probe_route(
        &app,
        reqwest::Method::POST,
        &format!("/v1/sessions/{session}/poses"),
        point_pose(1, "cal"),
    )
    .await;
    probe_route(
        &app,
        reqwest::Method::POST,
        "/v1/robots/BADJSON/parameter-sets/latest/forward",
        serde_json::json!({"joints_deg": [[0.0, 10.0, 10.0, 0.0, 60.0, 0.0]]}),
    )
    .await;
}
