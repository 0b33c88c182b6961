//! Space a crash or a deletion leaves behind is given back: the images and
//! spool file of an upload killed midway go when the server starts again
//! (their writer is known to be gone), and the SQLite file shrinks after a
//! robot's images are deleted (incremental vacuum).

use std::io::Cursor;
use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::{json, Value};
use sqlx::Connection;

use robocal::store;

use crate::support::*;

const WAIT: Duration = Duration::from_secs(20);

/// Spool files of robocal in `dir`.
fn spool_files(dir: &Path) -> usize {
    std::fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .starts_with("robocal-upload-")
        })
        .count()
}

async fn wait_until(what: &str, mut check: impl AsyncFnMut() -> bool) {
    let start = Instant::now();
    while !check().await {
        assert!(start.elapsed() < WAIT, "{what}");
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

#[tokio::test]
async fn the_images_and_spool_file_of_an_upload_killed_midway_go_at_restart() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let spool = dir.path().join("spool");
    std::fs::create_dir(&spool).unwrap();
    let args = [
        "--database-url",
        &db,
        "--bind",
        "127.0.0.1:0",
        "--upload-dir",
        spool.to_str().unwrap(),
    ];
    let c = reqwest::Client::new();
    let mut first = spawn_binary(&args, &[("ROBOCAL_TEST_UPLOAD_DELAY_MS", "500")]);
    let (session, pose, acknowledged) =
        robot_with_session(&c, &first.base, "KILL-UP", 7, "cal").await;

    let images: Vec<Vec<u8>> = (0..6).map(|i| png(CAMERA_W, CAMERA_H, 60 + i)).collect();
    let names: Vec<String> = (0..images.len()).map(|i| format!("v{i}.png")).collect();
    let manifest: Vec<Value> = names
        .iter()
        .map(|n| json!({"joints_deg": [1, 2, 3, 4, 5, 6], "image": n}))
        .collect();
    let manifest = serde_json::to_vec(&manifest).unwrap();
    let mut entries: Vec<(&str, &[u8])> = vec![("poses.json", &manifest)];
    entries.extend(
        names
            .iter()
            .map(String::as_str)
            .zip(images.iter().map(Vec::as_slice)),
    );
    let zip = zip_bytes(&entries);
    let upload = {
        let url = format!("{}/v1/sessions/{session}/dataset", first.base);
        let c = c.clone();
        tokio::spawn(async move {
            c.post(url)
                .header("content-type", "application/zip")
                .body(zip)
                .send()
                .await
        })
    };
    let store = store::connect(&db).await.unwrap();
    let first_image = sha256_hex(&images[0]);
    wait_until("the upload stored its first image", async || {
        store.get_blob(&first_image).await.unwrap().is_some()
    })
    .await;
    assert_eq!(
        spool_files(&spool),
        1,
        "the archive is spooled while it is read"
    );
    first.child.kill().unwrap(); // SIGKILL mid-upload: no clean-up at all
    first.child.wait().unwrap();
    assert!(upload.await.unwrap().is_err(), "the upload was cut off");
    assert!(store.get_blob(&first_image).await.unwrap().is_some());

    let mut second = spawn_binary(&args, &[]);
    wait_until("the killed upload's images are collected", async || {
        for image in &images {
            if store.get_blob(&sha256_hex(image)).await.unwrap().is_some() {
                return false;
            }
        }
        true
    })
    .await;
    assert_eq!(spool_files(&spool), 0, "the spool file is gone");
    // What was acknowledged before the kill is all there.
    let stored = c
        .get(format!(
            "{}/v1/sessions/{session}/poses/{pose}/image",
            second.base
        ))
        .send()
        .await
        .unwrap();
    assert_eq!(stored.status(), 200);
    assert_eq!(
        sha256_hex(&stored.bytes().await.unwrap()),
        sha256_hex(&acknowledged)
    );
    let listed: Value = c
        .get(format!("{}/v1/sessions/{session}", second.base))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    assert_eq!(listed["pose_count"], 5, "{listed}");
    second.child.kill().unwrap();
    second.child.wait().unwrap();
}

/// Incompressible grey PNG of `w` x `h` (about `w`·`h` bytes).
fn noise_png(w: u32, h: u32, seed: u64) -> Vec<u8> {
    let mut state = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
    let img = image::GrayImage::from_fn(w, h, |_, _| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        image::Luma([(state >> 56) as u8])
    });
    let mut out = Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

/// The main database file's size after the WAL is written back into it.
async fn sqlite_file_bytes(database_url: &str) -> u64 {
    let mut c = sqlx::SqliteConnection::connect(database_url).await.unwrap();
    sqlx::query("PRAGMA wal_checkpoint(TRUNCATE)")
        .execute(&mut c)
        .await
        .unwrap();
    drop(c);
    let path = database_url.strip_prefix("sqlite://").unwrap();
    std::fs::metadata(path).unwrap().len()
}

#[tokio::test]
async fn the_sqlite_file_shrinks_when_a_robot_s_images_are_deleted() {
    if backend() != Backend::Sqlite {
        eprintln!("the_sqlite_file_shrinks…: not run, the backend is PostgreSQL");
        return;
    }
    let (w, h) = (640u32, 480u32);
    let app = spawn_app().await;
    assert_eq!(
        app.put_json("/v1/robots/BIG", &robot_body()).await.status(),
        201
    );
    let mut body = session_body();
    body["camera"]["width"] = json!(w);
    body["camera"]["height"] = json!(h);
    let session = app.new_session("BIG", &body).await;
    let images: Vec<Vec<u8>> = (0..8).map(|i| noise_png(w, h, i)).collect();
    let image_bytes: usize = images.iter().map(Vec::len).sum();
    let names: Vec<String> = (0..images.len()).map(|i| format!("n{i}.png")).collect();
    let manifest: Vec<Value> = names
        .iter()
        .map(|n| json!({"joints_deg": [1, 2, 3, 4, 5, 6], "image": n}))
        .collect();
    let manifest = serde_json::to_vec(&manifest).unwrap();
    let mut entries: Vec<(&str, &[u8])> = vec![("poses.json", &manifest)];
    entries.extend(
        names
            .iter()
            .map(String::as_str)
            .zip(images.iter().map(Vec::as_slice)),
    );
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/dataset")))
        .header("content-type", "application/zip")
        .body(zip_bytes(&entries))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    let full = sqlite_file_bytes(&app.database_url).await;
    assert!(
        full as usize > image_bytes,
        "{full} bytes hold {image_bytes} of images"
    );

    let r = app
        .client
        .delete(app.url("/v1/robots/BIG"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 204);
    let after = sqlite_file_bytes(&app.database_url).await;
    assert!(
        after + (image_bytes as u64) * 9 / 10 < full,
        "the file kept {after} of {full} bytes after {image_bytes} bytes of images went"
    );
}
