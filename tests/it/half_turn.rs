//! The half turn of a symmetric board settled from the robot data (issue
//! 14, `src/pipeline/board_turn.rs`). An 8x6 chessboard, and an 8x6 dot grid
//! without its origin marker, look the same after a half turn, so a
//! detector numbers some views from the other corner; the simulator's
//! IRB-2400 campaign is uploaded as image points labelled that way in a few
//! views, with its joints (a kinematic session) or with the true flange
//! poses (a hand–eye session). The job must relabel exactly those views
//! (and say so) and calibrate as if nothing had happened; with robot data
//! that cannot decide (the same joints or flange pose uploaded for every
//! view) it must refuse naming the target's field, never guess.

use std::time::Duration;

use robocal_calib::geometry::{pose_from_matrix_rows, pose_to_matrix_rows, Pose};
use robocal_calib::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::{Board, PoseSet};
use serde_json::{json, Value};

use crate::support::*;

const COLS: usize = 8;
const ROWS: usize = 6;
const SQUARE_MM: f64 = 25.0;
const CAL_POSES: usize = 16;
const VAL_POSES: usize = 6;
const SEED: u64 = 1407;
/// Views uploaded with the half-turned numbering (a minority).
const TURNED: [usize; 4] = [2, 7, 11, 19];
const WAIT: Duration = Duration::from_secs(240);
/// The validation poses' mean error after calibration, mm: the simulator's
/// 0.1 px noise gives a few hundredths; a wrongly numbered view bends the
/// fit by far more (its board frame is 175 x 125 mm away, turned by 180°).
const MAX_VAL_MEAN_MM: f64 = 0.3;
/// The hand–eye of a flange-pose session must be this many reported
/// standard deviations from the truth at most (per component).
const SIGMAS: f64 = 4.0;
/// Dot diameter of the marker-less grid, mm.
const DOT_MM: f64 = 8.0;

/// Where the uploaded poses say the robot was.
#[derive(Clone, Copy, PartialEq)]
enum RobotData {
    /// Each view's joints (a kinematic session).
    Joints,
    /// The first view's joints for every view: they cannot decide.
    SameJoints,
    /// Each view's true flange pose (a hand–eye session; all views `cal`).
    FlangePoses,
    /// The first view's flange pose for every view.
    SameFlangePose,
}

fn chessboard() -> Value {
    json!({"kind": "chessboard", "inner_corners": [COLS, ROWS], "square_mm": SQUARE_MM})
}

fn dot_grid() -> Value {
    json!({"kind": "dots", "rows": ROWS, "cols": COLS, "pitch_mm": SQUARE_MM,
           "dot_diameter_mm": DOT_MM})
}

/// The flange pose of view `i` the controller of the true robot reports:
/// `target_to_camera = target_to_base * base_to_flange * flange_to_camera`.
fn flange_pose(c: &Campaign, i: usize) -> Value {
    let target_to_base = pose_from_matrix_rows(&c.truth.target_to_base).unwrap();
    let flange_to_camera = pose_from_matrix_rows(&c.truth.flange_to_camera).unwrap();
    let base_to_flange: Pose =
        target_to_base.inverse() * c.poses[i].target_to_camera * flange_to_camera.inverse();
    let m = pose_to_matrix_rows(&base_to_flange);
    json!({
        "translation_mm": [m[0][3], m[1][3], m[2][3]],
        "matrix": [
            [m[0][0], m[0][1], m[0][2]],
            [m[1][0], m[1][1], m[1][2]],
            [m[2][0], m[2][1], m[2][2]],
        ],
    })
}

fn campaign() -> Campaign {
    campaign_of(ROWS, COLS)
}

fn campaign_of(rows: usize, cols: usize) -> Campaign {
    let mut spec = CampaignSpec::standard("irb2400", SEED).unwrap();
    spec.cal_poses = CAL_POSES;
    spec.val_poses = VAL_POSES;
    spec.board = Board {
        rows,
        cols,
        pitch_mm: SQUARE_MM,
        dot_diameter_mm: DOT_MM,
    };
    simulate_campaign(&spec).unwrap()
}

fn label(i: usize) -> String {
    format!("view-{i:02}")
}

