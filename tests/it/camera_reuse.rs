//! `camera_calibration_id` at session creation (404/422 naming the field,
//! `latest` resolved), and the store's pose-detection writes (lease-checked,
//! whole-session replacement). The numerics with a reused camera run in
//! `e2e_points`.

use serde_json::{json, Value};

use robocal::domain::{now_unix_ms, ImageDetection, LeaseStatus, MeasuredPoint, MeasuredPose};
use robocal::schema::job::JobOptions;
use robocal::store;
use robocal::store::{NewJob, NewParameterSet, PoseDetection};

use crate::support::*;

const FIELD: &str = "camera_calibration_id";

async fn problem_field(r: reqwest::Response, status: u16) -> Value {
    assert_eq!(r.status(), status);
    assert_eq!(
        r.headers()["content-type"].to_str().unwrap(),
        "application/problem+json"
    );
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], FIELD, "{p}");
    p
}

fn session_reusing(id: &str) -> Value {
    let mut body = session_body();
    body[FIELD] = json!(id);
    body
}

/// A camera parameter set as the pipeline stores one (intrinsics in the
/// parameter set, the image size in the report's camera section).
fn camera_set(fx: f64, width: u32, height: u32) -> NewParameterSet {
    let intrinsics = json!({"fx": fx, "fy": fx, "cx": 32.0, "cy": 24.0,
        "k1": -0.1, "k2": 0.05, "p1": 0.0, "p2": 0.0, "k3": 0.0});
    NewParameterSet::approved(
        camera_only_set(intrinsics),
        json!({"camera": {"mode": "refined", "image_width": width, "image_height": height}}),
    )
}

#[tokio::test]
async fn camera_calibration_id_must_name_a_camera_calibration_of_the_same_image_size() {
    let app = spawn_app().await;
    app.robot_and_session("CAM-1").await;
    let sessions = "/v1/robots/CAM-1/sessions";

    // Unknown serial or version: 404 naming the field.
    for id in ["NOPE/1", "CAM-1/1", "CAM-1/latest"] {
        let r = app.post_json(sessions, &session_reusing(id)).await;
        problem_field(r, 404).await;
    }
    // Not "{serial}/{version}": 422.
    for id in ["CAM-1", "CAM-1/0", "CAM-1/v2", "a b/1"] {
        let r = app.post_json(sessions, &session_reusing(id)).await;
        problem_field(r, 422).await;
    }

    let store = store::connect(&app.database_url).await.unwrap();
    // Version 1: no camera (a tracker calibration); 2: a 64x48 camera;
    // 3: a camera of another image size.
    let tracker = NewParameterSet::approved(tracker_set(), json!({}));
    store
        .insert_parameter_set("CAM-1", None, &tracker)
        .await
        .unwrap();
    store
        .insert_parameter_set("CAM-1", None, &camera_set(100.0, CAMERA_W, CAMERA_H))
        .await
        .unwrap();
    store
        .insert_parameter_set("CAM-1", None, &camera_set(900.0, 1280, 1024))
        .await
        .unwrap();

    let p = problem_field(
        app.post_json(sessions, &session_reusing("CAM-1/1")).await,
        422,
    )
    .await;
    assert!(
        p["errors"][0]["message"]
            .as_str()
            .unwrap()
            .contains("no camera intrinsics"),
        "{p}"
    );
    let p = problem_field(
        app.post_json(sessions, &session_reusing("CAM-1/3")).await,
        422,
    )
    .await;
    assert!(
        p["errors"][0]["message"]
            .as_str()
            .unwrap()
            .contains("1280x1024"),
        "{p}"
    );
    // "latest" is version 3 now: refused for its size, never silently version 2.
    problem_field(
        app.post_json(sessions, &session_reusing("CAM-1/latest"))
            .await,
        422,
    )
    .await;

    // A tracker session has no camera to reuse intrinsics for.
    let tracker_session = json!({"instrument": "tracker", FIELD: "CAM-1/2"});
    problem_field(app.post_json(sessions, &tracker_session).await, 422).await;

    // Accepted, and shown as given.
    let r = app.post_json(sessions, &session_reusing("CAM-1/2")).await;
    assert_eq!(r.status(), 201);
    let created: Value = r.json().await.unwrap();
    assert_eq!(created[FIELD], "CAM-1/2");
    let id = created["id"].as_str().unwrap();
    let r = app.get(&format!("/v1/sessions/{id}")).await;
    assert_eq!(r.json::<Value>().await.unwrap()[FIELD], "CAM-1/2");

    // "latest" is resolved when the session is created: later calibrations
    // of that robot do not change which intrinsics the session reuses.
    store
        .insert_parameter_set("CAM-1", None, &camera_set(120.0, CAMERA_W, CAMERA_H))
        .await
        .unwrap();
    let r = app
        .post_json(sessions, &session_reusing("CAM-1/latest"))
        .await;
    assert_eq!(r.status(), 201);
    assert_eq!(r.json::<Value>().await.unwrap()[FIELD], "CAM-1/4");
}

