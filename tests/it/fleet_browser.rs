//! The fleet page in a real browser (headless Chromium driven through
//! chromedriver's WebDriver): sign in with a read token, see the fleet,
//! follow a robot, check what a person sees, keep screenshots. Skipped,
//! saying so, when no Chromium is installed, unless
//! `ROBOCAL_TEST_REQUIRE_BROWSER=1` (CI sets it: there it must run).

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use base64::Engine;
use serde_json::{json, Value};

use robocal::domain::Scope;

use super::fleet_page::{read_token, robot_with_failed_job, robot_with_reported_set};
use super::release_reports::{job_of, robot_with_decided_sets};
use crate::support::*;

/// Set (not `0`): a missing browser fails the test instead of skipping it.
/// Validation delay per pose of the job the page shows running (ms).
const BROWSER_STAGE_DELAY_MS: u64 = 15_000;
const REQUIRE_BROWSER_VAR: &str = "ROBOCAL_TEST_REQUIRE_BROWSER";
/// A phone's viewport, CSS pixels (the page must fit it without scrolling sideways).
const PHONE_WIDTH: u32 = 412;
const PHONE_HEIGHT: u32 = 915;
/// The W3C WebDriver key of an element reference.
const ELEMENT_KEY: &str = "element-6066-11e4-a52e-4f735466cecf";
const DRIVER_START: Duration = Duration::from_secs(30);

fn find_binary(names: &[&str]) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|dir| names.iter().map(move |n| dir.join(n)))
        .find(|p| p.is_file())
}

/// Where screenshots go: `<target>/ci-artifacts/`.
fn artifact_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("the target directory")
        .join("ci-artifacts");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

struct Driver {
    child: Child,
    base: String,
    session: String,
    http: reqwest::Client,
    _profile: tempfile::TempDir,
}

