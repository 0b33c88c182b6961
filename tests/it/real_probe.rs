//! Issue 19's 6-DoF probe on real data through the service: the UR10 of
//! Landgraf 2021 was measured with a Leica T-Mac, whose orientation the
//! file gives as intrinsic X-Y-Z angles (`R = Rx·Ry·Rz`, probe in tracker;
//! `calib::kinematics::tracker_pose`, docs/decisions/0030-tmac-euler-convention.md).
//! A user converts them to the contract's pose and uploads every 10th pose
//! of Series B as `measured_pose` with the T-Mac's noise. The job fits the
//! orientation: it finds the probe's frame on the flange (a quarter turn
//! about z, 93 mm out) from a guess of the point only, and the wrist joint
//! 5 a position fit cannot pin down becomes identified; the held-out
//! position error stays that of the position-only fit.

use std::time::Duration;

use robocal_calib::geometry::{pose_error, pose_from_matrix_rows};
use robocal_calib::kinematics::presets;
use robocal_calib::kinematics::tracker_csv::landgraf2021_rows;
use serde_json::{json, Value};

use crate::probe_tracker::pose_body;
use crate::support::{spawn_app_with, TestApp};

const DATA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/calib/tests/data/kinematic/ur10_landgraf2021"
);
const SERIES_B: &str = "Series_B/measurements_joint_configurations.csv";
const SERIES_C_D: [&str; 2] = [
    "Series_C/measurements_random_poses.csv",
    "Series_D/measurements_iso_cubes.csv",
];
const STRIDE: usize = 10;
const HOLDOUT: f64 = 0.3;
/// The T-Mac's accuracy: 0.02 mm (half the tracker's MPE at 2–4 m) and
/// 0.01° (its stated rotation accuracy); `tracker_pose`'s floors.
const POSITION_SIGMA_MM: f64 = 0.02;
const ORIENTATION_SIGMA_DEG: f64 = 0.01;
/// The probe on the flange as the data give it (the helper's fit on all of
/// Series B): `Rz(-90°)`, origin 93.2 mm along z; the guess says 109 mm and
/// nothing of the rotation.
const PROBE_RZ_DEG: f64 = -90.0;
const PROBE_Z_MM: f64 = 93.2;
const GUESS_MM: [f64; 3] = [0.0, 0.0, 109.0];
const PROBE_ROTATION_TOLERANCE_DEG: f64 = 0.5;
const PROBE_Z_TOLERANCE_MM: f64 = 1.0;
/// dtheta_5's σ with the orientation over without: the calib bench
/// measures 0.11 rad → 2e-4 rad on all of B.
const DTHETA_5_RATIO_MAX: f64 = 0.1;
/// Held-out position error with the orientation against without (ratio):
/// the calib bench shows the orientation does not change it on this robot.
const POSITION_RATIO_MAX: f64 = 1.05;
/// Why the protocol approves B's set whatever its gate said.
const PROTOCOL_REASON: &str = "the issue's protocol validates B's set on C and D";
const WAIT: Duration = Duration::from_secs(1200);

/// A series' every `stride`-th pose as JSON bodies (set `set`): joints,
/// position and the probe's pose in the contract's form (with its exact
/// matrix).
fn pose_bodies(file: &str, stride: usize, set: &str) -> Vec<Value> {
    let text = std::fs::read_to_string(format!("{DATA}/{file}")).unwrap();
    landgraf2021_rows(&text)
        .unwrap()
        .into_iter()
        .step_by(stride)
        .map(|row| {
            // The probe's pose in the tracker frame (calib's reading of the
            // T-Mac's angles), sent as the contract's pose.
            let m = row.pose_measurement().expect("the T-Mac's angles");
            pose_body(&m.joints_rad, &m.observed, set)
        })
        .collect()
}

