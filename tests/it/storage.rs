//! What the service keeps and what it lets go (issue 12): serials every
//! client can address, a deleted robot's past gone with it, images no pose
//! names collected, spool files of killed uploads removed, and the labels
//! that tie a pose to its photo.

use std::time::{Duration, Instant, SystemTime};

use reqwest::multipart::Form;
use serde_json::{json, Value};
use sqlx::Connection;
use tokio::io::{AsyncReadExt, AsyncWriteExt};

use robocal::store;
use robocal::store::NewParameterSet;

use crate::support::*;

/// How long a background sweep may take to show.
const SWEEP_WAIT: Duration = Duration::from_secs(10);

/// One value of a query run directly on the test database.
async fn scalar(database_url: &str, sql: &str) -> i64 {
    match backend() {
        Backend::Sqlite => {
            let mut c = sqlx::SqliteConnection::connect(database_url).await.unwrap();
            sqlx::query_scalar(sql).fetch_one(&mut c).await.unwrap()
        }
        Backend::Postgres => {
            let mut c = sqlx::PgConnection::connect(database_url).await.unwrap();
            sqlx::query_scalar(sql).fetch_one(&mut c).await.unwrap()
        }
    }
}

async fn execute(database_url: &str, sql: &str) {
    match backend() {
        Backend::Sqlite => {
            let mut c = sqlx::SqliteConnection::connect(database_url).await.unwrap();
            sqlx::query(sql).execute(&mut c).await.unwrap();
        }
        Backend::Postgres => {
            let mut c = sqlx::PgConnection::connect(database_url).await.unwrap();
            sqlx::query(sql).execute(&mut c).await.unwrap();
        }
    }
}

async fn blob_count(app: &TestApp) -> i64 {
    scalar(&app.database_url, "SELECT count(*) FROM blobs").await
}

/// Sends one request as raw bytes (no client normalises its path) and
/// returns the status and body.
async fn raw_request(base: &str, method: &str, path: &str, body: &str) -> (u16, Value) {
    let addr = base.trim_start_matches("http://");
    let mut stream = tokio::net::TcpStream::connect(addr).await.unwrap();
    let request = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    );
    stream.write_all(request.as_bytes()).await.unwrap();
    let mut response = Vec::new();
    stream.read_to_end(&mut response).await.unwrap();
    let text = String::from_utf8_lossy(&response);
    let status = text[9..12].parse().unwrap();
    let (head, body) = text.split_once("\r\n\r\n").unwrap();
    assert!(
        head.to_ascii_lowercase()
            .contains("content-type: application/problem+json"),
        "{head}"
    );
    (status, serde_json::from_str(body).unwrap_or(Value::Null))
}

async fn upload_pose(app: &TestApp, session: &str, bytes: Vec<u8>, file_name: &str) -> Value {
    let form = Form::new()
        .text("joints_deg", "[1, 2, 3, 4, 5, 6]")
        .part("image", image_part(bytes, file_name));
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/poses")))
        .multipart(form)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    r.json().await.unwrap()
}

async fn upload_zip(app: &TestApp, session: &str, zip: Vec<u8>) -> reqwest::Response {
    app.client
        .post(app.url(&format!("/v1/sessions/{session}/dataset")))
        .header("content-type", "application/zip")
        .body(zip)
        .send()
        .await
        .unwrap()
}

