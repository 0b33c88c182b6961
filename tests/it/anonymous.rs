//! Anonymous mode answers only requests addressed to the loopback bind (no
//! DNS rebinding), and which routes need no token: `/metrics` only with
//! `--public-metrics`; `/healthz`, `/readyz`, `/docs`, `/openapi.json` always.

use reqwest::header::HOST;
use serde_json::Value;

use robocal::domain::Scope;

use crate::support::*;
use crate::tokens::stored_token;

fn port(app: &TestApp) -> u16 {
    app.base.rsplit(':').next().unwrap().parse().unwrap()
}

async fn get_with_host(app: &TestApp, path: &str, host: &str) -> reqwest::Response {
    app.client
        .get(app.url(path))
        .header(HOST, host)
        .send()
        .await
        .unwrap()
}

#[tokio::test]
async fn anonymous_mode_accepts_only_loopback_host_names() {
    let app = spawn_app().await;
    let port = port(&app);
    for host in [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
    ] {
        let r = get_with_host(&app, "/v1/robots", &host).await;
        assert_eq!(r.status(), 200, "{host}");
    }
    for host in [
        format!("evil.example:{port}"),
        format!("localhost.evil.example:{port}"),
        format!("127.0.0.1:{}", port.wrapping_add(1)),
        "localhost".to_string(),
    ] {
        let r = get_with_host(&app, "/v1/robots", &host).await;
        assert_eq!(r.status(), 421, "{host}");
        assert_eq!(r.headers()["content-type"], "application/problem+json");
        let p: Value = r.json().await.unwrap();
        assert!(p["detail"].as_str().unwrap().contains("localhost"), "{p}");
    }
    // Writes too (a rebound page would POST).
    let r = app
        .client
        .put(app.url("/v1/robots/R1"))
        .header(HOST, format!("evil.example:{port}"))
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 421);
    assert_eq!(
        app.get("/v1/robots/R1").await.status(),
        404,
        "nothing written"
    );

    // With tokens the token decides, whatever the Host.
    let read = stored_token(&app, Scope::Read, None).await;
    let r = app
        .client
        .get(app.url("/v1/robots"))
        .header(HOST, format!("robocal.example:{port}"))
        .bearer_auth(&read)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 200);
}

#[tokio::test]
async fn metrics_need_a_read_token_unless_public() {
    let app = spawn_app().await;
    // Anonymous mode: open to the loopback, as every route.
    assert_eq!(app.get("/metrics").await.status(), 200);
    let port = port(&app);
    assert_eq!(
        get_with_host(&app, "/metrics", &format!("evil.example:{port}"))
            .await
            .status(),
        421
    );

    let read = stored_token(&app, Scope::Read, None).await;
    let r = app.get("/metrics").await;
    assert_eq!(r.status(), 401);
    assert_eq!(r.headers()["content-type"], "application/problem+json");
    let r = app
        .client
        .get(app.url("/metrics"))
        .bearer_auth(&read)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 200);
    assert!(r.text().await.unwrap().contains("robocal_queue_depth"));
    // Probes and the contract stay public.
    for path in ["/healthz", "/readyz", "/docs/", "/openapi.json"] {
        assert_eq!(app.get(path).await.status(), 200, "{path}");
    }

    let public = spawn_app_with(|c| c.public_metrics = true).await;
    stored_token(&public, Scope::Read, None).await;
    assert_eq!(public.get("/v1/robots").await.status(), 401);
    assert_eq!(public.get("/metrics").await.status(), 200);
}

#[test]
fn public_metrics_is_a_flag_and_an_environment_variable() {
    let out = run_binary(&["serve", "--help"]);
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(help.contains("--public-metrics"), "{help}");
    assert!(help.contains("ROBOCAL_PUBLIC_METRICS"), "{help}");
}