fn detection(pose_id: &str, job: &str, x: f64) -> PoseDetection {
    PoseDetection {
        pose_id: pose_id.to_string(),
        detection: MeasuredPose {
            source: "image_points",
            points: vec![MeasuredPoint {
                row: 0,
                col: 0,
                x,
                y: 2.0,
                raw_x: None,
                raw_y: None,
                residual_px: None,
                outlier: false,
            }],
            error: None,
            residual_rms_px: None,
            job_id: Some(job.to_string()),
        },
        image_detection: None,
    }
}

#[tokio::test]
async fn detections_are_written_whole_and_only_by_the_lease_holder() {
    let app = spawn_app().await;
    let session = app.robot_and_session("DET-1").await;
    app.add_point_poses(&session, 3, 0).await;
    let poses: Value = app
        .get(&format!("/v1/sessions/{session}/poses"))
        .await
        .json()
        .await
        .unwrap();
    let ids: Vec<String> = poses["items"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["id"].as_str().unwrap().to_string())
        .collect();
    let uploaded = poses["items"][0]["points"].clone();
    assert!(poses["items"][0].get("detection").is_none(), "{poses}");

    // Stop the app's own workers from claiming the job we insert.
    let (_dir, db) = app.shutdown().await;
    let s = store::connect(&db.to_string()).await.unwrap();
    let job = s
        .enqueue_job(
            &NewJob {
                session_id: session.clone(),
                serial: "DET-1".into(),
                options: JobOptions::Calibration(Default::default()),
                max_attempts: 2,
            },
            10,
        )
        .await
        .unwrap();
    let now = now_unix_ms();
    s.claim_job("W", now, now + 60_000).await.unwrap().unwrap();

    // Another worker (lease lost) writes nothing.
    let all: Vec<PoseDetection> = ids.iter().map(|id| detection(id, "X", 9.0)).collect();
    assert_eq!(
        s.record_detections(&job.id, "other", &all).await.unwrap(),
        LeaseStatus::Lost
    );
    let p = s.get_pose(&session, &ids[0]).await.unwrap().unwrap();
    assert!(p.detection.is_none());

    // The holder writes every pose; a second write replaces the first
    // whole: a pose it does not list shows no stale points.
    // A pose the job detected first keeps the detector's outcome as its
    // image_detection (issue 12), never overwritten by a later job.
    let first_seen = ImageDetection::failed("first".into(), "no_board", true);
    let mut all: Vec<PoseDetection> = ids.iter().map(|id| detection(id, &job.id, 1.0)).collect();
    all[0].image_detection = Some(first_seen.clone());
    assert_eq!(
        s.record_detections(&job.id, "W", &all).await.unwrap(),
        LeaseStatus::Held
    );
    let p = s.get_pose(&session, &ids[2]).await.unwrap().unwrap();
    assert_eq!(p.detection.unwrap()["points"][0]["x"], 1.0);
    assert_eq!(p.image_detection, None);
    let mut two = [
        detection(&ids[0], &job.id, 5.0),
        detection(&ids[1], &job.id, 6.0),
    ];
    two[0].image_detection = Some(ImageDetection::failed("second".into(), "no_board", true));
    assert_eq!(
        s.record_detections(&job.id, "W", &two).await.unwrap(),
        LeaseStatus::Held
    );
    let page = s.list_poses(&session, 10, None).await.unwrap();
    let xs: Vec<Option<f64>> = page
        .items
        .iter()
        .map(|p| {
            p.detection
                .as_ref()
                .map(|d| d["points"][0]["x"].as_f64().unwrap())
        })
        .collect();
    assert_eq!(xs, vec![Some(5.0), Some(6.0), None]);
    assert_eq!(page.items[0].image_detection, Some(first_seen));
    // The uploaded points stay as uploaded.
    assert_eq!(
        serde_json::to_value(&page.items[0].points).unwrap(),
        uploaded
    );

    // A cancelled job writes nothing more.
    s.cancel_job(&job.id).await.unwrap();
    assert_eq!(
        s.record_detections(&job.id, "W", &all).await.unwrap(),
        LeaseStatus::Cancelled
    );
    let p = s.get_pose(&session, &ids[2]).await.unwrap().unwrap();
    assert!(p.detection.is_none());
}
