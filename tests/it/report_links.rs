//! Signed read-only report links: they open their one report (HTML, SVG,
//! JSON) without a header until they expire, on every replica; altered or
//! expired links are refused with problem+json.

use serde_json::{json, Value};

use robocal::api::report_links::sign;
use robocal::domain::{now_unix_ms, Scope};
use robocal::report::sample::sample_report;
use robocal::server::start;
use robocal::store;
use robocal::store::NewParameterSet;

use crate::support::*;
use crate::tokens::stored_token;

/// Two parameter sets of `RL-1` and one of `RL-2`, each with a drawable report.
async fn reports(app: &TestApp) {
    for serial in ["RL-1", "RL-2"] {
        let r = app
            .put_json(&format!("/v1/robots/{serial}"), &robot_body())
            .await;
        assert_eq!(r.status(), 201);
    }
    let s = store::connect(&app.database_url).await.unwrap();
    let set = NewParameterSet::approved(
        placeholder_set("s"),
        serde_json::to_value(sample_report()).unwrap(),
    );
    for serial in ["RL-1", "RL-1", "RL-2"] {
        s.insert_parameter_set(serial, None, &set).await.unwrap();
    }
}

async fn create_link(app: &TestApp, token: &str, path: &str, body: Value) -> reqwest::Response {
    app.client
        .post(app.url(path))
        .bearer_auth(token)
        .json(&body)
        .send()
        .await
        .unwrap()
}

/// A headerless GET of `url`, relative to the app when it starts with `/`.
async fn open(url: &str) -> reqwest::Response {
    reqwest::Client::new().get(url).send().await.unwrap()
}

async fn refused(r: reqwest::Response, status: u16) -> String {
    assert_eq!(r.status(), status, "{}", r.url());
    assert_eq!(r.headers()["content-type"], "application/problem+json");
    let p: Value = r.json().await.unwrap();
    p["detail"].as_str().unwrap().to_string()
}

#[tokio::test]
async fn report_links_open_one_report_without_a_header_until_they_expire() {
    let app = spawn_app().await;
    reports(&app).await;
    stored_token(&app, Scope::Admin, None).await;
    let read = stored_token(&app, Scope::Read, None).await;
    let latest = "/v1/robots/RL-1/parameter-sets/latest/report-links";

    // Without a token the report is closed.
    assert_eq!(
        app.get("/v1/robots/RL-1/parameter-sets/2/report.html")
            .await
            .status(),
        401
    );

    // A read token may ask for a link; `latest` is resolved to version 2.
    let r = create_link(&app, &read, latest, json!({"expires_in_minutes": 5})).await;
    assert_eq!(r.status(), 201);
    let link: Value = r.json().await.unwrap();
    let url = link["url"].as_str().unwrap().to_string();
    assert!(url.starts_with(&app.base), "{url}");
    assert!(
        url.contains("/v1/robots/RL-1/parameter-sets/2/report.html?"),
        "{url}"
    );
    let expires_at = humantime::parse_rfc3339(link["expires_at"].as_str().unwrap()).unwrap();
    let minutes = expires_at
        .duration_since(std::time::SystemTime::now())
        .unwrap()
        .as_secs_f64()
        / 60.0;
    assert!((4.0..=5.01).contains(&minutes), "{minutes}");

    // It opens without a header, in each rendering.
    let r = open(&url).await;
    assert_eq!(r.status(), 200);
    assert!(r.headers()["content-type"]
        .to_str()
        .unwrap()
        .starts_with("text/html"));
    assert!(r.text().await.unwrap().contains("<html"));
    let r = open(link["svg_url"].as_str().unwrap()).await;
    assert_eq!(r.status(), 200);
    assert_eq!(r.headers()["content-type"], "image/svg+xml");
    let r = open(link["json_url"].as_str().unwrap()).await;
    assert_eq!(r.status(), 200);
    let report: Value = r.json().await.unwrap();
    assert_eq!(
        (report["serial"].as_str(), report["version"].as_i64()),
        (Some("RL-1"), Some(2))
    );

    // Not for another report, another robot, or anything else; not altered.
    let query = url.split_once('?').unwrap().1.to_string();
    let elsewhere = [
        "/v1/robots/RL-1/parameter-sets/1/report.html",
        "/v1/robots/RL-2/parameter-sets/1/report.html",
        "/v1/robots/RL-1/parameter-sets/latest/report.html",
        "/v1/robots/RL-1/parameter-sets/2",
        "/v1/robots",
        "/v1/tokens",
    ];
    for path in elsewhere {
        let detail = refused(open(&app.url(&format!("{path}?{query}"))).await, 403).await;
        assert!(detail.contains("link"), "{path}: {detail}");
    }
    let later = url.replace("expires=", "expires=9");
    refused(open(&later).await, 403).await;
    let at = url.find("sig=").unwrap() + 8;
    let flipped = if &url[at..at + 1] == "A" { "B" } else { "A" };
    let forged = format!("{}{flipped}{}", &url[..at], &url[at + 1..]);
    refused(open(&forged).await, 403).await;
    let r = app
        .client
        .put(app.url(&format!("/v1/robots/RL-1?{query}")))
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert!(
        matches!(r.status().as_u16(), 401 | 403),
        "a link never writes"
    );

    // Expired: a link signed with the fleet's key whose time has passed.
    let s = store::connect(&app.database_url).await.unwrap();
    let secret = s.server_secret("report-links", "unused").await.unwrap();
    assert_ne!(secret, "unused", "the key was created with the first link");
    let set_path = "/v1/robots/RL-1/parameter-sets/2";
    let created = s
        .get_parameter_set("RL-1", Some(2))
        .await
        .unwrap()
        .unwrap()
        .created_at;
    let past = now_unix_ms() / 1000 - 1;
    let expired = app.url(&format!(
        "{set_path}/report.html?expires={past}&sig={}",
        sign(&secret, set_path, &created, past)
    ));
    let detail = refused(open(&expired).await, 401).await;
    assert!(detail.contains("expired"), "{detail}");
    let future = past + 120;
    let fresh = app.url(&format!(
        "{set_path}/report.svg?expires={future}&sig={}",
        sign(&secret, set_path, &created, future)
    ));
    assert_eq!(open(&fresh).await.status(), 200, "the same key, in time");

    // Another replica on the same database accepts the link.
    let dir = tempfile::tempdir().unwrap();
    let replica = start(test_config(&app.database_url, &dir)).await.unwrap();
    let there = url.replace(&app.base, &format!("http://{}", replica.addr));
    assert_eq!(open(&there).await.status(), 200);
    replica.shutdown().await;
}

