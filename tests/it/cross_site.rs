//! Writes from another site are refused in every mode, whatever they carry
//! (issue 32, item 4): a foreign `Origin`, `Origin: null`, `Sec-Fetch-Site:
//! cross-site`; and form body types on the API.

use reqwest::multipart::Form;
use serde_json::Value;

use robocal::domain::Scope;

use crate::support::*;
use crate::tokens::stored_token;

async fn pose_count(app: &TestApp, session: &str, token: Option<&str>) -> i64 {
    let mut r = app.client.get(app.url(&format!("/v1/sessions/{session}")));
    if let Some(t) = token {
        r = r.bearer_auth(t);
    }
    r.send().await.unwrap().json::<Value>().await.unwrap()["pose_count"]
        .as_i64()
        .unwrap()
}

#[tokio::test]
async fn anonymous_mode_refuses_cross_site_writes_of_every_shape() {
    let app = spawn_app().await;
    let session = app.robot_and_session("X1").await;
    let host = app.base.trim_start_matches("http://").to_string();
    let poses = app.url(&format!("/v1/sessions/{session}/poses"));
    let cross: [(&str, &str); 3] = [
        ("origin", "http://evil.example"),
        ("origin", "null"),
        ("sec-fetch-site", "cross-site"),
    ];
    for (name, value) in cross {
        // A JSON write, a body-less write, a multipart upload.
        let json = app
            .client
            .post(&poses)
            .header(name, value)
            .json(&point_pose(0, "cal"))
            .send()
            .await
            .unwrap();
        assert_eq!(json.status(), 403, "{name}: {value}");
        let problem: Value = json.json().await.unwrap();
        assert_eq!(
            problem["type"], "urn:robocal:problem:cross-site",
            "{problem}"
        );
        let bare = app
            .client
            .post(app.url(&format!("/v1/sessions/{session}/calibrations")))
            .header(name, value)
            .send()
            .await
            .unwrap();
        assert_eq!(bare.status(), 403, "{name}: {value}");
        let form = Form::new()
            .text("joints_deg", "[1,2,3,4,5,6]")
            .text("set", "cal")
            .part("image", image_part(png(CAMERA_W, CAMERA_H, 1), "p.png"));
        let upload = app
            .client
            .post(&poses)
            .header(name, value)
            .multipart(form)
            .send()
            .await
            .unwrap();
        assert_eq!(upload.status(), 403, "{name}: {value}");
    }
    assert_eq!(pose_count(&app, &session, None).await, 0, "nothing written");
    let jobs: Value = app.get_ok("/v1/jobs").await;
    assert_eq!(jobs["items"].as_array().unwrap().len(), 0, "no job started");

    // A page of the service itself, and programs without the headers, write.
    let same = app
        .client
        .post(&poses)
        .header("origin", format!("http://{host}"))
        .header("sec-fetch-site", "same-origin")
        .json(&point_pose(0, "cal"))
        .send()
        .await
        .unwrap();
    assert_eq!(same.status(), 201);
    let plain = app
        .post_json(&poses.replace(&app.base, ""), &point_pose(1, "cal"))
        .await;
    assert_eq!(plain.status(), 201);
    assert_eq!(pose_count(&app, &session, None).await, 2);
}

#[tokio::test]
async fn form_body_types_are_refused_on_the_api_and_tokens_do_not_excuse_cross_site() {
    let app = spawn_app().await;
    let session = app.robot_and_session("X2").await;
    let token = stored_token(&app, Scope::Write, None).await;
    // What an HTML form on any site can send without a preflight.
    for media in ["text/plain", "application/x-www-form-urlencoded"] {
        let r = app
            .client
            .post(app.url(&format!("/v1/sessions/{session}/calibrations")))
            .bearer_auth(&token)
            .header("content-type", media)
            .body("{}")
            .send()
            .await
            .unwrap();
        assert_eq!(r.status(), 415, "{media}");
    }
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/poses")))
        .bearer_auth(&token)
        .header("origin", "https://evil.example")
        .json(&point_pose(0, "cal"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 403);
    assert_eq!(pose_count(&app, &session, Some(&token)).await, 0);
}
