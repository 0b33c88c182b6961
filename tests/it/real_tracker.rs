//! Issue 19 on real laser-tracker data through the service: a user's
//! upload (the robot's DH table, a tracker session with the tool guess,
//! the poses as measured) calibrated with the terms allowed (the tracker
//! default) and without (`non_geometric: false`), on the campaigns in
//! `calib/tests/data/kinematic` (UR5: Jacobi 2025; UR10: Landgraf 2021).
//!
//! The default test takes every 10th pose of the UR5 grid (100) and
//! validates on the 20 random poses, a few seconds in debug. The full
//! figures of the issue (UR5 1000 grid → 20 random; UR10 Series B → C and
//! D with the base re-fitted on all of each by a `scope: base` job and
//! validated on all of it, the protocol exactly) are the
//! ignored test `real_tracker::full_campaigns` (BENCHMARKS.md, with its
//! command).

use std::time::Duration;

use robocal_calib::kinematics::presets;
use robocal_calib::kinematics::tracker_csv::{jacobi2025_rows, landgraf2021_rows, TrackerRow};
use serde_json::{json, Value};

use crate::support::{spawn_app_with, TestApp};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/calib/tests/data/kinematic");
/// The UR5 data's nominal tool (its targets are the nominal flange plus
/// 31 mm along z) and the UR10's T-Mac probe (`Trafo_TM_F_init.txt`).
const UR5_TOOL_MM: [f64; 3] = [0.0, 0.0, 31.0];
const UR10_TOOL_MM: [f64; 3] = [0.0, 0.0, 109.0];
/// The default test's share of the UR5 grid.
const GRID_STRIDE: usize = 10;
/// The geometric fit on 1000 grid poses validates at 0.1007 mm mean on the
/// 20 random poses (BENCHMARKS.md); on a tenth of the grid it must stay
/// within this, with or without terms.
const UR5_SUBSET_MAX_MM: f64 = 0.15;
/// Terms are kept only when they generalise: on the held-out random poses
/// a set with terms may be at most this much worse than without (mm).
const TERMS_SLACK_MM: f64 = 0.01;
const WAIT: Duration = Duration::from_secs(3600);

/// One measured pose: joints (deg) and the tracker's position (mm), as
/// a user sends them.
#[derive(Clone)]
struct Pose {
    joints_deg: Vec<f64>,
    position_mm: [f64; 3],
}

fn poses(rows: Vec<TrackerRow>) -> Vec<Pose> {
    rows.into_iter()
        .map(|r| Pose {
            joints_deg: r.joints_rad.iter().map(|q| q.to_degrees()).collect(),
            position_mm: r.position_mm.into(),
        })
        .collect()
}

fn read(path: &str) -> String {
    std::fs::read_to_string(format!("{DATA}/{path}")).unwrap()
}

/// A Jacobi 2025 UR5 file.
fn ur5(file: &str) -> Vec<Pose> {
    poses(jacobi2025_rows(&read(&format!("ur5_wam_jacobi2025/{file}"))).unwrap())
}

/// A Landgraf 2021 UR10 file.
fn ur10(series: &str, file: &str) -> Vec<Pose> {
    poses(landgraf2021_rows(&read(&format!("ur10_landgraf2021/{series}/{file}"))).unwrap())
}

/// A tracker session of `cal` (set `cal`) and `val` (set `val`) poses.
async fn session(
    app: &TestApp,
    serial: &str,
    tool_mm: [f64; 3],
    cal: &[Pose],
    val: &[Pose],
) -> String {
    let body = json!({
        "instrument": "tracker",
        "flange_to_camera_guess": {"translation_mm": tool_mm, "rotation_deg": [0.0, 0.0, 0.0]},
    });
    let sets = cal
        .iter()
        .map(|p| (p, "cal"))
        .chain(val.iter().map(|p| (p, "val")));
    let poses = sets.map(|(p, set)| (p.joints_deg.clone(), p.position_mm, set));
    app.tracker_session(serial, &body, poses).await
}

/// Runs a calibration job of `session` with `options`; its result.
async fn calibrate(app: &TestApp, session: &str, options: Value) -> Value {
    let path = format!("/v1/sessions/{session}/calibrations");
    app.finished_job(&path, &options, WAIT).await["result"].clone()
}

/// The kept terms of set `version` (name, value, σ, unit), one a line.
async fn kept_terms(app: &TestApp, serial: &str, version: u32) -> Vec<String> {
    let set = app
        .get_ok(&format!("/v1/robots/{serial}/parameter-sets/{version}"))
        .await;
    set["terms"]["terms"]
        .as_array()
        .map(|terms| {
            terms
                .iter()
                .map(|t| {
                    assert!(t["std_dev"].as_f64().unwrap() > 0.0, "{t}");
                    format!(
                        "{} = {:.3e} ± {:.1e} {}",
                        t["name"].as_str().unwrap(),
                        t["value"].as_f64().unwrap(),
                        t["std_dev"].as_f64().unwrap(),
                        t["unit"].as_str().unwrap()
                    )
                })
                .collect()
        })
        .unwrap_or_default()
}

