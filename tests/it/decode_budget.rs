//! Decode cost priced from the image header before decoding: pixels
//! against the server's ceiling even without a session camera, and bytes
//! from the header's bit depth and channels (a 422 naming the part).

use std::io::Cursor;

use image::{DynamicImage, ImageBuffer, Luma, Rgb, Rgba};
use reqwest::multipart::{Form, Part};
use serde_json::{json, Value};

use robocal::store;

use crate::support::*;

/// The PNG or JPEG bytes of `img`.
fn encoded(img: &DynamicImage, format: image::ImageFormat) -> Vec<u8> {
    let mut out = Vec::new();
    img.write_to(&mut Cursor::new(&mut out), format).unwrap();
    out
}

fn grey8(w: u32, h: u32) -> DynamicImage {
    DynamicImage::ImageLuma8(ImageBuffer::from_fn(w, h, |x, y| {
        Luma([((x * 3 + y * 5) % 256) as u8])
    }))
}

/// Posts `bytes` as the `image` part of a pose; the response status and body.
async fn post_image(app: &TestApp, session: &str, bytes: Vec<u8>, mime: &str) -> (u16, Value) {
    let form = Form::new().text("joints_deg", "[0,0,0,0,0,0]").part(
        "image",
        Part::bytes(bytes).file_name("view").mime_str(mime).unwrap(),
    );
    let r = app
        .client
        .post(app.url(&format!("/v1/sessions/{session}/poses")))
        .multipart(form)
        .send()
        .await
        .unwrap();
    let status = r.status().as_u16();
    (status, r.json().await.unwrap_or(Value::Null))
}

/// The refusal names the part and the server option behind it.
fn assert_refused(status: u16, problem: &Value, option: &str) {
    assert_eq!(status, 422, "{problem}");
    assert_eq!(problem["errors"][0]["field"], "image", "{problem}");
    let message = problem["errors"][0]["message"].as_str().unwrap();
    assert!(message.contains(option), "{message}");
}

/// A session stored before the server's ceiling was lowered (or before
/// there was one) names a camera over it: its images were decoded at that
/// size because they matched it.
#[tokio::test]
async fn an_image_over_the_pixel_ceiling_is_refused_even_when_its_session_camera_allows_it() {
    let app = spawn_app_with(|c| c.max_camera_pixels = 10_000).await;
    assert_eq!(
        app.put_json("/v1/robots/OLDCAM", &robot_body())
            .await
            .status(),
        201
    );
    let mut body = session_body();
    body["camera"]["width"] = json!(200);
    body["camera"]["height"] = json!(100);
    // Through the API the camera is refused now ...
    let r = app.post_json("/v1/robots/OLDCAM/sessions", &body).await;
    assert_eq!(r.status(), 422);
    // ... but a session stored before keeps it.
    let store = store::connect(&app.database_url).await.unwrap();
    let spec = serde_json::from_value(body).unwrap();
    let s = store
        .create_session("OLDCAM", "camera", &spec)
        .await
        .unwrap()
        .id;

    let png = encoded(&grey8(200, 100), image::ImageFormat::Png);
    let (status, problem) = post_image(&app, &s, png, "image/png").await;
    assert_refused(status, &problem, "--max-camera-pixels");
}

/// Bytes per pixel come from the header: a 16-bit RGBA PNG is decoded row
/// by row into 4 bytes a pixel, an 8-bit grey one into 1 (and the circle
/// detector's 4-byte copy), an RGB JPEG holds its components beside them.
#[tokio::test]
async fn a_decode_over_the_byte_budget_is_refused_from_the_header() {
    let pixels = u64::from(CAMERA_W * CAMERA_H);
    let app = spawn_app_with(|c| c.max_decode_bytes = 6 * pixels).await;
    let s = app.robot_and_session("BUDGET").await;
    let (w, h) = (CAMERA_W, CAMERA_H);

    let rgba16 = DynamicImage::ImageRgba16(ImageBuffer::from_fn(w, h, |x, y| {
        Rgba([(x * 1000) as u16, (y * 1000) as u16, 40_000, 65_535])
    }));
    let (status, pose) = post_image(
        &app,
        &s,
        encoded(&rgba16, image::ImageFormat::Png),
        "image/png",
    )
    .await;
    assert_eq!(status, 201, "16-bit RGBA PNG, 4 bytes a pixel: {pose}");
    let (status, pose) = post_image(
        &app,
        &s,
        encoded(&grey8(w, h), image::ImageFormat::Png),
        "image/png",
    )
    .await;
    assert_eq!(status, 201, "8-bit grey PNG, 5 bytes a pixel: {pose}");

    let rgb = DynamicImage::ImageRgb8(ImageBuffer::from_fn(w, h, |x, y| {
        Rgb([(x * 4) as u8, (y * 5) as u8, 90])
    }));
    let (status, problem) = post_image(
        &app,
        &s,
        encoded(&rgb, image::ImageFormat::Jpeg),
        "image/jpeg",
    )
    .await;
    assert_refused(status, &problem, "--max-decode-bytes");
    let detail = problem["errors"][0]["message"].as_str().unwrap();
    assert!(detail.contains("8-bit RGB JPEG"), "{detail}");
    let session: Value = app
        .get(&format!("/v1/sessions/{s}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(session["pose_count"], 2, "{session}");
}