#[tokio::test]
async fn report_link_requests_are_checked() {
    let app = spawn_app().await;
    reports(&app).await;
    let read = stored_token(&app, Scope::Read, None).await;
    let path = "/v1/robots/RL-1/parameter-sets/1/report-links";
    for bad in [
        json!({"expires_in_minutes": 0}),
        json!({"expires_in_minutes": 10081}),
        json!({}),
    ] {
        let r = create_link(&app, &read, path, bad.clone()).await;
        assert!(matches!(r.status().as_u16(), 400 | 422), "{bad}");
        assert!(
            r.text().await.unwrap().contains("expires_in_minutes"),
            "{bad}"
        );
    }
    let r = create_link(
        &app,
        &read,
        "/v1/robots/RL-1/parameter-sets/9/report-links",
        json!({"expires_in_minutes": 1}),
    )
    .await;
    refused(r, 404).await;
    let r = app
        .client
        .post(app.url(path))
        .json(&json!({"expires_in_minutes": 1}))
        .send()
        .await
        .unwrap();
    refused(r, 401).await;
}

/// Issue 32, item 8: an old link opened the report of a robot deleted and
/// created again under its serial; link URLs followed the request's `Host`.
#[tokio::test]
async fn a_link_names_its_set_not_a_serial_and_version_and_uses_the_public_base() {
    let app =
        spawn_app_with(|c| c.public_base_url = Some("https://robocal.plant.example/".into())).await;
    reports(&app).await;
    let admin = stored_token(&app, Scope::Admin, None).await;
    let path = "/v1/robots/RL-2/parameter-sets/1/report-links";
    let r = create_link(&app, &admin, path, json!({"expires_in_minutes": 5})).await;
    assert_eq!(r.status(), 201);
    let link: Value = r.json().await.unwrap();
    let url = link["url"].as_str().unwrap();
    let public = "https://robocal.plant.example/v1/robots/RL-2/parameter-sets/1/report.html?";
    assert!(url.starts_with(public), "{url}");
    let local = url.replace("https://robocal.plant.example", &app.base);
    assert_eq!(open(&local).await.status(), 200);

    // The robot is deleted and created again; its new set 1 is another set.
    let r = app
        .client
        .delete(app.url("/v1/robots/RL-2"))
        .bearer_auth(&admin)
        .send()
        .await
        .unwrap();
    assert!(r.status().is_success(), "{}", r.status());
    let r = app
        .client
        .put(app.url("/v1/robots/RL-2"))
        .bearer_auth(&admin)
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let s = store::connect(&app.database_url).await.unwrap();
    let set = NewParameterSet::approved(
        placeholder_set("s"),
        serde_json::to_value(sample_report()).unwrap(),
    );
    tokio::time::sleep(std::time::Duration::from_millis(5)).await;
    s.insert_parameter_set("RL-2", None, &set).await.unwrap();
    refused(open(&local).await, 403).await;
}
