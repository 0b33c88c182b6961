//! One calibration over several board placements through the service
//! (issue 18, "Regions"). One simulated PUMA 560 (one seed: one true
//! robot, hand–eye and camera) sees its board in three regions of its
//! workspace; each region is one session of image points. Judged against
//! the simulator's true camera poses through `forward` with `session_id`:
//! - the multi-session model is within 1.15x of each region's local model
//!   in that region;
//! - it is better, per region, than the other regions' local models
//!   carried over with only a base re-fit (`scope: base`), on average;
//! - the report has one `regions` entry per session with the local set
//!   beside it; the set serves every session's board.
//!
//! And the 422s: no sessions, an unknown session, a session of another
//! robot, a `session_id` the set does not know.

use std::time::Duration;

use robocal_calib::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::PoseSet;
use serde_json::{json, Value};

use crate::sim_upload::{joints_deg, post_pose, true_error_mm, upload_session};
use crate::support::*;

const SERIAL: &str = "PUMA-REGIONS";
const SEED: u64 = 18;
/// Home joints (deg) that put the board in three regions (as calib's
/// `kinematics::regions_tests`): in front, swung left, swung right and lower.
const REGION_HOMES_DEG: [[f64; 6]; 3] = [
    [0.0, 70.0, -140.0, 0.0, -20.0, 0.0],
    [70.0, 60.0, -130.0, 0.0, -20.0, 0.0],
    [-60.0, 85.0, -150.0, 0.0, -25.0, 0.0],
];
const REGION_NAMES: [&str; 3] = ["front", "left", "right low"];
const CAL_POSES: usize = 24;
const VAL_POSES: usize = 12;
/// The bound: the global model within this factor of each
/// region's local model in that region.
const MAX_GLOBAL_OVER_LOCAL: f64 = 1.15;
/// Compensated joints of a true camera pose against the true joints (deg):
/// the model's remaining error is hundredths of a millimetre.
const MAX_COMPENSATED_JOINT_DEG: f64 = 0.05;
const WAIT: Duration = Duration::from_secs(600);
/// The lying pose's joint-1 error (deg) and label.
const LIE_DEG: f64 = 3.0;
const LIE_LABEL: &str = "lying-pose";

/// The same robot, its board placed by each home pose; each placement
/// its own stream of stations and noise (calib's `pose_stream`: with one
/// stream the placements redrew the same stations and pixel noise).
fn campaigns() -> Vec<Campaign> {
    REGION_HOMES_DEG
        .iter()
        .enumerate()
        .map(|(i, home)| {
            let mut spec = CampaignSpec::standard("puma560", SEED).unwrap();
            spec.pose_stream = i as u64 + 1;
            spec.home_joints_rad = home.iter().map(|d| d.to_radians()).collect();
            spec.cal_poses = CAL_POSES;
            spec.val_poses = VAL_POSES;
            simulate_campaign(&spec).unwrap()
        })
        .collect()
}

/// Waits for job `r` (a 202) to succeed; the version of its set.
async fn version_of(app: &TestApp, r: reqwest::Response) -> i64 {
    assert_eq!(r.status(), 202, "{}", r.text().await.unwrap());
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let done = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    done["result"]["version"].as_i64().unwrap()
}

async fn calibrate(app: &TestApp, session: &str, options: Value) -> i64 {
    let r = app
        .post_json(&format!("/v1/sessions/{session}/calibrations"), &options)
        .await;
    version_of(app, r).await
}

/// Makes `version` the robot's latest approved set (what `scope: base`
/// holds).
async fn approve(app: &TestApp, version: i64) {
    let r = app
        .post_json(
            &format!("/v1/robots/{SERIAL}/parameter-sets/{version}/approve"),
            &json!({"reason": "carried over by the test"}),
        )
        .await;
    assert!(r.status() == 200 || r.status() == 409, "{}", r.status());
}

/// Largest joint difference (deg) of a compensate answer's first target
/// from `truth_deg`; `None` when the target was not solved.
fn joint_gap_deg(answer: &Value, truth_deg: &[f64]) -> Option<f64> {
    let joints = answer["joints_deg"][0].as_array()?;
    Some(
        joints
            .iter()
            .zip(truth_deg)
            .map(|(j, t)| (j.as_f64().unwrap() - t).abs())
            .fold(0.0, f64::max),
    )
}