/// The JSON pose of view `i`: where the robot was as `data` says, its
/// features numbered as if the board were turned by `quarter_turns` (2:
/// from the other corner; 1 and 3 only for a square grid).
fn pose_body_turned(c: &Campaign, i: usize, quarter_turns: u8, data: RobotData) -> Value {
    let p = &c.poses[i];
    let (rows, cols) = (c.truth.board.rows, c.truth.board.cols);
    let points: Vec<Value> = (0..rows)
        .flat_map(|r| (0..cols).map(move |col| (r, col)))
        .map(|(r, col)| {
            let px = p.observed_px[r * cols + col];
            let (row, col) = match quarter_turns {
                1 => (col, rows - 1 - r),
                2 => (rows - 1 - r, cols - 1 - col),
                3 => (cols - 1 - col, r),
                _ => (r, col),
            };
            json!({"row": row, "col": col, "x": px.x, "y": px.y})
        })
        .collect();
    let joints = |k: usize| -> Vec<f64> {
        c.poses[k]
            .joints_rad
            .iter()
            .map(|q| q.to_degrees())
            .collect()
    };
    let mut body = json!({
        "set": if p.set == PoseSet::Cal { "cal" } else { "val" },
        "label": label(i),
        "image_points": points,
    });
    match data {
        RobotData::Joints => body["joints_deg"] = json!(joints(i)),
        RobotData::SameJoints => body["joints_deg"] = json!(joints(0)),
        RobotData::FlangePoses => body["flange_pose"] = flange_pose(c, i),
        RobotData::SameFlangePose => body["flange_pose"] = flange_pose(c, 0),
    }
    if matches!(data, RobotData::FlangePoses | RobotData::SameFlangePose) {
        body["set"] = json!("cal");
    }
    body
}

async fn run(
    app: &TestApp,
    serial: &str,
    c: &Campaign,
    target: Value,
    data: RobotData,
) -> (Value, Value) {
    let turns: Vec<u8> = (0..c.poses.len())
        .map(|i| if TURNED.contains(&i) { 2 } else { 0 })
        .collect();
    run_turned(app, serial, c, target, data, &turns).await
}

