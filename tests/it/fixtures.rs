//! Request bodies and payloads the tests send: a robot and a camera
//! session, a pose of image points, small PNGs and zips, multipart parts,
//! and the built binary's output (re-exported by `support`).

use std::io::Write;
use std::process::Command;

use serde_json::{json, Value};
use sha2::{Digest, Sha256};

pub fn robot_body() -> Value {
    // A six-joint arm given joint by joint (IRB-2400-like proportions).
    let joints: Vec<Value> = [
        (100.0, -90.0, 615.0),
        (705.0, 0.0, 0.0),
        (135.0, -90.0, 0.0),
        (0.0, 90.0, 755.0),
        (0.0, -90.0, 0.0),
        (0.0, 0.0, 85.0),
    ]
    .iter()
    .map(|(a, alpha, d)| json!({"type":"revolute","a_mm":a,"alpha_deg":alpha,"d_mm":d,"theta_offset_deg":0.0,"min_deg":-170.0,"max_deg":170.0}))
    .collect();
    json!({"model": "Test arm", "kinematics": {"joints": joints}})
}

pub const CAMERA_W: u32 = 64;
pub const CAMERA_H: u32 = 48;

pub fn session_body() -> Value {
    json!({
        "instrument": "camera",
        "target": {"rows": 7, "cols": 9, "pitch_mm": 20.0, "dot_diameter_mm": 8.0, "origin_marker_diameter_mm": 12.0},
        "camera": {"width": CAMERA_W, "height": CAMERA_H, "pixel_size_um": 5.5, "nominal_focal_mm": 8.0}
    })
}

pub fn point_pose(i: usize, set: &str) -> Value {
    let q = i as f64;
    json!({
        "joints_deg": [q, -10.0 + q, 20.0, 0.0, 30.0 - q, 5.0],
        "set": set,
        "image_points": [{"row":0,"col":0,"x":10.5,"y":12.25},{"row":0,"col":1,"x":20.0,"y":12.0},{"row":1,"col":0,"x":10.0,"y":22.0}]
    })
}

/// A small valid PNG whose pixels depend on `seed` (so each is a distinct blob).
pub fn png(width: u32, height: u32, seed: u8) -> Vec<u8> {
    let img = image::RgbImage::from_fn(width, height, |x, y| {
        image::Rgb([
            (x as u8).wrapping_mul(3) ^ seed,
            (y as u8).wrapping_add(seed),
            seed,
        ])
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

pub fn sha256_hex(bytes: &[u8]) -> String {
    hex::encode(Sha256::digest(bytes))
}

/// A zip archive of `(name, bytes)` entries, deflated.
pub fn zip_bytes(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in entries {
        w.start_file(*name, options).unwrap();
        w.write_all(bytes).unwrap();
    }
    w.finish().unwrap().into_inner()
}

pub fn image_part(bytes: Vec<u8>, name: &str) -> reqwest::multipart::Part {
    reqwest::multipart::Part::bytes(bytes)
        .file_name(name.to_string())
        .mime_str("image/png")
        .unwrap()
}

/// Runs `robocal <args>` to completion.
pub fn run_binary(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_robocal"))
        .args(args)
        .env("RUST_LOG", "warn")
        .output()
        .unwrap()
}
