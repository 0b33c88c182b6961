//! Token lifecycle: `{items}` listing, revocation, expiry, last use, the
//! first token created anonymously, and `robocal token(s) create|list|revoke`.

use std::time::Duration;

use serde_json::{json, Value};

use robocal::api::auth::{generate_token, hash_token};
use robocal::domain::{now_unix_ms, Scope};
use robocal::store;

use crate::support::*;

/// A token stored directly (as `robocal token create` does).
pub async fn stored_token(app: &TestApp, scope: Scope, expires_ms: Option<i64>) -> String {
    let s = store::connect(&app.database_url).await.unwrap();
    let t = generate_token();
    s.create_token_expiring("test", &hash_token(&t), scope, expires_ms)
        .await
        .unwrap();
    t
}

async fn get_as(app: &TestApp, path: &str, token: &str) -> reqwest::Response {
    app.client
        .get(app.url(path))
        .bearer_auth(token)
        .send()
        .await
        .unwrap()
}

async fn list(app: &TestApp, admin: &str) -> Vec<Value> {
    let r = get_as(app, "/v1/tokens", admin).await;
    assert_eq!(r.status(), 200);
    let body: Value = r.json().await.unwrap();
    body["items"].as_array().expect("{items}").clone()
}

fn by_name<'a>(items: &'a [Value], name: &str) -> &'a Value {
    items
        .iter()
        .find(|t| t["name"] == name)
        .unwrap_or_else(|| panic!("no token {name} in {items:?}"))
}

async fn problem(r: reqwest::Response, status: u16) -> Value {
    assert_eq!(r.status(), status);
    assert_eq!(r.headers()["content-type"], "application/problem+json");
    r.json().await.unwrap()
}

#[tokio::test]
async fn tokens_are_listed_as_items_revoked_and_expire() {
    let app = spawn_app().await;
    let admin = stored_token(&app, Scope::Admin, None).await;
    let c = &app.client;

    // Created through the API with an expiry; the answer says when.
    let r = c
        .post(app.url("/v1/tokens"))
        .bearer_auth(&admin)
        .json(&json!({"name": "ci", "scope": "read", "expires_in_secs": 3600}))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let created: Value = r.json().await.unwrap();
    let read = created["token"].as_str().unwrap().to_string();
    let read_id = created["id"].as_str().unwrap().to_string();
    assert!(created["expires_at"].is_string(), "{created}");
    assert!(created.get("notice").is_none(), "not the first token");
    for bad in [json!(0), json!(-5), json!(400_000_000), json!("1h")] {
        let r = c
            .post(app.url("/v1/tokens"))
            .bearer_auth(&admin)
            .json(&json!({"name": "x", "scope": "read", "expires_in_secs": bad}))
            .send()
            .await
            .unwrap();
        assert!(matches!(r.status().as_u16(), 400 | 422), "{bad}");
        assert!(r.text().await.unwrap().contains("expires_in_secs"), "{bad}");
    }

    // Never used yet; a use is recorded (off the request path, so poll).
    let items = list(&app, &admin).await;
    let ci = by_name(&items, "ci");
    assert_eq!(ci["state"], "active");
    assert!(ci["last_used_at"].is_null());
    assert!(ci["revoked_at"].is_null());
    assert_eq!(get_as(&app, "/v1/robots", &read).await.status(), 200);
    let mut used = Value::Null;
    for _ in 0..100 {
        used = by_name(&list(&app, &admin).await, "ci")["last_used_at"].clone();
        if used.is_string() {
            break;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert!(used.is_string(), "last use recorded");
    // At most once a minute: a second use leaves the record as it was.
    assert_eq!(get_as(&app, "/v1/robots", &read).await.status(), 200);
    tokio::time::sleep(Duration::from_millis(200)).await;
    assert_eq!(
        by_name(&list(&app, &admin).await, "ci")["last_used_at"],
        used
    );

    // An expired token is refused with 401 and listed as expired.
    let expired = stored_token(&app, Scope::Admin, Some(now_unix_ms() - 1000)).await;
    let p = problem(get_as(&app, "/v1/robots", &expired).await, 401).await;
    assert!(p["detail"].as_str().unwrap().contains("expired"), "{p}");

    // Revocation: admin only, 204, then the token is refused; unknown id 404.
    let r = c
        .delete(app.url(&format!("/v1/tokens/{read_id}")))
        .bearer_auth(&read)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 403, "revoking needs admin");
    let r = c
        .delete(app.url(&format!("/v1/tokens/{read_id}")))
        .bearer_auth(&admin)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 204);
    let p = problem(get_as(&app, "/v1/robots", &read).await, 401).await;
    assert!(p["detail"].as_str().unwrap().contains("revoked"), "{p}");
    let r = c
        .delete(app.url("/v1/tokens/no-such-token"))
        .bearer_auth(&admin)
        .send()
        .await
        .unwrap();
    problem(r, 404).await;

    let items = list(&app, &admin).await;
    let ci = by_name(&items, "ci");
    assert_eq!(ci["state"], "revoked");
    assert!(ci["revoked_at"].is_string());
    let states: Vec<&str> = items.iter().map(|t| t["state"].as_str().unwrap()).collect();
    assert!(states.contains(&"expired"), "{states:?}");
    assert!(!serde_json::to_string(&items).unwrap().contains(&read));

    // Revoking every token does not bring anonymous access back. Over the
    // API the last admin token stays (409); the CLI's way revokes it.
    for t in &items {
        let id = t["id"].as_str().unwrap();
        let r = c
            .delete(app.url(&format!("/v1/tokens/{id}")))
            .bearer_auth(&admin)
            .send()
            .await
            .unwrap();
        assert!(
            matches!(r.status().as_u16(), 204 | 401 | 409),
            "{}",
            r.status()
        );
    }
    let s = store::connect(&app.database_url).await.unwrap();
    for t in &items {
        s.revoke_token(t["id"].as_str().unwrap()).await.unwrap();
    }
    assert_eq!(app.get("/v1/robots").await.status(), 401);
}