/// `compensate` and `filter` with `session_id` work in that session's
/// board frame: the true camera pose of one of its validation views, as a
/// target, gives back joints close to the true ones; without `session_id`
/// (the first board's frame) it does not. An unknown `session_id` on the
/// streamed path is a 422 naming it before any line.
async fn compensates_in_a_session_frame(app: &TestApp, version: i64, session: &str, c: &Campaign) {
    let p = c.poses.iter().find(|p| p.set == PoseSet::Val).unwrap();
    let target = serde_json::to_value(robocal::schema::PoseOut::new(&p.target_to_camera)).unwrap();
    let truth = joints_deg(&p.true_joints_rad);
    let set = format!("/v1/robots/{SERIAL}/parameter-sets/{version}");
    // `filter` asks for the tool the targets are for: the set's camera.
    let camera = app.get_ok(&set).await["flange_to_camera"].clone();
    for verb in ["compensate", "filter"] {
        let path = format!("{set}/{verb}");
        let mut body = json!({"targets": [target], "seed_joints_deg": joints_deg(&p.joints_rad),
                              "session_id": session});
        if verb == "filter" {
            body["tool"] = crate::compensate::target_of(&camera);
        }
        let r = app.post_json(&path, &body).await;
        assert_eq!(r.status(), 200, "{verb}: {}", r.text().await.unwrap());
        let answer: Value = r.json().await.unwrap();
        let gap = joint_gap_deg(&answer, &truth).unwrap_or_else(|| panic!("{verb}: {answer}"));
        assert!(
            gap < MAX_COMPENSATED_JOINT_DEG,
            "{verb}: {gap} deg: {answer}"
        );
        body.as_object_mut().unwrap().remove("session_id");
        let r = app.post_json(&path, &body).await;
        assert_eq!(r.status(), 200, "{verb}");
        let other_board: Value = r.json().await.unwrap();
        let gap = joint_gap_deg(&other_board, &truth);
        assert!(
            gap.is_none_or(|g| g > 10.0 * MAX_COMPENSATED_JOINT_DEG),
            "{verb}: {other_board}"
        );
        body["session_id"] = json!("nope");
        let r = app
            .client
            .post(app.url(&path))
            .header("accept", "application/x-ndjson")
            .json(&body)
            .send()
            .await
            .unwrap();
        problem_field(r, "session_id").await;
    }
}

