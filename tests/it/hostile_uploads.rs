//! Hostile uploads: multipart poses and zip datasets (truncated, not images,
//! oversized, zip-slip, zip bomb), each a 4xx naming the problem.

use reqwest::multipart::{Form, Part};
use reqwest::Method;
use serde_json::{json, Value};

use crate::hostile::{hostile_app, run_cases, Case, MAX_ARCHIVE, MAX_IMAGE};
use crate::support::*;

#[tokio::test]
async fn hostile_uploads_get_4xx_and_server_keeps_serving() {
    let app = hostile_app().await;
    let s = app.robot_and_session("H1").await;
    let c = &app.client;
    let poses = app.url(&format!("/v1/sessions/{s}/poses"));
    let dataset = app.url(&format!("/v1/sessions/{s}/dataset"));
    let raw = |m: Method, url: &str, ct: &str, body: Vec<u8>| {
        c.request(m, url).header("content-type", ct).body(body)
    };
    let zip_post = |bytes: Vec<u8>| raw(Method::POST, &dataset, "application/zip", bytes);
    let good_png = png(CAMERA_W, CAMERA_H, 1);
    let multipart = |form: Form| c.post(&poses).multipart(form);
    let img = |b: Vec<u8>| {
        Part::bytes(b)
            .file_name("x.png")
            .mime_str("image/png")
            .unwrap()
    };
    let manifest = br#"[{"joints_deg":[0,0,0,0,0,0],"image":"a.png"}]"#;
    // 30 MB of zeros deflate to ~30 kB: stopped after MAX_IMAGE bytes are unpacked.
    let bomb = zip_bytes(&[("poses.json", manifest), ("a.png", &vec![0u8; 30_000_000])]);
    let mut truncated = b"--XyZ\r\nContent-Disposition: form-data; name=\"joints_deg\"\r\n\r\n[0,0,0,0,0,0]\r\n--XyZ\r\nContent-Disposition: form-data; name=\"image\"; filename=\"a.png\"\r\n\r\n".to_vec();
    truncated.extend_from_slice(&good_png[..good_png.len() / 2]);
    // Two entries named a.png (the zip writer refuses that: renamed in the bytes).
    let mut duplicate = zip_bytes(&[
        ("poses.json", manifest),
        ("a.png", &good_png),
        ("b.png", &good_png),
    ]);
    for i in 0..duplicate.len() - 5 {
        if &duplicate[i..i + 5] == b"b.png" {
            duplicate[i] = b'a';
        }
    }
    let nul_manifest = br#"[{"joints_deg":[0,0,0,0,0,0],"image":"a.png","label":"x\u0000"}]"#;
    let cases = vec![
        Case {
            name: "duplicate zip entries",
            request: zip_post(duplicate),
            status: 422,
            field: Some("archive/a.png"),
        },
        Case {
            name: "NUL in the manifest",
            request: zip_post(zip_bytes(&[
                ("poses.json", nul_manifest),
                ("a.png", &good_png),
            ])),
            status: 422,
            field: Some("poses.json[0].label"),
        },
        Case {
            name: "wrong joint count",
            request: c.post(&poses).json(
                &json!({"joints_deg": [1, 2], "image_points": [{"row":0,"col":0,"x":1,"y":1}]}),
            ),
            status: 422,
            field: Some("joints_deg"),
        },
        Case {
            name: "joints not an array",
            request: c
                .post(&poses)
                .json(&json!({"joints_deg": "1,2,3", "image_points": []})),
            status: 422,
            field: Some("joints_deg"),
        },
        Case {
            name: "point outside image",
            request: c.post(&poses).json(&{
                let mut p = point_pose(0, "cal");
                p["image_points"][0]["x"] = json!(1e9);
                p
            }),
            status: 422,
            field: Some("image_points[0].x"),
        },
        Case {
            name: "bad pose set",
            request: c.post(&poses).json(&{
                let mut p = point_pose(0, "cal");
                p["set"] = json!("test");
                p
            }),
            status: 422,
            field: Some("set"),
        },
        Case {
            name: "truncated multipart",
            request: raw(
                Method::POST,
                &poses,
                "multipart/form-data; boundary=XyZ",
                truncated,
            ),
            status: 400,
            field: Some("multipart"),
        },
        Case {
            name: "non-image called .png",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(b"GIF89a not really an image at all".to_vec())),
            ),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "corrupt PNG",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(good_png[..good_png.len() - 30].to_vec())),
            ),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "image of the wrong size",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(png(10, 10, 0))),
            ),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "oversized image",
            request: multipart(
                Form::new()
                    .text("joints_deg", "[0,0,0,0,0,0]")
                    .part("image", img(vec![0u8; MAX_IMAGE as usize + 1])),
            ),
            status: 413,
            field: Some("max_image_bytes"),
        },
        Case {
            name: "multipart without image",
            request: multipart(Form::new().text("joints_deg", "[0,0,0,0,0,0]")),
            status: 422,
            field: Some("image"),
        },
        Case {
            name: "joints part not JSON",
            request: multipart(
                Form::new()
                    .text("joints_deg", "zero")
                    .part("image", img(good_png.clone())),
            ),
            status: 422,
            field: Some("joints_deg"),
        },
        Case {
            name: "not a zip",
            request: zip_post(b"PK\x03\x04 this is not a zip".to_vec()),
            status: 400,
            field: Some("archive"),
        },
        Case {
            name: "zip slip",
            request: zip_post(zip_bytes(&[
                ("poses.json", manifest),
                ("../../etc/passwd", b"x"),
            ])),
            status: 422,
            field: Some("archive/../../etc/passwd"),
        },
        Case {
            name: "absolute path in zip",
            request: zip_post(zip_bytes(&[("poses.json", manifest), ("/abs.png", b"x")])),
            status: 422,
            field: Some("archive//abs.png"),
        },
        Case {
            name: "zip bomb",
            request: zip_post(bomb),
            status: 413,
            field: Some("max_image_bytes"),
        },
        Case {
            name: "archive too large",
            request: zip_post(vec![0u8; MAX_ARCHIVE as usize + 1]),
            status: 413,
            field: Some("max_archive_bytes"),
        },
        Case {
            name: "zip without poses.json",
            request: zip_post(zip_bytes(&[("a.png", &good_png)])),
            status: 422,
            field: Some("archive/poses.json"),
        },
        Case {
            name: "manifest names a missing image",
            request: zip_post(zip_bytes(&[("poses.json", manifest)])),
            status: 422,
            field: Some("archive/a.png"),
        },
        Case {
            name: "manifest not JSON",
            request: zip_post(zip_bytes(&[("poses.json", b"[{")])),
            status: 400,
            field: Some("poses.json"),
        },
        Case {
            name: "dataset as JSON",
            request: c.post(&dataset).json(&json!({})),
            status: 415,
            field: None,
        },
    ];
    let corrupt = good_png[..good_png.len() - 30].to_vec();
    let corrupt_zip = zip_post(zip_bytes(&[("poses.json", manifest), ("a.png", &corrupt)]));
    run_cases(&app, cases).await;
    // A corrupt image in an archive is named by its file, not only its index.
    let r = corrupt_zip.send().await.unwrap();
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], "poses.json[0].image", "{p}");
    assert!(
        p["errors"][0]["message"]
            .as_str()
            .unwrap()
            .starts_with("a.png: "),
        "{p}"
    );
    let session: Value = app
        .get(&format!("/v1/sessions/{s}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(session["pose_count"], 0, "nothing hostile was stored");
}

/// A PNG of `side` x `side` black pixels at 1 bit per pixel: a few tens of
/// kB that decode to `side`² bytes (324 MB at 18000) or more.
fn huge_small_png(side: u32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, side, side);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::One);
    let mut writer = encoder.write_header().unwrap();
    let mut stream = writer.stream_writer().unwrap();
    let row = vec![0u8; side.div_ceil(8) as usize];
    for _ in 0..side {
        std::io::Write::write_all(&mut stream, &row).unwrap();
    }
    stream.finish().unwrap();
    writer.finish().unwrap();
    out
}

