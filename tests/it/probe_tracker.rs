//! Issue 19's 6-DoF tracker through the service: a simulated UR10 campaign
//! measured by a probe (position and orientation, `measured_pose`, the
//! probe turned a quarter on the flange; `calib::sim::tracker_campaign`
//! with `orientation_noise_rad`) and with compliance and periodic errors.
//! The default job fits the orientation with the session's weight: the
//! set says `measurement: "pose"`, holds the probe's frame, keeps the true
//! terms, and its wrist parameters are narrower than the same campaign's
//! position-only set (`measurement: "position"`); `forward` predicts the
//! held-out orientations at the probe's noise. Bad noise values, a
//! `measured_pose` that disagrees with its position, and `measurement:
//! "pose"` over a pose without orientation are refused naming the field.

use std::time::Duration;

use robocal_calib::geometry::{pose_error, pose_to_matrix_rows, PoseXyzRpy};
use robocal_calib::kinematics::identify::Observed;
use robocal_calib::kinematics::presets;
use robocal_calib::sim::tracker_campaign::{simulate_tracker, TrackerCampaign, TrackerSpec};
use serde_json::{json, Value};

use crate::support::{spawn_app_with, TestApp};

const CAL_POSES: usize = 200;
const VAL_POSES: usize = 40;
const NOISE_MM: f64 = 0.01;
/// A T-Mac's 0.01° (deg).
const ORIENTATION_NOISE_DEG: f64 = 0.01;
/// A quick re-check's poses.
const CHECK_POSES: usize = 5;
const JOB_WAIT: Duration = Duration::from_secs(600);
/// Geometric mean over the wrist parameters of σ with the orientation
/// over σ without: the calib test (`tracker_probe_tests`) measures 0.36 on
/// 300 poses (joint 5's 7x narrower, joint 4's a few percent).
const WRIST_SIGMA_RATIO_MAX: f64 = 0.6;
/// The kinds of a joint's parameters in the set's names.
const JOINT_PARAMETERS: [&str; 5] = ["dtheta", "a", "d", "alpha", "beta"];
/// The probe's frame found within this of the truth (rad): the nominal
/// kinematics' errors are about 1 mrad, the fit removes most of them.
const PROBE_FRAME_TOLERANCE_RAD: f64 = 2e-3;

fn campaign() -> TrackerCampaign {
    simulate_tracker(
        &presets::ur10(),
        &TrackerSpec {
            poses: CAL_POSES + VAL_POSES,
            noise_mm: NOISE_MM,
            seed: 7,
            non_geometric: true,
            orientation_noise_rad: Some(ORIENTATION_NOISE_DEG.to_radians()),
        },
    )
}

fn deg(q: &[f64]) -> Vec<f64> {
    q.iter().map(|r| r.to_degrees()).collect()
}

/// A pose's JSON body: the position and the probe's full pose.
pub(crate) fn pose_body(joints_rad: &[f64], observed: &Observed, set: &str) -> Value {
    let Observed::Pose { world_to_tool, .. } = observed else {
        panic!("a probe campaign measures poses")
    };
    let form = PoseXyzRpy::from_pose(world_to_tool);
    json!({
        "joints_deg": deg(joints_rad),
        "set": set,
        "measured_position_mm": form.translation_mm,
        "measured_pose": {
            "translation_mm": form.translation_mm,
            "rotation_deg": form.rotation_deg,
            "matrix": pose_to_matrix_rows(world_to_tool),
        },
    })
}

fn probe_session() -> Value {
    json!({
        "instrument": "tracker",
        "payload_kg": 0.0,
        "tracker_sigma_mm": NOISE_MM,
        "tracker_orientation_sigma_deg": ORIENTATION_NOISE_DEG,
    })
}

/// σ of the wrist's parameters (joints 4 to 6) of set `version`, by name.
async fn wrist_sigmas(app: &TestApp, serial: &str, version: u32) -> Vec<(String, f64)> {
    let set = app
        .get_ok(&format!("/v1/robots/{serial}/parameter-sets/{version}"))
        .await;
    set["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| {
            // The layout's names: `dtheta_4`, `a_5`, ... (1-based joints).
            let name = p["name"].as_str().unwrap();
            name.rsplit_once('_').is_some_and(|(kind, joint)| {
                ["4", "5", "6"].contains(&joint) && JOINT_PARAMETERS.contains(&kind)
            }) && !p["fixed"].as_bool().unwrap()
        })
        .map(|p| {
            (
                p["name"].as_str().unwrap().to_string(),
                p["std"].as_f64().unwrap(),
            )
        })
        .collect()
}

