//! The UR5 tracker campaign (Jacobi 2025, `calib/tests/data/kinematic`)
//! as a user uploads it, calibrated geometrically: the set the controller
//! tests (issue 34) export and check against.

use std::time::Duration;

use robocal_calib::kinematics::presets;
use robocal_calib::kinematics::tracker_csv::{jacobi2025_rows, TrackerRow};
use serde_json::{json, Value};

use crate::support::TestApp;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/calib/tests/data/kinematic");
/// The UR5 data's nominal tool: the flange plus 31 mm along z.
const UR5_TOOL_MM: [f64; 3] = [0.0, 0.0, 31.0];
/// Every 10th pose of the grid calibrates (100 poses, seconds in debug).
const GRID_STRIDE: usize = 10;
const WAIT: Duration = Duration::from_secs(600);

/// Robot `serial` (the UR5's table, `kinematics` overriding it when given)
/// with a tracker session of the UR5 grid (every 10th pose, `cal`) and
/// the 20 random poses (`val`); `session_extra` adds session fields.
/// Returns the session id.
pub(crate) async fn ur5_session(
    app: &TestApp,
    serial: &str,
    robot_extra: Value,
    session_extra: Value,
) -> String {
    let grid = ur5_rows("3D_UR5_uncalibrated_grid_cleaned.csv");
    let random = ur5_rows("3D_UR5_uncalibrated_random_cleaned.csv");
    let kinematics = robocal::schema::robot::model_to_doc(&presets::ur5());
    let mut robot = json!({"model": "UR5", "kinematics": kinematics});
    merge(&mut robot, robot_extra);
    let r = app.put_json(&format!("/v1/robots/{serial}"), &robot).await;
    assert!(r.status().is_success(), "{}", r.text().await.unwrap());
    let mut body = ur5_session_body();
    merge(&mut body, session_extra);
    let cal = grid.iter().step_by(GRID_STRIDE).map(|r| (r, "cal"));
    let val = random.iter().map(|r| (r, "val"));
    let poses = cal.chain(val).map(|(r, set)| {
        let joints_deg = r.joints_rad.iter().map(|q| q.to_degrees()).collect();
        (joints_deg, r.position_mm.into(), set)
    });
    app.tracker_session(serial, &body, poses).await
}

/// The rows of a Jacobi 2025 UR5 file.
pub(crate) fn ur5_rows(file: &str) -> Vec<TrackerRow> {
    let text = std::fs::read_to_string(format!("{DATA}/ur5_wam_jacobi2025/{file}")).unwrap();
    jacobi2025_rows(&text).unwrap()
}

/// The tracker session body of the UR5 campaign.
pub(crate) fn ur5_session_body() -> Value {
    json!({
        "instrument": "tracker",
        "flange_to_camera_guess": {"translation_mm": UR5_TOOL_MM, "rotation_deg": [0.0, 0.0, 0.0]},
    })
}

pub(crate) fn merge(into: &mut Value, extra: Value) {
    if let (Some(into), Value::Object(extra)) = (into.as_object_mut(), extra) {
        into.extend(extra);
    }
}

/// A geometric calibration (no terms: kinematics.yaml cannot hold them)
/// of `session`; the job's result.
pub(crate) async fn calibrate(app: &TestApp, session: &str) -> Value {
    let path = format!("/v1/sessions/{session}/calibrations");
    app.finished_job(&path, &json!({"non_geometric": false}), WAIT)
        .await["result"]
        .clone()
}
