//! NUL characters in any string (issue 32, item 5): PostgreSQL answered 500
//! ("invalid byte sequence for encoding UTF8: 0x00") to ids in paths,
//! cursors, `model`, a token's `name`. Every one is a 422 naming the field,
//! on both backends (`tests/pg` runs this module on PostgreSQL).

use serde_json::json;

use crate::hostile::{run_cases, Case};
use crate::support::*;

#[tokio::test]
async fn nul_in_any_string_is_422_naming_the_field() {
    let app = spawn_app().await;
    let session = app.robot_and_session("N1").await;
    let c = &app.client;
    let u = |p: &str| app.url(p);
    let mut robot = robot_body();
    robot["model"] = json!("arm\u{0}1");
    let mut pose = point_pose(0, "cal");
    pose["label"] = json!("p\u{0}");
    let case = |name, request, field| Case {
        name,
        request,
        status: 422,
        field: Some(field),
    };
    let cases = vec![
        case("job id", c.get(u("/v1/jobs/ab%00cd")), "id"),
        case("session id", c.get(u("/v1/sessions/x%00y")), "id"),
        case(
            "pose id",
            c.delete(u(&format!("/v1/sessions/{session}/poses/p%00"))),
            "pose_id",
        ),
        case("token id", c.delete(u("/v1/tokens/t%00")), "id"),
        case("webhook id", c.get(u("/v1/webhooks/w%00")), "id"),
        case("robots cursor", c.get(u("/v1/robots?cursor=%00")), "cursor"),
        case("jobs cursor", c.get(u("/v1/jobs?cursor=a%00b")), "cursor"),
        case(
            "jobs serial filter",
            c.get(u("/v1/jobs?serial=N%001")),
            "serial",
        ),
        case("model", c.put(u("/v1/robots/N2")).json(&robot), "model"),
        case(
            "token name",
            c.post(u("/v1/tokens"))
                .json(&json!({"name": "fuzz\u{0}", "scope": "read"})),
            "name",
        ),
        case(
            "pose label",
            c.post(u(&format!("/v1/sessions/{session}/poses")))
                .json(&pose),
            "label",
        ),
        case(
            "webhook url",
            c.post(u("/v1/webhooks"))
                .json(&json!({"url": "http://example.com/\u{0}", "events": ["job.succeeded"]})),
            "url",
        ),
    ];
    run_cases(&app, cases).await;
    // Nothing was stored, and anonymous mode is still on (no token made).
    assert_eq!(app.get("/v1/robots/N2").await.status(), 404);
    assert_eq!(app.get("/v1/tokens").await.status(), 200);
}