/// [`run`] with view `i` numbered as turned by `turns[i]` quarter turns.
async fn run_turned(
    app: &TestApp,
    serial: &str,
    c: &Campaign,
    target: Value,
    data: RobotData,
    turns: &[u8],
) -> (Value, Value) {
    let r = app
        .put_json(
            &format!("/v1/robots/{serial}"),
            &json!({"model": "IRB", "preset": "irb2400"}),
        )
        .await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    let t = &c.truth;
    let session = json!({
        "instrument": "camera",
        "target": target,
        "camera": {"width": t.image_width, "height": t.image_height,
                   "pixel_size_um": 3.45, "nominal_focal_mm": 12.0}
    });
    let id = app.new_session(serial, &session).await;
    for (i, &turn) in turns.iter().enumerate().take(c.poses.len()) {
        let body = pose_body_turned(c, i, turn, data);
        let r = app
            .post_json(&format!("/v1/sessions/{id}/poses"), &body)
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    let r = app
        .post_json(&format!("/v1/sessions/{id}/calibrations"), &json!({}))
        .await;
    assert_eq!(r.status(), 202);
    let job_id = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let job = app.wait_job(&job_id, WAIT, is_finished).await;
    let report = if job["state"] == "succeeded" {
        app.get(&format!("/v1/robots/{serial}/parameter-sets/latest/report"))
            .await
            .json()
            .await
            .unwrap()
    } else {
        Value::Null
    };
    (job, report)
}

/// The report's note on the relabelled views names exactly [`TURNED`],
/// and no pose is an outlier.
fn assert_relabelled_exactly_the_turned_views(report: &Value, data: &str) -> String {
    let note = report_note(report, "half turn");
    let expected: Vec<String> = TURNED.iter().map(|&i| label(i)).collect();
    assert!(
        note.ends_with(&format!("relabelled: {}.", expected.join(", "))),
        "{note}"
    );
    assert!(
        note.contains(&format!(
            "the {data} showed it turned in {} image(s)",
            TURNED.len()
        )),
        "{note}"
    );
    let outliers: Vec<&Value> = report["per_pose"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["outlier"] == true)
        .collect();
    assert!(outliers.is_empty(), "{outliers:?}");
    note.to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn half_turned_views_are_relabelled_from_the_joints_and_said_so() {
    let c = campaign();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    for (serial, target) in [("HALF-TURN", chessboard()), ("HALF-TURN-DOTS", dot_grid())] {
        let (job, report) = run(&app, serial, &c, target, RobotData::Joints).await;
        assert_eq!(job["state"], "succeeded", "{serial}: {job}");
        let note = assert_relabelled_exactly_the_turned_views(&report, "joints");
        let val_mean = report["after"]["mean_mm"].as_f64().unwrap();
        eprintln!("{serial}: {note}; validation mean {val_mean:.4} mm");
        assert!(
            val_mean < MAX_VAL_MEAN_MM,
            "{serial}: validation mean {val_mean} mm"
        );
    }
    app.shutdown().await;
}

/// A square marker-less grid looks the same after any quarter turn: views
/// numbered a quarter, half and three quarters turned are all relabelled.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn quarter_turned_views_of_a_square_grid_are_relabelled_from_the_joints() {
    const SIDE: usize = 6;
    const QUARTER: [(usize, u8); 4] = [(2, 1), (7, 2), (11, 3), (19, 1)];
    let c = campaign_of(SIDE, SIDE);
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let turns: Vec<u8> = (0..c.poses.len())
        .map(|i| QUARTER.iter().find(|q| q.0 == i).map_or(0, |q| q.1))
        .collect();
    let target = json!({"kind": "dots", "rows": SIDE, "cols": SIDE, "pitch_mm": SQUARE_MM,
                        "dot_diameter_mm": DOT_MM});
    let (job, report) =
        run_turned(&app, "QUARTER-TURN", &c, target, RobotData::Joints, &turns).await;
    assert_eq!(job["state"], "succeeded", "{job}");
    let note = report_note(&report, "quarter or half turn");
    let expected: Vec<String> = QUARTER.iter().map(|&(i, _)| label(i)).collect();
    assert!(
        note.ends_with(&format!("relabelled: {}.", expected.join(", "))),
        "{note}"
    );
    let val_mean = report["after"]["mean_mm"].as_f64().unwrap();
    eprintln!("QUARTER-TURN: {note}; validation mean {val_mean:.4} mm");
    assert!(val_mean < MAX_VAL_MEAN_MM, "validation mean {val_mean} mm");
    app.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn half_turned_views_are_relabelled_from_the_flange_poses() {
    let c = campaign();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let serial = "HALF-TURN-FLANGE";
    let (job, report) = run(&app, serial, &c, chessboard(), RobotData::FlangePoses).await;
    assert_eq!(job["state"], "succeeded", "{job}");
    let note = assert_relabelled_exactly_the_turned_views(&report, "flange poses");
    // A view left numbered from the other corner would put its board
    // 175 x 125 mm away, turned by 180°: the hand–eye would be far off or
    // the view flagged. Both frames within SIGMAS of the truth.
    let he = &report["hand_eye"];
    for (frame, truth) in [
        ("flange_to_camera", &c.truth.flange_to_camera),
        ("target_to_base", &c.truth.target_to_base),
    ] {
        let truth = pose_from_matrix_rows(truth).unwrap().translation.vector;
        let f = &he[frame];
        for k in 0..3 {
            let got = f["translation_mm"][k].as_f64().unwrap();
            let sigma = f["std_translation_mm"][k]
                .as_f64()
                .unwrap()
                .max(f["formal_std_translation_mm"][k].as_f64().unwrap());
            eprintln!(
                "{frame} t[{k}]: {got:.3} vs truth {:.3} (sigma {sigma:.3})",
                truth[k]
            );
            assert!(
                (got - truth[k]).abs() < SIGMAS * sigma,
                "{frame} t[{k}]: {got} vs truth {} (sigma {sigma})",
                truth[k]
            );
        }
    }
    eprintln!("{serial}: {note}");
    app.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn robot_data_that_cannot_decide_the_half_turn_fail_the_job_naming_the_field() {
    let c = campaign();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let cases = [
        (
            "HALF-TURN-NO",
            chessboard(),
            RobotData::SameJoints,
            "target.inner_corners",
            "joints",
        ),
        (
            "HALF-TURN-NO-DOTS",
            dot_grid(),
            RobotData::SameJoints,
            "target.origin_marker_diameter_mm",
            "joints",
        ),
        (
            "HALF-TURN-NO-FLANGE",
            chessboard(),
            RobotData::SameFlangePose,
            "target.inner_corners",
            "flange poses",
        ),
    ];
    for (serial, target, data, field, words) in cases {
        let (job, _) = run(&app, serial, &c, target, data).await;
        assert_eq!(job["state"], "failed", "{serial}: {job}");
        let error = job["error"].to_string();
        eprintln!("{serial} refused: {error}");
        assert!(error.contains(field), "{serial}: {job}");
        assert!(error.contains("half turn"), "{serial}: {job}");
        assert!(
            error.contains(&format!("the {words} cannot tell")),
            "{serial}: {job}"
        );
    }
    app.shutdown().await;
}
