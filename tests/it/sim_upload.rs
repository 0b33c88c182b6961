//! A simulated camera campaign uploaded as a user would: a camera session
//! of image points (no images), one POST per pose, and the error of a set
//! against the simulator's true camera positions through `forward`.

use robocal_calib::sim::campaign::{Campaign, SimPose};
use robocal_calib::sim::campaign_io::PoseSet;
use serde_json::{json, Value};

use crate::support::TestApp;

pub fn joints_deg(joints_rad: &[f64]) -> Vec<f64> {
    joints_rad.iter().map(|q| q.to_degrees()).collect()
}

/// A session of campaign `c`'s image points, named `region`.
pub async fn upload_session(app: &TestApp, serial: &str, c: &Campaign, region: &str) -> String {
    let t = &c.truth;
    let session = json!({
        "instrument": "camera",
        "region": region,
        "target": {"rows": t.board.rows, "cols": t.board.cols, "pitch_mm": t.board.pitch_mm,
                   "dot_diameter_mm": t.board.dot_diameter_mm},
        "camera": {"width": t.image_width, "height": t.image_height,
                   "pixel_size_um": 3.45, "nominal_focal_mm": 12.0},
        "flange_to_camera_guess": {"translation_mm": [0.0, 60.0, 110.0], "rotation_deg": [0.0, 0.0, 0.0]}
    });
    let r = app
        .post_json(&format!("/v1/robots/{serial}/sessions"), &session)
        .await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    let id = r.json::<Value>().await.unwrap()["id"]
        .as_str()
        .unwrap()
        .to_string();
    for (i, p) in c.poses.iter().enumerate() {
        post_pose(
            app,
            &id,
            c,
            p,
            &format!("view-{i:02}"),
            joints_deg(&p.joints_rad),
        )
        .await;
    }
    id
}

/// Uploads pose `p`'s image points with `joints` under `label`.
pub async fn post_pose(
    app: &TestApp,
    session: &str,
    c: &Campaign,
    p: &SimPose,
    label: &str,
    joints: Vec<f64>,
) {
    let cols = c.truth.board.cols;
    let points: Vec<Value> = p
        .observed_px
        .iter()
        .enumerate()
        .map(|(k, px)| json!({"row": k / cols, "col": k % cols, "x": px.x, "y": px.y}))
        .collect();
    let body = json!({
        "set": if p.set == PoseSet::Cal { "cal" } else { "val" },
        "label": label,
        "joints_deg": joints,
        "image_points": points,
    });
    let r = app
        .post_json(&format!("/v1/sessions/{session}/poses"), &body)
        .await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
}

/// Mean 3-D error (mm) of set `version` (in session `session_id`'s board
/// frame, when given) at campaign `c`'s validation poses against the
/// simulator's true camera positions.
pub async fn true_error_mm(
    app: &TestApp,
    serial: &str,
    version: i64,
    session_id: Option<&str>,
    c: &Campaign,
) -> f64 {
    let val: Vec<_> = c.poses.iter().filter(|p| p.set == PoseSet::Val).collect();
    let mut body =
        json!({"joints_deg": val.iter().map(|p| joints_deg(&p.joints_rad)).collect::<Vec<_>>()});
    if let Some(id) = session_id {
        body["session_id"] = json!(id);
    }
    let r = app
        .post_json(
            &format!("/v1/robots/{serial}/parameter-sets/{version}/forward"),
            &body,
        )
        .await;
    assert_eq!(r.status(), 200, "{}", r.text().await.unwrap());
    let answer: Value = r.json().await.unwrap();
    let poses = answer["poses"].as_array().unwrap();
    assert_eq!(poses.len(), val.len());
    let total: f64 = poses
        .iter()
        .zip(&val)
        .map(|(got, p)| {
            let t = &got["camera_in_target"]["translation_mm"];
            let truth = p.target_to_camera.translation.vector;
            (0..3)
                .map(|k| (t[k].as_f64().unwrap() - truth[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .sum();
    total / val.len() as f64
}
