//! Circle boards other than robocal's marker board through the service
//! (issue 14): OpenCV's asymmetric circle grid (printed, detected, and a
//! whole simulated campaign re-rendered on it, with odd and with even rows)
//! and the marker-less dot grid.

use nalgebra::Point3;
use robocal::calib::vision::{detect_asymmetric, AsymmetricCirclesSpec};
use robocal_calib::geometry::pose_from_matrix_rows;
use robocal_calib::sim::campaign_io::{PoseEntry, Truth};
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_circles::render_circle_board;
use robocal_calib::vision::{CircleBoard, GrayImage};
use serde_json::{json, Value};

use crate::board_campaign::{
    calibrates_through_the_service, rerendered_campaign, CAL_POSES, MIN_IMPROVEMENT, VAL_POSES,
};
use crate::support::{spawn_app, spawn_app_with, upload_and_calibrate};
use crate::targets::rasterise;

/// An asymmetric grid inside the simulator's 9x9 board area (200 x 200 mm):
/// 11 rows of 5, so every view that saw the dot board sees all of it.
fn board() -> AsymmetricCirclesSpec {
    AsymmetricCirclesSpec {
        rows: 11,
        cols: 5,
        pitch_mm: 20.0,
        dot_diameter_mm: 12.0,
    }
}

/// Rows of the half-turn-symmetric variant of [`board`].
const EVEN_ROWS: usize = 10;

fn target_of(spec: &AsymmetricCirclesSpec) -> Value {
    json!({
        "kind": "asymmetric_circles", "rows": spec.rows, "cols": spec.cols,
        "pitch_mm": spec.pitch_mm, "dot_diameter_mm": spec.dot_diameter_mm,
    })
}

