//! The release gate over HTTP (issue 17): `latest` is the newest approved
//! set; approve/reject change it, recorded with who and when, listed in
//! the robot's history; the 4xx answers name the field (a version of
//! another robot, a check or a partial scope on a robot with no approved
//! set). Sets are stored directly, as a job's gate would leave them; the
//! gate's decision on a real job (a paper-mode set never becomes `latest`)
//! is in `e2e_points`, its numerics in `pipeline::gate` and calib's
//! `kinematics::recheck`.

use robocal::domain::{CalibratedSet, ParameterSet, Release, ReleaseStatus};
use robocal::report::ParameterReport;
use robocal::store;
use robocal::store::NewParameterSet;
use serde_json::{json, Value};

use crate::support::*;

/// A free parameter's row: identified `value` from nominal 0.
fn row(name: &str, unit: &str, value: f64, std: f64) -> ParameterReport {
    ParameterReport {
        name: name.into(),
        unit: unit.into(),
        nominal: 0.0,
        identified: value,
        std,
        fixed: false,
    }
}

pub fn set(k: f64, status: ReleaseStatus) -> NewParameterSet {
    NewParameterSet {
        parameters: CalibratedSet::Kinematic(ParameterSet {
            parameters: vec![
                row("dtheta_2", "deg", k, 0.01),
                row("target_to_base.tx", "mm", k, 0.1),
            ],
            ..ParameterSet::placeholder(format!("k{k}"))
        }),
        report: json!({"after": {"mean_mm": k}}),
        release: Release {
            status,
            reason: Some(format!("stored by the test as {}", status.as_str())),
        },
    }
}

async fn json_of(r: reqwest::Response, status: u16) -> Value {
    assert_eq!(r.status(), status);
    r.json().await.unwrap()
}

async fn latest_version(app: &TestApp, serial: &str) -> Value {
    let r = app
        .get(&format!("/v1/robots/{serial}/parameter-sets/latest"))
        .await;
    json_of(r, 200).await["version"].clone()
}

async fn problem_field(r: reqwest::Response, status: u16, field: &str) -> Value {
    assert_eq!(r.status(), status);
    assert_eq!(
        r.headers()["content-type"].to_str().unwrap(),
        "application/problem+json"
    );
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], field, "{p}");
    p
}