async fn eventually(what: &str, mut check: impl AsyncFnMut() -> bool) {
    let start = Instant::now();
    while !check().await {
        assert!(start.elapsed() < SWEEP_WAIT, "{what}");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

#[tokio::test]
async fn dot_segment_serials_are_refused_when_sent_raw() {
    let app = spawn_app().await;
    let body = robot_body().to_string();
    for serial in [".", "..", "%2e%2e", "%2E"] {
        let path = format!("/v1/robots/{serial}");
        let (status, problem) = raw_request(&app.base, "PUT", &path, &body).await;
        assert_eq!(status, 422, "PUT {path}: {problem}");
        assert_eq!(problem["errors"][0]["field"], "serial", "{problem}");
        for (method, path) in [
            ("GET", path.clone()),
            ("DELETE", path.clone()),
            ("GET", format!("{path}/sessions")),
            ("GET", format!("{path}/parameter-sets/latest")),
        ] {
            let (status, problem) = raw_request(&app.base, method, &path, "").await;
            assert_eq!(status, 422, "{method} {path}: {problem}");
            assert_eq!(problem["errors"][0]["field"], "serial");
        }
    }
    let list: Value = app.get("/v1/robots").await.json().await.unwrap();
    assert_eq!(list["items"], json!([]), "nothing was stored");
    // Dots inside a serial stay valid.
    assert_eq!(
        app.put_json("/v1/robots/a..b", &robot_body())
            .await
            .status(),
        201
    );
}

#[tokio::test]
async fn a_deleted_robots_past_does_not_come_back() {
    let app = spawn_app().await;
    let session = app.robot_and_session("GONE-1").await;
    // Enough calibration poses for a job to be queued.
    for (seed, name) in [(1, "a.png"), (2, "b.png"), (3, "c.png")] {
        upload_pose(&app, &session, png(CAMERA_W, CAMERA_H, seed), name).await;
    }
    let job: Value = app
        .post_json(&format!("/v1/sessions/{session}/calibrations"), &json!({}))
        .await
        .json()
        .await
        .unwrap();
    let job = job["job_id"].as_str().unwrap().to_string();
    let store = store::connect(&app.database_url).await.unwrap();
    let set = NewParameterSet::approved(placeholder_set("s"), json!({}));
    assert_eq!(
        store
            .insert_parameter_set("GONE-1", Some(&job), &set)
            .await
            .unwrap(),
        1
    );
    assert_eq!(
        store
            .insert_parameter_set("GONE-1", None, &set)
            .await
            .unwrap(),
        2
    );
    let latest = "/v1/robots/GONE-1/parameter-sets/latest";
    assert_eq!(app.get(latest).await.status(), 200);

    let r = app
        .client
        .delete(app.url("/v1/robots/GONE-1"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 204);
    assert_eq!(
        app.put_json("/v1/robots/GONE-1", &robot_body())
            .await
            .status(),
        201
    );

    assert_eq!(app.get(latest).await.status(), 404);
    assert_eq!(
        app.get("/v1/robots/GONE-1/parameter-sets/1").await.status(),
        404
    );
    let sets: Value = app
        .get("/v1/robots/GONE-1/parameter-sets")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(sets["items"], json!([]));
    let forward = app
        .post_json(
            "/v1/robots/GONE-1/parameter-sets/latest/forward",
            &json!({"joints_deg": [[0, 0, 0, 0, 0, 0]]}),
        )
        .await;
    assert_eq!(forward.status(), 404);
    let sessions: Value = app
        .get("/v1/robots/GONE-1/sessions")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(sessions["items"], json!([]));
    assert_eq!(
        app.get(&format!("/v1/sessions/{session}")).await.status(),
        404
    );
    assert_eq!(app.get(&format!("/v1/jobs/{job}")).await.status(), 404);
    // The new robot's sets count from 1 again.
    assert_eq!(
        store
            .insert_parameter_set("GONE-1", None, &set)
            .await
            .unwrap(),
        1
    );
}

#[tokio::test]
async fn deleting_a_robot_deletes_the_images_only_it_named() {
    let app = spawn_app().await;
    let own = app.robot_and_session("IMG-1").await;
    let other = app.robot_and_session("IMG-2").await;
    let shared = png(CAMERA_W, CAMERA_H, 10);
    upload_pose(&app, &own, png(CAMERA_W, CAMERA_H, 11), "only.png").await;
    upload_pose(&app, &own, shared.clone(), "shared.png").await;
    let kept = upload_pose(&app, &other, shared.clone(), "shared.png").await;
    assert_eq!(blob_count(&app).await, 2);

    let r = app
        .client
        .delete(app.url("/v1/robots/IMG-1"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 204);
    assert_eq!(
        blob_count(&app).await,
        1,
        "the image only IMG-1 named is gone"
    );
    let id = kept["id"].as_str().unwrap();
    let image = app
        .get(&format!("/v1/sessions/{other}/poses/{id}/image"))
        .await;
    assert_eq!(image.status(), 200);
    assert_eq!(
        sha256_hex(&image.bytes().await.unwrap()),
        sha256_hex(&shared)
    );
}

#[tokio::test]
async fn a_refused_archive_leaves_no_images() {
    let app = spawn_app().await;
    let session = app.robot_and_session("ZIP-1").await;
    let named = png(CAMERA_W, CAMERA_H, 20);
    upload_pose(&app, &session, named.clone(), "named.png").await;
    let (a, b) = (png(CAMERA_W, CAMERA_H, 21), png(CAMERA_W, CAMERA_H, 22));
    let wrong_size = png(CAMERA_W + 1, CAMERA_H, 23);
    let manifest = json!([
        {"joints_deg": [1, 2, 3, 4, 5, 6], "image": "a.png"},
        {"joints_deg": [1, 2, 3, 4, 5, 6], "image": "named.png"},
        {"joints_deg": [1, 2, 3, 4, 5, 6], "image": "b.png"},
        {"joints_deg": [1, 2, 3, 4, 5, 6], "image": "wrong.png"},
    ])
    .to_string();
    let zip = zip_bytes(&[
        ("poses.json", manifest.as_bytes()),
        ("a.png", &a),
        ("named.png", &named),
        ("b.png", &b),
        ("wrong.png", &wrong_size),
    ]);
    let r = upload_zip(&app, &session, zip).await;
    assert_eq!(r.status(), 422);
    assert_eq!(
        blob_count(&app).await,
        1,
        "only the image a pose names is left"
    );
    let poses: Value = app
        .get(&format!("/v1/sessions/{session}/poses"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(poses["items"].as_array().unwrap().len(), 1);
}

#[tokio::test]
async fn unreferenced_images_are_collected_after_their_grace() {
    let app = spawn_app().await;
    let store = store::connect(&app.database_url).await.unwrap();
    let session = app.robot_and_session("GC-1").await;
    upload_pose(&app, &session, png(CAMERA_W, CAMERA_H, 30), "kept.png").await;
    // An image an upload stored but never attached (killed midway).
    let orphan = png(CAMERA_W, CAMERA_H, 31);
    let meta = robocal::domain::ImageMeta {
        sha256: sha256_hex(&orphan),
        size_bytes: orphan.len() as i64,
        content_type: "image/png".into(),
        width: CAMERA_W,
        height: CAMERA_H,
    };
    store.put_blob(&meta, &orphan).await.unwrap();
    // Within the grace an upload in progress may still attach it.
    let an_hour_ago = robocal::domain::now_unix_ms() - 3_600_000;
    assert_eq!(store.collect_blobs(an_hour_ago).await.unwrap(), 0);
    assert_eq!(blob_count(&app).await, 2);
    // Past it, only the unreferenced one goes.
    execute(&app.database_url, "UPDATE blobs SET touched_ms = 0").await;
    assert_eq!(store.collect_blobs(an_hour_ago).await.unwrap(), 1);
    assert_eq!(blob_count(&app).await, 1);
}

#[tokio::test]
async fn start_collects_old_unreferenced_images_and_stale_spool_files() {
    let app = spawn_app().await;
    let store = store::connect(&app.database_url).await.unwrap();
    let orphan = png(CAMERA_W, CAMERA_H, 40);
    let meta = robocal::domain::ImageMeta {
        sha256: sha256_hex(&orphan),
        size_bytes: orphan.len() as i64,
        content_type: "image/png".into(),
        width: CAMERA_W,
        height: CAMERA_H,
    };
    store.put_blob(&meta, &orphan).await.unwrap();
    execute(&app.database_url, "UPDATE blobs SET touched_ms = 0").await;
    let (dir, db) = app.shutdown().await;

    let spool = tempfile::tempdir().unwrap();
    let old = SystemTime::now() - 2 * robocal::housekeeping::SPOOL_STALE;
    for (name, modified) in [
        ("robocal-upload-killed", old),
        ("robocal-upload-running", SystemTime::now()),
        ("not-ours.zip", old),
    ] {
        let path = spool.path().join(name);
        std::fs::write(&path, b"PK").unwrap();
        let file = std::fs::File::options().write(true).open(&path).unwrap();
        file.set_modified(modified).unwrap();
    }
    let mut config = test_config(&db, &dir);
    config.upload_dir = Some(spool.path().to_path_buf());
    let server = robocal::server::start(config).await.unwrap();
    let url = db.to_string();
    eventually("the orphan image is collected at start", async || {
        scalar(&url, "SELECT count(*) FROM blobs").await == 0
    })
    .await;
    eventually("the stale spool file is removed at start", async || {
        !spool.path().join("robocal-upload-killed").exists()
    })
    .await;
    assert!(spool.path().join("robocal-upload-running").exists());
    assert!(spool.path().join("not-ours.zip").exists());
    server.shutdown().await;
}

#[tokio::test]
async fn poses_carry_their_labels() {
    let app = spawn_app().await;
    let session = app.robot_and_session("LBL-1").await;
    let pose = upload_pose(
        &app,
        &session,
        png(CAMERA_W, CAMERA_H, 50),
        "day1/shot_007.png",
    )
    .await;
    assert_eq!(pose["label"], "shot_007.png");
    let id = pose["id"].as_str().unwrap();
    let got: Value = app
        .get(&format!("/v1/sessions/{session}/poses/{id}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(got["label"], "shot_007.png");

    let mut body = point_pose(0, "cal");
    body["label"] = json!("station 4, left");
    let r = app
        .post_json(&format!("/v1/sessions/{session}/poses"), &body)
        .await;
    assert_eq!(r.status(), 201);
    assert_eq!(r.json::<Value>().await.unwrap()["label"], "station 4, left");
    let unlabelled = app
        .post_json(
            &format!("/v1/sessions/{session}/poses"),
            &point_pose(1, "cal"),
        )
        .await;
    assert!(unlabelled
        .json::<Value>()
        .await
        .unwrap()
        .get("label")
        .is_none());
    for bad in [json!(""), json!("a\nb"), json!("x".repeat(201))] {
        body["label"] = bad;
        let r = app
            .post_json(&format!("/v1/sessions/{session}/poses"), &body)
            .await;
        assert_eq!(r.status(), 422);
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], "label", "{problem}");
    }

    let manifest = json!([
        {"joints_deg": [1, 2, 3, 4, 5, 6], "image": "img/0001.png"},
        {"joints_deg": [1, 2, 3, 4, 5, 6], "image": "img/0002.png", "set": "val"},
    ])
    .to_string();
    let zip = zip_bytes(&[
        ("poses.json", manifest.as_bytes()),
        ("img/0001.png", &png(CAMERA_W, CAMERA_H, 51)),
        ("img/0002.png", &png(CAMERA_W, CAMERA_H, 52)),
    ]);
    let r = upload_zip(&app, &session, zip).await;
    assert_eq!(r.status(), 201);
    let out: Value = r.json().await.unwrap();
    for (id, label) in out["pose_ids"]
        .as_array()
        .unwrap()
        .iter()
        .zip(["img/0001.png", "img/0002.png"])
    {
        let got: Value = app
            .get(&format!(
                "/v1/sessions/{session}/poses/{}",
                id.as_str().unwrap()
            ))
            .await
            .json()
            .await
            .unwrap();
        assert_eq!(got["label"], label);
    }
}

/// A set stored before sets carried `kind` (only kinematic sets were
/// stored without it) reads as a kinematic set, and is served with its
/// `kind`; an old hand–eye row keeps its variant.
#[tokio::test]
async fn a_set_stored_without_kind_reads_as_kinematic() {
    let app = spawn_app().await;
    app.robot_and_session("OLD-1").await;
    let store = store::connect(&app.database_url).await.unwrap();
    for _ in 0..2 {
        let set = NewParameterSet::approved(placeholder_set("new"), json!({}));
        store
            .insert_parameter_set("OLD-1", None, &set)
            .await
            .unwrap();
    }
    let identity = json!({"translation_mm": [0.0, 0.0, 0.0], "rotation_deg": [0.0, 0.0, 0.0],
        "matrix": [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]});
    let intrinsics = json!({"fx": 900.0, "fy": 900.0, "cx": 32.0, "cy": 24.0,
        "k1": 0.0, "k2": 0.0, "p1": 0.0, "p2": 0.0, "k3": 0.0});
    let old_kinematic = json!({"instrument": "camera", "session_id": "old",
        "kinematics": {"joints": []}, "target_to_base": identity,
        "flange_to_camera": identity, "fixed": [], "parameters": []});
    let old_hand_eye = json!({"kind": "hand_eye", "instrument": "camera", "session_id": "old-he",
        "target_to_base": identity, "flange_to_camera": identity, "base_to_target": identity,
        "board_scale": 1.0, "camera": intrinsics, "camera_mode": "refined",
        "fixed": [], "parameters": []});
    for (version, doc) in [(1, &old_kinematic), (2, &old_hand_eye)] {
        let sql = format!(
            "UPDATE parameter_sets SET parameters = '{doc}' WHERE serial = 'OLD-1' AND version = {version}"
        );
        execute(&app.database_url, &sql).await;
    }
    let served = |v: i64| {
        let app = &app;
        async move {
            let r = app
                .get(&format!("/v1/robots/OLD-1/parameter-sets/{v}"))
                .await;
            assert_eq!(r.status(), 200);
            r.json::<Value>().await.unwrap()
        }
    };
    let v1 = served(1).await;
    assert_eq!(v1["kind"], "kinematic", "{v1}");
    assert_eq!(v1["session_id"], "old");
    assert_eq!(v1["target_to_base"], identity);
    let v2 = served(2).await;
    assert_eq!(v2["kind"], "hand_eye", "{v2}");
    assert_eq!(v2["board_scale"], 1.0);
    // The typed read: the old row is the kinematic variant.
    let stored = store
        .get_parameter_set("OLD-1", Some(1))
        .await
        .unwrap()
        .unwrap();
    assert!(stored.parameters.kinematic().is_some());
    // A hand–eye set has no model to evaluate: 409, as before.
    let r = app
        .post_json(
            "/v1/robots/OLD-1/parameter-sets/2/forward",
            &json!({"joints_deg": [[0.0, 0.0, 0.0, 0.0, 0.0, 0.0]]}),
        )
        .await;
    assert_eq!(r.status(), 409);
}