/// The IRB 2400 campaign (simulator seed `seed`) in `dir`, every image
/// drawn again on the asymmetric grid `spec`.
fn asymmetric_campaign(dir: &std::path::Path, spec: AsymmetricCirclesSpec, seed: u64) {
    let board = CircleBoard::Asymmetric(spec);
    rerendered_campaign(
        dir,
        seed,
        6,
        target_of(&spec),
        &|intrinsics, camera_to_target, w, h, rng| {
            render_circle_board(
                intrinsics,
                camera_to_target,
                &board,
                w,
                h,
                &RenderOptions::default(),
                rng,
            )
            .unwrap()
            .image
        },
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn asymmetric_grid_campaign_calibrates_through_the_service() {
    let dir = tempfile::tempdir().unwrap();
    asymmetric_campaign(dir.path(), board(), 52);
    calibrates_through_the_service(dir.path(), "ACIRCLES-1", "asymmetric_circles").await;
}

/// The images of the campaign in `dir` whose detection numbers the board
/// from the other corner: the detector's first dot is nearer the image of
/// the last dot than of the first one (truth projected through the truth
/// intrinsics).
fn views_read_half_turned(dir: &std::path::Path, spec: &AsymmetricCirclesSpec) -> Vec<String> {
    let read = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    let truth: Truth = serde_json::from_str(&read("truth.json")).unwrap();
    let entries: Vec<PoseEntry> = serde_json::from_str(&read("poses.json")).unwrap();
    let at = |i: usize, row: usize, col: usize| {
        let [x, y, z] = spec.dot_centre_mm(row, col);
        // The simulator's names: `p_camera = target_to_camera⁻¹ * p_target`
        // (as `rerendered_campaign` hands the renderer).
        let camera_to_target = pose_from_matrix_rows(&truth.target_to_camera[i])
            .unwrap()
            .inverse();
        truth
            .intrinsics
            .project(&(camera_to_target * Point3::new(x, y, z)))
            .unwrap()
    };
    let mut turned = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let image = GrayImage::from_dynamic(&image::open(dir.join(&entry.image)).unwrap());
        let found = detect_asymmetric(&image, spec).unwrap();
        assert!(
            !found.ordering_unique,
            "{}: even rows are ambiguous",
            entry.image
        );
        let first = nalgebra::Point2::new(found.dots[0].x, found.dots[0].y);
        let (own, other) = (at(i, 0, 0), at(i, spec.rows - 1, spec.cols - 1));
        if nalgebra::distance(&first, &other) < nalgebra::distance(&first, &own) {
            turned.push(entry.image.clone());
        }
    }
    turned
}

/// An asymmetric grid with an even number of rows looks the same after a
/// half turn: the detector reads every image (at upload) with its first dot
/// nearest the image's top-left corner, so views in which the board lies
/// the other way are numbered from the other corner. The job must settle
/// each view's turn from the joints, relabel exactly the views whose
/// numbering disagrees with the majority (and say so), and calibrate as
/// well as on an odd-row grid. Left unrelabelled, a turned view's board
/// frame would be 180 mm away and turned by 180°: the job would fail or its
/// validation error would be many times larger.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "the IRB 2400 campaign (seed 52) never shows the board half turned: \
            the detector reads all 32 views like the truth; needs views rolled \
            by joint 6 (session 9 targets2 notes)"]
async fn asymmetric_grid_with_even_rows_is_settled_from_the_joints() {
    const SERIAL: &str = "ACIRCLES-EVEN";
    let spec = AsymmetricCirclesSpec {
        rows: EVEN_ROWS,
        ..board()
    };
    let dir = tempfile::tempdir().unwrap();
    asymmetric_campaign(dir.path(), spec, 52);
    let mut turned = views_read_half_turned(dir.path(), &spec);
    let views = CAL_POSES + VAL_POSES;
    if 2 * turned.len() > views {
        // The majority's numbering is the one kept: the others are relabelled.
        let all: Vec<PoseEntry> =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("poses.json")).unwrap())
                .unwrap();
        turned = all
            .into_iter()
            .map(|e| e.image)
            .filter(|name| !turned.contains(name))
            .collect();
    }
    assert!(
        !turned.is_empty() && 2 * turned.len() < views,
        "the campaign must show the board both ways: {turned:?}"
    );
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    upload_and_calibrate(&app, SERIAL, dir.path()).await;
    let report: Value = app
        .get(&format!("/v1/robots/{SERIAL}/parameter-sets/latest/report"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(
        report["detection"]["images_detected"], views,
        "{}",
        report["detection"]
    );
    let notes: Vec<&str> = report["notes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    let note = notes
        .iter()
        .find(|n| n.contains("half turn"))
        .unwrap_or_else(|| panic!("no half-turn note in {notes:?}"));
    assert!(
        note.ends_with(&format!("relabelled: {}.", turned.join(", "))),
        "expected {turned:?}: {note}"
    );
    assert!(
        note.contains(&format!(
            "the joints showed it turned in {} image(s)",
            turned.len()
        )),
        "{note}"
    );
    let before = report["before"]["mean_mm"].as_f64().unwrap();
    let after = report["after"]["mean_mm"].as_f64().unwrap();
    eprintln!("{SERIAL}: {note} Validation mean {before:.3} mm before, {after:.4} mm after.");
    assert!(
        before / after >= MIN_IMPROVEMENT,
        "before {before} after {after}"
    );
    app.shutdown().await;
}

#[tokio::test]
async fn circle_board_specs_are_checked_naming_the_field() {
    let app = spawn_app().await;
    let r = app
        .put_json(
            "/v1/robots/AC-BAD",
            &json!({"model": "IRB", "preset": "irb2400"}),
        )
        .await;
    assert_eq!(r.status(), 201);
    let camera =
        json!({"width": 1280, "height": 1024, "pixel_size_um": 5.3, "nominal_focal_mm": 11.0});
    let good = json!({"kind": "asymmetric_circles", "rows": 11, "cols": 4,
                      "pitch_mm": 20.0, "dot_diameter_mm": 14.0});
    let cases = [
        (json!({"dot_diameter_mm": 30.0}), "target.dot_diameter_mm"),
        (json!({"pitch_mm": 0.0}), "target.pitch_mm"),
        (json!({"rows": 1}), "target.rows"),
        (
            json!({"origin_marker_diameter_mm": 20.0}),
            "target.origin_marker_diameter_mm",
        ),
        (json!({"square_mm": 20.0}), "target.square_mm"),
    ];
    for (change, field) in cases {
        let mut target = good.clone();
        for (k, v) in change.as_object().unwrap() {
            target[k] = v.clone();
        }
        let body = json!({"instrument": "camera", "target": target, "camera": camera});
        let r = app.post_json("/v1/robots/AC-BAD/sessions", &body).await;
        assert_eq!(r.status(), 422, "{change}");
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], field, "{change}: {problem}");
    }
    let missing = json!({"kind": "asymmetric_circles", "rows": 11, "cols": 4, "pitch_mm": 20.0});
    let body = json!({"instrument": "camera", "target": missing, "camera": camera});
    let problem: Value = app
        .post_json("/v1/robots/AC-BAD/sessions", &body)
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(problem["errors"][0]["field"], "target.dot_diameter_mm");
    // Both circle boards are accepted: the asymmetric grid, and the dot
    // grid without its origin marker.
    let bare = json!({"rows": 7, "cols": 9, "pitch_mm": 25.0, "dot_diameter_mm": 10.0});
    for target in [good, bare] {
        let body = json!({"instrument": "camera", "target": target, "camera": camera});
        let r = app.post_json("/v1/robots/AC-BAD/sessions", &body).await;
        assert_eq!(r.status(), 201, "{target}");
    }
    app.shutdown().await;
}