#[tokio::test]
async fn latest_is_the_newest_approved_set_and_decisions_are_recorded() {
    let app = spawn_app().await;
    let session = app.robot_and_session("GATE-1").await;
    app.robot_and_session("GATE-2").await;
    let store = store::connect(&app.database_url).await.unwrap();

    // No approved set yet: latest is 404, a check and a partial scope 409
    // naming the field.
    store
        .insert_parameter_set("GATE-1", None, &set(1.0, ReleaseStatus::Candidate))
        .await
        .unwrap();
    let r = app.get("/v1/robots/GATE-1/parameter-sets/latest").await;
    assert_eq!(r.status(), 404);
    let r = app
        .post_json(&format!("/v1/sessions/{session}/checks"), &json!({}))
        .await;
    let p = problem_field(r, 409, "serial").await;
    assert!(p["detail"].as_str().unwrap().contains("GATE-1"), "{p}");
    let r = app
        .post_json(
            &format!("/v1/sessions/{session}/calibrations"),
            &json!({"scope": "base"}),
        )
        .await;
    problem_field(r, 409, "scope").await;

    // v2 approved, v3 a candidate (worse than before): latest is v2.
    for status in [ReleaseStatus::Approved, ReleaseStatus::Candidate] {
        store
            .insert_parameter_set("GATE-1", None, &set(2.0, status))
            .await
            .unwrap();
    }
    assert_eq!(latest_version(&app, "GATE-1").await, 2);
    let v3 = json_of(app.get("/v1/robots/GATE-1/parameter-sets/3").await, 200).await;
    assert_eq!(v3["status"], "candidate");
    assert_eq!(v3["status_by"], "gate");
    let list = json_of(app.get("/v1/robots/GATE-1/parameter-sets").await, 200).await;
    let statuses: Vec<&str> = list["items"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["status"].as_str().unwrap())
        .collect();
    assert_eq!(statuses, ["candidate", "approved", "candidate"]);

    // A person approves v3: it is latest, with who and when.
    let r = app
        .post_json(
            "/v1/robots/GATE-1/parameter-sets/3/approve",
            &json!({"reason": "checked on the cell"}),
        )
        .await;
    let v3 = json_of(r, 200).await;
    assert_eq!(v3["status"], "approved");
    assert_eq!(v3["status_by"], "anonymous");
    assert_eq!(v3["status_reason"], "checked on the cell");
    assert!(v3["status_at"].is_string());
    assert_eq!(latest_version(&app, "GATE-1").await, 3);
    // ... then rejects it: latest is v2 again; the report says its status.
    let r = app
        .post_json("/v1/robots/GATE-1/parameter-sets/3/reject", &json!({}))
        .await;
    assert_eq!(json_of(r, 200).await["status"], "rejected");
    assert_eq!(latest_version(&app, "GATE-1").await, 2);
    let report = json_of(
        app.get("/v1/robots/GATE-1/parameter-sets/latest/report?compare=1")
            .await,
        200,
    )
    .await;
    assert_eq!(report["version"], 2);
    assert_eq!(report["status"], "approved");
    // Side by side: v1's kinematic parameter against v2's, in σ units
    // (frames are not compared).
    let comparison = &report["comparison"];
    assert_eq!(comparison["version"], 1);
    assert_eq!(comparison["status"], "candidate");
    let changes = comparison["changes"].as_array().unwrap();
    assert_eq!(changes.len(), 1, "{comparison}");
    assert_eq!(changes[0]["name"], "dtheta_2");
    let sigmas = changes[0]["sigmas"].as_f64().unwrap();
    assert!((sigmas - 1.0 / (2.0_f64 * 0.01 * 0.01).sqrt()).abs() < 1e-9);

    // The history: approved versions (v2; v3 was approved, then
    // rejected), every decision in order.
    let history = json_of(app.get("/v1/robots/GATE-1/history").await, 200).await;
    let approved: Vec<i64> = history["approved"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["version"].as_i64().unwrap())
        .collect();
    assert_eq!(approved, [2]);
    let decisions: Vec<(i64, &str, &str)> = history["decisions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["version"].as_i64().unwrap(),
                d["status"].as_str().unwrap(),
                d["decided_by"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        decisions,
        [
            (1, "candidate", "gate"),
            (2, "approved", "gate"),
            (3, "candidate", "gate"),
            (3, "approved", "anonymous"),
            (3, "rejected", "anonymous"),
        ]
    );

    // Bad input names the field: a version GATE-2 does not have, a
    // version that is not a number, a comparison with a missing version.
    let r = app
        .post_json("/v1/robots/GATE-2/parameter-sets/3/approve", &json!({}))
        .await;
    let p = problem_field(r, 404, "version").await;
    assert!(p["detail"].as_str().unwrap().contains("GATE-2"), "{p}");
    let r = app
        .post_json(
            "/v1/robots/GATE-1/parameter-sets/latest/approve",
            &json!({}),
        )
        .await;
    problem_field(r, 422, "version").await;
    let r = app
        .post_json("/v1/robots/NOPE/parameter-sets/1/approve", &json!({}))
        .await;
    assert_eq!(r.status(), 404);
    let r = app
        .get("/v1/robots/GATE-1/parameter-sets/2/report?compare=9")
        .await;
    problem_field(r, 404, "compare").await;
    let r = app
        .post_json(
            "/v1/robots/GATE-1/parameter-sets/2/approve",
            &json!({"reason": 3}),
        )
        .await;
    assert!(matches!(r.status().as_u16(), 400 | 422), "{}", r.status());

    // With an approved set, the check is queued (its numerics need a
    // calibrated set: this marker set fails the job, never the request).
    let r = app
        .post_json(&format!("/v1/sessions/{session}/checks"), &json!({}))
        .await;
    let accepted = json_of(r, 202).await;
    assert_eq!(accepted["kind"], "check");
}

/// Sends `poses` (as served after a job: joints, set, detected points)
/// again as a new session of image points (the centres as detected).
async fn session_of_points(app: &TestApp, serial: &str, body: &Value, poses: &[&Value]) -> String {
    let r = app
        .post_json(&format!("/v1/robots/{serial}/sessions"), body)
        .await;
    let session = json_of(r, 201).await["id"].as_str().unwrap().to_string();
    for (i, pose) in poses.iter().enumerate() {
        let points: Vec<Value> = pose["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let (x, y) = match p.get("raw_x") {
                    Some(x) => (x.clone(), p["raw_y"].clone()),
                    None => (p["x"].clone(), p["y"].clone()),
                };
                json!({"row": p["row"], "col": p["col"], "x": x, "y": y})
            })
            .collect();
        // Every third pose validates a calibration of this session.
        let set = if i % 3 == 2 { "val" } else { "cal" };
        let r = app
            .post_json(
                &format!("/v1/sessions/{session}/poses"),
                &json!({"joints_deg": pose["joints_deg"], "set": set, "image_points": points}),
            )
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    session
}