async fn problem_field(r: reqwest::Response, field: &str) -> Value {
    assert_eq!(r.status(), 422);
    assert_eq!(
        r.headers()["content-type"].to_str().unwrap(),
        "application/problem+json"
    );
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], field, "{p}");
    p
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn one_model_over_three_board_placements_matches_the_local_models() {
    let campaigns = campaigns();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let r = app
        .put_json(
            &format!("/v1/robots/{SERIAL}"),
            &json!({"model": "PUMA 560", "preset": "puma560"}),
        )
        .await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    let mut sessions = Vec::new();
    for (c, name) in campaigns.iter().zip(REGION_NAMES) {
        sessions.push(upload_session(&app, SERIAL, c, name).await);
    }
    // Each region's local model, then carried to the other regions with a
    // base-only re-fit (it is the approved set the `base` scope holds).
    let n = campaigns.len();
    let mut local = vec![0.0; n];
    let mut local_versions = vec![0; n];
    let mut carried = vec![Vec::new(); n];
    for r in 0..n {
        let v = calibrate(&app, &sessions[r], json!({})).await;
        approve(&app, v).await;
        local_versions[r] = v;
        local[r] = true_error_mm(&app, SERIAL, v, None, &campaigns[r]).await;
        for s in (0..n).filter(|&s| s != r) {
            let moved = calibrate(&app, &sessions[s], json!({"scope": "base"})).await;
            carried[s].push(true_error_mm(&app, SERIAL, moved, None, &campaigns[s]).await);
        }
    }
    // A pose whose joints contradict its image (joint 1 off by
    // LIE_DEG) in the last session, added after its local and carried-over sets:
    // the multi-session job screens it out and lists it as an outlier.
    let last = campaigns.len() - 1;
    let lied = campaigns[last]
        .poses
        .iter()
        .find(|p| p.set == PoseSet::Cal)
        .unwrap();
    let mut lie = joints_deg(&lied.joints_rad);
    lie[0] += LIE_DEG;
    post_pose(
        &app,
        &sessions[last],
        &campaigns[last],
        lied,
        LIE_LABEL,
        lie,
    )
    .await;
    // The one model over all three placements.
    let r = app
        .post_json(
            &format!("/v1/robots/{SERIAL}/calibrations"),
            &json!({"sessions": sessions, "validation": "val_set"}),
        )
        .await;
    let global_version = version_of(&app, r).await;
    for s in 0..n {
        let global = true_error_mm(
            &app,
            SERIAL,
            global_version,
            Some(&sessions[s]),
            &campaigns[s],
        )
        .await;
        let carried_mean = carried[s].iter().sum::<f64>() / carried[s].len() as f64;
        eprintln!(
            "region {s} ({}): global {global:.4} mm, local {:.4} mm ({:.2}x), carried over {:?} mm",
            REGION_NAMES[s],
            local[s],
            global / local[s],
            carried[s]
        );
        assert!(
            global <= MAX_GLOBAL_OVER_LOCAL * local[s],
            "region {s}: global {global} mm, local {} mm",
            local[s]
        );
        assert!(
            global < carried_mean,
            "region {s}: global {global} mm, carried over {carried_mean} mm"
        );
    }

    // The set serves every session's board; the first is target_to_base.
    let set: Value = app
        .get(&format!(
            "/v1/robots/{SERIAL}/parameter-sets/{global_version}"
        ))
        .await
        .json()
        .await
        .unwrap();
    let boards = set["session_target_to_base"]
        .as_array()
        .unwrap_or_else(|| panic!("{set}"));
    let ids: Vec<&str> = boards
        .iter()
        .map(|b| b["session_id"].as_str().unwrap())
        .collect();
    assert_eq!(ids, sessions.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(boards[0]["target_to_base"], set["target_to_base"]);
    // The report: one region per session, its local set beside it.
    let report: Value = app
        .get(&format!(
            "/v1/robots/{SERIAL}/parameter-sets/{global_version}/report"
        ))
        .await
        .json()
        .await
        .unwrap();
    let regions = report["regions"].as_array().unwrap();
    assert_eq!(regions.len(), n, "{report}");
    for (s, region) in regions.iter().enumerate() {
        assert_eq!(region["session_id"], sessions[s].as_str());
        assert_eq!(region["region"], REGION_NAMES[s]);
        assert_eq!(region["local"]["version"], local_versions[s], "{region}");
        let (before, after) = (
            region["before"]["mean_mm"].as_f64().unwrap(),
            region["after"]["mean_mm"].as_f64().unwrap(),
        );
        assert!(after < before, "region {s}: {before} -> {after} mm");
    }
    let html = app
        .get(&format!(
            "/v1/robots/{SERIAL}/parameter-sets/{global_version}/report.html"
        ))
        .await
        .text()
        .await
        .unwrap();
    assert!(html.contains("Regions"), "no regions section");
    // report.svg draws the same figures; the terminal table (`robocal
    // report`) has a row per region with its local set's version.
    let svg = app
        .get(&format!(
            "/v1/robots/{SERIAL}/parameter-sets/{global_version}/report.svg"
        ))
        .await
        .text()
        .await
        .unwrap();
    for title in ["Error per region", "Error per volume"] {
        assert!(svg.contains(title), "report.svg lacks {title:?}");
    }
    let typed: robocal::report::Report = serde_json::from_value(report.clone()).unwrap();
    let table = robocal::report::render_table(&typed);
    for (s, name) in REGION_NAMES.iter().enumerate() {
        let version = format!("v{}", local_versions[s]);
        assert!(
            table.lines().any(|l| l.trim_start().starts_with(name)
                && l.contains(sessions[s].as_str())
                && l.contains(&version)),
            "no row for region {name}:\n{table}"
        );
    }
    // The lying pose is in per_pose, marked, with its reason.
    let flagged: Vec<&Value> = report["per_pose"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["outlier"] == true)
        .collect();
    assert_eq!(flagged.len(), 1, "{flagged:?}");
    assert_eq!(flagged[0]["label"], LIE_LABEL, "{:?}", flagged[0]);
    assert!(flagged[0]["reason"].as_str().is_some_and(|r| !r.is_empty()));

    compensates_in_a_session_frame(&app, global_version, &sessions[1], &campaigns[1]).await;
    sigma_is_the_sessions_own(&app, global_version, &sessions, &campaigns[1]).await;

    // A session the set does not know.
    let r = app
        .post_json(
            &format!("/v1/robots/{SERIAL}/parameter-sets/{global_version}/forward"),
            &json!({"joints_deg": [[0.0, 70.0, -140.0, 0.0, -20.0, 0.0]], "session_id": "nope"}),
        )
        .await;
    problem_field(r, "session_id").await;
    app.shutdown().await;
}

#[tokio::test]
async fn a_multi_session_job_refuses_empty_unknown_and_foreign_sessions() {
    let app = spawn_app().await;
    let mine = app.robot_and_session("REG-A").await;
    let theirs = app.robot_and_session("REG-B").await;
    let path = "/v1/robots/REG-A/calibrations";
    let r = app.post_json(path, &json!({"sessions": []})).await;
    problem_field(r, "sessions").await;
    let r = app.post_json(path, &json!({})).await;
    problem_field(r, "sessions").await;
    let r = app
        .post_json(path, &json!({"sessions": [mine, "no-such-session"]}))
        .await;
    problem_field(r, "sessions").await;
    let r = app
        .post_json(path, &json!({"sessions": [mine, theirs]}))
        .await;
    let p = problem_field(r, "sessions").await;
    assert!(
        p["detail"].to_string().contains("REG-B") || p.to_string().contains("REG-B"),
        "{p}"
    );
    // A path serial that is not the sessions' robot.
    let r = app
        .post_json(
            "/v1/robots/REG-B/calibrations",
            &json!({"sessions": [mine]}),
        )
        .await;
    problem_field(r, "sessions").await;
    // A session's own endpoint takes no list.
    let r = app
        .post_json(
            &format!("/v1/sessions/{mine}/calibrations"),
            &json!({"sessions": [mine, theirs]}),
        )
        .await;
    problem_field(r, "sessions").await;
    // One session is that session's own calibration: refused while it
    // has no calibration pose (422 naming `poses`), queued once it has.
    let r = app.post_json(path, &json!({"sessions": [mine]})).await;
    problem_field(r, "poses").await;
    app.add_point_poses(&mine, 3, 1).await;
    let r = app.post_json(path, &json!({"sessions": [mine]})).await;
    assert_eq!(r.status(), 202, "{}", r.text().await.unwrap());
}

/// `forward`'s σ in a session's board frame uses that board's own base
/// covariance: the camera's σ differs between two sessions' frames for the
/// same joints, the flange's (link parameters only) does not.
async fn sigma_is_the_sessions_own(app: &TestApp, version: i64, sessions: &[String], c: &Campaign) {
    let joints: Vec<Vec<f64>> = c
        .poses
        .iter()
        .filter(|p| p.set == PoseSet::Val)
        .map(|p| joints_deg(&p.joints_rad))
        .collect();
    let path = format!("/v1/robots/{SERIAL}/parameter-sets/{version}/forward");
    let mut answers = Vec::new();
    for session in &sessions[..2] {
        let body = json!({"joints_deg": joints, "session_id": session});
        let r = app.post_json(&path, &body).await;
        assert_eq!(r.status(), 200);
        answers.push(r.json::<Value>().await.unwrap());
    }
    let sigma = |a: &Value, key: &str| -> Vec<f64> {
        a["poses"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p[key].as_f64().unwrap_or_else(|| panic!("{key}: {p}")))
            .collect()
    };
    let (flange_0, flange_1) = (
        sigma(&answers[0], "flange_position_std_mm"),
        sigma(&answers[1], "flange_position_std_mm"),
    );
    for (a, b) in flange_0.iter().zip(&flange_1) {
        assert!((a - b).abs() <= 1e-6 * a.max(*b), "flange σ {a} vs {b}");
    }
    let (camera_0, camera_1) = (
        sigma(&answers[0], "position_std_mm"),
        sigma(&answers[1], "position_std_mm"),
    );
    let differ = camera_0
        .iter()
        .zip(&camera_1)
        .filter(|(a, b)| (*a - *b).abs() > 1e-3 * a.max(**b))
        .count();
    eprintln!("camera σ in session 0's frame {camera_0:.4?}, in session 1's {camera_1:.4?}");
    assert!(
        differ > 0,
        "the same σ in both boards' frames: {camera_0:?}"
    );
    // The uncertainty map in session 1's frame answers forward's σ there.
    let map = app
        .post_ok(
            &format!("/v1/robots/{SERIAL}/parameter-sets/{version}/uncertainty-map"),
            &json!({"joints_deg": joints, "session_id": sessions[1]}),
        )
        .await;
    let mapped: Vec<f64> = map["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["position_std_mm"].as_f64().unwrap())
        .collect();
    assert_eq!(mapped.len(), camera_1.len());
    for (m, f) in mapped.iter().zip(&camera_1) {
        assert!(
            (m - f).abs() <= 1e-9 * f.max(*m),
            "map σ {m} vs forward's {f}"
        );
    }
}
