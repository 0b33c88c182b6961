//! Circle boards other than robocal's marker board through the service
//! (issue 14): OpenCV's asymmetric circle grid (printed, detected, and a
//! whole simulated campaign re-rendered on it, with an odd and with an
//! even number of rows) and the marker-less dot grid.

use std::cell::RefCell;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use robocal::calib::vision::{detect_asymmetric, AsymmetricCirclesSpec};
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_circles::render_circle_board;
use robocal_calib::vision::CircleBoard;
use serde_json::{json, Value};

use crate::board_campaign::{calibrates_through_the_service, rerendered_campaign};
use crate::support::{report_note, spawn_app};
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

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn asymmetric_grid_campaign_calibrates_through_the_service() {
    let dir = tempfile::tempdir().unwrap();
    let spec = board();
    let target = json!({
        "kind": "asymmetric_circles", "rows": spec.rows, "cols": spec.cols,
        "pitch_mm": spec.pitch_mm, "dot_diameter_mm": spec.dot_diameter_mm,
    });
    let board = CircleBoard::Asymmetric(spec);
    rerendered_campaign(
        dir.path(),
        52,
        6,
        target,
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
    calibrates_through_the_service(dir.path(), "ACIRCLES-1", "asymmetric_circles").await;
}

/// 10 rows of 5 in the same 200 x 200 mm area: an even number of rows
/// looks the same after a half turn about the dots' centre.
const EVEN_ROWS: usize = 10;
/// The grid is drawn turned in the board plane by this angle about its
/// centre (a fixed target frame for the job): the detector then numbers
/// the views of the IRB-2400 campaign from either end depending on the
/// camera's roll (it starts nearest the image's top-left corner), so some
/// are numbered half-turned against the others. Chosen so that both
/// readings occur; the test asserts that they do.
const EVEN_GRID_TURN_DEG: f64 = 90.0;

/// Whether `image`'s reading starts at the dot drawn as `(rows-1, cols-1)`
/// (numbered from the other end), judged against the renderer's truth.
fn read_half_turned(
    view: &robocal_calib::sim::render::RenderedView,
    spec: &AsymmetricCirclesSpec,
) -> bool {
    let found = detect_asymmetric(&view.image, spec).unwrap();
    assert!(
        !found.ordering_unique,
        "an even-row grid must report its half turn"
    );
    let first = (found.dots[0].x, found.dots[0].y);
    let near = |row: usize, col: usize| {
        let t = view
            .truth
            .iter()
            .find(|t| t.row == row && t.col == col)
            .unwrap();
        (t.x - first.0).hypot(t.y - first.1)
    };
    near(spec.rows - 1, spec.cols - 1) < near(0, 0)
}

/// An asymmetric grid with an even number of rows, read from the images at
/// upload: the detector's numbering of each view is known only up to a
/// half turn, the job settles it from the joints (relabelling exactly the
/// minority of views numbered from the other end, and saying so) and
/// calibrates as on the odd-row grid.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn even_row_asymmetric_grid_is_read_at_upload_and_its_half_turn_settled_from_the_joints() {
    let dir = tempfile::tempdir().unwrap();
    let spec = AsymmetricCirclesSpec {
        rows: EVEN_ROWS,
        ..board()
    };
    let target = json!({
        "kind": "asymmetric_circles", "rows": spec.rows, "cols": spec.cols,
        "pitch_mm": spec.pitch_mm, "dot_diameter_mm": spec.dot_diameter_mm,
    });
    let (a, b) = (
        spec.dot_centre_mm(0, 0),
        spec.dot_centre_mm(spec.rows - 1, spec.cols - 1),
    );
    let centre = Vector3::new(0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.0);
    let in_plane = Translation3::from(centre)
        * Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), EVEN_GRID_TURN_DEG.to_radians()),
        )
        * Translation3::from(-centre);
    let board = CircleBoard::Asymmetric(spec);
    let half_turned = RefCell::new(Vec::new());
    rerendered_campaign(
        dir.path(),
        52,
        6,
        target,
        &|intrinsics, camera_to_target, w, h, rng| {
            let view = render_circle_board(
                intrinsics,
                &(camera_to_target * in_plane),
                &board,
                w,
                h,
                &RenderOptions::default(),
                rng,
            )
            .unwrap();
            half_turned
                .borrow_mut()
                .push(read_half_turned(&view, &spec));
            view.image
        },
    );
    let half_turned = half_turned.into_inner();
    let entries: Vec<Value> =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("poses.json")).unwrap())
            .unwrap();
    // The job relabels the minority reading.
    let turned_count = half_turned.iter().filter(|&&t| t).count();
    let minority = turned_count * 2 < half_turned.len();
    let expected: Vec<&str> = entries
        .iter()
        .zip(&half_turned)
        .filter(|&(_, &t)| t == minority)
        .map(|(e, _)| e["image"].as_str().unwrap())
        .collect();
    assert!(
        !expected.is_empty() && expected.len() * 2 < entries.len(),
        "both readings must occur: {turned_count} of {} views numbered from the other end",
        entries.len()
    );
    let report =
        calibrates_through_the_service(dir.path(), "ACIRCLES-EVEN", "asymmetric_circles").await;
    let note = report_note(&report, "half turn");
    eprintln!("even-row asymmetric grid: {note}");
    assert!(note.contains("the joints showed it turned"), "{note}");
    assert!(
        note.ends_with(&format!("relabelled: {}.", expected.join(", "))),
        "expected {expected:?}: {note}"
    );
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
