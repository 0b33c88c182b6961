//! The restart and fleet harness, shared by `restart.rs` (one process killed
//! and started again) and `tests/pg/fleet.rs` (several processes on one
//! database): real `robocal serve` processes on port 0, and the small
//! session every such test calibrates.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

use reqwest::multipart::Form;
use serde_json::Value;

use crate::support::{image_part, png, point_pose, robot_body, session_body, CAMERA_H, CAMERA_W};

/// The real binary, started on port 0; its address is read from stdout.
/// Killed (if still running) when dropped, so a failing test leaves no
/// process behind.
pub struct BinaryServer {
    pub child: Child,
    pub base: String,
}

impl BinaryServer {
    pub fn pid(&self) -> u32 {
        self.child.id()
    }
}

impl Drop for BinaryServer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `robocal serve <args>` with the test hooks `envs`; calibrations stop
/// after validation (`ROBOCAL_TEST_VALIDATE_ONLY`) unless `envs` says not.
pub fn spawn_binary(args: &[&str], envs: &[(&str, &str)]) -> BinaryServer {
    spawn_binaries(1, args, envs).pop().expect("one process")
}

/// `n` processes of [`spawn_binary`], all started before any is waited
/// for (so they migrate one database together).
pub fn spawn_binaries(n: usize, args: &[&str], envs: &[(&str, &str)]) -> Vec<BinaryServer> {
    let children: Vec<Child> = (0..n)
        .map(|_| {
            let mut cmd = Command::new(env!("CARGO_BIN_EXE_robocal"));
            cmd.arg("serve").args(args);
            cmd.env("RUST_LOG", "warn");
            cmd.env("ROBOCAL_TEST_VALIDATE_ONLY", "true");
            for (k, v) in envs {
                cmd.env(k, v);
            }
            cmd.stdout(Stdio::piped())
                .stderr(Stdio::null())
                .spawn()
                .expect("robocal binary starts")
        })
        .collect();
    children
        .into_iter()
        .map(|mut child| {
            let mut line = String::new();
            BufReader::new(child.stdout.take().unwrap())
                .read_line(&mut line)
                .unwrap();
            let base = line
                .trim()
                .strip_prefix("robocal listening on ")
                .unwrap_or_else(|| panic!("unexpected first line {line:?}"))
                .to_string();
            BinaryServer { child, base }
        })
        .collect()
}

/// A robot `serial` on the server at `base` with a session of 3 cal + 1
/// val point poses and one image pose (set `image_set`, pixels from
/// `seed`); returns (session id, image pose id, image bytes).
pub async fn robot_with_session(
    c: &reqwest::Client,
    base: &str,
    serial: &str,
    seed: u8,
    image_set: &str,
) -> (String, String, Vec<u8>) {
    let r = c
        .put(format!("{base}/v1/robots/{serial}"))
        .json(&robot_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let r = c
        .post(format!("{base}/v1/robots/{serial}/sessions"))
        .json(&session_body())
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let session = r.json::<Value>().await.unwrap()["id"]
        .as_str()
        .unwrap()
        .to_string();
    for i in 0..4 {
        let set = if i < 3 { "cal" } else { "val" };
        let r = c
            .post(format!("{base}/v1/sessions/{session}/poses"))
            .json(&point_pose(i, set))
            .send()
            .await
            .unwrap();
        assert_eq!(r.status(), 201);
    }
    let image = png(CAMERA_W, CAMERA_H, seed);
    let form = Form::new()
        .text("joints_deg", "[1,2,3,4,5,6]")
        .text("set", image_set.to_string())
        .part("image", image_part(image.clone(), "p.png"));
    let r = c
        .post(format!("{base}/v1/sessions/{session}/poses"))
        .multipart(form)
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 201);
    let pose = r.json::<Value>().await.unwrap()["id"]
        .as_str()
        .unwrap()
        .to_string();
    (session, pose, image)
}
