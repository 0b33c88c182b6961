//! The model ladder on a simulated tracker campaign through the service
//! (docs/method.md §6.8, §7.6): a UR10 measured in six configuration
//! groups (only the wrist moving inside each), each group's last pose
//! uploaded as `val`, the poses carrying their `group`. The validation then
//! repeats calibration configurations: the report says so, ranks the rungs
//! by their held-out position error (mm), and the headline and the gate
//! are the held-out predictions.

use std::time::Duration;

use robocal_calib::kinematics::identify::Observed;
use robocal_calib::kinematics::presets;
use robocal_calib::sim::grouped_campaign::Grouping;
use robocal_calib::sim::tracker_campaign::{grouped_positions, simulate_tracker, TrackerSpec};
use serde_json::json;

use crate::support::spawn_app_with;

const WAIT: Duration = Duration::from_secs(600);
const NOISE_MM: f64 = 0.01;
/// The simulator's tool point on the flange (mm).
const TOOL_MM: [f64; 3] = [10.0, -5.0, 100.0];
const GROUPS: usize = 6;
const PER_GROUP: usize = 6;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_grouped_tracker_campaign_is_judged_on_held_out_configurations() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let spec = TrackerSpec {
        poses: 1,
        noise_mm: NOISE_MM,
        seed: 41,
        non_geometric: false,
        orientation_noise_rad: None,
    };
    let truth = simulate_tracker(&presets::ur10(), &spec);
    let grouping = Grouping {
        groups: GROUPS,
        per_group: PER_GROUP,
        shoulder_jitter_deg: 1.0,
        wrist_range_deg: 40.0,
    };
    let (cal, _) = grouped_positions(&truth, grouping, 0, NOISE_MM, 41);
    app.put_kinematics("UR10-GROUPS", "UR10", &presets::ur10())
        .await;
    let body = json!({
        "instrument": "tracker",
        "flange_to_camera_guess": {"translation_mm": TOOL_MM, "rotation_deg": [0.0, 0.0, 0.0]},
    });
    let session = app.new_session("UR10-GROUPS", &body).await;
    for (i, m) in cal.iter().enumerate() {
        let Observed::Position { position_mm, .. } = &m.observed else {
            unreachable!("positions simulated")
        };
        let joints: Vec<f64> = m.joints_rad.iter().map(|q| q.to_degrees()).collect();
        let set = if i % PER_GROUP == PER_GROUP - 1 {
            "val"
        } else {
            "cal"
        };
        let pose = json!({
            "joints_deg": joints,
            "measured_position_mm": [position_mm.x, position_mm.y, position_mm.z],
            "set": set,
            "group": format!("config_{}", i / PER_GROUP),
        });
        let r = app
            .post_json(&format!("/v1/sessions/{session}/poses"), &pose)
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    let path = format!("/v1/sessions/{session}/calibrations");
    app.finished_job(&path, &json!({}), WAIT).await;
    let report = app
        .get_ok("/v1/robots/UR10-GROUPS/parameter-sets/1/report")
        .await;
    let m = &report["model_selection"];
    eprintln!("model selection: {m}");
    assert_eq!(m["configurations"], GROUPS, "{m}");
    assert_eq!(m["val_shares_configurations"], true);
    assert_eq!(m["validation"], "leave_group_out");
    let rungs = m["rungs"].as_array().unwrap();
    // Terms are on by default for a tracker: six rungs, judged in mm.
    assert_eq!(rungs.len(), 6, "{m}");
    assert!(
        rungs.iter().all(|r| r["heldout_rms_mm"].as_f64().is_some()),
        "{m}"
    );
    assert!(rungs.iter().all(|r| r["heldout_rms_px"].is_null()), "{m}");
    // The headline is every pose's held-out prediction, and the gate
    // judged that figure.
    assert_eq!(
        report["after"]["n"],
        GROUPS * PER_GROUP,
        "{}",
        report["after"]
    );
    let after = report["after"]["mean_mm"].as_f64().unwrap();
    let kept = rungs.iter().find(|r| r["rung"] == m["chosen"]).unwrap();
    assert!((kept["heldout_mean_mm"].as_f64().unwrap() - after).abs() < 1e-9);
    let gate = &report["gate"];
    assert!(
        (gate["mean_mm"].as_f64().unwrap() - after).abs() < 1e-9,
        "{gate}"
    );
    // The simulator's link errors (0.5 mm, 1 mrad): identification pays
    // on held-out configurations too.
    assert_ne!(m["chosen"], "hand_eye", "{m}");
    assert!(after < report["before"]["mean_mm"].as_f64().unwrap());
    let html = app
        .get("/v1/robots/UR10-GROUPS/parameter-sets/1/report.html")
        .await
        .text()
        .await
        .unwrap();
    assert!(
        html.contains("held-out RMS [mm]"),
        "tracker ladder shown in mm"
    );
}
