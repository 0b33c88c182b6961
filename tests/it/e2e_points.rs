//! End to end over HTTP (issue 6), one small rendered PUMA-560 campaign:
//! - the detect stage's dot centres land on the pose rows and are served by
//!   the pose endpoints, close to the simulator's true projections, with
//!   per-point residuals once the job succeeded;
//! - a second job (`refine_intrinsics: false`: the paper's camera, flagged
//!   as such) replaces them consistently, the images stay byte-identical;
//! - a session on another robot naming the first calibration in
//!   `camera_calibration_id` calibrates with those intrinsics held fixed.

use std::collections::BTreeMap;
use std::time::Duration;

use nalgebra::Point3;
use reqwest::multipart::{Form, Part};
use robocal::cli::campaign::{self, CampaignFile};
use robocal::cli::client::Client;
use robocal_calib::geometry::pose_from_matrix_rows;
use robocal_calib::sim::campaign_io::{PoseEntry, Truth};
use serde_json::{json, Value};

use crate::support::{is_finished, sha256_hex, spawn_app_with, TestApp};

const WAIT: Duration = Duration::from_secs(240);
/// A small campaign: identification needs a few more rows than the 30
/// parameters (6 per pose), validation a handful of poses.
const CAL_POSES: usize = 16;
const VAL_POSES: usize = 6;
const SEED: u64 = 21;
/// Dots on the simulated board.
const DOTS: usize = 81;
/// Detected (uncorrected) centre against the true projection of the dot's
/// centre: render noise plus the perspective bias of a blob centroid of
/// an 8 mm dot (method.md §4), px.
const MAX_DETECTION_ERROR_PX: f64 = 0.5;
/// RMS of all residuals against the calibrated model with refined (or
/// reused refined) intrinsics, px: the renderer's pixel noise is about a
/// hundredth; a wrong model, pose or intrinsics gives pixels.
const MAX_RESIDUAL_RMS_PX: f64 = 0.05;
/// The same with the paper's intrinsics (their few-percent focal bias
/// leaves about a pixel, method.md §4) and no joint refinement.
const MAX_PAPER_RESIDUAL_RMS_PX: f64 = 3.0;
/// Mean validation error must improve this many times with the fixed camera.
const MIN_IMPROVEMENT: f64 = 12.0;
/// Poses of a session too small to identify (3 cal + 1 val): its job fails
/// after the detect stage.
const TOO_FEW_POSES: usize = 4;

async fn run_job(app: &TestApp, client: &Client, session: &str, options: Value) -> Value {
    let job = client.start_calibration(session, &options).await.unwrap();
    let done = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    done
}

async fn json_of(app: &TestApp, path: &str) -> Value {
    let r = app.get(path).await;
    assert_eq!(r.status(), 200, "{path}");
    r.json().await.unwrap()
}

/// Every pose of a session as served, in upload order.
async fn poses_of(app: &TestApp, session: &str) -> Vec<Value> {
    let list = json_of(app, &format!("/v1/sessions/{session}/poses?limit=1000")).await;
    list["items"].as_array().unwrap().clone()
}

/// One served point: `x`, `y`, the raw centre (`raw_x`, `raw_y`, when
/// `x`, `y` are bias-corrected) and the residual.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Served {
    x: f64,
    y: f64,
    raw: Option<(f64, f64)>,
    residual: Option<[f64; 2]>,
}

impl Served {
    /// The centre as detected: the same for every job on one image.
    fn detected(&self) -> (f64, f64) {
        self.raw.unwrap_or((self.x, self.y))
    }
}

/// `(row, col) -> point` of a served pose.
type Points = BTreeMap<(u64, u64), Served>;