/// σ of a set's parameter `name`, `None` when held fixed.
async fn sigma(app: &TestApp, version: u32, name: &str) -> Option<f64> {
    let set = app
        .get_ok(&format!("/v1/robots/UR10-TMAC/parameter-sets/{version}"))
        .await;
    let p = set["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == name)
        .cloned()
        .unwrap_or_else(|| panic!("no {name} in {set}"));
    (!p["fixed"].as_bool().unwrap()).then(|| p["std"].as_f64().unwrap())
}

/// A T-Mac session of robot `serial` holding `bodies`; its id.
async fn probe_session(app: &TestApp, serial: &str, bodies: &[Value]) -> String {
    let session = app
        .new_session(
            serial,
            &json!({
                "instrument": "tracker",
                "flange_to_camera_guess": {"translation_mm": GUESS_MM, "rotation_deg": [0.0, 0.0, 0.0]},
                "tracker_sigma_mm": POSITION_SIGMA_MM,
                "tracker_orientation_sigma_deg": ORIENTATION_SIGMA_DEG,
            }),
        )
        .await;
    for body in bodies {
        let r = app
            .post_json(&format!("/v1/sessions/{session}/poses"), body)
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    session
}

#[tokio::test]
async fn the_t_mac_orientation_finds_the_probe_and_pins_the_wrist() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    app.put_kinematics("UR10-TMAC", "UR10", &presets::ur10())
        .await;
    let session = probe_session(&app, "UR10-TMAC", &pose_bodies(SERIES_B, STRIDE, "cal")).await;
    // Geometry only, so the comparison is the orientation's alone (the
    // terms on this robot: docs/decisions/0023-term-joint-ranges.md).
    let path = format!("/v1/sessions/{session}/calibrations");
    let options = |measurement: &str| {
        json!({
            "measurement": measurement,
            "non_geometric": false,
            "validation": {"holdout_fraction": HOLDOUT},
        })
    };
    let with = app.finished_job(&path, &options("pose"), WAIT).await;
    let without = app.finished_job(&path, &options("position"), WAIT).await;
    let mean = |job: &Value| job["result"]["summary"]["after_mean_mm"].as_f64().unwrap();
    eprintln!(
        "UR10 B/{STRIDE}, {HOLDOUT} held out: with the orientation {:.4} mm mean, position only {:.4} mm",
        mean(&with),
        mean(&without)
    );
    assert!(mean(&with) < POSITION_RATIO_MAX * mean(&without));

    let set = app.get_ok("/v1/robots/UR10-TMAC/parameter-sets/1").await;
    assert_eq!(set["measurement"], "pose");
    let tool = pose_from_matrix_rows(
        &serde_json::from_value(set["flange_to_tool"]["matrix"].clone()).unwrap(),
    )
    .unwrap();
    let probe = robocal_calib::geometry::pose_from_xyz_rpy_deg(
        [0.0, 0.0, PROBE_Z_MM],
        [0.0, 0.0, PROBE_RZ_DEG],
    )
    .unwrap();
    let e = pose_error(&tool, &probe);
    eprintln!("probe frame against Rz(-90°), 93.2 mm: {e:.4}");
    assert!(
        e.fixed_rows::<3>(3).norm().to_degrees() < PROBE_ROTATION_TOLERANCE_DEG,
        "{e}"
    );
    assert!(
        (tool.translation.z - PROBE_Z_MM).abs() < PROBE_Z_TOLERANCE_MM,
        "{e}"
    );

    let (pose_sd, position_sd) = (
        sigma(&app, 1, "dtheta_5").await,
        sigma(&app, 2, "dtheta_5").await,
    );
    eprintln!("dtheta_5 σ: with the orientation {pose_sd:?}, position only {position_sd:?}");
    let pose_sd = pose_sd.expect("identified with the orientation");
    assert!(position_sd.is_none_or(|s| pose_sd < DTHETA_5_RATIO_MAX * s));
}

/// The UR10 protocol with the T-Mac's orientation (BENCHMARKS.md,
/// session 12): all of Series B fitted with the orientation (`options`),
/// approved, then C and D each a `scope: base` re-fit of the probe's set
/// on all of the series with their orientations, validated on the same
/// poses. `(label, mean mm)` per series and the kept terms.
async fn ur10_probe_protocol(app: &TestApp, serial: &str, options: Value) -> Vec<(String, f64)> {
    app.put_kinematics(serial, "UR10", &presets::ur10()).await;
    let both = |file: &str| [pose_bodies(file, 1, "cal"), pose_bodies(file, 1, "val")].concat();
    let s = probe_session(app, serial, &both(SERIES_B)).await;
    let path = |s: &str| format!("/v1/sessions/{s}/calibrations");
    let fit = app.finished_job(&path(&s), &options, WAIT).await;
    let mean = |job: &Value| job["result"]["summary"]["after_mean_mm"].as_f64().unwrap();
    let mut out = vec![("B (in-sample)".to_string(), mean(&fit))];
    let set = app
        .get_ok(&format!("/v1/robots/{serial}/parameter-sets/1"))
        .await;
    assert_eq!(set["measurement"], "pose");
    let kept: Vec<String> = set["terms"]["terms"]
        .as_array()
        .map(|t| {
            t.iter()
                .map(|t| t["name"].as_str().unwrap().to_string())
                .collect()
        })
        .unwrap_or_default();
    out.push((format!("kept {kept:?}"), f64::NAN));
    app.approve_unless_approved(serial, 1, PROTOCOL_REASON)
        .await;
    for file in SERIES_C_D {
        let s = probe_session(app, serial, &both(file)).await;
        let refit = app
            .finished_job(&path(&s), &json!({"scope": "base"}), WAIT)
            .await;
        out.push((format!("{file} (base re-fitted)"), mean(&refit)));
    }
    out
}

/// `cargo test --test it -- --ignored real_probe::full_protocol --nocapture`
#[tokio::test]
#[ignore = "minutes in debug: the UR10 protocol with the T-Mac's orientation"]
async fn full_protocol() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let with = ur10_probe_protocol(&app, "UR10-TMAC-T", json!({})).await;
    eprintln!("UR10 T-Mac, terms allowed (default): {with:?}");
    let without = ur10_probe_protocol(&app, "UR10-TMAC-G", json!({"non_geometric": false})).await;
    eprintln!("UR10 T-Mac, geometric: {without:?}");
}