/// Peak resident memory of this process so far, kB (`VmHWM`).
fn peak_rss_kb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .unwrap()
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap()
}

/// Memory a refused upload may add to the peak (the server runs in this
/// process), kB: far below the 324 MB a decode of 18000² pixels needs.
const MAX_REFUSED_UPLOAD_PEAK_KB: u64 = 100_000;

#[tokio::test]
async fn a_huge_image_in_a_small_file_is_refused_from_its_header() {
    let side = 18_000;
    let bytes = huge_small_png(side);
    assert!(bytes.len() < MAX_IMAGE as usize, "{} bytes", bytes.len());
    // The same header, its pixel data cut off: a decode would fail first.
    let cut = {
        let mut b = bytes.clone();
        b.truncate(200);
        b
    };
    let app = hostile_app().await;
    let s = app.robot_and_session("H2").await;
    let poses = app.url(&format!("/v1/sessions/{s}/poses"));
    let before = peak_rss_kb();
    for (name, png) in [("valid", bytes), ("cut", cut)] {
        let form = Form::new().text("joints_deg", "[0,0,0,0,0,0]").part(
            "image",
            Part::bytes(png)
                .file_name("huge.png")
                .mime_str("image/png")
                .unwrap(),
        );
        let r = app
            .client
            .post(&poses)
            .multipart(form)
            .send()
            .await
            .unwrap();
        assert_eq!(r.status(), 422, "{name}");
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], "image", "{name}: {problem}");
        let message = problem["errors"][0]["message"].as_str().unwrap();
        assert!(
            message.contains(&format!(
                "image is {side}x{side}, the session camera is {CAMERA_W}x{CAMERA_H}"
            )),
            "{name}: {message}"
        );
    }
    let grown = peak_rss_kb().saturating_sub(before);
    assert!(
        grown < MAX_REFUSED_UPLOAD_PEAK_KB,
        "peak grew by {grown} kB"
    );
}

/// Issue 32, item 2: a write token could create a session with an
/// 18000x18000 camera, and its images were then decoded at that size.
#[tokio::test]
async fn a_session_camera_over_the_pixel_ceiling_is_refused() {
    // The default ceiling (50 MP).
    let app = spawn_app().await;
    let r = app.put_json("/v1/robots/CEIL", &robot_body()).await;
    assert_eq!(r.status(), 201);
    let mut huge = session_body();
    huge["camera"]["width"] = json!(18_000);
    huge["camera"]["height"] = json!(18_000);
    let r = app.post_json("/v1/robots/CEIL/sessions", &huge).await;
    assert_eq!(r.status(), 422);
    let problem: Value = r.json().await.unwrap();
    assert_eq!(problem["errors"][0]["field"], "camera", "{problem}");
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("--max-camera-pixels"),
        "{problem}"
    );
    // The test camera is far below the ceiling.
    let r = app
        .post_json("/v1/robots/CEIL/sessions", &session_body())
        .await;
    assert_eq!(r.status(), 201);
}
