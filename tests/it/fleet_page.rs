//! The fleet pages over plain HTTP: what they show, who may see them
//! (anonymous on loopback; with tokens, a login that sets a session
//! cookie), and that they load nothing from outside.

use reqwest::redirect::Policy;
use reqwest::StatusCode;
use serde_json::json;

use robocal::api::auth::{generate_token, hash_token};
use robocal::domain::Scope;
use robocal::report::sample::sample_report;
use robocal::store::{self, NewParameterSet};

use crate::support::*;

/// A robot `serial` with one parameter set whose report is the sample's.
pub async fn robot_with_reported_set(app: &TestApp, serial: &str) -> f64 {
    let r = app
        .put_json(&format!("/v1/robots/{serial}"), &robot_body())
        .await;
    assert_eq!(r.status(), 201);
    let s = store::connect(&app.database_url).await.unwrap();
    let report = sample_report();
    let mean = report.after.norm.mean_mm;
    s.insert_parameter_set(
        serial,
        None,
        &NewParameterSet::approved(
            crate::support::placeholder_set("s"),
            serde_json::to_value(&report).unwrap(),
        ),
    )
    .await
    .unwrap();
    mean
}

pub async fn read_token(app: &TestApp, scope: Scope) -> (String, String) {
    let s = store::connect(&app.database_url).await.unwrap();
    let t = generate_token();
    let record = s
        .create_token("fleet-page", &hash_token(&t), scope)
        .await
        .unwrap();
    (t, record.id)
}

fn no_redirects() -> reqwest::Client {
    reqwest::Client::builder()
        .redirect(Policy::none())
        .build()
        .unwrap()
}

#[tokio::test]
async fn anonymous_fleet_page_shows_robots_sets_accuracy_and_links() {
    let app = spawn_app().await;
    let empty = app.get("/").await;
    assert_eq!(empty.status(), 200);
    assert!(empty.text().await.unwrap().contains("No robots yet"));

    let mean = robot_with_reported_set(&app, "FP-1").await;
    app.robot_and_session("FP-2").await;
    let r = app.get("/").await;
    assert_eq!(r.status(), 200);
    assert!(r.headers()["content-type"]
        .to_str()
        .unwrap()
        .starts_with("text/html"));
    let csp = r.headers()["content-security-policy"]
        .to_str()
        .unwrap()
        .to_string();
    assert!(csp.contains("default-src 'none'"), "{csp}");
    let page = r.text().await.unwrap();
    assert!(page.contains("name=\"viewport\""));
    assert!(page.contains("href=\"/robots/FP-1\""), "{page}");
    assert!(page.contains("href=\"/robots/FP-2\""));
    assert!(page.contains("v1 · just now"), "{page}");
    let accuracy = robocal::report::format::mm(mean);
    assert!(page.contains(&format!("{accuracy} mm mean")), "{page}");
    assert!(page.contains("not calibrated"), "FP-2 has no set: {page}");
    assert!(page.contains(robocal::api::fleet::NO_CHECKS));
    for outside in ["http://", "https://", "<script", "src=\""] {
        assert!(!page.contains(outside), "{outside} in {page}");
    }

    let robot = app.get("/robots/FP-1").await.text().await.unwrap();
    assert!(robot.contains("href=\"/robots/FP-1/reports/1\""), "{robot}");
    assert!(robot.contains("(current)"));
    let report = app.get("/robots/FP-1/reports/1").await;
    assert_eq!(report.status(), 200);
    assert!(report.text().await.unwrap().contains("validation poses"));

    let missing = app.get("/robots/NOPE").await;
    assert_eq!(missing.status(), 404);
    assert!(missing
        .text()
        .await
        .unwrap()
        .contains("There is no robot NOPE"));
    assert_eq!(app.get("/robots/FP-1/reports/9").await.status(), 404);
    assert_eq!(app.get("/robots/FP-1/reports/x").await.status(), 404);
}

/// The login form (checked), its nonce and its cookie as `name=value`.
pub async fn login_form(c: &reqwest::Client, app: &TestApp) -> (String, String) {
    let form = c.get(app.url("/login")).send().await.unwrap();
    assert_eq!(form.status(), 200);
    let cookie = form.headers()["set-cookie"].to_str().unwrap();
    assert!(
        cookie.contains("HttpOnly") && cookie.contains("SameSite=Strict"),
        "{cookie}"
    );
    let cookie = cookie.split(';').next().unwrap().to_string();
    let text = form.text().await.unwrap();
    assert!(text.contains("action=\"/login\""));
    let nonce = text
        .split("name=\"nonce\" value=\"")
        .nth(1)
        .and_then(|rest| rest.split('"').next())
        .expect("the form carries a nonce")
        .to_string();
    (cookie, nonce)
}

