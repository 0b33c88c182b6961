//! Every error is problem+json: requests hyper refuses before the service
//! sees them (400, 414, 431), path segments that are not UTF-8, a value of
//! the wrong type in an enum field, oversize multipart text parts, and
//! unknown part names (named, not echoed whole).

use reqwest::multipart::{Form, Part};
use serde_json::{json, Value};

use crate::raw_http::*;
use crate::support::*;

#[tokio::test]
async fn requests_hyper_refuses_are_answered_in_problem_json() {
    let app = spawn_app().await;
    let huge_header = format!(
        "GET /healthz HTTP/1.1\r\nHost: {host}\r\nX-Big: {}\r\n\r\n",
        "a".repeat(100_000),
        host = crate::raw_http::addr_of(&app.base)
    );
    let r = exchange(&app.base, huge_header.as_bytes()).await;
    assert_eq!(r.status, 431);
    assert!(r.problem()["detail"].as_str().unwrap().contains("bytes"));

    let long_uri = format!(
        "GET /v1/robots/{} HTTP/1.1\r\nHost: {host}\r\n\r\n",
        "a".repeat(70_000),
        host = crate::raw_http::addr_of(&app.base)
    );
    let r = exchange(&app.base, long_uri.as_bytes()).await;
    assert_eq!(r.status, 414, "{r:?}");
    r.problem();

    let bad_header = format!(
        "GET /healthz HTTP/1.1\r\nHost: {}\r\nno colon here\r\n\r\n",
        crate::raw_http::addr_of(&app.base)
    );
    let r = exchange(&app.base, bad_header.as_bytes()).await;
    assert_eq!(r.status, 400);
    r.problem();

    let bad_line = format!(
        "GET\x01 / HTTP/1.1\r\nHost: {}\r\n\r\n",
        crate::raw_http::addr_of(&app.base)
    );
    let r = exchange(&app.base, bad_line.as_bytes()).await;
    assert_eq!(r.status, 400);
    r.problem();

    // The server keeps serving.
    assert_eq!(app.get("/healthz").await.status(), 200);
}

#[tokio::test]
async fn a_path_segment_that_is_not_utf8_is_a_problem() {
    let app = spawn_app().await;
    for path in [
        "/v1/robots/%FF%FE",
        "/v1/sessions/%C3%28/poses",
        "/v1/jobs/%80",
    ] {
        let request = format!(
            "GET {path} HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n",
            host = crate::raw_http::addr_of(&app.base)
        );
        let r = exchange(&app.base, request.as_bytes()).await;
        assert_eq!(r.status, 400, "{path}: {r:?}");
        let problem = r.problem();
        assert!(problem["detail"].as_str().unwrap().len() > 5, "{problem}");
        if !path.starts_with("/v1/robots/") {
            assert_eq!(problem["errors"][0]["field"], "id", "{problem}");
        }
    }
}

#[tokio::test]
async fn a_wrong_type_in_an_enum_field_is_a_422_naming_it() {
    let app = spawn_app().await;
    for preset in [
        json!(-58800),
        json!(true),
        json!([1]),
        json!("no-such-robot"),
    ] {
        let r = app
            .put_json("/v1/robots/E1", &json!({"model": "m", "preset": preset}))
            .await;
        assert_eq!(r.status(), 422, "{preset}");
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], "preset", "{problem}");
    }
    // Broken JSON stays a 400.
    let r = app
        .client
        .put(app.url("/v1/robots/E1"))
        .header("content-type", "application/json")
        .body("{\"model\": ")
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 400);
}

#[tokio::test]
async fn multipart_text_parts_and_unknown_names_get_precise_problems() {
    let app = spawn_app().await;
    let session = app.robot_and_session("M1").await;
    let url = app.url(&format!("/v1/sessions/{session}/poses"));
    let image = || {
        Part::bytes(png(CAMERA_W, CAMERA_H, 3))
            .file_name("a.png")
            .mime_str("image/png")
            .unwrap()
    };

    let long_joints = format!("[{}0]", "0,".repeat(40_000));
    let form = Form::new()
        .text("joints_deg", long_joints)
        .part("image", image());
    let r = app.client.post(&url).multipart(form).send().await.unwrap();
    assert_eq!(r.status(), 413);
    let problem: Value = r.json().await.unwrap();
    let detail = problem["detail"].as_str().unwrap();
    assert!(!detail.contains("max-json-bytes"), "{detail}");
    assert!(detail.contains("joints_deg"), "{detail}");
    assert_eq!(problem["errors"][0]["field"], "joints_deg");

    let name = "x".repeat(100_000);
    let form = Form::new()
        .text("joints_deg", "[0,0,0,0,0,0]")
        .text(name.clone(), "1")
        .part("image", image());
    let r = app.client.post(&url).multipart(form).send().await.unwrap();
    assert_eq!(r.status(), 422);
    let body = r.text().await.unwrap();
    assert!(
        body.len() < 2_000,
        "the name is echoed whole: {} bytes",
        body.len()
    );
    let problem: Value = serde_json::from_str(&body).unwrap();
    let field = problem["errors"][0]["field"].as_str().unwrap();
    assert!(field.starts_with("xxxx"), "{field}");
}
