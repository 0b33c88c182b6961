//! Malformed and hostile requests: each gets the right 4xx as problem+json
//! naming the field, and the server keeps serving.

use reqwest::multipart::{Form, Part};
use reqwest::{Method, RequestBuilder};
use serde_json::{json, Value};

use crate::support::*;

const MAX_IMAGE: u64 = 100_000;
const MAX_ARCHIVE: u64 = 1_000_000;
const MAX_JSON: u64 = 200_000;

struct Case {
    name: &'static str,
    request: RequestBuilder,
    status: u16,
    /// The field the problem document must name (if any).
    field: Option<&'static str>,
}

fn joints(mut body: Value, f: impl FnOnce(&mut Value)) -> Value {
    f(&mut body["kinematics"]["joints"][0]);
    body
}

#[tokio::test]
async fn hostile_requests_get_4xx_and_server_keeps_serving() {
    let app = spawn_app_with(|c| {
        c.max_image_bytes = MAX_IMAGE;
        c.max_archive_bytes = MAX_ARCHIVE;
        c.max_json_bytes = MAX_JSON;
    })
    .await;
    let s = app.robot_and_session("H1").await;
    let c = &app.client;
    let u = |p: &str| app.url(p);
    let poses = u(&format!("/v1/sessions/{s}/poses"));
    let dataset = u(&format!("/v1/sessions/{s}/dataset"));
    let robot = u("/v1/robots/H2");
    let raw = |m: Method, url: &str, ct: &str, body: Vec<u8>| {
        c.request(m, url).header("content-type", ct).body(body)
    };
    let json_text = |m: Method, url: &str, body: &str| {
        raw(m, url, "application/json", body.as_bytes().to_vec())
    };
    let zip_post = |bytes: Vec<u8>| raw(Method::POST, &dataset, "application/zip", bytes);
    let good_png = png(CAMERA_W, CAMERA_H, 1);
    let multipart = |form: Form| c.post(&poses).multipart(form);
    let img = |b: Vec<u8>| {
        Part::bytes(b)
            .file_name("x.png")
            .mime_str("image/png")
            .unwrap()
    };
    let bomb = zip_bytes(&[
        (
            "poses.json",
            br#"[{"joints_deg":[0,0,0,0,0,0],"image":"a.png"}]"#,
        ),
        ("a.png", &vec![0u8; 30_000_000]),
    ]);
    let manifest = br#"[{"joints_deg":[0,0,0,0,0,0],"image":"a.png"}]"#;
    let mut truncated = b"--XyZ\r\nContent-Disposition: form-data; name=\"joints_deg\"\r\n\r\n[0,0,0,0,0,0]\r\n--XyZ\r\nContent-Disposition: form-data; name=\"image\"; filename=\"a.png\"\r\n\r\n".to_vec();
    truncated.extend_from_slice(&good_png[..good_png.len() / 2]);

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
            name: "wrong joint count",
            request: c.post(&poses).json(
                &json!({"joints_deg": [1, 2], "image_points": [{"row":0,"col":0,"x":1,"y":1}]}),
            ),
            status: 422,
            field: Some("joints_deg"),
        },
        Case {
            name: "joints not an array",
            request: c
                .post(&poses)
                .json(&json!({"joints_deg": "1,2,3", "image_points": []})),
            status: 422,
            field: Some("joints_deg"),
        },
        Case {
            name: "point outside image",
            request: c.post(&poses).json(&{
                let mut p = point_pose(0, "cal");
                p["image_points"][0]["x"] = json!(1e9);
                p
            }),
            status: 422,
            field: Some("image_points[0].x"),
        },
        Case {
            name: "bad pose set",
            request: c.post(&poses).json(&{
                let mut p = point_pose(0, "cal");
                p["set"] = json!("test");
                p
            }),
            status: 422,
            field: Some("set"),
        },
        Case {
            name: "truncated multipart",
            request: raw(
                Method::POST,
                &poses,
                "multipart/form-data; boundary=XyZ",
                truncated,
            ),
            status: 400,
            field: Some("multipart"),
        },
        Case {
            name: "non-image called .png",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(b"GIF89a not really an image at all".to_vec())),
            ),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "corrupt PNG",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(good_png[..good_png.len() - 30].to_vec())),
            ),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "image of the wrong size",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(png(10, 10, 0))),
            ),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "oversized image",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(vec![0u8; MAX_IMAGE as usize + 1])),
            ),
            status: 413,
            field: Some("max_image_bytes"),
        },
        Case {
            name: "multipart without image",
            request: multipart(Form::new().text("joints_deg", "[0,0,0,0,0,0]")),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "joints part not JSON",
            request: multipart(
                Form::new()
                    .text("joints_deg", "zero")
                    .part("image", img(good_png.clone())),
            ),
            status: 422,
            field: Some("joints_deg"),
        },
        Case {
            name: "not a zip",
            request: zip_post(b"PK\x03\x04 this is not a zip".to_vec()),
            status: 400,
            field: Some("archive"),
        },
        Case {
            name: "zip slip",
            request: zip_post(zip_bytes(&[
                ("poses.json", manifest),
                ("../../etc/passwd", b"x"),
            ])),
            status: 422,
            field: Some("archive/../../etc/passwd"),
        },
        Case {
            name: "absolute path in zip",
            request: zip_post(zip_bytes(&[("poses.json", manifest), ("/abs.png", b"x")])),
            status: 422,
            field: Some("archive//abs.png"),
        },
        Case {
            name: "zip bomb",
            request: zip_post(bomb),
            status: 413,
            field: Some("max_image_bytes"),
        },
        Case {
            name: "archive too large",
            request: zip_post(vec![0u8; MAX_ARCHIVE as usize + 1]),
            status: 413,
            field: Some("max_archive_bytes"),
        },
        Case {
            name: "zip without poses.json",
            request: zip_post(zip_bytes(&[("a.png", &good_png)])),
            status: 422,
            field: Some("archive/poses.json"),
        },
        Case {
            name: "manifest names a missing image",
            request: zip_post(zip_bytes(&[("poses.json", manifest)])),
            status: 422,
            field: Some("archive/a.png"),
        },
        Case {
            name: "manifest not JSON",
            request: zip_post(zip_bytes(&[("poses.json", b"[{")])),
            status: 400,
            field: Some("poses.json"),
        },
        Case {
            name: "dataset as JSON",
            request: c.post(&dataset).json(&json!({})),
            status: 415,
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
    let total = cases.len();
    assert!(total >= 30);
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
    let robots: Value = app.get("/v1/robots").await.json().await.unwrap();
    assert_eq!(
        robots["items"].as_array().unwrap().len(),
        1,
        "nothing hostile was stored"
    );
    let session: Value = app
        .get(&format!("/v1/sessions/{s}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(session["pose_count"], 0);
}
