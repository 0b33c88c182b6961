//! Test harness: `spawn_app()` starts the real server in-process on port 0
//! with a fresh database; `spawn_binary()` runs the real `robocal` binary
//! (for kill -9 / SIGTERM tests). The backend is fixed per test binary:
//! `tests/it` runs every test on SQLite, `tests/pg` compiles the same modules
//! again for PostgreSQL (see `test_db.rs` for the per-test databases).

use std::time::{Duration, Instant};

use robocal::config::ServeConfig;
use robocal::server::{start, RunningServer};
use serde_json::{json, Value};

pub use crate::fixtures::*;

pub use super::processes::{robot_with_session, spawn_binary};
pub use super::test_db::TestDb;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    Sqlite,
    Postgres,
}

/// Selects the backend of a test run: `sqlite` or `postgres`.
pub const BACKEND_VAR: &str = "ROBOCAL_TEST_BACKEND";
/// Set (not `0`): the PostgreSQL suite fails, instead of running on SQLite,
/// when there is no server (CI sets it).
pub const REQUIRE_PG_VAR: &str = "ROBOCAL_TEST_REQUIRE_PG";

/// The backend every test of this run uses, chosen once. [`BACKEND_VAR`]
/// names it; unset, `tests/it` runs on SQLite and `tests/pg` on PostgreSQL
/// at [`super::test_db::pg_admin_url`] when a server answers there (or
/// [`REQUIRE_PG_VAR`] is set: then a missing server fails each test), else
/// on SQLite, said once on stderr.
pub fn backend() -> Backend {
    static CHOSEN: std::sync::OnceLock<Backend> = std::sync::OnceLock::new();
    *CHOSEN.get_or_init(|| match std::env::var(BACKEND_VAR).as_deref() {
        Ok("sqlite") => Backend::Sqlite,
        Ok("postgres") => Backend::Postgres,
        Ok(other) => panic!("{BACKEND_VAR}={other:?}: expected sqlite or postgres"),
        Err(_) if env!("CARGO_CRATE_NAME") != "pg" => Backend::Sqlite,
        Err(_) => {
            let required = std::env::var_os(REQUIRE_PG_VAR).is_some_and(|v| v != "0");
            let url = super::test_db::pg_admin_url();
            if required || super::test_db::server_reachable(&url) {
                Backend::Postgres
            } else {
                eprintln!(
                    "PostgreSQL suite on SQLite: no server at {url} (set ROBOCAL_TEST_PG_URL to \
                     use one, {REQUIRE_PG_VAR}=1 to require it)"
                );
                Backend::Sqlite
            }
        }
    })
}

/// Whether a test whose subject is the numerics (a whole simulated or real
/// campaign calibrated through the service, minutes on 2 cores) runs in
/// this run: always on SQLite, and on PostgreSQL only when
/// [`NUMERICS_ON_PG_VAR`] is set. Its store traffic is that of every other
/// job test, which does run on both backends; its figures do not depend on
/// the backend. Says so on stderr when it does not run.
pub fn numerics_run_here(test: &str) -> bool {
    let run = backend() == Backend::Sqlite
        || std::env::var_os(NUMERICS_ON_PG_VAR).is_some_and(|v| v != "0");
    if !run {
        eprintln!(
            "{test}: not run on PostgreSQL (a numerics test; set {NUMERICS_ON_PG_VAR}=1 to run it)"
        );
    }
    run
}

/// Set (not `0`): [`numerics_run_here`] also runs the numerics tests on PostgreSQL.
pub const NUMERICS_ON_PG_VAR: &str = "ROBOCAL_TEST_NUMERICS_ON_PG";

/// A fresh, empty database for one test, on the selected backend. Keep the
/// guard for the whole test: the PostgreSQL database is dropped with it.
pub fn fresh_database(dir: &tempfile::TempDir) -> TestDb {
    match backend() {
        Backend::Sqlite => TestDb::sqlite(dir),
        Backend::Postgres => TestDb::postgres(),
    }
}

pub struct TestApp {
    pub base: String,
    pub client: reqwest::Client,
    pub database_url: String,
    server: Option<RunningServer>,
    _dir: tempfile::TempDir,
    _db: TestDb,
}

pub fn test_config(database_url: &str, dir: &tempfile::TempDir) -> ServeConfig {
    let mut config = ServeConfig::for_database(database_url);
    config.bind = "127.0.0.1:0".parse().unwrap();
    config.workers = Some(2);
    config.poll_ms = 50;
    config.lease_secs = 2;
    config.shutdown_grace_secs = 5;
    config.upload_dir = Some(dir.path().to_path_buf());
    // Webhook receivers of the tests listen on loopback.
    config.webhook_allow_networks = vec!["127.0.0.0/8".parse().unwrap()];
    // Queue and API tests use tiny synthetic sessions; `e2e` turns the
    // numerical stages back on.
    config.test_validate_only = true;
    config
}

