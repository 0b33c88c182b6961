//! A set bound to the controller it was made for (issue 34): the robot's
//! `controller` is recorded by its sessions and inherited by their sets;
//! `compensate`, `filter`, `export` and the re-check answer 409 naming
//! `controller` with both identities when the caller expects another;
//! changing the robot's controller is in its history, and a re-check
//! measured on the new controller answers `controller_changed`, which the
//! fleet page shows.

use std::time::Duration;

use serde_json::{json, Value};

use crate::support::{spawn_app_with, TestApp};
use crate::ur5_tracker_set::{calibrate, merge, ur5_rows, ur5_session, ur5_session_body};

const SERIAL: &str = "UR5-ID";
/// Poses of the re-check session (the first of the UR5's random poses).
const CHECK_POSES: usize = 8;
/// Of which the job's validation rule wants some `cal`, some `val`.
const CHECK_CAL_POSES: usize = 6;
const WAIT: Duration = Duration::from_secs(600);

fn controller(serial: &str, hash: &str) -> Value {
    json!({"vendor": "Universal Robots", "serial": serial, "software": "5.11.1", "kinematics_hash": hash})
}

/// A 409 naming `controller`, with both identities.
async fn assert_mismatch(r: reqwest::Response, expected_serial: &str, what: &str) {
    assert_eq!(r.status(), 409, "{what}");
    assert_eq!(
        r.headers()["content-type"],
        "application/problem+json",
        "{what}"
    );
    let problem: Value = r.json().await.unwrap();
    assert_eq!(
        problem["errors"][0]["field"], "controller",
        "{what}: {problem}"
    );
    assert_eq!(
        problem["controller"]["expected"]["serial"], expected_serial,
        "{what}: {problem}"
    );
    assert_eq!(
        problem["controller"]["recorded"]["serial"], "2019301234",
        "{what}: {problem}"
    );
    let detail = problem["detail"].as_str().unwrap();
    assert!(
        detail.contains(expected_serial) && detail.contains("2019301234"),
        "{what}: {detail}"
    );
}

async fn post_with_query(app: &TestApp, path: &str, body: &Value) -> reqwest::Response {
    app.client
        .post(app.url(path))
        .json(body)
        .send()
        .await
        .unwrap()
}