#[tokio::test]
async fn first_token_created_anonymously_says_anonymous_access_ends() {
    let app = spawn_app().await;
    let r = app
        .post_json("/v1/tokens", &json!({"name": "first", "scope": "read"}))
        .await;
    assert_eq!(r.status(), 201);
    let created: Value = r.json().await.unwrap();
    let notice = created["notice"].as_str().expect("a notice");
    assert!(notice.contains("anonymous access has ended"), "{notice}");
    assert!(
        notice.contains("admin"),
        "a read token warns about admin: {notice}"
    );
    // It is so: anonymous is refused, the token works.
    assert_eq!(app.get("/v1/robots").await.status(), 401);
    let token = created["token"].as_str().unwrap();
    assert_eq!(get_as(&app, "/v1/robots", token).await.status(), 200);

    // An admin creating more tokens gets no notice.
    let admin = stored_token(&app, Scope::Admin, None).await;
    let r = app
        .client
        .post(app.url("/v1/tokens"))
        .bearer_auth(&admin)
        .json(&json!({"name": "second", "scope": "admin"}))
        .send()
        .await
        .unwrap();
    let created: Value = r.json().await.unwrap();
    assert!(created.get("notice").is_none(), "{created}");
}

fn cli(args: &[&str]) -> (String, String) {
    let out = run_binary(args);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout).to_string(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    );
    assert!(out.status.success(), "{args:?}: {stderr}");
    (stdout, stderr)
}

#[tokio::test]
async fn cli_creates_lists_and_revokes_tokens() {
    let app = spawn_app().await;
    let db = app.database_url.clone();
    let (token, stderr) = cli(&[
        "token",
        "create",
        "--scope",
        "read",
        "--name",
        "month",
        "--expires-in",
        "30d",
        "--database-url",
        &db,
    ]);
    let token = token.trim().to_string();
    assert!(stderr.contains("expires"), "{stderr}");
    assert_eq!(get_as(&app, "/v1/robots", &token).await.status(), 200);

    let (table, _) = cli(&["tokens", "list", "--database-url", &db]);
    let line = table
        .lines()
        .find(|l| l.contains("month"))
        .unwrap_or_else(|| panic!("{table}"));
    assert!(line.contains("active"), "{line}");
    assert!(!table.contains(&token), "secrets are never listed");
    // Expiry about 30 days out.
    let in_30_days = humantime::format_rfc3339_seconds(
        std::time::SystemTime::now() + Duration::from_secs(30 * 86400),
    )
    .to_string();
    assert!(line.contains(&in_30_days[..10]), "{line} vs {in_30_days}");

    let id = line.split_whitespace().next().unwrap().to_string();
    cli(&["tokens", "revoke", &id, "--database-url", &db]);
    assert_eq!(get_as(&app, "/v1/robots", &token).await.status(), 401);
    let (table, _) = cli(&["tokens", "list", "--database-url", &db]);
    assert!(
        table
            .lines()
            .any(|l| l.contains(&id) && l.contains("revoked")),
        "{table}"
    );

    let out = run_binary(&["tokens", "revoke", "nope", "--database-url", &db]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no token"));
    let out = run_binary(&[
        "token",
        "create",
        "--scope",
        "read",
        "--expires-in",
        "soon",
        "--database-url",
        &db,
    ]);
    assert!(!out.status.success(), "a bad duration is refused");
}

/// Issue 32, item 10: the fuzzer revoked its own admin token and locked
/// itself out. The last usable admin token cannot be revoked over the API.
#[tokio::test]
async fn the_last_admin_token_cannot_be_revoked() {
    let app = spawn_app().await;
    let first = stored_token(&app, Scope::Admin, None).await;
    let ids = |list: Value| -> Vec<String> {
        list["items"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| t["id"].as_str().unwrap().to_string())
            .collect()
    };
    let list = get_as(&app, "/v1/tokens", &first)
        .await
        .json()
        .await
        .unwrap();
    let first_id = ids(list)[0].clone();
    let delete = |id: String, as_token: String| {
        let c = app.client.clone();
        let url = app.url(&format!("/v1/tokens/{id}"));
        async move { c.delete(url).bearer_auth(as_token).send().await.unwrap() }
    };
    let refused = delete(first_id.clone(), first.clone()).await;
    assert_eq!(refused.status(), 409);
    let problem: Value = refused.json().await.unwrap();
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("last usable admin"),
        "{problem}"
    );
    assert_eq!(
        get_as(&app, "/v1/tokens", &first).await.status(),
        200,
        "still admin"
    );

    let second = stored_token(&app, Scope::Admin, None).await;
    assert_eq!(delete(first_id.clone(), second.clone()).await.status(), 204);
    let list = get_as(&app, "/v1/tokens", &second)
        .await
        .json()
        .await
        .unwrap();
    let second_id = ids(list).into_iter().find(|i| *i != first_id).unwrap();
    assert_eq!(delete(second_id, second.clone()).await.status(), 409);
}
