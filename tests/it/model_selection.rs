//! How much of the kinematics a campaign carries, through the service
//! (docs/method.md §6.8, §7.6): simulated campaigns shot in six
//! configuration groups of four poses (joints 1–3 within ±1° inside a
//! group, as real hand–eye campaigns are), sent as image points.
//! - Validation poses that repeat calibration configurations: the report
//!   says so, the headline before/after are leave-group-out predictions and
//!   the gate judges those.
//! - An arm already at its nominal model: identification cannot pay, the
//!   set keeps the nominal kinematics and is approved as the first set.

use std::time::Duration;

use robocal_calib::sim::campaign::{Campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::grouped_campaign::{simulate_grouped_campaign, Grouping};
use serde_json::{json, Value};

use crate::support::{is_finished, spawn_app_with, TestApp};

const WAIT: Duration = Duration::from_secs(300);
const SEED: u64 = 21;

fn session_body() -> Value {
    json!({
        "instrument": "camera",
        "target": {"rows": 9, "cols": 9, "pitch_mm": 25, "dot_diameter_mm": 8,
                   "origin_marker_diameter_mm": 12},
        "camera": {"width": 2048, "height": 1536, "pixel_size_um": 3.45, "nominal_focal_mm": 12},
        "flange_to_camera_guess": {"translation_mm": [0, 60, 110], "rotation_deg": [0, 0, 0]}
    })
}

/// The IRB-2400 campaign of `SEED` in six groups of four, with `val`
/// validation poses spread over the workspace; link errors scaled.
fn campaign(error_scale: f64, val: usize) -> Campaign {
    let mut spec = CampaignSpec::standard("irb2400", SEED).unwrap();
    spec.val_poses = val;
    spec.joint_offset_sigma_deg *= error_scale;
    spec.length_sigma_mm *= error_scale;
    spec.twist_sigma_deg *= error_scale;
    simulate_grouped_campaign(&spec, Grouping::SIX_BY_FOUR).unwrap()
}

/// Creates the robot and a session, posts every pose as image points with
/// the set `set_of(index)` gives, runs the default job; the set and its
/// report.
async fn calibrate(
    app: &TestApp,
    serial: &str,
    c: &Campaign,
    set_of: impl Fn(usize) -> &'static str,
) -> (Value, Value) {
    calibrate_grouped(app, serial, c, set_of, |_| None).await
}

/// [`calibrate`] with each pose's explicit `group` (`group_of(index)`).
async fn calibrate_grouped(
    app: &TestApp,
    serial: &str,
    c: &Campaign,
    set_of: impl Fn(usize) -> &'static str,
    group_of: impl Fn(usize) -> Option<&'static str>,
) -> (Value, Value) {
    let r = app
        .put_json(
            &format!("/v1/robots/{serial}"),
            &json!({"model": "IRB 2400/16", "preset": "irb2400"}),
        )
        .await;
    assert_eq!(r.status(), 201);
    let r = app
        .post_json(&format!("/v1/robots/{serial}/sessions"), &session_body())
        .await;
    assert_eq!(r.status(), 201);
    let session = r.json::<Value>().await.unwrap()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let cols = c.truth.board.cols;
    for (i, pose) in c.poses.iter().enumerate() {
        let points: Vec<Value> = pose
            .observed_px
            .iter()
            .enumerate()
            .map(|(k, p)| json!({"row": k / cols, "col": k % cols, "x": p.x, "y": p.y}))
            .collect();
        let joints: Vec<f64> = pose.joints_rad.iter().map(|q| q.to_degrees()).collect();
        let mut body = json!({"joints_deg": joints, "set": set_of(i), "image_points": points});
        if let Some(g) = group_of(i) {
            body["group"] = json!(g);
        }
        let r = app
            .post_json(&format!("/v1/sessions/{session}/poses"), &body)
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    let r = app
        .post_json(&format!("/v1/sessions/{session}/calibrations"), &json!({}))
        .await;
    assert_eq!(r.status(), 202);
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let done = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    let sets: Value = app
        .get(&format!("/v1/robots/{serial}/parameter-sets"))
        .await
        .json()
        .await
        .unwrap();
    let set = sets["items"][0].clone();
    let version = set["version"].as_i64().unwrap();
    let report: Value = app
        .get(&format!(
            "/v1/robots/{serial}/parameter-sets/{version}/report"
        ))
        .await
        .json()
        .await
        .unwrap();
    (set, report)
}

/// The README's Aubo recipe on a simulated campaign: the last pose of
/// each group validates. The validation then repeats calibration
/// configurations, and the headline and the gate are held-out.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn validation_that_repeats_configurations_is_replaced_by_held_out_groups() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let c = campaign(1.0, 0);
    let (_, report) = calibrate(&app, "IRB-GROUPS", &c, |i| {
        if i % 4 == 3 {
            "val"
        } else {
            "cal"
        }
    })
    .await;
    let m = &report["model_selection"];
    eprintln!("model selection: {m}");
    assert_eq!(m["configurations"], 6, "{m}");
    assert_eq!(m["val_shares_configurations"], true);
    assert_eq!(m["validation"], "leave_group_out");
    assert_eq!(m["rungs"].as_array().unwrap().len(), 5);
    // The headline is every pose's held-out prediction, and the gate
    // judged that figure.
    assert_eq!(report["after"]["n"], 24, "{}", report["after"]);
    assert_eq!(report["before"]["n"], 24);
    let after = report["after"]["mean_mm"].as_f64().unwrap();
    let gate = &report["gate"];
    assert!(
        (gate["mean_mm"].as_f64().unwrap() - after).abs() < 1e-9,
        "{gate}"
    );
    let kept = m["rungs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["rung"] == m["chosen"])
        .unwrap();
    assert!((kept["heldout_mean_mm"].as_f64().unwrap() - after).abs() < 1e-9);
    // Usual link errors: identification pays on held-out groups too.
    assert_ne!(m["chosen"], "hand_eye", "{m}");
    assert!(after < report["before"]["mean_mm"].as_f64().unwrap());
    assert_eq!(gate["status"], "approved", "{gate}");
}

/// An arm at its nominal model, validation poses spread over the
/// workspace: the set keeps the nominal kinematics, says why, and is
/// approved.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn identification_that_does_not_pay_keeps_the_nominal_geometry() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let c = campaign(0.0, 8);
    let (set, report) = calibrate(&app, "IRB-NOMINAL", &c, |i| {
        if c.poses[i].set == PoseSet::Val {
            "val"
        } else {
            "cal"
        }
    })
    .await;
    let m = &report["model_selection"];
    eprintln!("model selection: {m}");
    // (A spread validation pose may still fall within 3° of a group's
    // shoulder: then the validation is leave-group-out, as it should be.)
    assert!(m["configurations"].as_u64().unwrap() >= 6, "{m}");
    assert_eq!(m["chosen"], "hand_eye", "{m}");
    // Every kinematic parameter at nominal, held.
    for p in report["parameters"].as_array().unwrap() {
        let name = p["name"].as_str().unwrap();
        if name.starts_with("target_to_base") || name.starts_with("flange_to_camera") {
            continue;
        }
        assert_eq!(p["fixed"], true, "{p}");
        assert_eq!(p["identified"], p["nominal"], "{p}");
    }
    assert_eq!(set["status"], "approved", "{set}");
    assert!(report["gate"]["reason"]
        .as_str()
        .unwrap()
        .contains("stay nominal"));
}

/// Explicit `group` fields win over the clustering on joints 1–3: three
/// shot configurations named one group are merged, one configuration
/// named two groups is split, and the two unnamed configurations are
/// still found by their joints (clustering alone finds 6).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn explicit_groups_are_held_out_as_named() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let c = campaign(1.0, 0);
    let group_of = |i: usize| match i / 4 {
        0..=2 => Some("merged"),
        3 if i.is_multiple_of(2) => Some("split_a"),
        3 => Some("split_b"),
        _ => None,
    };
    let val = |i: usize| if i % 4 == 3 { "val" } else { "cal" };
    let (_, report) = calibrate_grouped(&app, "IRB-NAMED", &c, val, group_of).await;
    let m = &report["model_selection"];
    eprintln!("model selection: {m}");
    assert_eq!(m["configurations"], 1 + 2 + 2, "{m}");
    assert_eq!(m["folds"], 5, "{m}");
    assert_eq!(m["val_shares_configurations"], true, "{m}");
}
