//! A ChArUco campaign through the service (issue 14): the simulator's
//! campaign with every image re-rendered as a ChArUco board in the same
//! target frame; the session says `"kind": "charuco"`. Detection at upload
//! finds the corners, the job calibrates as well as on the dot board, and a
//! bad ChArUco spec is a 422 naming the field.

use rand::{rngs::StdRng, SeedableRng};
use robocal_calib::geometry::pose_from_matrix_rows;
use robocal_calib::sim::campaign_io::{PoseEntry, Truth};
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_charuco::render_charuco;
use robocal_calib::vision::charuco::CharucoSpec;
use serde_json::{json, Value};

use crate::support::{spawn_app, spawn_app_with, upload_and_calibrate};

const CAL_POSES: usize = 24;
const VAL_POSES: usize = 8;
/// Same bar as the dot-board campaign (`e2e.rs`).
const MIN_IMPROVEMENT: f64 = 12.0;

fn board() -> CharucoSpec {
    CharucoSpec {
        squares: [10, 8],
        square_mm: 25.0,
        marker_mm: 18.0,
        dictionary: "DICT_5X5_100".into(),
        legacy_layout: false,
    }
}

/// The simulated campaign in `dir`, its images re-rendered as ChArUco.
fn charuco_campaign(dir: &std::path::Path) {
    robocal::cli::campaign::simulate("irb2400", dir, CAL_POSES, VAL_POSES, 51).unwrap();
    let read = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    let truth: Truth = serde_json::from_str(&read("truth.json")).unwrap();
    let entries: Vec<PoseEntry> = serde_json::from_str(&read("poses.json")).unwrap();
    let spec = board();
    let mut rng = StdRng::seed_from_u64(5);
    for (i, entry) in entries.iter().enumerate() {
        let camera_to_target = pose_from_matrix_rows(&truth.target_to_camera[i])
            .unwrap()
            .inverse();
        let view = render_charuco(
            &truth.intrinsics,
            &camera_to_target,
            &spec,
            truth.image_width as usize,
            truth.image_height as usize,
            &RenderOptions::default(),
            &mut rng,
        )
        .unwrap();
        view.image.to_luma8().save(dir.join(&entry.image)).unwrap();
    }
    let mut campaign: Value = serde_json::from_str(&read("campaign.json")).unwrap();
    campaign["session"]["target"] = json!({
        "kind": "charuco", "squares": spec.squares, "square_mm": spec.square_mm,
        "marker_mm": spec.marker_mm, "dictionary": spec.dictionary,
    });
    std::fs::write(dir.join("campaign.json"), campaign.to_string()).unwrap();
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn charuco_campaign_calibrates_through_the_service() {
    let dir = tempfile::tempdir().unwrap();
    charuco_campaign(dir.path());
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let serial = "CHARUCO-1";
    let job = upload_and_calibrate(&app, serial, dir.path()).await;
    let session = job["session_id"].as_str().unwrap();
    let s: Value = app
        .get(&format!("/v1/sessions/{session}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(s["target"]["kind"], "charuco", "{s}");
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
    assert!(
        before / after >= MIN_IMPROVEMENT,
        "before {before} after {after}"
    );
    let rms = report["camera"]["reprojection_rms_px"].as_f64().unwrap();
    eprintln!(
        "charuco campaign: before {before:.3} mm, after {after:.4} mm, reprojection {rms:.3} px"
    );
    assert!(rms < 0.2, "reprojection {rms} px");
    app.shutdown().await;
}

#[tokio::test]
async fn bad_charuco_specs_are_422_naming_the_field() {
    let app = spawn_app().await;
    let r = app
        .put_json(
            "/v1/robots/CH-BAD",
            &json!({"model": "IRB", "preset": "irb2400"}),
        )
        .await;
    assert_eq!(r.status(), 201);
    let camera =
        json!({"width": 1280, "height": 1024, "pixel_size_um": 5.3, "nominal_focal_mm": 11.0});
    let good = json!({"kind": "charuco", "squares": [10, 8], "square_mm": 25.0,
                      "marker_mm": 18.0, "dictionary": "DICT_5X5_100"});
    let cases = [
        (json!({"marker_mm": 30.0}), "target.marker_mm"),
        (json!({"square_mm": -1.0}), "target.square_mm"),
        (json!({"dictionary": "DICT_9X9_7"}), "target.dictionary"),
        (
            json!({"dictionary": "DICT_4X4_50", "squares": [20, 20]}),
            "target.dictionary",
        ),
        (json!({"pitch_mm": 25.0}), "target.pitch_mm"),
        (json!({"squares": [1, 8]}), "target.squares[0]"),
    ];
    for (change, field) in cases {
        let mut target = good.clone();
        for (k, v) in change.as_object().unwrap() {
            target[k] = v.clone();
        }
        let body = json!({"instrument": "camera", "target": target, "camera": camera});
        let r = app.post_json("/v1/robots/CH-BAD/sessions", &body).await;
        assert_eq!(r.status(), 422, "{change}");
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], field, "{change}: {problem}");
    }
    let body = json!({"instrument": "camera", "target": good, "camera": camera});
    assert_eq!(
        app.post_json("/v1/robots/CH-BAD/sessions", &body)
            .await
            .status(),
        201
    );
    app.shutdown().await;
}