/// The check's or the calibration's finished job.
async fn finished(app: &TestApp, r: reqwest::Response) -> Value {
    let job = json_of(r, 202).await["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let done = app
        .wait_job(&job, std::time::Duration::from_secs(120), is_finished)
        .await;
    assert_eq!(done["state"], "succeeded", "{done}");
    done
}

/// Poses of a quick check and of a base-only recalibration.
const CHECK_POSES: usize = 8;
/// The bound on a base-only recalibration's validation (mm).
const MAX_BASE_ONLY_MM: f64 = 0.1;

/// A robot whose latest approved set is calibrated from `poses`' campaign:
/// a re-check of 8 of its poses (those not in the calibration first)
/// passes, and a base-only recalibration from them validates to 0.1 mm
/// and is approved only if better than the set as it was.
pub(crate) async fn recheck_through_the_service(
    app: &TestApp,
    serial: &str,
    body: &Value,
    poses: &[Value],
) {
    let mut chosen: Vec<&Value> = poses.iter().filter(|p| p["set"] == "val").collect();
    chosen.extend(poses.iter().filter(|p| p["set"] == "cal"));
    chosen.truncate(CHECK_POSES);
    let session = session_of_points(app, serial, body, &chosen).await;
    let check = finished(
        app,
        app.post_json(&format!("/v1/sessions/{session}/checks"), &json!({}))
            .await,
    )
    .await;
    let result = &check["result"];
    eprintln!("re-check of an unchanged robot: {result}");
    assert_eq!(result["verdict"], "pass", "{result}");
    assert_eq!(result["poses"], CHECK_POSES);
    assert!(result["p_value"].as_f64().unwrap() >= result["significance"].as_f64().unwrap());
    assert!(result["expected_mean_mm"].as_f64().unwrap() > 0.0);

    let base = finished(
        app,
        app.post_json(
            &format!("/v1/sessions/{session}/calibrations"),
            &json!({"scope": "base"}),
        )
        .await,
    )
    .await;
    let summary = &base["result"]["summary"];
    eprintln!("base-only recalibration: {}", base["result"]);
    assert!(
        summary["after_mean_mm"].as_f64().unwrap() <= MAX_BASE_ONLY_MM,
        "{summary}"
    );
    let version = base["result"]["version"].as_i64().unwrap();
    let set = json_of(
        app.get(&format!("/v1/robots/{serial}/parameter-sets/{version}"))
            .await,
        200,
    )
    .await;
    assert_eq!(set["session_id"], session);
    assert_eq!(set["camera_mode"], "fixed");
    let better = summary["after_mean_mm"].as_f64() < summary["before_mean_mm"].as_f64();
    assert_eq!(
        set["status"] == "approved",
        better,
        "{}",
        set["status_reason"]
    );
}