/// After-mean (mm) of a calibration result's summary.
fn after_mm(result: &Value) -> f64 {
    result["summary"]["after_mean_mm"].as_f64().unwrap()
}

/// UR5 on a grid (`stride`-th poses) validated on the 20 random poses,
/// with and without terms: `(with, without, kept)`.
async fn ur5_campaign(app: &TestApp, stride: usize) -> (f64, f64, Vec<String>) {
    let grid: Vec<Pose> = ur5("3D_UR5_uncalibrated_grid_cleaned.csv")
        .into_iter()
        .step_by(stride)
        .collect();
    let random = ur5("3D_UR5_uncalibrated_random_cleaned.csv");
    app.put_kinematics("UR5-JACOBI", "UR5", &presets::ur5())
        .await;
    let s = session(app, "UR5-JACOBI", UR5_TOOL_MM, &grid, &random).await;
    let with = after_mm(&calibrate(app, &s, json!({})).await);
    let without = after_mm(&calibrate(app, &s, json!({"non_geometric": false})).await);
    let kept = kept_terms(app, "UR5-JACOBI", 1).await;
    eprintln!(
        "UR5 {} grid -> {} random: with terms {with:.4} mm mean, geometric {without:.4} mm; kept {kept:#?}",
        grid.len(),
        random.len()
    );
    (with, without, kept)
}

#[tokio::test]
async fn ur5_tracker_campaign_calibrates_with_terms_allowed() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let (with, without, _) = ur5_campaign(&app, GRID_STRIDE).await;
    assert!(without < UR5_SUBSET_MAX_MM, "{without}");
    assert!(with < without + TERMS_SLACK_MM, "{with} vs {without}");
    let report = app
        .get_ok("/v1/robots/UR5-JACOBI/parameter-sets/1/report")
        .await;
    let terms = &report["terms"];
    assert!(
        terms["lines"].as_array().is_some_and(|l| !l.is_empty()),
        "{terms}"
    );
    assert!(
        terms["lines"]
            .as_array()
            .unwrap()
            .iter()
            .all(|l| l["why"].as_str().is_some_and(|w| !w.is_empty())),
        "{terms}"
    );
}

/// The UR10 protocol through the service for one robot: calibrate on
/// all of Series B (`options`), approve the set, then for C and D a
/// `scope: base` re-fit on all of the series through the approved set,
/// validated on the same poses.
async fn ur10_campaign(app: &TestApp, serial: &str, options: Value) -> Vec<(String, f64)> {
    app.put_kinematics(serial, "UR10", &presets::ur10()).await;
    let b = ur10("Series_B", "measurements_joint_configurations.csv");
    // The protocol: B fitted whole. Its poses are uploaded again
    // as validation poses (the job needs some; B's own figure is then
    // in-sample, and only C's and D's matter).
    let s = session(app, serial, UR10_TOOL_MM, &b, &b).await;
    let fit = calibrate(app, &s, options).await;
    let mut out = vec![("B (in-sample)".to_string(), after_mm(&fit))];
    app.approve_unless_approved(
        serial,
        1,
        "the issue's protocol validates B's set on C and D",
    )
    .await;
    for (series, file) in [
        ("Series_C", "measurements_random_poses.csv"),
        ("Series_D", "measurements_iso_cubes.csv"),
    ] {
        let poses = ur10(series, file);
        // The base re-fitted on all of the series, validated on all of
        // it (the same poses uploaded again as `val`), as the issue's
        // protocol and the calib benchmark do.
        let s = session(app, serial, UR10_TOOL_MM, &poses, &poses).await;
        let refit = calibrate(app, &s, json!({"scope": "base"})).await;
        out.push((
            format!("{series} ({} poses, base re-fitted)", poses.len()),
            after_mm(&refit),
        ));
    }
    out
}

/// The figures (BENCHMARKS.md): `cargo test --test it --
/// --ignored real_tracker::full_campaigns --nocapture`.
#[tokio::test]
#[ignore = "minutes in debug: the issue's full real-data figures"]
async fn full_campaigns() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let (with, without, _) = ur5_campaign(&app, 1).await;
    assert!(with < without + TERMS_SLACK_MM, "{with} vs {without}");
    let with = ur10_campaign(&app, "UR10-T", json!({})).await;
    eprintln!(
        "UR10 with terms: {with:?}; kept {:#?}",
        kept_terms(&app, "UR10-T", 1).await
    );
    let without = ur10_campaign(&app, "UR10-G", json!({"non_geometric": false})).await;
    eprintln!("UR10 geometric only: {without:?}");
}