#[tokio::test]
async fn printed_asymmetric_grid_is_exact_scale_and_detected() {
    let app = spawn_app().await;
    let r = app
        .get("/v1/targets/render?kind=asymmetric_circles&rows=11&cols=4&pitch_mm=20&dot_diameter_mm=14")
        .await;
    assert_eq!(r.status(), 200);
    let svg = r.text().await.unwrap();
    assert!(
        svg.contains("\"kind\": \"asymmetric_circles\""),
        "spec in the margin"
    );
    let found = detect_asymmetric(&rasterise(&svg), &AsymmetricCirclesSpec::opencv_4x11()).unwrap();
    assert_eq!(found.dots.len(), 44);
    assert!(found.ordering_unique);
    // Dots in a row 40 mm apart on paper (400 px at 10 px/mm), rows 20 mm.
    let at = |row: usize, col: usize| found.dots[row * 4 + col];
    for (row, col) in [(0, 0), (5, 1), (10, 2)] {
        let (a, b) = (at(row, col), at(row, col + 1));
        let d = (b.x - a.x).hypot(b.y - a.y);
        assert!((d - 400.0).abs() < 0.1, "({row},{col}) spacing {d} px");
        let c = at(row + usize::from(row < 10), col);
        let dy = (c.y - a.y).abs();
        assert!(row == 10 || (dy - 200.0).abs() < 0.1, "row spacing {dy}");
    }
    for (query, field) in [
        (
            "kind=asymmetric_circles&rows=11&cols=4&pitch_mm=20&dot_diameter_mm=29",
            "dot_diameter_mm",
        ),
        (
            "kind=asymmetric_circles&rows=11&cols=4&pitch_mm=-2&dot_diameter_mm=14",
            "pitch_mm",
        ),
        (
            "kind=asymmetric_circles&rows=11&cols=4&pitch_mm=20&dot_diameter_mm=14&origin_marker_diameter_mm=20",
            "origin_marker_diameter_mm",
        ),
        (
            "kind=asymmetric_circles&rows=11&pitch_mm=20&dot_diameter_mm=14",
            "cols",
        ),
    ] {
        let r = app.get(&format!("/v1/targets/render?{query}")).await;
        assert_eq!(r.status(), 422, "{query}");
        let body: Value = r.json().await.unwrap();
        assert_eq!(body["errors"][0]["field"], field, "{query}: {body}");
    }
    app.shutdown().await;
}
