//! A simulated campaign re-rendered on another board kind and calibrated
//! through the service (issue 14): shared by the ChArUco and circle-board
//! campaigns. The simulator's truth gives each view's `target_to_camera`;
//! each image is drawn again on the other board in the same target frame.

use rand::{rngs::StdRng, SeedableRng};
use robocal_calib::camera::model::Intrinsics;
use robocal_calib::geometry::{pose_from_matrix_rows, Pose};
use robocal_calib::sim::campaign_io::{PoseEntry, Truth};
use robocal_calib::vision::image::GrayImage;
use serde_json::Value;

use crate::support::{spawn_app_with, upload_and_calibrate};

pub const CAL_POSES: usize = 24;
pub const VAL_POSES: usize = 8;
/// Same bar as the dot-board campaign (`e2e.rs`).
pub const MIN_IMPROVEMENT: f64 = 12.0;
/// Reprojection RMS a rendered board must reach (px).
const MAX_REPROJECTION_PX: f64 = 0.2;

/// Draws one view: `(intrinsics, camera_to_target, width, height, rng)`.
pub type Renderer<'a> = dyn Fn(&Intrinsics, &Pose, usize, usize, &mut StdRng) -> GrayImage + 'a;

/// The IRB 2400 campaign in `dir` (simulator seed `seed`), every image
/// redrawn by `render` (noise seed `render_seed`) and the session's target
/// replaced by `target`.
pub fn rerendered_campaign(
    dir: &std::path::Path,
    seed: u64,
    render_seed: u64,
    target: Value,
    render: &Renderer,
) {
    robocal::cli::campaign::simulate("irb2400", dir, CAL_POSES, VAL_POSES, seed).unwrap();
    let read = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    let truth: Truth = serde_json::from_str(&read("truth.json")).unwrap();
    let entries: Vec<PoseEntry> = serde_json::from_str(&read("poses.json")).unwrap();
    let mut rng = StdRng::seed_from_u64(render_seed);
    for (i, entry) in entries.iter().enumerate() {
        let camera_to_target = pose_from_matrix_rows(&truth.target_to_camera[i])
            .unwrap()
            .inverse();
        let image = render(
            &truth.intrinsics,
            &camera_to_target,
            truth.image_width as usize,
            truth.image_height as usize,
            &mut rng,
        );
        image.to_luma8().save(dir.join(&entry.image)).unwrap();
    }
    let mut campaign: Value = serde_json::from_str(&read("campaign.json")).unwrap();
    campaign["session"]["target"] = target;
    std::fs::write(dir.join("campaign.json"), campaign.to_string()).unwrap();
}

/// Upload and calibrate the campaign in `dir` as robot `serial`; check that
/// the session kept the target `kind`, every image was detected, the
/// accuracy improved as on the dot board and the reprojection is small.
/// Returns the calibration report.
pub async fn calibrates_through_the_service(
    dir: &std::path::Path,
    serial: &str,
    kind: &str,
) -> Value {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let job = upload_and_calibrate(&app, serial, dir).await;
    let session = job["session_id"].as_str().unwrap();
    let s: Value = app
        .get(&format!("/v1/sessions/{session}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(s["target"]["kind"], kind, "{s}");
    let report: Value = app
        .get(&format!("/v1/robots/{serial}/parameter-sets/latest/report"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(
        report["detection"]["images_detected"],
        CAL_POSES + VAL_POSES,
        "{}",
        report["detection"]
    );
    let before = report["before"]["mean_mm"].as_f64().unwrap();
    let after = report["after"]["mean_mm"].as_f64().unwrap();
    let rms = report["camera"]["reprojection_rms_px"].as_f64().unwrap();
    eprintln!(
        "{kind} campaign: before {before:.3} mm, after {after:.4} mm, reprojection {rms:.3} px"
    );
    assert!(
        before / after >= MIN_IMPROVEMENT,
        "before {before} after {after}"
    );
    assert!(rms < MAX_REPROJECTION_PX, "reprojection {rms} px");
    app.shutdown().await;
    report
}
