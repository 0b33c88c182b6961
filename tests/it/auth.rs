use serde_json::{json, Value};

use robocal::api::auth::{generate_token, hash_token};
use robocal::domain::Scope;
use robocal::server::{start, StartError};
use robocal::store;

use crate::support::*;

async fn token(app: &TestApp, scope: Scope) -> String {
    let s = store::connect(&app.database_url).await.unwrap();
    let t = generate_token();
    s.create_token("test", &hash_token(&t), scope)
        .await
        .unwrap();
    t
}

#[tokio::test]
async fn token_scopes_are_enforced() {
    let app = spawn_app().await;
    // No token yet, loopback bind: anonymous works.
    assert_eq!(app.get("/v1/robots").await.status(), 200);
    let read = token(&app, Scope::Read).await;
    let write = token(&app, Scope::Write).await;
    let admin = token(&app, Scope::Admin).await;
    let c = &app.client;

    // With tokens configured, anonymous is refused (ops routes stay open).
    let r = app.get("/v1/robots").await;
    assert_eq!(r.status(), 401);
    assert_eq!(r.headers()["www-authenticate"], "Bearer");
    assert_eq!(app.get("/healthz").await.status(), 200);
    let bad = c
        .get(app.url("/v1/robots"))
        .bearer_auth("rbc_wrong")
        .send()
        .await
        .unwrap();
    assert_eq!(bad.status(), 401);

    // read: can read, cannot write.
    assert_eq!(
        c.get(app.url("/v1/robots"))
            .bearer_auth(&read)
            .send()
            .await
            .unwrap()
            .status(),
        200
    );
    let r = c
        .put(app.url("/v1/robots/A1"))
        .bearer_auth(&read)
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 403);

    // write: can write, cannot manage tokens.
    let r = c
        .put(app.url("/v1/robots/A1"))
        .bearer_auth(&write)
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let r = c
        .post(app.url("/v1/tokens"))
        .bearer_auth(&write)
        .json(&json!({"name": "x", "scope": "read"}))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 403);
    assert_eq!(
        c.get(app.url("/v1/tokens"))
            .bearer_auth(&write)
            .send()
            .await
            .unwrap()
            .status(),
        403
    );

    // admin: manages tokens; a new token works at once and its secret is not listed.
    let r = c
        .post(app.url("/v1/tokens"))
        .bearer_auth(&admin)
        .json(&json!({"name": "ci", "scope": "read"}))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let created: Value = r.json().await.unwrap();
    let new = created["token"].as_str().unwrap();
    assert_eq!(
        c.get(app.url("/v1/robots/A1"))
            .bearer_auth(new)
            .send()
            .await
            .unwrap()
            .status(),
        200
    );
    let list = c
        .get(app.url("/v1/tokens"))
        .bearer_auth(&admin)
        .send()
        .await
        .unwrap()
        .text()
        .await
        .unwrap();
    assert!(!list.contains(new), "secrets are never listed");
    assert!(list.contains("\"ci\""));
}

#[tokio::test]
async fn non_loopback_bind_without_tokens_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let mut config = test_config(&db, &dir);
    config.bind = "0.0.0.0:0".parse().unwrap();
    match start(config).await {
        Err(StartError::Refused(message)) => assert!(message.contains("loopback"), "{message}"),
        Err(e) => panic!("wrong error: {e}"),
        Ok(_) => panic!("must refuse to start"),
    }
}

#[tokio::test]
async fn binary_refuses_open_bind_without_tokens_and_serves_with_one() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let out = run_binary(&["serve", "--bind", "0.0.0.0:0", "--database-url", &db]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("loopback"));

    let out = run_binary(&["token", "create", "--scope", "read", "--database-url", &db]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let token = String::from_utf8(out.stdout).unwrap().trim().to_string();
    assert!(token.starts_with("rbc_"));

    let mut server = spawn_binary(
        &[
            "--bind",
            "0.0.0.0:0",
            "--database-url",
            &db,
            "--workers",
            "1",
        ],
        &[],
    );
    let port = server.base.rsplit(':').next().unwrap().to_string();
    let base = format!("http://127.0.0.1:{port}");
    let c = reqwest::Client::new();
    assert_eq!(
        c.get(format!("{base}/v1/robots"))
            .send()
            .await
            .unwrap()
            .status(),
        401,
        "anonymous refused"
    );
    let ok = c
        .get(format!("{base}/v1/robots"))
        .bearer_auth(&token)
        .send()
        .await
        .unwrap();
    assert_eq!(ok.status(), 200);
    server.child.kill().unwrap();
    server.child.wait().unwrap();
}
