//! The `robocal` client commands, run as the real binary against a server:
//! `upload` keeps an existing robot unless `--replace-robot`, `calibrate`
//! checks `--serial` and logs plain progress lines off a terminal,
//! `forward` and `compensate` print tables or JSON, `filter FILE.csv`
//! streams CSV lines; a hand–eye campaign (flange poses instead of joints)
//! uploads as a directory or a zip.

use std::process::Output;

use serde_json::{json, Value};

use crate::flange_pose::{rct_dir, rct_flange_pose, rct_session, RCT_IMAGES};
use crate::support::{run_binary, spawn_app_with, zip_bytes, TestApp};

/// A small rendered PUMA-560 campaign: enough rows to identify the model.
const CAL_POSES: usize = 16;
const VAL_POSES: usize = 6;
const SEED: u64 = 21;
const SERIAL: &str = "CLI-1";
/// Compensated joints reproduce the forward pose to well below a micron.
const MAX_RESIDUAL_MM: f64 = 1e-3;
/// RCT's hand–eye turns the camera by about -90 deg about its axis
/// (`tests/it/flange_pose.rs` holds the full check of that campaign).
const RCT_HAND_EYE_YAW_DEG: f64 = -90.0;
const RCT_YAW_TOLERANCE_DEG: f64 = 3.0;

