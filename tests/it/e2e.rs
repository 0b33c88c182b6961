//! End to end over HTTP (issue 6): simulate a campaign with rendered
//! images, upload it as a zip through the CLI's client, calibrate, and
//! compare the served parameter set with the simulator's truth.

use robocal::cli::client::Client;
use robocal_calib::geometry::pose_from_matrix_rows;
use robocal_calib::sim::campaign_io::{PoseEntry, PoseSet, Truth};
use serde_json::{json, Value};

use crate::support::{spawn_app_with, upload_and_calibrate};

/// Poses of the (deliberately small, for CI) campaigns.
const CAL_POSES: usize = 24;
const VAL_POSES: usize = 8;
/// Mean validation error after calibration must be this many times smaller.
const MIN_IMPROVEMENT: f64 = 12.0;
/// Served forward kinematics against the true camera position (mm).
const MAX_FORWARD_ERROR_MM: f64 = 0.1;

async fn campaign_through_the_service(preset: &str, serial: &str, seed: u64) {
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate(preset, dir.path(), CAL_POSES, VAL_POSES, seed).unwrap();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let job = upload_and_calibrate(&app, serial, dir.path()).await;
    let client = Client::new(&app.base, None).unwrap();
    assert_eq!(job["result"]["version"], 1, "{job}");

    let report = client.report(serial, None).await.unwrap();
    let improvement = report.before.norm.mean_mm / report.after.norm.mean_mm;
    assert!(
        improvement >= MIN_IMPROVEMENT,
        "{preset}: before {} mm, after {} mm",
        report.before.norm.mean_mm,
        report.after.norm.mean_mm
    );
    assert_eq!(report.version, 1);
    let flagged: Vec<_> = report
        .per_pose
        .iter()
        .filter(|p| p.outlier)
        .map(|p| (p.label.clone(), p.reason.clone()))
        .collect();
    assert_eq!(report.per_pose.len(), VAL_POSES, "{flagged:?}");

    // Forward predictions at the validation joints against the truth.
    let truth: Truth =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("truth.json")).unwrap())
            .unwrap();
    let entries: Vec<PoseEntry> =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("poses.json")).unwrap())
            .unwrap();
    let val: Vec<usize> = (0..entries.len())
        .filter(|&i| entries[i].set == PoseSet::Val)
        .collect();
    let joints: Vec<Vec<f64>> = val.iter().map(|&i| entries[i].joints_deg.clone()).collect();
    let path = format!("/v1/robots/{serial}/parameter-sets/latest/forward");
    let r = app.post_json(&path, &json!({ "joints_deg": joints })).await;
    assert_eq!(r.status(), 200);
    let forward: Value = r.json().await.unwrap();
    let mut worst = 0.0f64;
    for (row, &i) in val.iter().enumerate() {
        let m = &forward["poses"][row]["camera_in_target"]["matrix"];
        let predicted = nalgebra::Vector3::new(
            m[0][3].as_f64().unwrap(),
            m[1][3].as_f64().unwrap(),
            m[2][3].as_f64().unwrap(),
        );
        let true_pose = pose_from_matrix_rows(&truth.target_to_camera[i]).unwrap();
        worst = worst.max((predicted - true_pose.translation.vector).norm());
    }
    assert!(
        worst < MAX_FORWARD_ERROR_MM,
        "{preset}: worst forward error {worst} mm"
    );

    // Compensation: the calibrated model reaches its own targets.
    let target = &forward["poses"][0]["camera_in_target"];
    let r = app
        .post_json(
            &format!("/v1/robots/{serial}/parameter-sets/1/compensate"),
            &json!({"targets": [{"translation_mm": target["translation_mm"], "rotation_deg": target["rotation_deg"], "matrix": target["matrix"]}],
                    "seed_joints_deg": joints[0]}),
        )
        .await;
    assert_eq!(r.status(), 200);
    let comp: Value = r.json().await.unwrap();
    assert!(comp["residual_mm"][0].as_f64().unwrap() < 0.01, "{comp}");

    for (suffix, kind) in [
        ("report.svg", "image/svg+xml"),
        ("report.html", "text/html"),
    ] {
        let r = app
            .get(&format!(
                "/v1/robots/{serial}/parameter-sets/latest/{suffix}"
            ))
            .await;
        assert_eq!(r.status(), 200);
        assert!(r.headers()["content-type"]
            .to_str()
            .unwrap()
            .starts_with(kind));
        assert!(r.text().await.unwrap().contains(serial));
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn irb2400_campaign_calibrates_through_the_service() {
    campaign_through_the_service("irb2400", "IRB-E2E", 11).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn puma560_campaign_with_the_papers_camera_calibrates_through_the_service() {
    campaign_through_the_service("puma560", "PUMA-E2E", 12).await;
}
