//! Malformed and hostile requests: each gets the right 4xx as problem+json
//! naming the field, and the server keeps serving. JSON documents, paths and
//! queries here; uploads (multipart, zip) in `hostile_uploads.rs`.

use reqwest::{Method, RequestBuilder};
use serde_json::{json, Value};

use crate::support::*;

pub const MAX_IMAGE: u64 = 100_000;
pub const MAX_ARCHIVE: u64 = 1_000_000;
pub const MAX_JSON: u64 = 200_000;

pub struct Case {
    pub name: &'static str,
    pub request: RequestBuilder,
    pub status: u16,
    /// The field the problem document must name (if any).
    pub field: Option<&'static str>,
}

fn joints(mut body: Value, f: impl FnOnce(&mut Value)) -> Value {
    f(&mut body["kinematics"]["joints"][0]);
    body
}

/// The server under attack: small limits so oversize cases stay cheap.
pub async fn hostile_app() -> TestApp {
    spawn_app_with(|c| {
        c.max_image_bytes = MAX_IMAGE;
        c.max_archive_bytes = MAX_ARCHIVE;
        c.max_json_bytes = MAX_JSON;
    })
    .await
}

/// Sends each case; checks status, problem+json, the named field, and that
/// the server still serves afterwards.
pub async fn run_cases(app: &TestApp, cases: Vec<Case>) {
    for case in cases {
        let r = case
            .request
            .send()
            .await
            .unwrap_or_else(|e| panic!("{}: {e}", case.name));
        let status = r.status().as_u16();
        let ct = r
            .headers()
            .get("content-type")
            .map(|v| v.to_str().unwrap().to_string());
        let body = r.text().await.unwrap();
        assert_eq!(status, case.status, "{}: {body}", case.name);
        assert_eq!(
            ct.as_deref(),
            Some("application/problem+json"),
            "{}",
            case.name
        );
        let problem: Value = serde_json::from_str(&body).unwrap();
        assert_eq!(problem["status"], status, "{}", case.name);
        if let Some(field) = case.field {
            let fields: Vec<&str> = problem["errors"]
                .as_array()
                .map(|a| a.iter().filter_map(|e| e["field"].as_str()).collect())
                .unwrap_or_default();
            assert!(
                fields.contains(&field),
                "{}: expected field {field:?} in {body}",
                case.name
            );
        }
        // Still serving after every hostile request.
        assert_eq!(app.get("/healthz").await.status(), 200, "{}", case.name);
    }
}