impl Drop for Driver {
    /// Kills chromedriver's process group: the browser it started too, also
    /// when a failed assertion left the session open.
    fn drop(&mut self) {
        let group = format!("-{}", self.child.id());
        let _ = Command::new("kill").args(["-KILL", "--", &group]).status();
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Driver {
    async fn start(chromium: &Path, chromedriver: &Path) -> Driver {
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let child = Command::new(chromedriver)
            .arg(format!("--port={port}"))
            // Its own process group, which the browser joins (see `drop`).
            .process_group(0)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts");
        let base = format!("http://127.0.0.1:{port}");
        let http = reqwest::Client::new();
        let start = Instant::now();
        loop {
            let ready = http.get(format!("{base}/status")).send().await;
            if let Ok(r) = ready {
                let v: Value = r.json().await.unwrap_or_default();
                if v["value"]["ready"] == true {
                    break;
                }
            }
            assert!(start.elapsed() < DRIVER_START, "chromedriver did not start");
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
        let profile = tempfile::tempdir().unwrap();
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": chromium,
                "args": ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                         "--disable-breakpad", "--disable-crash-reporter",
                         format!("--window-size={PHONE_WIDTH},{PHONE_HEIGHT}"),
                         format!("--user-data-dir={}", profile.path().display())],
                // A phone's viewport: device metrics, not only a small window.
                "mobileEmulation": {"deviceMetrics": {"width": PHONE_WIDTH, "height": PHONE_HEIGHT, "pixelRatio": 2.0}}
            }
        }}});
        let r: Value = http
            .post(format!("{base}/session"))
            .json(&caps)
            .send()
            .await
            .unwrap()
            .json()
            .await
            .unwrap();
        let session = r["value"]["sessionId"]
            .as_str()
            .unwrap_or_else(|| panic!("no WebDriver session: {r}"))
            .to_string();
        Driver {
            child,
            base,
            session,
            http,
            _profile: profile,
        }
    }

    async fn call(&self, method: reqwest::Method, path: &str, body: Option<Value>) -> Value {
        let url = format!("{}/session/{}{path}", self.base, self.session);
        let mut req = self.http.request(method, url);
        if let Some(b) = body {
            req = req.json(&b);
        }
        let v: Value = req.send().await.unwrap().json().await.unwrap();
        assert!(v["value"]["error"].is_null(), "WebDriver {path}: {v}");
        v["value"].clone()
    }

    async fn goto(&self, url: &str) {
        self.call(reqwest::Method::POST, "/url", Some(json!({ "url": url })))
            .await;
    }

    async fn url(&self) -> String {
        self.call(reqwest::Method::GET, "/url", None)
            .await
            .as_str()
            .unwrap()
            .to_string()
    }

    /// Waits until the browser is at `url` (a click on a link or a form
    /// returns before the navigation it starts).
    async fn wait_for_url(&self, url: &str) {
        let start = Instant::now();
        loop {
            let at = self.url().await;
            if at == url {
                return;
            }
            if start.elapsed() > DRIVER_START {
                let shown = self.text("body").await;
                panic!("the browser is at {at}, not {url}: {shown}");
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    }

    async fn find(&self, css: &str) -> String {
        let v = self
            .call(
                reqwest::Method::POST,
                "/element",
                Some(json!({"using": "css selector", "value": css})),
            )
            .await;
        v[ELEMENT_KEY]
            .as_str()
            .unwrap_or_else(|| panic!("no element {css}: {v}"))
            .to_string()
    }

    async fn text(&self, css: &str) -> String {
        let id = self.find(css).await;
        self.call(reqwest::Method::GET, &format!("/element/{id}/text"), None)
            .await
            .as_str()
            .unwrap()
            .to_string()
    }

    async fn click(&self, css: &str) {
        let id = self.find(css).await;
        self.call(
            reqwest::Method::POST,
            &format!("/element/{id}/click"),
            Some(json!({})),
        )
        .await;
    }

    async fn type_into(&self, css: &str, text: &str) {
        let id = self.find(css).await;
        self.call(
            reqwest::Method::POST,
            &format!("/element/{id}/value"),
            Some(json!({ "text": text })),
        )
        .await;
    }

    async fn script(&self, js: &str) -> Value {
        self.call(
            reqwest::Method::POST,
            "/execute/sync",
            Some(json!({"script": js, "args": []})),
        )
        .await
    }

    /// Saves a PNG of the viewport and prints its path.
    async fn screenshot(&self, name: &str) -> PathBuf {
        let b64 = self.call(reqwest::Method::GET, "/screenshot", None).await;
        let png = base64::engine::general_purpose::STANDARD
            .decode(b64.as_str().unwrap())
            .unwrap();
        assert!(png.starts_with(b"\x89PNG"), "a PNG screenshot");
        let path = artifact_dir().join(name);
        std::fs::write(&path, png).unwrap();
        eprintln!("fleet browser test: screenshot saved to {}", path.display());
        path
    }

    async fn quit(&self) {
        let _ = self
            .http
            .delete(format!("{}/session/{}", self.base, self.session))
            .send()
            .await;
    }
}

#[tokio::test]
async fn a_person_signs_in_sees_the_fleet_and_follows_a_robot_in_chromium() {
    let chromium = find_binary(&["chromium", "chromium-browser", "google-chrome"]);
    let chromedriver = find_binary(&["chromedriver"]);
    let (Some(chromium), Some(chromedriver)) = (chromium, chromedriver) else {
        let required = std::env::var_os(REQUIRE_BROWSER_VAR).is_some_and(|v| v != "0");
        assert!(
            !required,
            "{REQUIRE_BROWSER_VAR} is set but chromium or chromedriver is not on PATH \
             (apt-get install chromium chromium-driver)"
        );
        eprintln!(
            "SKIPPED fleet browser test: no chromium and chromedriver on PATH \
             (apt-get install chromium chromium-driver; CI sets {REQUIRE_BROWSER_VAR}=1)"
        );
        return;
    };
    // Jobs that stay running while the browser looks (4 poses ×
    // BROWSER_STAGE_DELAY_MS; cancelled at the end, so the length costs
    // nothing). 3 s a pose was too short once under CI's load: Chromium's
    // start outlasted the 12 s and the page showed no job in progress.
    let app = spawn_app_with(|c| c.test_stage_delay_ms = BROWSER_STAGE_DELAY_MS).await;
    let mean = robot_with_reported_set(&app, "CELL-7").await;
    // Sets a gate and people decided on, and a robot whose only job failed
    // (before CELL-8's job holds the worker).
    robot_with_decided_sets(&app, "CELL-9").await;
    let failed = robot_with_failed_job(&app, "CELL-F").await;
    let session = app.robot_and_session("CELL-8").await;
    app.add_point_poses(&session, 3, 1).await;
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/calibrations")))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 202);
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    app.wait_job(&job, Duration::from_secs(30), |v| v["state"] == "running")
        .await;
    let (token, _) = read_token(&app, Scope::Read).await;
    let (admin, _) = read_token(&app, Scope::Admin).await;

    let browser = Driver::start(&chromium, &chromedriver).await;
    browser.goto(&app.url("/")).await;
    assert!(
        browser.url().await.ends_with("/login"),
        "signed out: the login form"
    );
    browser.type_into("#token", &token).await;
    browser.click("button[type=submit]").await;

    browser.wait_for_url(&app.url("/")).await;
    let history = browser.script("return window.location.href;").await;
    assert!(
        !history.as_str().unwrap().contains(&token),
        "the token is in no URL"
    );
    let summary = browser.text("#fleet-summary").await;
    assert_eq!(summary, "4 robots · 1 job in progress");
    let seven = browser.text("#robot-CELL-7").await;
    assert!(seven.contains("v1 · just now"), "{seven}");
    let accuracy = robocal::report::format::mm(mean);
    assert!(seven.contains(&format!("{accuracy} mm mean")), "{seven}");
    assert!(seven.contains("no checks"), "{seven}");
    let eight = browser.text("#robot-CELL-8").await;
    assert!(eight.contains("not calibrated"), "{eight}");
    assert!(eight.contains("calibration running"), "{eight}");
    let fits = browser
        .script("return document.documentElement.scrollWidth <= window.innerWidth;")
        .await;
    assert_eq!(fits, true, "the fleet page fits a phone's width");
    let cookies = browser.call(reqwest::Method::GET, "/cookie", None).await;
    let session_cookie = cookies
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == robocal::api::fleet::COOKIE)
        .unwrap_or_else(|| panic!("a session cookie: {cookies}"));
    assert_eq!(session_cookie["httpOnly"], true);
    assert_eq!(session_cookie["sameSite"], "Strict");
    browser.screenshot("fleet.png").await;

    browser.click("#robot-CELL-7 h2 a").await;
    browser.wait_for_url(&app.url("/robots/CELL-7")).await;
    assert_eq!(browser.text("h1").await, "CELL-7");
    let versions = browser.text("#versions").await;
    assert!(versions.contains("v1 (current)"), "{versions}");
    assert!(versions.contains("report v1"), "{versions}");
    browser.screenshot("robot.png").await;

    browser.click("#versions a").await;
    browser
        .wait_for_url(&app.url("/robots/CELL-7/reports/1"))
        .await;
    let report = browser.text("body").await;
    assert!(report.contains("validation poses"), "{report}");

    // The report a click reaches names its own version and job and says
    // the set's current status, who gave it and why (issue 37, items 1-2).
    browser.goto(&app.url("/robots/CELL-9")).await;
    let versions = browser.text("#versions").await;
    assert!(versions.contains("Status"), "{versions}");
    assert!(
        browser.text("#v4 .status").await == "rejected · by anonymous",
        "{versions}"
    );
    assert!(browser.text("#v3 .status").await.starts_with("candidate"));
    browser.click("#v2 a").await;
    browser
        .wait_for_url(&app.url("/robots/CELL-9/reports/2"))
        .await;
    let header = browser.text("header").await;
    assert!(
        header.contains("Parameter set") && header.contains("v2") && !header.contains("v0"),
        "{header}"
    );
    assert!(header.contains(&job_of(2)), "{header}");
    let status = browser.text("#release-status").await;
    assert!(
        status.starts_with("APPROVED by anonymous") && status.contains("re-measured on the cell"),
        "{status}"
    );
    // The gate's "before" is traced: both figures, and v1's own report's.
    let gate = browser.text("#release-gate").await;
    let own = robocal::report::format::mm(super::release_reports::GATE_OWN_MEAN_MM);
    assert!(
        gate.contains("CELL-9/1 on these poses")
            && gate.contains("CELL-9/1 in its own report (session session-of-v1)")
            && gate.contains(&format!("{own} mm")),
        "{gate}"
    );
    browser.screenshot("report-approved.png").await;
    browser.goto(&app.url("/robots/CELL-9/reports/4")).await;
    let status = browser.text("#release-status").await;
    assert!(status.starts_with("REJECTED by anonymous"), "{status}");

    // A robot whose only job failed: its card says so, why, and the whole
    // job id, which the robot page's jobs table shows too (item 10).
    browser.goto(&app.url("/")).await;
    let card = browser.text("#robot-CELL-F").await;
    assert!(card.contains("calibration failed"), "{card}");
    assert!(card.contains(&format!("job {failed}")), "{card}");
    let border = browser
        .script("return getComputedStyle(document.getElementById('robot-CELL-F')).borderTopWidth;")
        .await;
    assert_eq!(border, "2px", "a failed robot's card stands out");
    browser.screenshot("fleet-failed.png").await;
    browser.click("#robot-CELL-F .failed a").await;
    browser
        .wait_for_url(&app.url(&format!("/robots/CELL-F#job-{failed}")))
        .await;
    let row = browser.text(&format!("#job-{failed}")).await;
    assert!(
        row.contains(&failed) && row.contains(super::fleet_page::FAILED_JOB_REASON),
        "{row}"
    );
    browser.quit().await;
    // The running job stops at its next pose instead of holding the runtime.
    app.client
        .delete(app.url(&format!("/v1/jobs/{job}")))
        .bearer_auth(&admin)
        .send()
        .await
        .unwrap();
    app.shutdown().await;
}