pub async fn spawn_app() -> TestApp {
    spawn_app_with(|_| {}).await
}

pub async fn spawn_app_with(tweak: impl FnOnce(&mut ServeConfig)) -> TestApp {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let database_url = db.to_string();
    let mut config = test_config(&database_url, &dir);
    tweak(&mut config);
    let server = start(config).await.expect("server starts");
    let addr = server.addr;
    TestApp {
        base: format!("http://{addr}"),
        client: reqwest::Client::new(),
        database_url,
        server: Some(server),
        _dir: dir,
        _db: db,
    }
}

impl TestApp {
    pub fn url(&self, path: &str) -> String {
        format!("{}{}", self.base, path)
    }

    pub async fn get(&self, path: &str) -> reqwest::Response {
        self.client.get(self.url(path)).send().await.unwrap()
    }

    pub async fn put_json(&self, path: &str, body: &Value) -> reqwest::Response {
        self.client
            .put(self.url(path))
            .json(body)
            .send()
            .await
            .unwrap()
    }

    pub async fn post_json(&self, path: &str, body: &Value) -> reqwest::Response {
        self.client
            .post(self.url(path))
            .json(body)
            .send()
            .await
            .unwrap()
    }

    /// Stops the server cleanly; the returned directory and database guard
    /// keep the database (SQLite file, PostgreSQL database) while held.
    pub async fn shutdown(mut self) -> (tempfile::TempDir, TestDb) {
        if let Some(s) = self.server.take() {
            s.shutdown().await;
        }
        (self._dir, self._db)
    }

    /// A robot `serial` with the 6-joint test table, and a camera session.
    pub async fn robot_and_session(&self, serial: &str) -> String {
        let r = self
            .put_json(&format!("/v1/robots/{serial}"), &robot_body())
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
        self.new_session(serial, &session_body()).await
    }

    /// A session of robot `serial` with the fields `body`; its id.
    pub async fn new_session(&self, serial: &str, body: &Value) -> String {
        let r = self
            .post_json(&format!("/v1/robots/{serial}/sessions"), body)
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
        r.json::<Value>().await.unwrap()["id"]
            .as_str()
            .unwrap()
            .to_string()
    }

    /// Adds `cal` calibration and `val` validation poses with image points.
    pub async fn add_point_poses(&self, session: &str, cal: usize, val: usize) {
        for i in 0..cal + val {
            let set = if i < cal { "cal" } else { "val" };
            let r = self
                .post_json(
                    &format!("/v1/sessions/{session}/poses"),
                    &point_pose(i, set),
                )
                .await;
            assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
        }
    }

    /// `GET path`, 200, as JSON.
    pub async fn get_ok(&self, path: &str) -> Value {
        let r = self.get(path).await;
        assert_eq!(r.status(), 200, "{path}");
        r.json().await.unwrap()
    }

    /// `POST path` with `body`, 200, as JSON.
    pub async fn post_ok(&self, path: &str, body: &Value) -> Value {
        let r = self.post_json(path, body).await;
        assert_eq!(r.status(), 200, "{path}: {}", r.text().await.unwrap());
        r.json().await.unwrap()
    }

    /// `POST path` with `body` (a calibration, a check): accepted, and the
    /// job it queued, succeeded within `timeout`.
    pub async fn finished_job(&self, path: &str, body: &Value, timeout: Duration) -> Value {
        let r = self.post_json(path, body).await;
        assert_eq!(r.status(), 202, "{}", r.text().await.unwrap());
        let job = r.json::<Value>().await.unwrap()["job_id"]
            .as_str()
            .unwrap()
            .to_string();
        let done = self.wait_job(&job, timeout, is_finished).await;
        assert_eq!(done["state"], "succeeded", "{done}");
        done
    }

    /// Robot `serial` (`model`) with `robot`'s joint table, as a user
    /// describes an arm of their own: 201.
    pub async fn put_kinematics(
        &self,
        serial: &str,
        model: &str,
        robot: &robocal_calib::kinematics::RobotModel,
    ) {
        let kinematics = robocal::schema::robot::model_to_doc(robot);
        let r = self
            .put_json(
                &format!("/v1/robots/{serial}"),
                &json!({"model": model, "kinematics": kinematics}),
            )
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }

    /// Approves set `version` of `serial` unless the gate already did
    /// (`reason`: why a person overrides it).
    pub async fn approve_unless_approved(&self, serial: &str, version: u32, reason: &str) {
        let set = format!("/v1/robots/{serial}/parameter-sets/{version}");
        let report = self.get_ok(&format!("{set}/report")).await;
        if report["gate"]["status"] == "approved" {
            return;
        }
        let r = self
            .post_json(&format!("{set}/approve"), &json!({"reason": reason}))
            .await;
        assert!(r.status().is_success(), "{}", r.text().await.unwrap());
    }