fn points_of(pose: &Value) -> Points {
    pose["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let residual = p
                .get("residual_px")
                .map(|r| [r[0].as_f64().unwrap(), r[1].as_f64().unwrap()]);
            let raw = p
                .get("raw_x")
                .map(|x| (x.as_f64().unwrap(), p["raw_y"].as_f64().unwrap()));
            (
                (p["row"].as_u64().unwrap(), p["col"].as_u64().unwrap()),
                Served {
                    x: p["x"].as_f64().unwrap(),
                    y: p["y"].as_f64().unwrap(),
                    raw,
                    residual,
                },
            )
        })
        .collect()
}

/// The pose rows show the points job `job` detected, with residuals; the
/// detected centres lie on the true projections. Returns them by pose.
fn check_points(
    poses: &[Value],
    job: &str,
    truth: &Truth,
    pitch_mm: f64,
    max_rms_px: f64,
    corrected: bool,
) -> Vec<Points> {
    let mut squares = (0.0, 0usize);
    // Squared distances to the true projections: served x, y and raw.
    let (mut served_sq, mut raw_sq, mut compared) = (0.0, 0.0, 0usize);
    let mut out = Vec::new();
    for (i, pose) in poses.iter().enumerate() {
        assert_eq!(pose["source"], "image");
        assert_eq!(pose["detection"]["job_id"], job, "{pose}");
        let pose_rms = pose["detection"]["residual_rms_px"].as_f64().unwrap();
        assert!(pose_rms < 2.0 * max_rms_px, "pose {i}: {pose_rms} px");
        let points = points_of(pose);
        assert_eq!(points.len(), DOTS, "pose {i}");
        assert_eq!(pose["detected_points"], DOTS);
        let camera = pose_from_matrix_rows(&truth.target_to_camera[i])
            .unwrap()
            .inverse();
        for (&(row, col), point) in &points {
            let (x, y, residual) = (point.x, point.y, point.residual);
            let dot = Point3::new(col as f64 * pitch_mm, row as f64 * pitch_mm, 0.0);
            let truth_px = truth.intrinsics.project(&(camera * dot)).unwrap();
            let error = ((x - truth_px.x).powi(2) + (y - truth_px.y).powi(2)).sqrt();
            // Corrected centres (all but the origin marker, which the fits
            // leave out) come with the raw ones.
            assert_eq!(
                point.raw.is_some(),
                corrected && (row, col) != (0, 0),
                "pose {i} dot ({row},{col})"
            );
            if let Some((rx, ry)) = point.raw {
                served_sq += error * error;
                raw_sq += (rx - truth_px.x).powi(2) + (ry - truth_px.y).powi(2);
                compared += 1;
            }
            assert!(
                error < MAX_DETECTION_ERROR_PX,
                "pose {i} dot ({row},{col}): detected ({x}, {y}), true ({}, {})",
                truth_px.x,
                truth_px.y
            );
            match residual {
                // The origin marker is left out of the fits.
                None => assert_eq!((row, col), (0, 0)),
                Some([dx, dy]) => {
                    squares.0 += dx * dx + dy * dy;
                    squares.1 += 1;
                }
            }
        }
        out.push(points);
    }
    let rms = (squares.0 / squares.1 as f64).sqrt();
    eprintln!("job {job}: residual rms {rms} px");
    if corrected {
        // Issue 12: the served x, y are the bias-corrected centres, closer
        // to the truth than the raw ellipse centres.
        let served = (served_sq / compared as f64).sqrt();
        let raw = (raw_sq / compared as f64).sqrt();
        eprintln!("job {job}: served centres {served} px from the truth, raw {raw} px");
        assert!(served < raw, "served {served} px, raw {raw} px");
    }
    assert!(rms < max_rms_px, "residual rms {rms} px");
    assert_eq!(squares.1, poses.len() * (DOTS - 1));
    out
}

