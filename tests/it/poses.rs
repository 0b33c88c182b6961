use reqwest::multipart::Form;
use serde_json::{json, Value};

use crate::support::*;

#[tokio::test]
async fn multipart_pose_stores_image_byte_identical() {
    let app = spawn_app().await;
    let session = app.robot_and_session("M1").await;
    let bytes = png(CAMERA_W, CAMERA_H, 7);
    let form = Form::new()
        .text("joints_deg", "[1, 2, 3, 4, 5, 6]")
        .text("set", "val")
        .part("image", image_part(bytes.clone(), "p.png"));
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/poses")))
        .multipart(form)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let pose: Value = r.json().await.unwrap();
    assert_eq!(pose["set"], "val");
    assert_eq!(pose["source"], "image");
    assert_eq!(pose["image"]["sha256"], sha256_hex(&bytes));
    assert_eq!(pose["image"]["width"], CAMERA_W);
    let id = pose["id"].as_str().unwrap();
    let back = app
        .get(&format!("/v1/sessions/{session}/poses/{id}/image"))
        .await;
    assert_eq!(back.headers()["content-type"], "image/png");
    assert_eq!(sha256_hex(&back.bytes().await.unwrap()), sha256_hex(&bytes));
    let got: Value = app
        .get(&format!("/v1/sessions/{session}/poses/{id}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(got["joints_deg"], json!([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]));
}

#[tokio::test]
async fn json_poses_points_and_tracker_measurements() {
    let app = spawn_app().await;
    let session = app.robot_and_session("J1").await;
    app.add_point_poses(&session, 3, 2).await;
    let list: Value = app
        .get(&format!("/v1/sessions/{session}/poses?limit=4"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(list["items"].as_array().unwrap().len(), 4);
    assert_eq!(list["items"][0]["detected_points"], 3);
    assert_eq!(list["items"][0]["points"][0]["x"], 10.5);
    let cursor = list["next_cursor"].as_str().unwrap();
    let rest: Value = app
        .get(&format!(
            "/v1/sessions/{session}/poses?limit=4&cursor={cursor}"
        ))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(rest["items"][0]["set"], "val");

    let tracker: Value = app
        .post_json("/v1/robots/J1/sessions", &json!({"instrument": "tracker"}))
        .await
        .json()
        .await
        .unwrap();
    let tid = tracker["id"].as_str().unwrap();
    let r = app
        .post_json(
            &format!("/v1/sessions/{tid}/poses"),
            &json!({"joints_deg": [0, 0, 0, 0, 0, 0], "measured_position_mm": [1000.5, -20.0, 800.0]}),
        )
        .await;
    assert_eq!(r.status(), 201);
    let pose: Value = r.json().await.unwrap();
    assert_eq!(pose["source"], "measured");
    assert_eq!(pose["measured_position_mm"], json!([1000.5, -20.0, 800.0]));
}

#[tokio::test]
async fn dataset_zip_creates_all_poses() {
    let app = spawn_app().await;
    let session = app.robot_and_session("D1").await;
    let images: Vec<Vec<u8>> = (0..4).map(|i| png(CAMERA_W, CAMERA_H, i)).collect();
    let manifest = json!([
        {"joints_deg": [0, 1, 2, 3, 4, 5], "image": "img/0.png"},
        {"joints_deg": [1, 1, 2, 3, 4, 5], "image": "img/1.png", "set": "cal"},
        {"joints_deg": [2, 1, 2, 3, 4, 5], "image": "img/2.png"},
        {"joints_deg": [3, 1, 2, 3, 4, 5], "image": "img/3.png", "set": "val"}
    ])
    .to_string();
    let mut entries: Vec<(&str, &[u8])> = vec![("poses.json", manifest.as_bytes())];
    let names = ["img/0.png", "img/1.png", "img/2.png", "img/3.png"];
    for (n, b) in names.iter().zip(&images) {
        entries.push((n, b));
    }
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/dataset")))
        .header("content-type", "application/zip")
        .body(zip_bytes(&entries))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let out: Value = r.json().await.unwrap();
    assert_eq!(out["poses_created"], 4);
    let last = out["pose_ids"][3].as_str().unwrap();
    let back = app
        .get(&format!("/v1/sessions/{session}/poses/{last}/image"))
        .await;
    assert_eq!(
        sha256_hex(&back.bytes().await.unwrap()),
        sha256_hex(&images[3])
    );
    let s: Value = app
        .get(&format!("/v1/sessions/{session}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(s["pose_count"], 4);
}

/// A pose's `group` (JSON, multipart part, dataset manifest) is stored and
/// served back; a bad one is refused with a 422 naming it.
#[tokio::test]
async fn pose_group_is_stored_and_a_bad_one_is_named() {
    let app = spawn_app().await;
    let session = app.robot_and_session("G1").await;
    let url = format!("/v1/sessions/{session}/poses");
    let points = json!([{"row": 0, "col": 0, "x": 10.5, "y": 20.0}]);
    let r = app
        .post_json(
            &url,
            &json!({"joints_deg": [0, 1, 2, 3, 4, 5], "image_points": points, "group": "shoulder_a-1"}),
        )
        .await;
    assert_eq!(r.status(), 201);
    let pose: Value = r.json().await.unwrap();
    let id = pose["id"].as_str().unwrap();
    let got: Value = app.get(&format!("{url}/{id}")).await.json().await.unwrap();
    assert_eq!(got["group"], "shoulder_a-1", "{got}");
    for bad in ["a b", "", "x/y", &"g".repeat(33)] {
        let r = app
            .post_json(
                &url,
                &json!({"joints_deg": [0, 1, 2, 3, 4, 5], "image_points": points, "group": bad}),
            )
            .await;
        assert_eq!(r.status(), 422, "{bad:?}");
        let p: Value = r.json().await.unwrap();
        assert_eq!(p["errors"][0]["field"], "group", "{p}");
    }
    let multipart = |group: &str| {
        Form::new()
            .text("joints_deg", "[1, 2, 3, 4, 5, 6]")
            .text("group", group.to_string())
            .part("image", image_part(png(CAMERA_W, CAMERA_H, 3), "p.png"))
    };
    let send = |form: Form| app.client.post(app.url(&url)).multipart(form).send();
    let r = send(multipart("wrist_b")).await.unwrap();
    assert_eq!(r.status(), 201);
    assert_eq!(r.json::<Value>().await.unwrap()["group"], "wrist_b");
    let r = send(multipart("wrist b!")).await.unwrap();
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], "group", "{p}");

    let image = png(CAMERA_W, CAMERA_H, 4);
    let dataset = |group: &str| {
        let manifest = json!([
            {"joints_deg": [0, 1, 2, 3, 4, 5], "image": "a.png", "group": group}
        ])
        .to_string();
        zip_bytes(&[("poses.json", manifest.as_bytes()), ("a.png", &image)])
    };
    let post_dataset = |body: Vec<u8>| {
        app.client
            .post(app.url(&format!("/v1/sessions/{session}/dataset")))
            .header("content-type", "application/zip")
            .body(body)
            .send()
    };
    let r = post_dataset(dataset("day2")).await.unwrap();
    assert_eq!(r.status(), 201);
    let out: Value = r.json().await.unwrap();
    let id = out["pose_ids"][0].as_str().unwrap();
    let got: Value = app.get(&format!("{url}/{id}")).await.json().await.unwrap();
    assert_eq!(got["group"], "day2");
    let r = post_dataset(dataset("day 2")).await.unwrap();
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], "poses.json[0].group", "{p}");
}
