//! Issue 18, regions: a session names where its board was placed
//! (`region`) and the volume its poses span (`volume`), kept with the
//! session; bad names answer 422 naming the field. (The one fit over
//! several sessions is `robocal_calib::kinematics::regions`, tested on the
//! simulator there.)

use serde_json::{json, Value};

use crate::support::*;

#[tokio::test]
async fn a_session_keeps_its_region_and_volume_and_refuses_bad_names() {
    let app = spawn_app().await;
    app.robot_and_session("REG-1").await;
    let sessions = "/v1/robots/REG-1/sessions";
    let mut body = session_body();
    body["region"] = json!("left table");
    body["volume"] = json!("600x400x300 mm");
    let r = app.post_json(sessions, &body).await;
    assert_eq!(r.status(), 201);
    let id = r.json::<Value>().await.unwrap()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let got: Value = app
        .get(&format!("/v1/sessions/{id}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(got["region"], "left table", "{got}");
    assert_eq!(got["volume"], "600x400x300 mm", "{got}");

    let long = "x".repeat(robocal::schema::session::MAX_REGION_NAME_CHARS + 1);
    for (field, value) in [("region", json!("  ")), ("volume", json!(long))] {
        let mut body = session_body();
        body[field] = value;
        let r = app.post_json(sessions, &body).await;
        assert_eq!(r.status(), 422);
        let p: Value = r.json().await.unwrap();
        assert_eq!(p["errors"][0]["field"], field, "{p}");
    }
}