/// A job that fails after its detect stage still leaves the points it
/// detected (without residuals) on the poses.
async fn failed_job_leaves_detected_points(
    app: &TestApp,
    client: &Client,
    dir: &std::path::Path,
    entries: &[PoseEntry],
    session_body: &Value,
) {
    let session = client
        .create_session("PUMA-PTS", session_body)
        .await
        .unwrap();
    upload_images(app, &session, dir, entries, TOO_FEW_POSES).await;
    let job = client
        .start_calibration(&session, &json!({}))
        .await
        .unwrap();
    let done = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(done["state"], "failed", "{done}");
    for pose in poses_of(app, &session).await {
        assert_eq!(pose["detection"]["job_id"], job.as_str(), "{pose}");
        assert!(pose["detection"].get("residual_rms_px").is_none());
        let points = points_of(&pose);
        assert_eq!(points.len(), DOTS);
        assert!(points.values().all(|p| p.residual.is_none()));
    }
}

/// Uploads `count` of the campaign's images to `session` (3 cal, the rest
/// val), returning each 201 body.
async fn upload_images(
    app: &TestApp,
    session: &str,
    dir: &std::path::Path,
    entries: &[PoseEntry],
    count: usize,
) -> Vec<Value> {
    let mut out = Vec::new();
    for (i, entry) in entries.iter().take(count).enumerate() {
        let bytes = std::fs::read(dir.join(&entry.image)).unwrap();
        let set = if i + 1 < count { "cal" } else { "val" };
        let form = Form::new()
            .text(
                "joints_deg",
                serde_json::to_string(&entry.joints_deg).unwrap(),
            )
            .text("set", set)
            .part(
                "image",
                Part::bytes(bytes)
                    .file_name("p.png")
                    .mime_str("image/png")
                    .unwrap(),
            );
        let r = app
            .client
            .post(app.url(&format!("/v1/sessions/{session}/poses")))
            .multipart(form)
            .send()
            .await
            .unwrap();
        assert_eq!(r.status(), 201);
        out.push(r.json().await.unwrap());
    }
    out
}

