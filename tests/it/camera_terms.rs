//! Issue 19 for a camera session: a simulated PUMA 560 whose true joints
//! have the switch's terms (compliance of joints 2 and 3 under the tool,
//! periodic errors of joints 1 and 4; calib's `sim::tracker_campaign::
//! typical_terms`) photographs its board; a job with `non_geometric: true`
//! selects the terms on the image points (calib's `image_term_selection`)
//! and the set, used through `forward`, beats the geometric set of the same
//! poses against the simulator's true camera positions. The same robot
//! without terms keeps none.

use robocal_calib::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use robocal_calib::sim::tracker_campaign::typical_terms;
use serde_json::{json, Value};

use robocal_calib::sim::campaign_io::PoseSet;

use crate::sim_upload::{joints_deg, true_error_mm, upload_session};
use crate::support::*;

const SEED: u64 = 1;
const CAL_POSES: usize = 80;
const VAL_POSES: usize = 30;
/// The gear term a camera campaign separates from the geometry (calib's
/// `image_term_selection_tests`: kept and within 3σ on every seed).
const WRIST_TERM: &str = "periodic_4.cos2";
/// Largest RMS of true error over `forward`'s σ accepted: 1 is honest; the
/// unidentifiable compliance of joint 2 stays as unmodelled error.
const MAX_SIGMA_RATIO: f64 = 2.5;
const WAIT: std::time::Duration = std::time::Duration::from_secs(600);

fn campaign(switch: bool) -> Campaign {
    let mut spec = CampaignSpec::standard("puma560", SEED).unwrap();
    spec.cal_poses = CAL_POSES;
    spec.val_poses = VAL_POSES;
    spec.non_geometric = switch;
    simulate_campaign(&spec).unwrap()
}

/// A robot `serial` with campaign `c` in one session; a set calibrated
/// with `options`, as `(version, set, report)`.
async fn calibrate(
    app: &TestApp,
    serial: &str,
    session: &str,
    options: Value,
) -> (i64, Value, Value) {
    let path = format!("/v1/sessions/{session}/calibrations");
    let done = app.finished_job(&path, &options, WAIT).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    let version = done["result"]["version"].as_i64().unwrap();
    let set = app
        .get_ok(&format!("/v1/robots/{serial}/parameter-sets/{version}"))
        .await;
    let report = app
        .get_ok(&format!(
            "/v1/robots/{serial}/parameter-sets/{version}/report"
        ))
        .await;
    (version, set, report)
}

/// RMS over the validation poses of the true camera position error over
/// `forward`'s `position_std_mm` of set `version`.
async fn sigma_ratio(app: &TestApp, serial: &str, version: i64, c: &Campaign) -> f64 {
    let val: Vec<_> = c.poses.iter().filter(|p| p.set == PoseSet::Val).collect();
    let body =
        json!({"joints_deg": val.iter().map(|p| joints_deg(&p.joints_rad)).collect::<Vec<_>>()});
    let answer = app
        .post_ok(
            &format!("/v1/robots/{serial}/parameter-sets/{version}/forward"),
            &body,
        )
        .await;
    let poses = answer["poses"].as_array().unwrap();
    let sum: f64 = poses
        .iter()
        .zip(&val)
        .map(|(got, p)| {
            let t = &got["camera_in_target"]["translation_mm"];
            let truth = p.target_to_camera.translation.vector;
            let err2: f64 = (0..3)
                .map(|k| (t[k].as_f64().unwrap() - truth[k]).powi(2))
                .sum();
            err2 / got["position_std_mm"].as_f64().unwrap().powi(2)
        })
        .sum();
    (sum / val.len() as f64).sqrt()
}

/// Mean over the session's poses of the served detection's residual rms
/// (px), as the last job left them.
async fn mean_residual_px(app: &TestApp, session: &str) -> f64 {
    let list = app
        .get_ok(&format!("/v1/sessions/{session}/poses?limit=1000"))
        .await;
    let poses = list["items"].as_array().unwrap();
    let sum: f64 = poses
        .iter()
        .map(|p| p["detection"]["residual_rms_px"].as_f64().unwrap())
        .sum();
    sum / poses.len() as f64
}

async fn robot(app: &TestApp, serial: &str) {
    let r = app
        .put_json(
            &format!("/v1/robots/{serial}"),
            &json!({"model": "PUMA 560", "preset": "puma560"}),
        )
        .await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
}

