//! The half turn of a symmetric chessboard settled from the joints (issue
//! 14, `src/pipeline/half_turn.rs`). An 8x6 board looks the same after a
//! half turn, so a detector numbers some views from the other corner; the
//! simulator's IRB-2400 campaign is uploaded as image points labelled that
//! way in a few views. The job must relabel exactly those views (and say
//! so) and calibrate as if nothing had happened; with joints that cannot
//! decide (the same joints uploaded for every view) it must refuse naming
//! `target.inner_corners`, never guess.

use std::time::Duration;

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

fn campaign() -> Campaign {
    let mut spec = CampaignSpec::standard("irb2400", SEED).unwrap();
    spec.cal_poses = CAL_POSES;
    spec.val_poses = VAL_POSES;
    spec.board = Board {
        rows: ROWS,
        cols: COLS,
        pitch_mm: SQUARE_MM,
        dot_diameter_mm: 8.0,
    };
    simulate_campaign(&spec).unwrap()
}

fn label(i: usize) -> String {
    format!("view-{i:02}")
}

/// The JSON pose of view `i`: its joints (or `joints_deg` instead), its
/// corners numbered from the other corner when `turned`.
fn pose_body(c: &Campaign, i: usize, turned: bool, joints_deg: Option<Vec<f64>>) -> Value {
    let p = &c.poses[i];
    let points: Vec<Value> = (0..ROWS)
        .flat_map(|r| (0..COLS).map(move |col| (r, col)))
        .map(|(r, col)| {
            let px = p.observed_px[r * COLS + col];
            let (row, col) = if turned {
                (ROWS - 1 - r, COLS - 1 - col)
            } else {
                (r, col)
            };
            json!({"row": row, "col": col, "x": px.x, "y": px.y})
        })
        .collect();
    let joints =
        joints_deg.unwrap_or_else(|| p.joints_rad.iter().map(|q| q.to_degrees()).collect());
    json!({
        "joints_deg": joints,
        "set": if p.set == PoseSet::Cal { "cal" } else { "val" },
        "label": label(i),
        "image_points": points,
    })
}

async fn run(app: &TestApp, serial: &str, c: &Campaign, same_joints: bool) -> (Value, Value) {
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
        "target": {"kind": "chessboard", "inner_corners": [COLS, ROWS], "square_mm": SQUARE_MM},
        "camera": {"width": t.image_width, "height": t.image_height,
                   "pixel_size_um": 3.45, "nominal_focal_mm": 12.0}
    });
    let r = app
        .post_json(&format!("/v1/robots/{serial}/sessions"), &session)
        .await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    let id = r.json::<Value>().await.unwrap()["id"]
        .as_str()
        .unwrap()
        .to_string();
    let first: Vec<f64> = c.poses[0]
        .joints_rad
        .iter()
        .map(|q| q.to_degrees())
        .collect();
    for i in 0..c.poses.len() {
        let joints = same_joints.then(|| first.clone());
        let body = pose_body(c, i, TURNED.contains(&i), joints);
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

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn half_turned_views_are_relabelled_from_the_joints_and_said_so() {
    let c = campaign();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let (job, report) = run(&app, "HALF-TURN", &c, false).await;
    assert_eq!(job["state"], "succeeded", "{job}");
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
    let expected: Vec<String> = TURNED.iter().map(|&i| label(i)).collect();
    assert!(
        note.ends_with(&format!("relabelled: {}.", expected.join(", "))),
        "{note}"
    );
    assert!(
        note.contains(&format!("in {} image(s)", TURNED.len())),
        "{note}"
    );
    let val_mean = report["after"]["mean_mm"].as_f64().unwrap();
    eprintln!("half turn: {note}; validation mean {val_mean:.4} mm");
    assert!(val_mean < MAX_VAL_MEAN_MM, "validation mean {val_mean} mm");
    let outliers: Vec<&Value> = report["per_pose"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["outlier"] == true)
        .collect();
    assert!(outliers.is_empty(), "{outliers:?}");
    app.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn joints_that_cannot_decide_the_half_turn_fail_the_job_naming_the_field() {
    let c = campaign();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let (job, _) = run(&app, "HALF-TURN-NO", &c, true).await;
    assert_eq!(job["state"], "failed", "{job}");
    let error = job["error"].to_string();
    eprintln!("refused: {error}");
    assert!(error.contains("target.inner_corners"), "{job}");
    assert!(error.contains("half turn"), "{job}");
    app.shutdown().await;
}