/// Issue 12: a session whose target (7x9) is not the board in the images
/// (9x9): each upload is kept but says the board was not found, and the
/// failed job names that cause for the session, not a symptom on one pose.
async fn wrong_target_is_named_at_upload_and_for_the_session(
    app: &TestApp,
    client: &Client,
    dir: &std::path::Path,
    entries: &[PoseEntry],
    session_body: &Value,
) {
    let mut body = session_body.clone();
    body["target"]["rows"] = json!(7);
    let session = client.create_session("PUMA-PTS", &body).await.unwrap();
    let created = upload_images(app, &session, dir, entries, TOO_FEW_POSES).await;
    for pose in &created {
        assert_eq!(pose["detected_points"], 0, "{pose}");
        assert!(pose["points"].as_array().unwrap().is_empty());
        assert!(pose["detection_error"].is_string(), "{pose}");
    }
    let job = client
        .start_calibration(&session, &json!({}))
        .await
        .unwrap();
    let done = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(done["state"], "failed", "{done}");
    let error = done["error"].as_str().unwrap();
    let expected = format!(
        "no image shows the session's 7x9 target: {TOO_FEW_POSES} of {TOO_FEW_POSES} images"
    );
    eprintln!("wrong target: {error}");
    assert!(error.contains(&expected), "{error}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn detected_points_residuals_and_a_reused_camera_through_the_service() {
    let dir = tempfile::tempdir().unwrap();
    campaign::simulate("puma560", dir.path(), CAL_POSES, VAL_POSES, SEED).unwrap();
    let truth: Truth =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("truth.json")).unwrap())
            .unwrap();
    let entries: Vec<PoseEntry> =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("poses.json")).unwrap())
            .unwrap();
    let pitch_mm = campaign::simulated_target().pitch_mm;
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let client = Client::new(&app.base, None).unwrap();
    let session = robocal::cli::upload(
        &client,
        "PUMA-PTS",
        dir.path(),
        robocal::cli::RobotPolicy::CreateIfMissing,
    )
    .await
    .unwrap();

    // Before any job: the dots found at upload (issue 12), raw centres.
    let before = poses_of(&app, &session).await;
    assert_eq!(before.len(), entries.len());
    for pose in &before {
        assert_eq!(pose["detected_points"], DOTS, "{pose}");
        assert!(pose.get("detection").is_none());
        assert!(pose.get("detection_error").is_none());
        assert!(points_of(pose).values().all(|p| p.raw.is_none()));
    }

    let file: CampaignFile =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("campaign.json")).unwrap())
            .unwrap();
    let session_body = serde_json::to_value(&file.session).unwrap();
    failed_job_leaves_detected_points(&app, &client, dir.path(), &entries, &session_body).await;
    wrong_target_is_named_at_upload_and_for_the_session(
        &app,
        &client,
        dir.path(),
        &entries,
        &session_body,
    )
    .await;

    // Job 1 (defaults): detected points with residuals on every pose.
    let job1 = run_job(&app, &client, &session, json!({})).await;
    let job1_id = job1["id"].as_str().unwrap();
    let poses = poses_of(&app, &session).await;
    let first = check_points(&poses, job1_id, &truth, pitch_mm, MAX_RESIDUAL_RMS_PX, true);
    // One pose read alone serves the same.
    let one = json_of(
        &app,
        &format!(
            "/v1/sessions/{session}/poses/{}",
            poses[3]["id"].as_str().unwrap()
        ),
    )
    .await;
    assert_eq!(one["points"], poses[3]["points"]);
    let set1 = json_of(&app, "/v1/robots/PUMA-PTS/parameter-sets/1").await;
    assert_eq!(set1["camera_mode"], "refined", "{set1}");
    // Each pose is named by its image's path in the archive, in the API
    // and on every pose of the report.
    for (pose, entry) in poses.iter().zip(&entries) {
        assert_eq!(pose["label"], entry.image.as_str());
    }
    let report1 = json_of(&app, "/v1/robots/PUMA-PTS/parameter-sets/1/report").await;
    let per_pose = report1["per_pose"].as_array().unwrap();
    assert_eq!(per_pose.len(), VAL_POSES);
    for p in per_pose {
        let pose = poses.iter().find(|q| q["id"] == p["pose_id"]).unwrap();
        assert_eq!(p["label"], pose["label"], "{p}");
    }

    // Job 2 on the same session, the paper's camera: the rows now show
    // job 2's points (the same centres: the detector is deterministic) and
    // job 2's residuals.
    let job2 = run_job(&app, &client, &session, json!({"refine_intrinsics": false})).await;
    let job2_id = job2["id"].as_str().unwrap();
    assert_eq!(job2["result"]["version"], 2);
    let poses = poses_of(&app, &session).await;
    // Paper mode fits the raw centres: served as x, y, no raw_x.
    let second = check_points(
        &poses,
        job2_id,
        &truth,
        pitch_mm,
        MAX_PAPER_RESIDUAL_RMS_PX,
        false,
    );
    let mut residuals_changed = false;
    for (a, b) in first.iter().zip(&second) {
        for (key, p1) in a {
            let p2 = b[key];
            assert_eq!(p1.detected(), p2.detected());
            residuals_changed |= p1.residual != p2.residual;
        }
    }
    assert!(residuals_changed, "job 2 left job 1's residuals");
    // Paper mode, flagged in the parameter set and the report.
    let set2 = json_of(&app, "/v1/robots/PUMA-PTS/parameter-sets/2").await;
    assert_eq!(set2["camera_mode"], "paper", "{set2}");
    let report2 = json_of(&app, "/v1/robots/PUMA-PTS/parameter-sets/2/report").await;
    assert_eq!(report2["camera"]["mode"], "paper");
    assert_eq!(report2["camera"]["fx"], set2["camera"]["fx"]);
    assert_ne!(set2["camera"]["fx"], set1["camera"]["fx"]);
    assert_warns_iff_worse(&report2);
    // The release gate (issue 17): set 1 was better than nominal and is
    // approved; the paper-mode set is held as a candidate (a hard
    // warning), `latest` stays 1, and its report says so first.
    assert_eq!(set1["status"], "approved", "{}", set1["status_reason"]);
    assert_eq!(set2["status"], "candidate", "{}", set2["status_reason"]);
    assert_eq!(job2["result"]["status"], "candidate");
    let latest = json_of(&app, "/v1/robots/PUMA-PTS/parameter-sets/latest").await;
    assert_eq!(latest["version"], 1);
    assert_eq!(
        report2["gate"]["compared_with"], "PUMA-PTS/1",
        "{}",
        report2["gate"]
    );
    eprintln!("paper set against set 1: {}", report2["gate"]["reason"]);
    // Quick re-checks and a base-only recalibration of the same robot,
    // from this campaign's validation poses sent again as image points.
    crate::release_gate::recheck_through_the_service(&app, "PUMA-PTS", &session_body, &poses).await;
    // Uploaded images are untouched by the jobs.
    for (pose, entry) in poses.iter().zip(&entries) {
        let id = pose["id"].as_str().unwrap();
        let r = app
            .get(&format!("/v1/sessions/{session}/poses/{id}/image"))
            .await;
        let served = r.bytes().await.unwrap();
        let file = std::fs::read(dir.path().join(&entry.image)).unwrap();
        assert_eq!(sha256_hex(&served), sha256_hex(&file));
    }

    // The camera moves to another robot: its session reuses calibration 1's
    // intrinsics, held fixed.
    let path = dir.path().join("campaign.json");
    let mut file = file;
    file.session.camera_calibration_id = Some("PUMA-PTS/1".into());
    std::fs::write(&path, serde_json::to_string(&file).unwrap()).unwrap();
    let reuse = robocal::cli::upload(
        &client,
        "PUMA-B",
        dir.path(),
        robocal::cli::RobotPolicy::CreateIfMissing,
    )
    .await
    .unwrap();
    let job3 = run_job(&app, &client, &reuse, json!({})).await;
    assert_eq!(job3["result"]["serial"], "PUMA-B");
    let set3 = json_of(&app, "/v1/robots/PUMA-B/parameter-sets/1").await;
    assert_eq!(set3["camera"], set1["camera"], "intrinsics not held fixed");
    assert_eq!(set3["camera_mode"], "fixed");
    assert_eq!(set3["camera_calibration_id"], "PUMA-PTS/1");
    let report3 = json_of(&app, "/v1/robots/PUMA-B/parameter-sets/1/report").await;
    assert_eq!(report3["camera"]["mode"], "fixed");
    assert_eq!(report3["camera"]["camera_calibration_id"], "PUMA-PTS/1");
    assert_eq!(report3["camera"]["fx"], set1["camera"]["fx"]);
    let notes = report3["notes"].to_string();
    assert!(
        notes.contains("held fixed") && notes.contains("PUMA-PTS/1"),
        "{notes}"
    );
    let improvement = report3["before"]["mean_mm"].as_f64().unwrap()
        / report3["after"]["mean_mm"].as_f64().unwrap();
    eprintln!(
        "fixed camera: before {} mm, after {} mm",
        report3["before"]["mean_mm"], report3["after"]["mean_mm"]
    );
    assert!(improvement >= MIN_IMPROVEMENT, "{}", report3["after"]);
    let job3_id = job3["id"].as_str().unwrap();
    let poses = poses_of(&app, &reuse).await;
    check_points(&poses, job3_id, &truth, pitch_mm, MAX_RESIDUAL_RMS_PX, true);
}

/// A set worse than the nominal model says so in its report, with what to do.
pub(crate) fn assert_warns_iff_worse(report: &Value) {
    let worse = report["after"]["mean_mm"].as_f64() > report["before"]["mean_mm"].as_f64();
    let warned = report["notes"].as_array().unwrap().iter().any(|n| {
        n.as_str()
            .unwrap()
            .starts_with("Warning: this set predicts")
    });
    assert_eq!(worse, warned, "{}", report["notes"]);
}