/// `robocal <args> --url <server>` off the async runtime (the server runs
/// in this process).
async fn robocal(app: &TestApp, args: &[&str]) -> Output {
    let mut all: Vec<String> = args.iter().map(|a| a.to_string()).collect();
    all.extend(["--url".to_string(), app.base.clone()]);
    tokio::task::spawn_blocking(move || {
        run_binary(&all.iter().map(String::as_str).collect::<Vec<_>>())
    })
    .await
    .unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn ok(out: &Output) -> String {
    assert!(out.status.success(), "stderr: {}", text(&out.stderr));
    text(&out.stdout)
}

/// A served pose as the CLI's six cells: x, y, z (mm), rx, ry, rz (deg).
fn pose_cells(pose: &Value) -> Vec<String> {
    let numbers = |key: &str| pose[key].as_array().unwrap().clone();
    [numbers("translation_mm"), numbers("rotation_deg")]
        .concat()
        .iter()
        .map(|v| v.as_f64().unwrap().to_string())
        .collect()
}

async fn robot_preset(app: &TestApp) -> Value {
    let r: Value = app
        .get(&format!("/v1/robots/{SERIAL}"))
        .await
        .json()
        .await
        .unwrap();
    r["preset"].clone()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn upload_calibrate_forward_and_compensate_through_the_binary() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate("puma560", dir.path(), CAL_POSES, VAL_POSES, SEED).unwrap();
    let campaign = dir.path().to_str().unwrap();

    // An existing robot keeps its kinematics unless --replace-robot.
    let r = app
        .put_json(
            &format!("/v1/robots/{SERIAL}"),
            &json!({"model": "IRB 2400/16", "preset": "irb2400"}),
        )
        .await;
    assert_eq!(r.status(), 201);
    let out = robocal(&app, &["upload", "--serial", SERIAL, campaign]).await;
    ok(&out);
    assert!(
        text(&out.stderr).contains("--replace-robot"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(robot_preset(&app).await, "irb2400");
    let out = robocal(
        &app,
        &["upload", "--serial", SERIAL, "--replace-robot", campaign],
    )
    .await;
    let session = ok(&out).trim().to_string();
    assert_eq!(robot_preset(&app).await, "puma560");

    // --serial is checked against the session's robot.
    let out = robocal(
        &app,
        &["calibrate", "--serial", "OTHER-9", "--session", &session],
    )
    .await;
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains(&format!("belongs to robot {SERIAL}")),
        "{}",
        text(&out.stderr)
    );

    // Progress off a terminal: plain lines, no carriage return.
    let out = robocal(
        &app,
        &[
            "calibrate",
            "--serial",
            SERIAL,
            "--session",
            &session,
            "--wait",
        ],
    )
    .await;
    // The end is a short summary, not the job document.
    let summary = ok(&out);
    assert!(
        summary.starts_with("job ") && summary.contains(&format!("{SERIAL} parameter set v1")),
        "{summary}"
    );
    assert!(
        serde_json::from_str::<Value>(&summary).is_err(),
        "{summary}"
    );
    let log = text(&out.stderr);
    assert!(!log.contains('\r'), "{log:?}");
    assert!(log.lines().any(|l| l.contains('%')), "{log:?}");

    // forward: a table and JSON.
    let joints = "0,-20,10,0,40,0";
    let out = robocal(&app, &["forward", "--serial", SERIAL, "--joints", joints]).await;
    let table = ok(&out);
    assert!(
        table
            .lines()
            .any(|l| l.starts_with("1 ") && l.contains("camera")),
        "{table}"
    );
    let out = robocal(
        &app,
        &[
            "forward",
            "--serial",
            SERIAL,
            "--version",
            "1",
            "--joints",
            joints,
            "--json",
        ],
    )
    .await;
    let forward: Value = serde_json::from_str(&ok(&out)).unwrap();
    let target = pose_cells(&forward["poses"][0]["camera_in_target"]);

    // compensate: the forward pose back to (near) the same joints.
    let out = robocal(
        &app,
        &[
            "compensate",
            "--serial",
            SERIAL,
            "--target",
            &target.join(","),
            "--seed",
            joints,
            "--json",
        ],
    )
    .await;
    let answer: Value = serde_json::from_str(&ok(&out)).unwrap();
    let residual = answer["residual_mm"][0].as_f64().unwrap();
    assert!(residual < MAX_RESIDUAL_MM, "{answer}");
    let out = robocal(
        &app,
        &[
            "compensate",
            "--serial",
            SERIAL,
            "--target",
            &target.join(","),
            "--seed",
            joints,
        ],
    )
    .await;
    let table = ok(&out);
    assert!(
        table.lines().nth(1).is_some_and(|l| l.starts_with("1 ")),
        "{table}"
    );

    // filter FILE.csv: streamed, one CSV line per target as it is solved;
    // a target out of reach is its own line with the error.
    let set: Value = app
        .get(&format!("/v1/robots/{SERIAL}/parameter-sets/latest"))
        .await
        .json()
        .await
        .unwrap();
    let tool = pose_cells(&set["flange_to_camera"]);
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("targets.csv");
    let far = "9000,0,0,0,0,0";
    std::fs::write(
        &csv,
        format!(
            "x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg\n{}\n{far}\n",
            target.join(",")
        ),
    )
    .unwrap();
    let csv = csv.to_str().unwrap();
    let filter_args = [
        "filter",
        csv,
        "--serial",
        SERIAL,
        "--tool",
        &tool.join(","),
        "--seed",
        joints,
    ];
    let out = robocal(&app, &filter_args).await;
    let streamed = ok(&out);
    let lines: Vec<&str> = streamed.lines().collect();
    assert_eq!(lines.len(), 3, "{streamed}");
    assert_eq!(lines[0], robocal::cli::filter::output_columns(6));
    let cells: Vec<&str> = lines[1].split(',').collect();
    assert_eq!(cells[0], "0", "{streamed}");
    // One column per joint, fixed decimals: no exponent, no round-off tail.
    assert_eq!(cells.len(), 15, "{streamed}");
    assert!(
        !lines[1].contains('e') && !lines[1].contains(' '),
        "{streamed}"
    );
    assert!(
        cells[13].parse::<f64>().unwrap() < MAX_RESIDUAL_MM,
        "{streamed}"
    );
    assert!(lines[2].starts_with("1,,,,,,,,,,,,,,\""), "{streamed}");
    // The same numbers as the whole JSON answer.
    let mut json_args = filter_args.to_vec();
    json_args.push("--json");
    let whole: Value = serde_json::from_str(&ok(&robocal(&app, &json_args).await)).unwrap();
    for (cell, whole) in cells[1..7]
        .iter()
        .zip(pose_cells(&whole["nominal_targets"][0]))
    {
        let (a, b): (f64, f64) = (cell.parse().unwrap(), whole.parse().unwrap());
        assert!((a - b).abs() <= 1e-6, "{cell} vs {whole}");
    }
    assert_eq!(whole["errors"][0]["index"], 1, "{whole}");

    // export: the URDF for the controller, written to a file.
    let urdf = dir.path().join("robot.urdf");
    let urdf_arg = urdf.to_str().unwrap();
    let export_args = [
        "export", "--serial", SERIAL, "--format", "urdf", "--out", urdf_arg,
    ];
    ok(&robocal(&app, &export_args).await);
    let text = std::fs::read_to_string(&urdf).unwrap();
    assert!(
        text.contains("<robot") && text.contains("name=\"flange\""),
        "{text}"
    );
}

/// A hand–eye campaign as a user lays it out: RCT's wrist-camera photos
/// with the controller's flange poses in `poses.json` (no joints).
fn rct_campaign(dir: &std::path::Path) {
    let rct = rct_dir();
    std::fs::create_dir_all(dir.join("images")).unwrap();
    let poses: Vec<Value> = (0..RCT_IMAGES)
        .map(|k| {
            let image = format!("images/{k}.png");
            std::fs::copy(rct.join(&image), dir.join(&image)).unwrap();
            json!({"flange_pose": rct_flange_pose(&rct, k), "image": image, "set": "cal"})
        })
        .collect();
    let campaign = json!({
        "robot": {"model": "RCT wrist-camera cell", "preset": "irb2400"},
        "session": rct_session(),
    });
    let write = |name: &str, v: &Value| {
        std::fs::write(dir.join(name), serde_json::to_vec_pretty(v).unwrap()).unwrap()
    };
    write("campaign.json", &campaign);
    write("poses.json", &json!(poses));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn flange_pose_campaign_uploads_and_calibrates_through_the_binary() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let dir = tempfile::tempdir().unwrap();
    let campaign = dir.path().join("rct");
    rct_campaign(&campaign);
    let serial = "CLI-RCT";

    // A directory: the robot is created, every pose stored with its flange pose.
    let out = robocal(
        &app,
        &["upload", "--serial", serial, campaign.to_str().unwrap()],
    )
    .await;
    let session = ok(&out).trim().to_string();
    let log = text(&out.stderr);
    assert!(
        log.contains(&format!("uploaded {RCT_IMAGES} poses")),
        "{log}"
    );
    let poses: Value = app
        .get(&format!("/v1/sessions/{session}/poses"))
        .await
        .json()
        .await
        .unwrap();
    let items = poses["items"].as_array().unwrap();
    assert_eq!(items.len(), RCT_IMAGES, "{poses}");
    assert!(
        items.iter().all(|p| p["flange_pose"]["matrix"].is_array()
            && p["joints_deg"].as_array().is_some_and(|j| j.is_empty())),
        "{poses}"
    );

    // The hand–eye job from the binary.
    let out = robocal(
        &app,
        &[
            "calibrate",
            "--serial",
            serial,
            "--session",
            &session,
            "--wait",
            "--json",
        ],
    )
    .await;
    // --json: the finished job's whole document.
    let job: Value = serde_json::from_str(&ok(&out)).unwrap();
    assert_eq!(job["state"], "succeeded", "{job}");
    assert_eq!(job["result"]["serial"], serial, "{job}");
    let report: Value = app
        .get(&format!("/v1/robots/{serial}/parameter-sets/latest/report"))
        .await
        .json()
        .await
        .unwrap();
    let yaw = report["hand_eye"]["flange_to_camera"]["rotation_deg"][2]
        .as_f64()
        .unwrap_or_else(|| panic!("no hand-eye in {report}"));
    eprintln!("CLI RCT: hand-eye yaw {yaw:.2} deg");
    assert!(
        (yaw - RCT_HAND_EYE_YAW_DEG).abs() < RCT_YAW_TOLERANCE_DEG,
        "{yaw}"
    );

    // The same directory calibrated without a server.
    let out = tokio::task::spawn_blocking({
        let dir = campaign.to_str().unwrap().to_string();
        move || run_binary(&["calibrate-local", &dir])
    })
    .await
    .unwrap();
    assert!(
        ok(&out).starts_with("Calibration report"),
        "{}",
        text(&out.stdout)
    );
    assert!(
        text(&out.stdout).contains(&format!(
            "job {}, session ",
            robocal::cli::campaign::LOCAL_JOB
        )),
        "no blank job: {}",
        text(&out.stdout)
    );

    // The same campaign zipped (campaign.json, poses.json, images) is sent as is.
    let read = |name: &str| std::fs::read(campaign.join(name)).unwrap();
    let names: Vec<String> = ["campaign.json".to_string(), "poses.json".to_string()]
        .into_iter()
        .chain((0..RCT_IMAGES).map(|k| format!("images/{k}.png")))
        .collect();
    let bytes: Vec<(String, Vec<u8>)> = names.iter().map(|n| (n.clone(), read(n))).collect();
    let entries: Vec<(&str, &[u8])> = bytes
        .iter()
        .map(|(n, b)| (n.as_str(), b.as_slice()))
        .collect();
    let zip = dir.path().join("rct.zip");
    std::fs::write(&zip, zip_bytes(&entries)).unwrap();
    let out = robocal(&app, &["upload", "--serial", serial, zip.to_str().unwrap()]).await;
    ok(&out);
    assert!(
        text(&out.stderr).contains(&format!("uploaded {RCT_IMAGES} poses")),
        "{}",
        text(&out.stderr)
    );

    // A pose with both joints and a flange pose: refused naming the field.
    let mut bad: Vec<Value> = serde_json::from_slice(&read("poses.json")).unwrap();
    bad[3]["joints_deg"] = json!([0, 0, 0, 0, 0, 0]);
    std::fs::write(
        campaign.join("poses.json"),
        serde_json::to_vec(&bad).unwrap(),
    )
    .unwrap();
    let out = robocal(
        &app,
        &["upload", "--serial", serial, campaign.to_str().unwrap()],
    )
    .await;
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains("poses.json[3].flange_pose"),
        "{}",
        text(&out.stderr)
    );
    app.shutdown().await;
}