#[tokio::test]
async fn a_probe_orientation_is_fitted_with_its_weight() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    app.put_kinematics("UR10-P", "UR10", &presets::ur10()).await;
    let c = campaign();
    let session = app.new_session("UR10-P", &probe_session()).await;
    for (i, m) in c.measurements.iter().enumerate() {
        let set = if i < CAL_POSES { "cal" } else { "val" };
        let r = app
            .post_json(
                &format!("/v1/sessions/{session}/poses"),
                &pose_body(&m.joints_rad, &m.observed, set),
            )
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    let path = format!("/v1/sessions/{session}/calibrations");
    app.finished_job(&path, &json!({}), JOB_WAIT).await;
    recheck_with_the_probe(&app, &c).await;
    app.finished_job(&path, &json!({"measurement": "position"}), JOB_WAIT)
        .await;
    // The position-only set is gated against the probe's on the tool point.
    let gate = &app
        .get_ok("/v1/robots/UR10-P/parameter-sets/2/report")
        .await["gate"];
    assert_eq!(gate["compared_with"], "UR10-P/1", "{gate}");
    let with = app.get_ok("/v1/robots/UR10-P/parameter-sets/1").await;
    let without = app.get_ok("/v1/robots/UR10-P/parameter-sets/2").await;
    assert_eq!(with["measurement"], "pose", "{with}");
    assert_eq!(without["measurement"], "position");
    let report = app
        .get_ok("/v1/robots/UR10-P/parameter-sets/1/report")
        .await;
    assert_eq!(report["measurement"], "pose");

    // The probe's frame: found although the start knew only its point.
    let tool = robocal_calib::geometry::pose_from_matrix_rows(
        &serde_json::from_value(with["flange_to_tool"]["matrix"].clone()).unwrap(),
    )
    .unwrap();
    let e = pose_error(&tool, &c.truth.flange_to_tool);
    assert!(
        e.fixed_rows::<3>(3).norm() < PROBE_FRAME_TOLERANCE_RAD,
        "{e}"
    );

    // The true terms are kept.
    let kept: Vec<&str> = with["terms"]["terms"]
        .as_array()
        .unwrap_or_else(|| panic!("no terms kept: {with}"))
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    for truth in &c.true_terms.terms {
        assert!(kept.contains(&truth.name().as_str()), "{kept:?}");
    }

    // The orientation narrows the wrist.
    let position: std::collections::HashMap<_, _> =
        wrist_sigmas(&app, "UR10-P", 2).await.into_iter().collect();
    let ratios: Vec<f64> = wrist_sigmas(&app, "UR10-P", 1)
        .await
        .into_iter()
        .filter_map(|(name, s)| Some(s / position.get(&name)?))
        .collect();
    eprintln!("wrist σ with orientation / without: {ratios:?}");
    assert!(ratios.len() >= 6, "{ratios:?}");
    let mean = (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64).exp();
    assert!(mean < WRIST_SIGMA_RATIO_MAX, "{ratios:?}");
    assert!(ratios.iter().all(|r| *r <= 1.0 + 1e-6), "{ratios:?}");

    // `forward` with the set: the held-out orientations at the probe's noise.
    let val = &c.measurements[CAL_POSES..];
    let rows: Vec<Vec<f64>> = val.iter().map(|m| deg(&m.joints_rad)).collect();
    let answer = app
        .post_ok(
            "/v1/robots/UR10-P/parameter-sets/1/forward",
            &json!({"joints_deg": rows}),
        )
        .await;
    let mut turn_sq = 0.0;
    for (m, pose) in val.iter().zip(answer["poses"].as_array().unwrap()) {
        let predicted = robocal_calib::geometry::pose_from_matrix_rows(
            &serde_json::from_value(pose["camera_in_target"]["matrix"].clone()).unwrap(),
        )
        .unwrap();
        let Observed::Pose { world_to_tool, .. } = &m.observed else {
            unreachable!()
        };
        turn_sq += pose_error(world_to_tool, &predicted)
            .fixed_rows::<3>(3)
            .norm_squared();
    }
    let turn_rms_deg = (turn_sq / val.len() as f64).sqrt().to_degrees();
    let floor_deg = 3f64.sqrt() * ORIENTATION_NOISE_DEG;
    eprintln!("forward orientation rms {turn_rms_deg:.4}° (floor {floor_deg:.4}°)");
    assert!(turn_rms_deg < 1.3 * floor_deg, "{turn_rms_deg}");
}