/// A tracker session of the first [`CHECK_POSES`] random poses.
async fn check_session(app: &TestApp) -> String {
    let rows = ur5_rows("3D_UR5_uncalibrated_random_cleaned.csv");
    let poses = rows.iter().take(CHECK_POSES).enumerate().map(|(i, r)| {
        let joints_deg = r.joints_rad.iter().map(|q| q.to_degrees()).collect();
        let set = if i < CHECK_CAL_POSES { "cal" } else { "val" };
        (joints_deg, r.position_mm.into(), set)
    });
    app.tracker_session(SERIAL, &ur5_session_body(), poses)
        .await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_set_is_bound_to_its_controller() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let first = controller("2019301234", "calib_111");
    let session = ur5_session(&app, SERIAL, json!({"controller": first}), json!({})).await;
    let robot = app.get_ok(&format!("/v1/robots/{SERIAL}")).await;
    assert_eq!(robot["controller"], first);
    let recorded = app.get_ok(&format!("/v1/sessions/{session}")).await;
    assert_eq!(recorded["controller"], first, "{recorded}");
    let result = calibrate(&app, &session).await;
    let version = result["version"].as_i64().unwrap();
    app.approve_unless_approved(SERIAL, version as u32, "controller test")
        .await;
    let set_path = format!("/v1/robots/{SERIAL}/parameter-sets/{version}");
    let set = app.get_ok(&set_path).await;
    assert_eq!(set["controller"], first, "the set inherits the session's");

    // compensate and filter: the body's expectation, or the query's serial.
    let target = app
        .post_ok(
            &format!("{set_path}/forward"),
            &json!({"joints_deg": [[0.0, -60.0, 60.0, -90.0, -90.0, 0.0]]}),
        )
        .await["poses"][0]["camera_in_target"]
        .clone();
    let target =
        json!({"translation_mm": target["translation_mm"], "rotation_deg": target["rotation_deg"]});
    let seed = json!([0.0, -60.0, 60.0, -90.0, -90.0, 0.0]);
    let other = controller("2019309999", "calib_111");
    let compensate = json!({"targets": [target], "seed_joints_deg": seed});
    let mut expecting_other = compensate.clone();
    merge(&mut expecting_other, json!({"expect_controller": other}));
    let r = post_with_query(&app, &format!("{set_path}/compensate"), &expecting_other).await;
    assert_mismatch(r, "2019309999", "compensate, expect_controller").await;
    let r = post_with_query(
        &app,
        &format!("{set_path}/compensate?controller_serial=C-OTHER"),
        &compensate,
    )
    .await;
    assert_mismatch(r, "C-OTHER", "compensate, controller_serial").await;
    let mut expecting_first = compensate.clone();
    merge(&mut expecting_first, json!({"expect_controller": first}));
    let r = post_with_query(&app, &format!("{set_path}/compensate"), &expecting_first).await;
    assert_eq!(r.status(), 200, "{}", r.text().await.unwrap());
    let r = post_with_query(
        &app,
        &format!("{set_path}/compensate?controller_serial=2019301234"),
        &compensate,
    )
    .await;
    assert_eq!(r.status(), 200);
    let tool = json!({"translation_mm": [0.0, 0.0, 31.0], "rotation_deg": [0.0, 0.0, 0.0]});
    let filter = json!({"targets": [target], "tool": tool, "expect_controller": other});
    let r = post_with_query(&app, &format!("{set_path}/filter"), &filter).await;
    assert_mismatch(r, "2019309999", "filter").await;
    // A streamed answer is refused before its first line.
    let r = app
        .client
        .post(app.url(&format!("{set_path}/filter")))
        .header("accept", "application/x-ndjson")
        .json(&filter)
        .send()
        .await
        .unwrap();
    assert_mismatch(r, "2019309999", "filter, streamed").await;

    // export: the query's serial; the header names the controller.
    let r = app
        .get(&format!(
            "{set_path}/export?format=krl-frames&controller_serial=C-OTHER"
        ))
        .await;
    assert_mismatch(r, "C-OTHER", "export").await;
    let r = app
        .get(&format!(
            "{set_path}/export?format=krl-frames&controller_serial=2019301234"
        ))
        .await;
    assert_eq!(r.status(), 200);
    let krl = r.text().await.unwrap();
    assert!(
        krl.contains("; controller: vendor Universal Robots, serial 2019301234, software 5.11.1, kinematics_hash calib_111"),
        "{krl}"
    );
    assert!(krl.contains("; status: approved"), "{krl}");

    // The re-check: refused up front for another controller.
    let check_on_first = check_session(&app).await;
    let r = post_with_query(
        &app,
        &format!("/v1/sessions/{check_on_first}/checks"),
        &json!({"expect_controller": other}),
    )
    .await;
    assert_mismatch(r, "2019309999", "re-check").await;
    let r = post_with_query(
        &app,
        &format!("/v1/sessions/{check_on_first}/checks?controller_serial=C-OTHER"),
        &json!({}),
    )
    .await;
    assert_mismatch(r, "C-OTHER", "re-check, controller_serial").await;
    let path = format!("/v1/sessions/{check_on_first}/checks");
    let done = app.finished_job(&path, &json!({}), WAIT).await;
    assert_ne!(done["result"]["verdict"], "controller_changed", "{done}");

    // The arm re-mastered: the robot's controller hash changes. History.
    let second = controller("2019301234", "calib_222");
    let kinematics =
        robocal::schema::robot::model_to_doc(&robocal_calib::kinematics::presets::ur5());
    let r = app
        .put_json(
            &format!("/v1/robots/{SERIAL}"),
            &json!({"model": "UR5", "kinematics": kinematics, "controller": second}),
        )
        .await;
    assert_eq!(r.status(), 200, "{}", r.text().await.unwrap());
    let history = app.get_ok(&format!("/v1/robots/{SERIAL}/history")).await;
    let changes = history["controller_changes"].as_array().unwrap();
    assert_eq!(changes.len(), 2, "{history}");
    assert_eq!(changes[0]["from"], Value::Null);
    assert_eq!(changes[0]["to"], first);
    assert_eq!(changes[1]["from"], first);
    assert_eq!(changes[1]["to"], second);
    assert!(changes[1]["changed_at"].as_str().unwrap().len() > 10);
    // The same identity again is no change.
    let r = app
        .put_json(
            &format!("/v1/robots/{SERIAL}"),
            &json!({"model": "UR5", "kinematics": kinematics, "controller": second}),
        )
        .await;
    assert_eq!(r.status(), 200);
    let history = app.get_ok(&format!("/v1/robots/{SERIAL}/history")).await;
    assert_eq!(history["controller_changes"].as_array().unwrap().len(), 2);

    // A re-check measured on the re-mastered controller.
    let check_on_second = check_session(&app).await;
    let path = format!("/v1/sessions/{check_on_second}/checks");
    let done = app.finished_job(&path, &json!({}), WAIT).await;
    let check = &done["result"];
    assert_eq!(check["verdict"], "controller_changed", "{check}");
    assert_eq!(check["controller_change"]["set"], first);
    assert_eq!(check["controller_change"]["session"], second);
    let fleet = app.get("/").await.text().await.unwrap();
    assert!(
        fleet.contains("<span class=\"verdict controller_changed\">controller_changed</span>"),
        "{fleet}"
    );
    assert!(fleet.contains("kinematics_hash calib_222"), "{fleet}");

    // An empty expectation is a 422 naming it.
    let mut empty = compensate.clone();
    merge(&mut empty, json!({"expect_controller": {}}));
    let r = post_with_query(&app, &format!("{set_path}/compensate"), &empty).await;
    assert_eq!(r.status(), 422);
    let problem: Value = r.json().await.unwrap();
    assert_eq!(problem["errors"][0]["field"], "expect_controller");
    app.shutdown().await;
}