#[tokio::test]
async fn with_tokens_the_pages_need_a_login_cookie_never_the_token_in_a_url() {
    let app = spawn_app().await;
    robot_with_reported_set(&app, "FP-3").await;
    let (token, token_id) = read_token(&app, Scope::Read).await;
    let c = no_redirects();

    let r = c.get(app.url("/")).send().await.unwrap();
    assert_eq!(r.status(), StatusCode::SEE_OTHER);
    assert_eq!(r.headers()["location"], "/login");
    let (form_cookie, nonce) = login_form(&c, &app).await;

    // Login CSRF: a form posted from elsewhere has no nonce matching the
    // browser's login cookie, and signs nobody in.
    for (cookie, body) in [
        (None, format!("token={token}")),
        (None, format!("token={token}&nonce={nonce}")),
        (
            Some(form_cookie.as_str()),
            format!("token={token}&nonce=other"),
        ),
    ] {
        let mut post = c
            .post(app.url("/login"))
            .header("content-type", "application/x-www-form-urlencoded")
            .body(body);
        if let Some(cookie) = cookie {
            post = post.header("cookie", cookie);
        }
        let forged = post.send().await.unwrap();
        assert_eq!(forged.status(), 403);
        assert!(!forged.headers()["set-cookie"]
            .to_str()
            .unwrap()
            .starts_with("robocal_session="));
    }

    let bad = c
        .post(app.url("/login"))
        .header("content-type", "application/x-www-form-urlencoded")
        .header("cookie", &form_cookie)
        .body(format!("token=rbc_wrong&nonce={nonce}"))
        .send()
        .await
        .unwrap();
    assert_eq!(bad.status(), 401);
    assert!(bad.headers()["set-cookie"]
        .to_str()
        .unwrap()
        .starts_with("robocal_login="));
    assert!(bad.text().await.unwrap().contains("unknown token"));

    let ok = c
        .post(app.url("/login"))
        .header("content-type", "application/x-www-form-urlencoded")
        .header("cookie", &form_cookie)
        .body(format!("token={token}&nonce={nonce}"))
        .send()
        .await
        .unwrap();
    assert_eq!(ok.status(), StatusCode::SEE_OTHER);
    assert_eq!(ok.headers()["location"], "/");
    let cookie = ok.headers()["set-cookie"].to_str().unwrap().to_string();
    assert!(cookie.starts_with("robocal_session="), "{cookie}");
    assert!(
        cookie.contains("HttpOnly") && cookie.contains("SameSite=Strict"),
        "{cookie}"
    );
    assert!(
        !cookie.contains(&token),
        "the cookie holds a session, not the token"
    );
    let session = cookie.split(';').next().unwrap().to_string();

    let page = c
        .get(app.url("/"))
        .header("cookie", &session)
        .send()
        .await
        .unwrap();
    assert_eq!(page.status(), 200);
    let text = page.text().await.unwrap();
    assert!(text.contains("href=\"/robots/FP-3\""));
    assert!(text.contains("action=\"/logout\""));

    // An altered cookie is no session.
    let forged = session.replacen(&token_id, "someone-else", 1);
    let r = c
        .get(app.url("/"))
        .header("cookie", forged)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), StatusCode::SEE_OTHER);

    // The API itself still wants the bearer token, not the cookie.
    let api = c
        .get(app.url("/v1/robots"))
        .header("cookie", &session)
        .send()
        .await
        .unwrap();
    assert_eq!(api.status(), 401);

    let out = c.post(app.url("/logout")).send().await.unwrap();
    assert_eq!(out.status(), StatusCode::SEE_OTHER);
    assert!(out.headers()["set-cookie"]
        .to_str()
        .unwrap()
        .contains("Max-Age=0"));

    // Revoking the token ends its sessions.
    let s = store::connect(&app.database_url).await.unwrap();
    s.revoke_token(&token_id).await.unwrap();
    let r = c
        .get(app.url("/"))
        .header("cookie", &session)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), StatusCode::SEE_OTHER);
}

#[tokio::test]
async fn anonymous_pages_refuse_a_rebound_host() {
    let app = spawn_app().await;
    let r = app
        .client
        .get(app.url("/"))
        .header("host", "evil.example")
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 421);
}

/// How long the failing job may take: its 3 poses each wait the test's
/// stage delay (15 s a pose in the browser test) before it fails.
const FAILED_JOB_WAIT: std::time::Duration = std::time::Duration::from_secs(150);

/// Why [`robot_with_failed_job`]'s job failed, as its error says.
pub const FAILED_JOB_REASON: &str = "val_set";

/// Robot `serial` whose only job failed (calibration poses but no
/// validation pose for the default `val_set`); its id.
pub async fn robot_with_failed_job(app: &TestApp, serial: &str) -> String {
    let session = app.robot_and_session(serial).await;
    app.add_point_poses(&session, 3, 0).await;
    let r = app
        .post_json(&format!("/v1/sessions/{session}/calibrations"), &json!({}))
        .await;
    assert_eq!(r.status(), 202);
    let job = r.json::<serde_json::Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let done = app.wait_job(&job, FAILED_JOB_WAIT, is_finished).await;
    assert_eq!(done["state"], "failed", "{done}");
    job
}

#[tokio::test]
async fn a_robot_whose_job_failed_says_why_with_the_whole_job_id() {
    let app = spawn_app().await;
    let job = robot_with_failed_job(&app, "FP-F").await;
    app.robot_and_session("FP-U").await;
    let page = app.get("/").await.text().await.unwrap();
    let card = page
        .split("id=\"robot-FP-F\"")
        .nth(1)
        .and_then(|c| c.split("</section>").next())
        .unwrap();
    assert!(page.contains("class=\"card robot failed\" id=\"robot-FP-F\""));
    assert!(card.contains("calibration failed</span>: "), "{card}");
    assert!(card.contains(FAILED_JOB_REASON), "the reason: {card}");
    assert!(
        card.contains(&format!("href=\"/robots/FP-F#job-{job}\">job {job}</a>")),
        "{card}"
    );
    assert!(
        page.contains("class=\"card robot\" id=\"robot-FP-U\""),
        "an untouched robot is not failed"
    );

    let robot = app.get("/robots/FP-F").await.text().await.unwrap();
    let row = robot
        .split(&format!("<tr id=\"job-{job}\">"))
        .nth(1)
        .and_then(|r| r.split("</tr>").next())
        .unwrap_or_else(|| panic!("a row for the whole id: {robot}"));
    assert!(
        row.contains(&format!("<td class=\"id\">{job}</td>")),
        "{row}"
    );
    assert!(row.contains(FAILED_JOB_REASON), "{row}");
}