#[tokio::test]
async fn a_camera_session_selects_terms_on_the_image_points() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let serial = "PUMA-TERMS";
    let c = campaign(true);
    robot(&app, serial).await;
    let session = upload_session(&app, serial, &c, "front").await;
    let (geometric, plain_set, _) =
        calibrate(&app, serial, &session, json!({"non_geometric": false})).await;
    let residual_geo = mean_residual_px(&app, &session).await;
    let (with_terms, set, report) =
        calibrate(&app, serial, &session, json!({"non_geometric": true})).await;
    // The served detections' residuals (at the recorded joints, through
    // the last job's set) go through the kept terms.
    let residual_terms = mean_residual_px(&app, &session).await;
    eprintln!(
        "mean pose residual rms: {residual_terms:.4} px with terms, {residual_geo:.4} px geometric"
    );
    assert!(
        residual_terms < residual_geo,
        "{residual_terms} vs {residual_geo}"
    );
    assert!(plain_set["terms"].is_null());
    // Selected on the image points, and said so.
    let criterion = report["terms"]["criterion"].as_str().unwrap();
    assert!(criterion.contains("image-level"), "{criterion}");
    let kept = set["terms"]["terms"]
        .as_array()
        .unwrap_or_else(|| panic!("no terms kept: {}", report["terms"]));
    let wrist = kept
        .iter()
        .find(|t| t["name"] == WRIST_TERM)
        .unwrap_or_else(|| panic!("{WRIST_TERM} not kept: {kept:?}"));
    let truth = typical_terms(&c.truth.model().unwrap());
    let true_value = truth.values[truth
        .terms
        .iter()
        .position(|k| k.name() == WRIST_TERM)
        .unwrap()];
    let (value, sd) = (
        wrist["value"].as_f64().unwrap(),
        wrist["std_dev"].as_f64().unwrap(),
    );
    // Recovered at the right size and sign (its 3σ recovery over seeds is
    // calib's test; here the job also kept periodic_4.cos1, which shares
    // the joint's narrow range with it: z = 3.1 on this campaign).
    assert!(sd > 0.0 && value.signum() == true_value.signum(), "{wrist}");
    assert!(
        (value / true_value - 1.0).abs() < 0.5,
        "{wrist} vs {true_value}"
    );
    let notes = report["notes"].to_string();
    assert!(
        notes.contains("refined with the geometry, hand–eye and intrinsics on the image points"),
        "{notes}"
    );
    // The report's kept count matches the set.
    assert_eq!(
        report["terms"]["kept"].as_u64().unwrap() as usize,
        kept.len()
    );
    // Through `forward` (with the terms) against the true camera positions.
    let e_terms = true_error_mm(&app, serial, with_terms, None, &c).await;
    let e_geo = true_error_mm(&app, serial, geometric, None, &c).await;
    eprintln!("true error at the validation poses: with terms {e_terms:.4} mm, geometric {e_geo:.4} mm; kept {kept:?}");
    assert!(e_terms < 0.5 * e_geo, "{e_terms} vs {e_geo}");
    // The terms' covariance with the parameters is stored (one row per
    // parameter of the set's covariance, one column per term) and `forward`'s
    // σ goes through it.
    let cov = &set["terms"]["covariance"];
    let rows = cov["with_parameters"].as_array().unwrap();
    assert_eq!(cov["names"], set["covariance"]["names"]);
    assert_eq!(rows.len(), cov["names"].as_array().unwrap().len());
    assert!(rows
        .iter()
        .all(|r| r.as_array().unwrap().len() == kept.len()));
    assert_eq!(cov["among_terms"].as_array().unwrap().len(), kept.len());
    let z = sigma_ratio(&app, serial, with_terms, &c).await;
    let z_geo = sigma_ratio(&app, serial, geometric, &c).await;
    eprintln!("true error over forward's σ at the validation poses (rms): {z:.2} with terms, {z_geo:.2} geometric");
    // Honest within the part of the terms a camera campaign cannot see
    // (joint 2's compliance is not identifiable from it).
    assert!(z < MAX_SIGMA_RATIO && z < z_geo, "{z} vs {z_geo}");

    // The same robot without terms: none kept, the set is the geometric one.
    let serial = "PUMA-PLAIN";
    let c = campaign(false);
    robot(&app, serial).await;
    let session = upload_session(&app, serial, &c, "front").await;
    let (_, set, report) = calibrate(&app, serial, &session, json!({"non_geometric": true})).await;
    assert!(set["terms"].is_null(), "{}", report["terms"]);
    assert_eq!(report["terms"]["kept"], 0);
}