    /// A session of robot `serial` (`body`: its fields) with one tracker
    /// pose per `(joints_deg, measured_position_mm, set)`; its id.
    pub async fn tracker_session(
        &self,
        serial: &str,
        body: &Value,
        poses: impl IntoIterator<Item = (Vec<f64>, [f64; 3], &'static str)>,
    ) -> String {
        let id = self.new_session(serial, body).await;
        for (joints_deg, position_mm, set) in poses {
            let pose =
                json!({"joints_deg": joints_deg, "measured_position_mm": position_mm, "set": set});
            let r = self
                .post_json(&format!("/v1/sessions/{id}/poses"), &pose)
                .await;
            assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
        }
        id
    }

    /// Polls a job until `done(job)` or the timeout.
    pub async fn wait_job(
        &self,
        job: &str,
        timeout: Duration,
        done: impl Fn(&Value) -> bool,
    ) -> Value {
        wait_job_at(&self.client, &self.base, job, timeout, done).await
    }
}

/// Starts a calibration of `session` (default options); returns the job id.
pub async fn start_calibration(c: &reqwest::Client, base: &str, session: &str) -> String {
    let r = c
        .post(format!("{base}/v1/sessions/{session}/calibrations"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 202);
    r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string()
}

pub async fn wait_job_at(
    client: &reqwest::Client,
    base: &str,
    job: &str,
    timeout: Duration,
    done: impl Fn(&Value) -> bool,
) -> Value {
    let start = Instant::now();
    loop {
        let v: Value = client
            .get(format!("{base}/v1/jobs/{job}"))
            .send()
            .await
            .unwrap()
            .json()
            .await
            .unwrap();
        if done(&v) {
            return v;
        }
        assert!(
            start.elapsed() < timeout,
            "job did not get there in time: {v}"
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

/// How long a calibration of a small simulated campaign may take in CI.
pub const CAMPAIGN_WAIT: Duration = Duration::from_secs(240);

/// Uploads campaign directory `dir` (as `robocal simulate` writes it) as
/// robot `serial` through the CLI's client, calibrates it and waits; the
/// job must succeed. Returns the finished job.
pub async fn upload_and_calibrate(app: &TestApp, serial: &str, dir: &std::path::Path) -> Value {
    let client = robocal::cli::client::Client::new(&app.base, None).unwrap();
    let session = robocal::cli::upload(
        &client,
        serial,
        dir,
        robocal::cli::RobotPolicy::CreateIfMissing,
    )
    .await
    .unwrap();
    let done = robocal::cli::calibrate(&client, serial, &session, false)
        .await
        .unwrap();
    let job = app
        .wait_job(done.job_id(), CAMPAIGN_WAIT, is_finished)
        .await;
    assert_eq!(job["state"], "succeeded", "{job}");
    job
}

/// The report's note containing `words` (panics naming the notes if none).
pub fn report_note<'a>(report: &'a Value, words: &str) -> &'a str {
    let notes: Vec<&str> = report["notes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    notes
        .iter()
        .find(|n| n.contains(words))
        .copied()
        .unwrap_or_else(|| panic!("no note with {words:?} in {notes:?}"))
}

pub fn is_finished(v: &Value) -> bool {
    matches!(
        v["state"].as_str(),
        Some("succeeded" | "failed" | "cancelled")
    )
}

/// A kinematic set whose content the test does not check (an empty joint
/// table, identity frames), told apart by its `session_id`.
pub fn placeholder_set(session_id: &str) -> robocal::domain::CalibratedSet {
    robocal::domain::CalibratedSet::Kinematic(robocal::domain::ParameterSet::placeholder(
        session_id,
    ))
}

/// A tracker set (no camera) whose content the test does not check.
pub fn tracker_set() -> robocal::domain::CalibratedSet {
    robocal::domain::CalibratedSet::Kinematic(robocal::domain::ParameterSet {
        instrument: robocal::schema::session::Instrument::Tracker,
        ..robocal::domain::ParameterSet::placeholder("tracker")
    })
}

/// A camera calibrated without a robot model (a stage camera set) with
/// `intrinsics` (`{"fx",...,"k3"}`).
pub fn camera_only_set(intrinsics: Value) -> robocal::domain::CalibratedSet {
    robocal::domain::CalibratedSet::StageCamera(robocal::domain::StageCameraSet {
        instrument: "stage".into(),
        session_id: "camera".into(),
        camera: serde_json::from_value(intrinsics).expect("intrinsics"),
        camera_mode: "stage".into(),
        camera_std: None,
        sequences: Vec::new(),
    })
}