#[tokio::test]
async fn hostile_documents_get_4xx_and_server_keeps_serving() {
    let app = hostile_app().await;
    let s = app.robot_and_session("H1").await;
    let c = &app.client;
    let u = |p: &str| app.url(p);
    let robot = u("/v1/robots/H2");
    let raw = |m: Method, url: &str, ct: &str, body: Vec<u8>| {
        c.request(m, url).header("content-type", ct).body(body)
    };
    let json_text = |m: Method, url: &str, body: &str| {
        raw(m, url, "application/json", body.as_bytes().to_vec())
    };
    let cases = vec![
        Case {
            name: "malformed JSON",
            request: json_text(Method::PUT, &robot, r#"{"model": "#),
            status: 400,
            field: Some("body"),
        },
        Case {
            name: "NaN literal",
            request: json_text(
                Method::PUT,
                &robot,
                r#"{"model":"m","kinematics":{"joints":[{"a_mm":NaN,"alpha_deg":0}]}}"#,
            ),
            status: 400,
            field: Some("body"),
        },
        Case {
            name: "number beyond f64",
            request: json_text(
                Method::PUT,
                &robot,
                r#"{"model":"m","kinematics":{"joints":[{"a_mm":1e999,"alpha_deg":0}]}}"#,
            ),
            status: 400,
            field: Some("body"),
        },
        Case {
            name: "wrong type",
            request: c
                .put(&robot)
                .json(&json!({"model": 5, "preset": "irb2400"})),
            status: 422,
            field: Some("model"),
        },
        Case {
            name: "missing field",
            request: c.put(&robot).json(&json!({"preset": "irb2400"})),
            status: 422,
            field: Some("model"),
        },
        Case {
            name: "neither kinematics nor preset",
            request: c.put(&robot).json(&json!({"model": "m"})),
            status: 422,
            field: Some("kinematics"),
        },
        Case {
            name: "both kinematics and preset",
            request: c.put(&robot).json(&{
                let mut b = robot_body();
                b["preset"] = json!("puma560");
                b
            }),
            status: 422,
            field: Some("preset"),
        },
        Case {
            name: "unknown preset",
            request: c.put(&robot).json(&json!({"model": "m", "preset": "kuka"})),
            status: 422,
            field: Some("preset"),
        },
        Case {
            name: "empty joint table",
            request: c
                .put(&robot)
                .json(&json!({"model": "m", "kinematics": {"joints": []}})),
            status: 422,
            field: Some("kinematics.joints"),
        },
        Case {
            name: "huge length",
            request: c
                .put(&robot)
                .json(&joints(robot_body(), |j| j["a_mm"] = json!(1e300))),
            status: 422,
            field: Some("kinematics.joints[0].a_mm"),
        },
        Case {
            name: "min above max",
            request: c
                .put(&robot)
                .json(&joints(robot_body(), |j| j["min_deg"] = json!(200.0))),
            status: 422,
            field: Some("kinematics.joints[0].max_deg"),
        },
        Case {
            name: "prismatic joint",
            request: c
                .put(&robot)
                .json(&joints(robot_body(), |j| j["type"] = json!("prismatic"))),
            status: 422,
            field: Some("kinematics.joints[0].type"),
        },
        Case {
            name: "unknown field",
            request: c
                .put(&robot)
                .json(&joints(robot_body(), |j| j["alpha"] = json!(1))),
            status: 422,
            field: Some("kinematics.joints[0].alpha"),
        },
        Case {
            name: "bad serial",
            request: c.put(u("/v1/robots/a%20b")).json(&robot_body()),
            status: 422,
            field: Some("serial"),
        },
        Case {
            name: "text/plain body",
            request: raw(Method::PUT, &robot, "text/plain", b"hello".to_vec()),
            status: 415,
            field: None,
        },
        Case {
            name: "oversized JSON body",
            request: json_text(
                Method::PUT,
                &robot,
                &format!("{{\"model\":\"{}\"}}", "x".repeat(MAX_JSON as usize)),
            ),
            status: 413,
            field: Some("max_json_bytes"),
        },
        Case {
            name: "unknown serial",
            request: c.get(u("/v1/robots/NOPE")),
            status: 404,
            field: None,
        },
        Case {
            name: "session for unknown serial",
            request: c.post(u("/v1/robots/NOPE/sessions")).json(&session_body()),
            status: 404,
            field: None,
        },
        Case {
            name: "camera session without target",
            request: c
                .post(u("/v1/robots/H1/sessions"))
                .json(&json!({"camera": session_body()["camera"]})),
            status: 422,
            field: Some("target"),
        },
        Case {
            name: "zero grid rows",
            request: c.post(u("/v1/robots/H1/sessions")).json(&{
                let mut b = session_body();
                b["target"]["rows"] = json!(0);
                b
            }),
            status: 422,
            field: Some("target.rows"),
        },
        Case {
            name: "negative rows",
            request: c.post(u("/v1/robots/H1/sessions")).json(&{
                let mut b = session_body();
                b["target"]["rows"] = json!(-3);
                b
            }),
            status: 422,
            field: Some("target.rows"),
        },
        Case {
            name: "unknown instrument",
            request: c
                .post(u("/v1/robots/H1/sessions"))
                .json(&json!({"instrument": "laser"})),
            status: 422,
            field: Some("instrument"),
        },
        Case {
            name: "unknown session",
            request: c.get(u("/v1/sessions/nope")),
            status: 404,
            field: None,
        },
        Case {
            name: "holdout out of range",
            request: c
                .post(u(&format!("/v1/sessions/{s}/calibrations")))
                .json(&json!({"validation": {"holdout_fraction": 1.5}})),
            status: 422,
            field: Some("validation.holdout_fraction"),
        },
        Case {
            name: "unknown option",
            request: c
                .post(u(&format!("/v1/sessions/{s}/calibrations")))
                .json(&json!({"turbo": true})),
            status: 422,
            field: Some("turbo"),
        },
        Case {
            name: "calibrate unknown session",
            request: c.post(u("/v1/sessions/nope/calibrations")),
            status: 404,
            field: None,
        },
        Case {
            name: "unknown job",
            request: c.get(u("/v1/jobs/nope")),
            status: 404,
            field: None,
        },
        Case {
            name: "bad version",
            request: c.get(u("/v1/robots/H1/parameter-sets/abc")),
            status: 422,
            field: Some("version"),
        },
        Case {
            name: "limit zero",
            request: c.get(u("/v1/robots?limit=0")),
            status: 422,
            field: Some("limit"),
        },
        Case {
            name: "limit not a number",
            request: c.get(u("/v1/robots?limit=lots")),
            status: 422,
            field: Some("limit"),
        },
        Case {
            name: "idempotency key too long",
            request: c
                .put(&robot)
                .header("idempotency-key", "k".repeat(300))
                .json(&robot_body()),
            status: 422,
            field: Some("Idempotency-Key"),
        },
        Case {
            name: "unknown route",
            request: c.get(u("/v1/nothing-here")),
            status: 404,
            field: None,
        },
        Case {
            name: "wrong method",
            request: c.patch(u("/v1/robots/H1")),
            status: 405,
            field: None,
        },
    ];
    assert!(cases.len() >= 30);
    run_cases(&app, cases).await;
    let robots: Value = app.get("/v1/robots").await.json().await.unwrap();
    assert_eq!(
        robots["items"].as_array().unwrap().len(),
        1,
        "nothing hostile was stored"
    );
}