/// A 5-pose re-check of the probe's set (version 1, approved by the
/// gate): with the probe's poses it passes; a check session of positions
/// only cannot be judged against a full tool frame and fails naming the
/// field.
async fn recheck_with_the_probe(app: &TestApp, c: &TrackerCampaign) {
    let gate = &app
        .get_ok("/v1/robots/UR10-P/parameter-sets/1/report")
        .await["gate"];
    assert_eq!(gate["status"], "approved", "{gate}");
    let fresh = &c.measurements[CAL_POSES..CAL_POSES + CHECK_POSES];
    let check = |positions_only: bool| async move {
        let session = app.new_session("UR10-P", &probe_session()).await;
        for (k, m) in fresh.iter().enumerate() {
            // A job's input wants both sets; a check reads every pose.
            let set = if k < 3 { "cal" } else { "val" };
            let mut body = pose_body(&m.joints_rad, &m.observed, set);
            if positions_only {
                body.as_object_mut().unwrap().remove("measured_pose");
            }
            let r = app
                .post_json(&format!("/v1/sessions/{session}/poses"), &body)
                .await;
            assert_eq!(r.status(), 201);
        }
        let r = app
            .post_json(&format!("/v1/sessions/{session}/checks"), &json!({}))
            .await;
        assert_eq!(r.status(), 202, "{}", r.text().await.unwrap());
        let job = r.json::<Value>().await.unwrap()["job_id"]
            .as_str()
            .unwrap()
            .to_string();
        app.wait_job(&job, JOB_WAIT, crate::support::is_finished)
            .await
    };
    let passed = check(false).await;
    assert_eq!(passed["state"], "succeeded", "{passed}");
    assert_eq!(passed["result"]["verdict"], "pass", "{passed}");
    assert_eq!(passed["result"]["checked_version"], 1);
    let refused = check(true).await;
    assert_eq!(refused["state"], "failed", "{refused}");
    assert!(refused.to_string().contains("measured_pose"), "{refused}");
}

#[tokio::test]
async fn probe_noise_and_orientations_are_checked() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    app.put_kinematics("UR10-Q", "UR10", &presets::ur10()).await;
    for (field, bad) in [
        ("tracker_sigma_mm", json!(-0.1)),
        ("tracker_sigma_mm", json!(0.0)),
        ("tracker_orientation_sigma_deg", json!(1e3)),
    ] {
        let mut body = probe_session();
        body[field] = bad;
        let r = app.post_json("/v1/robots/UR10-Q/sessions", &body).await;
        assert_eq!(r.status(), 422, "{field}");
        let problem: Value = r.json().await.unwrap();
        assert!(problem.to_string().contains(field), "{problem}");
    }
    // A camera session has no tracker noise.
    let mut camera = crate::support::session_body();
    camera["tracker_sigma_mm"] = json!(0.02);
    let r = app.post_json("/v1/robots/UR10-Q/sessions", &camera).await;
    assert_eq!(r.status(), 422);
    assert!(r.text().await.unwrap().contains("tracker_sigma_mm"));

    let c = campaign();
    let session = app.new_session("UR10-Q", &probe_session()).await;
    let poses = format!("/v1/sessions/{session}/poses");
    // The probe's translation is the tool point: a pose whose two disagree
    // is refused.
    let mut apart = pose_body(
        &c.measurements[0].joints_rad,
        &c.measurements[0].observed,
        "cal",
    );
    apart["measured_pose"]["translation_mm"][0] =
        json!(apart["measured_position_mm"][0].as_f64().unwrap() + 0.5);
    let r = app.post_json(&poses, &apart).await;
    assert_eq!(r.status(), 422);
    assert!(r
        .text()
        .await
        .unwrap()
        .contains("measured_pose.translation_mm"));
    // `measurement: "pose"` over a pose without its orientation fails
    // naming the field and the pose.
    for (i, m) in c.measurements.iter().take(30).enumerate() {
        let mut body = pose_body(
            &m.joints_rad,
            &m.observed,
            if i < 24 { "cal" } else { "val" },
        );
        if i == 3 {
            body.as_object_mut().unwrap().remove("measured_pose");
        }
        let r = app.post_json(&poses, &body).await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    let r = app
        .post_json(
            &format!("/v1/sessions/{session}/calibrations"),
            &json!({"measurement": "pose"}),
        )
        .await;
    assert_eq!(r.status(), 202);
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let done = app
        .wait_job(&job, JOB_WAIT, crate::support::is_finished)
        .await;
    assert_eq!(done["state"], "failed", "{done}");
    let text = done.to_string();
    assert!(
        text.contains("measurement") && text.contains("#4"),
        "{done}"
    );
}
