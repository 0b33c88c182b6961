//! Poses that lie (issue 14): a campaign with two swapped joint files and a
//! pose recorded 2° off in joint 2 calibrates as well as a clean one; the
//! three poses are flagged `outlier` with a reason and no good pose is.

use robocal_calib::sim::campaign_io::PoseEntry;
use serde_json::Value;

use crate::support::{spawn_app_with, upload_and_calibrate};

const CAL_POSES: usize = 24;
const VAL_POSES: usize = 8;
/// Same bar as the clean end-to-end campaign (`e2e.rs`).
const MIN_IMPROVEMENT: f64 = 12.0;
/// A pose "recorded before the robot settled": joint 2 this far off, deg.
const UNSETTLED_JOINT_DEG: f64 = 2.0;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn lying_poses_are_flagged_and_left_out() {
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate("irb2400", dir.path(), CAL_POSES, VAL_POSES, 21).unwrap();
    let path = dir.path().join("poses.json");
    let mut entries: Vec<PoseEntry> =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    // A wrong joint file: poses 3 and 4 swapped; pose 9 not settled.
    let (a, b) = (entries[3].joints_deg.clone(), entries[4].joints_deg.clone());
    entries[3].joints_deg = b;
    entries[4].joints_deg = a;
    entries[9].joints_deg[1] += UNSETTLED_JOINT_DEG;
    let liars: Vec<String> = [3, 4, 9]
        .iter()
        .map(|&i| entries[i].image.clone())
        .collect();
    std::fs::write(&path, serde_json::to_string(&entries).unwrap()).unwrap();

    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let serial = "LIAR-1";
    upload_and_calibrate(&app, serial, dir.path()).await;

    let report: Value = app
        .get(&format!("/v1/robots/{serial}/parameter-sets/latest/report"))
        .await
        .json()
        .await
        .unwrap();
    let per_pose = report["per_pose"].as_array().unwrap();
    let flagged: Vec<&Value> = per_pose.iter().filter(|p| p["outlier"] == true).collect();
    let mut names: Vec<String> = flagged
        .iter()
        .map(|p| p["label"].as_str().unwrap().to_string())
        .collect();
    names.sort();
    let mut want = liars.clone();
    want.sort();
    assert_eq!(names, want, "{per_pose:#?}");
    for p in &flagged {
        assert!(!p["reason"].as_str().unwrap().is_empty(), "{p}");
        // The lie is visible in the pose's own error, far above the others.
        assert!(p["before_mm"].as_f64().unwrap() > 5.0, "{p}");
    }
    // Every validation pose is still judged, and the fit is not bent.
    let val = per_pose.iter().filter(|p| p["outlier"] != true).count();
    assert_eq!(val, VAL_POSES);
    let before = report["before"]["mean_mm"].as_f64().unwrap();
    let after = report["after"]["mean_mm"].as_f64().unwrap();
    assert!(
        before / after >= MIN_IMPROVEMENT,
        "before {before} after {after}"
    );
    let notes = report["notes"].to_string();
    assert!(notes.contains("left out"), "{notes}");
    app.shutdown().await;
}
