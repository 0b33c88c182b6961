//! A ChArUco campaign through the service (issue 14): the simulator's
//! campaign with every image re-rendered as a ChArUco board in the same
//! target frame; the session says `"kind": "charuco"`. Detection at upload
//! finds the corners, the job calibrates as well as on the dot board, and a
//! bad ChArUco spec is a 422 naming the field.

use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_charuco::render_charuco;
use robocal_calib::vision::charuco::CharucoSpec;
use serde_json::{json, Value};

use crate::board_campaign::{calibrates_through_the_service, rerendered_campaign};
use crate::support::spawn_app;

fn board() -> CharucoSpec {
    CharucoSpec {
        squares: [10, 8],
        square_mm: 25.0,
        marker_mm: 18.0,
        dictionary: "DICT_5X5_100".into(),
        legacy_layout: false,
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn charuco_campaign_calibrates_through_the_service() {
    let dir = tempfile::tempdir().unwrap();
    let spec = board();
    let target = json!({
        "kind": "charuco", "squares": spec.squares, "square_mm": spec.square_mm,
        "marker_mm": spec.marker_mm, "dictionary": spec.dictionary,
    });
    rerendered_campaign(
        dir.path(),
        51,
        5,
        target,
        &|intrinsics, camera_to_target, w, h, rng| {
            render_charuco(
                intrinsics,
                camera_to_target,
                &spec,
                w,
                h,
                &RenderOptions::default(),
                rng,
            )
            .unwrap()
            .image
        },
    );
    calibrates_through_the_service(dir.path(), "CHARUCO-1", "charuco").await;
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

/// `robocal simulate --target charuco` (and `chessboard`): the campaign
/// written with the board drawn and described, calibrated through the
/// service like the dot grid's.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn simulate_writes_charuco_and_chessboard_campaigns_that_calibrate() {
    use crate::board_campaign::{CAL_POSES, VAL_POSES};
    use robocal::cli::campaign::{simulate_board, SimBoard};
    for (board, kind, serial) in [
        (SimBoard::Charuco, "charuco", "SIM-CHARUCO"),
        (SimBoard::Chessboard, "chessboard", "SIM-CHESS"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        simulate_board("irb2400", dir.path(), CAL_POSES, VAL_POSES, 3, board).unwrap();
        let campaign: Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join("campaign.json")).unwrap(),
        )
        .unwrap();
        assert_eq!(campaign["session"]["target"]["kind"], kind, "{campaign}");
        calibrates_through_the_service(dir.path(), serial, kind).await;
    }
}
