//! Campaign plans over HTTP (issue 16): the contract of `POST
//! /v1/robots/{serial}/campaign-plans`, every export format carrying the
//! same joint values as the JSON plan, the dot noise the prediction uses
//! (the request's, the robot's earlier camera job's, or the default), and
//! infeasible or bad requests as 422/404 problem+json naming the constraint
//! or field.

use robocal::store;
use robocal::store::NewParameterSet;
use robocal_calib::geometry::{pose_to_xyz_rpy_deg, Pose};
use robocal_calib::kinematics::presets;
use serde_json::{json, Value};

use crate::support::*;

/// Exported joint values must match the JSON plan to this (deg).
const ROUND_TRIP_DEG: f64 = 1e-5;
const CAL_POSES: usize = 12;
const VAL_POSES: usize = 3;
/// The simulator's IRB 2400 home (deg): the camera looks at the board.
const HOME_DEG: [f64; 6] = [0.0, 10.0, 10.0, 0.0, 60.0, 0.0];
const FLANGE_TO_CAMERA_MM: [f64; 3] = [0.0, 60.0, 110.0];
const BOARD_CENTRE_MM: f64 = 100.0;
const STANDOFF_MM: f64 = 800.0;

fn pose_doc(pose: &Pose) -> Value {
    let (t, r) = pose_to_xyz_rpy_deg(pose);
    json!({"translation_mm": t, "rotation_deg": r})
}

/// A request for a cell like the simulator's: the board 800 mm in front
/// of the camera at the home joints.
fn body(poses: usize, validation: usize) -> Value {
    let robot = presets::irb2400();
    let home: Vec<f64> = HOME_DEG.iter().map(|d| d.to_radians()).collect();
    let flange_to_camera = Pose::translation(
        FLANGE_TO_CAMERA_MM[0],
        FLANGE_TO_CAMERA_MM[1],
        FLANGE_TO_CAMERA_MM[2],
    );
    let base_to_target = robot.base_to_flange(&home).unwrap()
        * flange_to_camera
        * Pose::translation(-BOARD_CENTRE_MM, -BOARD_CENTRE_MM, STANDOFF_MM);
    json!({
        "target": {"rows": 9, "cols": 9, "pitch_mm": 25.0, "dot_diameter_mm": 8.0,
                   "origin_marker_diameter_mm": 12.0},
        "camera": {"width": 2048, "height": 1536, "pixel_size_um": 3.45, "nominal_focal_mm": 12.0},
        "flange_to_camera_guess": pose_doc(&flange_to_camera),
        "target_to_base_guess": pose_doc(&base_to_target.inverse()),
        "poses": poses,
        "validation_poses": validation,
        "distance_mm": [600, 1000],
        "view_angle_deg": [20, 45],
        "start_joints_deg": HOME_DEG,
    })
}

async fn robot(app: &TestApp, serial: &str) {
    let r = app
        .put_json(
            &format!("/v1/robots/{serial}"),
            &json!({"model": "IRB 2400", "preset": "irb2400"}),
        )
        .await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
}

/// Numbers inside every `open ... close` span of `text`, one vector per span.
fn spans(text: &str, open: &str, close: char) -> Vec<Vec<f64>> {
    text.split(open)
        .skip(1)
        .map(|s| {
            s[..s.find(close).unwrap()]
                .split([',', ' '])
                .filter_map(|v| v.trim().parse::<f64>().ok())
                .collect()
        })
        .collect()
}

fn assert_joints(what: &str, got: &[Vec<f64>], want: &[Vec<f64>]) {
    assert_eq!(got.len(), want.len(), "{what}: pose count");
    for (g, w) in got.iter().zip(want) {
        for (a, b) in g.iter().zip(w) {
            assert!((a - b).abs() < ROUND_TRIP_DEG, "{what}: {g:?} vs {w:?}");
        }
    }
}

#[tokio::test]
async fn plan_contract_and_exports_round_trip_joints() {
    let app = spawn_app().await;
    robot(&app, "PLAN-1").await;
    let r = app
        .post_json(
            "/v1/robots/PLAN-1/campaign-plans",
            &body(CAL_POSES, VAL_POSES),
        )
        .await;
    assert_eq!(r.status(), 201);
    let plan: Value = r.json().await.unwrap();
    let poses = plan["poses"].as_array().unwrap();
    assert_eq!(poses.len(), CAL_POSES + VAL_POSES);
    let sets: Vec<&str> = poses.iter().map(|p| p["set"].as_str().unwrap()).collect();
    assert_eq!(sets.iter().filter(|s| **s == "cal").count(), CAL_POSES);
    assert_eq!(sets.iter().filter(|s| **s == "val").count(), VAL_POSES);
    let limits = presets::irb2400();
    let joints: Vec<Vec<f64>> = poses
        .iter()
        .map(|p| {
            let q: Vec<f64> = serde_json::from_value(p["joints_deg"].clone()).unwrap();
            assert_eq!(q.len(), 6);
            for (v, j) in q.iter().zip(&limits.joints) {
                assert!(v.to_radians() >= j.min_rad - 1e-9 && v.to_radians() <= j.max_rad + 1e-9);
            }
            q
        })
        .collect();
    let predicted = &plan["predicted"];
    let error = predicted["validation_error_mean_mm"].as_f64().unwrap();
    assert!(error > 0.0 && error < 1.0, "{error}");
    assert!(predicted["condition_number"].as_f64().unwrap() >= 1.0);
    assert!(predicted["parameter_std_devs"]["a_2"].as_f64().unwrap() > 0.0);
    assert_eq!(plan["purpose"], "calibration");
    assert_eq!(plan["model"], "nominal");
    // No earlier job: the stated default, and the plan says so.
    assert_eq!(predicted["sigma_px"], 0.1);
    assert_eq!(predicted["sigma_px_source"], "default");
    let id = plan["id"].as_str().unwrap();
    let base = format!("/v1/robots/PLAN-1/campaign-plans/{id}");

    let stored: Value = app.get(&base).await.json().await.unwrap();
    assert_eq!(stored, plan);

    let text = |format: &'static str| {
        let url = format!("{base}?format={format}");
        let app = &app;
        async move {
            let r = app.get(&url).await;
            assert_eq!(r.status(), 200, "{format}");
            r.text().await.unwrap()
        }
    };
    let csv = text("csv").await;
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "pose,set,j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').skip(2).map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_joints("csv", &rows, &joints);

    let ur = text("urscript").await;
    assert!(ur.starts_with("def robocal_campaign():") && ur.contains("\nend\n"));
    assert_eq!(ur.matches("sleep(").count(), joints.len());
    let ur_deg: Vec<Vec<f64>> = spans(&ur, "movej([", ']')
        .into_iter()
        .map(|q| q.iter().map(|r| r.to_degrees()).collect())
        .collect();
    assert_joints("urscript", &ur_deg, &joints);

    let rapid = text("rapid").await;
    assert!(rapid.starts_with("MODULE RobocalCampaign") && rapid.ends_with("ENDMODULE\n"));
    assert_eq!(rapid.matches("MoveAbsJ pose").count(), joints.len());
    assert_eq!(rapid.matches("WaitTime").count(), joints.len());
    // Each program says plainly that its fixed pause must become the
    // cell's capture handshake.
    for program in [&ur, &rapid] {
        assert!(
            program.contains(robocal::export::campaign_program::EDIT_NOTE),
            "{program}"
        );
    }
    let robax: Vec<Vec<f64>> = spans(&rapid, ":= [[", ']');
    assert_joints("rapid", &robax, &joints);

    let krl = text("krl").await;
    assert!(krl.starts_with("DEF robocal_campaign()") && krl.ends_with("END\n"));
    assert_eq!(krl.matches("WAIT SEC").count(), joints.len());
    // `A1 0.000000, A2 ...`: the axis names do not parse as numbers.
    let axis: Vec<Vec<f64>> = spans(&krl, "PTP {AXIS:", '}');
    assert_joints("krl", &axis, &joints);

    let r = app.get(&format!("{base}?format=gcode")).await;
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], "format");
    let r = app
        .get("/v1/robots/PLAN-1/campaign-plans/00000000-0000-0000-0000-000000000000")
        .await;
    assert_eq!(r.status(), 404);
}

#[tokio::test]
async fn infeasible_and_bad_requests_name_the_constraint() {
    let app = spawn_app().await;
    robot(&app, "PLAN-2").await;
    // A keep-out box around the whole cell: nothing survives it.
    let mut blocked = body(CAL_POSES, 0);
    blocked["keep_out"] = json!([{"min_mm": [-5000, -5000, -5000], "max_mm": [5000, 5000, 5000]}]);
    let r = app
        .post_json("/v1/robots/PLAN-2/campaign-plans", &blocked)
        .await;
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], "keep_out", "{p}");
    let counts: Vec<(String, String)> = p["errors"]
        .as_array()
        .unwrap()
        .iter()
        .skip(1)
        .map(|e| {
            (
                e["field"].as_str().unwrap().to_string(),
                e["message"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert!(
        counts.contains(&("candidates.keep_out".into(), "0 survived".into())),
        "{counts:?}"
    );
    assert!(counts
        .iter()
        .any(|(f, m)| f == "candidates.joint_limits_deg" && m != "0 survived"));

    for (field, patch) in [
        ("poses", json!({"poses": 0})),
        ("distance_mm", json!({"distance_mm": [1000, 600]})),
        ("view_angle_deg", json!({"view_angle_deg": [10, 95]})),
        ("start_joints_deg", json!({"start_joints_deg": [0, 0, 0]})),
        ("joint_limits_deg", json!({"joint_limits_deg": [[0, 10]]})),
        (
            "target.pitch_mm",
            json!({"target": {"rows": 9, "cols": 9, "dot_diameter_mm": 8.0,
                                               "origin_marker_diameter_mm": 12.0}}),
        ),
    ] {
        let mut b = body(CAL_POSES, 0);
        for (k, v) in patch.as_object().unwrap() {
            b[k] = v.clone();
        }
        let r = app.post_json("/v1/robots/PLAN-2/campaign-plans", &b).await;
        assert_eq!(r.status(), 422, "{field}");
        let p: Value = r.json().await.unwrap();
        assert_eq!(p["errors"][0]["field"], field, "{p}");
    }
    let r = app
        .post_json("/v1/robots/NOPE/campaign-plans", &body(CAL_POSES, 0))
        .await;
    assert_eq!(r.status(), 404);
}

/// A camera parameter set as a job stores one, as far as the planner reads
/// it: the report's camera section with the image size and the dots'
/// reprojection RMS (no calibrated model: the plan keeps the nominal one).
fn camera_job(width: u32, height: u32, rms_px: f64) -> NewParameterSet {
    NewParameterSet::approved(
        camera_only_set(
            json!({"fx": 2000.0, "fy": 2000.0, "cx": 1024.0, "cy": 768.0,
            "k1": 0.0, "k2": 0.0, "p1": 0.0, "p2": 0.0, "k3": 0.0}),
        ),
        json!({"camera": {"mode": "refined", "image_width": width,
            "image_height": height, "reprojection_rms_px": rms_px}}),
    )
}

#[tokio::test]
async fn plan_predicts_with_the_dot_noise_of_the_robots_earlier_job() {
    let app = spawn_app().await;
    robot(&app, "PLAN-3").await;
    let url = "/v1/robots/PLAN-3/campaign-plans";
    let predicted = |b: Value| {
        let app = &app;
        async move {
            let r = app.post_json(url, &b).await;
            assert_eq!(r.status(), 201);
            r.json::<Value>().await.unwrap()["predicted"].clone()
        }
    };
    let default = predicted(body(CAL_POSES, 0)).await;
    assert_eq!(default["sigma_px_source"], "default");

    // Version 1: a camera job on the plan's 2048x1536 images, 0.3 px RMS
    // per dot; 2: a tracker job (no camera); 3: a camera job on other
    // images (another camera: says nothing of this one's noise).
    let store = store::connect(&app.database_url).await.unwrap();
    let tracker = NewParameterSet::approved(tracker_set(), json!({}));
    for set in [
        camera_job(2048, 1536, 0.3),
        tracker,
        camera_job(1280, 1024, 0.9),
    ] {
        store
            .insert_parameter_set("PLAN-3", None, &set)
            .await
            .unwrap();
    }
    let measured = predicted(body(CAL_POSES, 0)).await;
    assert_eq!(measured["sigma_px_source"], "PLAN-3/1", "{measured}");
    let sigma = measured["sigma_px"].as_f64().unwrap();
    assert!((sigma - 0.3 / 2f64.sqrt()).abs() < 1e-12, "{sigma}");
    // The predicted error scales with the dot noise (2.1x here; the plan
    // itself may differ a little, its selection starts from a fixed prior).
    let ratio = measured["validation_error_mean_mm"].as_f64().unwrap()
        / default["validation_error_mean_mm"].as_f64().unwrap();
    assert!(ratio > 1.8 && ratio < 2.5, "{ratio}");

    // A stated noise wins over the measured one.
    let mut stated = body(CAL_POSES, 0);
    stated["sigma_px"] = json!(0.05);
    let stated = predicted(stated).await;
    assert_eq!(stated["sigma_px_source"], "request");
    assert_eq!(stated["sigma_px"], 0.05);
}

/// A calibrated camera set of robot `serial` whose frames are those of
/// [`body`]'s guesses (the nominal IRB 2400 as its kinematics).
async fn calibrated_camera_set(app: &TestApp, serial: &str) {
    use robocal::domain::{CalibratedSet, ParameterSet};
    use robocal::schema::robot::{preset_doc, Preset};
    use robocal::schema::session::Instrument;
    use robocal::schema::PoseOut;
    let guesses = body(CAL_POSES, 0);
    let pose = |v: &Value| {
        let f = |k: &str| -> [f64; 3] { serde_json::from_value(v[k].clone()).unwrap() };
        robocal_calib::geometry::pose_from_xyz_rpy_deg(f("translation_mm"), f("rotation_deg"))
            .unwrap()
    };
    let set = ParameterSet {
        instrument: Instrument::Camera,
        measurement: None,
        session_id: "s".into(),
        kinematics: preset_doc(Preset::Irb2400),
        world_to_base: PoseOut::new(&pose(&guesses["target_to_base_guess"])),
        flange_to_tool: PoseOut::new(&pose(&guesses["flange_to_camera_guess"])),
        camera: None,
        camera_mode: None,
        camera_calibration_id: None,
        fixed: Vec::new(),
        parameters: Vec::new(),
        covariance: None,
        joint_noise_deg: None,
        terms: None,
        session_target_to_base: Vec::new(),
        controller: None,
    };
    let store = store::connect(&app.database_url).await.unwrap();
    store
        .insert_parameter_set(
            serial,
            None,
            &NewParameterSet::approved(CalibratedSet::Kinematic(set), json!({})),
        )
        .await
        .unwrap();
}

#[tokio::test]
async fn omitted_guesses_come_from_the_latest_set_and_a_wrong_one_is_named() {
    let app = spawn_app().await;
    robot(&app, "PLAN-4").await;
    let url = "/v1/robots/PLAN-4/campaign-plans";
    let mut bare = body(CAL_POSES, 0);
    let obj = bare.as_object_mut().unwrap();
    obj.remove("target_to_base_guess");
    obj.remove("flange_to_camera_guess");
    // No calibrated set yet: the 422 names both fields and says why.
    let r = app.post_json(url, &bare).await;
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    let fields: Vec<&str> = p["errors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["field"].as_str().unwrap())
        .collect();
    assert_eq!(
        fields,
        ["target_to_base_guess", "flange_to_camera_guess"],
        "{p}"
    );
    assert!(p.to_string().contains("no calibrated camera set"), "{p}");

    // With a calibrated set, the same request plans from its frames.
    calibrated_camera_set(&app, "PLAN-4").await;
    let r = app.post_json(url, &bare).await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());

    // A board guess a metre off: infeasible, and the answer says where the
    // latest set puts the board.
    let mut off = body(CAL_POSES, 0);
    off["target_to_base_guess"]["translation_mm"][2] = json!(
        off["target_to_base_guess"]["translation_mm"][2]
            .as_f64()
            .unwrap()
            + 3000.0
    );
    let r = app.post_json(url, &off).await;
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    let hint = p["errors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["field"] == "target_to_base_guess")
        .unwrap_or_else(|| panic!("a hint naming the guess: {p}"));
    let message = hint["message"].as_str().unwrap();
    assert!(
        message.contains("where the robot's latest set PLAN-4/1 puts the board")
            && message.contains("omit target_to_base_guess"),
        "{message}"
    );
}

/// A camera session of robot `serial` on the plan body's board and camera,
/// with one pose per joints (deg) in `cal` and `val`; its id.
async fn session_with_joints(
    app: &TestApp,
    serial: &str,
    cal: &[Vec<f64>],
    val: &[Vec<f64>],
) -> String {
    let b = body(CAL_POSES, 0);
    let session = json!({"instrument": "camera", "target": b["target"], "camera": b["camera"]});
    let id = app.new_session(serial, &session).await;
    let poses = cal
        .iter()
        .map(|q| (q, "cal"))
        .chain(val.iter().map(|q| (q, "val")));
    for (q, set) in poses {
        let pose = json!({"joints_deg": q, "set": set,
            "image_points": [{"row": 0, "col": 0, "x": 10.5, "y": 12.25}]});
        let r = app
            .post_json(&format!("/v1/sessions/{id}/poses"), &pose)
            .await;
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    id
}

/// `POST url` with `b`: 201, the plan.
async fn created(app: &TestApp, url: &str, b: &Value) -> Value {
    let r = app.post_json(url, b).await;
    assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    r.json().await.unwrap()
}

fn joints_of(plan: &Value) -> Vec<Vec<f64>> {
    plan["poses"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| serde_json::from_value(p["joints_deg"].clone()).unwrap())
        .collect()
}

/// Issue 30, "tell the user what to shoot next": a plan extending a
/// session returns only the poses to add (its board and camera taken from
/// the session), with the session's campaign predicted alone and the gain;
/// a session that is missing, another robot's, or without cal poses with
/// joints is a 422 naming `extend_session`.
#[tokio::test]
async fn plan_extends_a_session_with_the_predicted_gain() {
    const ADDED: usize = 6;
    let app = spawn_app().await;
    robot(&app, "PLAN-4").await;
    robot(&app, "PLAN-5").await;
    let url = "/v1/robots/PLAN-4/campaign-plans";
    let first = created(&app, url, &body(CAL_POSES, VAL_POSES)).await;
    let shot = joints_of(&first);
    let session = session_with_joints(&app, "PLAN-4", &shot[..CAL_POSES], &shot[CAL_POSES..]).await;

    let mut extend = body(ADDED, 0);
    let fields = extend.as_object_mut().unwrap();
    fields.remove("target");
    fields.remove("camera");
    fields.insert("extend_session".into(), json!(session));
    let plan = created(&app, url, &extend).await;
    assert_eq!(plan["extend_session"], session.as_str());
    // Only the poses to add, all for calibration (6 poses would be a quick
    // check on their own), none of them already shot.
    let added = joints_of(&plan);
    assert_eq!(added.len(), ADDED);
    assert!(plan["poses"]
        .as_array()
        .unwrap()
        .iter()
        .all(|p| p["set"] == "cal"));
    assert_eq!(plan["purpose"], "calibration");
    for q in &added {
        assert!(shot
            .iter()
            .all(|s| s.iter().zip(q).any(|(a, b)| (a - b).abs() > ROUND_TRIP_DEG)));
    }
    let predicted = &plan["predicted"];
    let existing = &predicted["existing"];
    assert_eq!(existing["poses"], CAL_POSES, "{predicted}");
    let before = existing["validation_error_mean_mm"].as_f64().unwrap();
    let after = predicted["validation_error_mean_mm"].as_f64().unwrap();
    let gain = existing["gain_mm"].as_f64().unwrap();
    assert!(after < before, "{before} -> {after}");
    assert!((gain - (before - after)).abs() < 1e-12, "{gain}");
    // The same campaign's plan on its own predicts the existing figure's
    // order (other validation draws: only roughly).
    let alone = first["predicted"]["validation_error_mean_mm"]
        .as_f64()
        .unwrap();
    assert!(
        before < 2.0 * alone && alone < 2.0 * before,
        "{before} vs {alone}"
    );
    // A plain plan says nothing of an existing campaign.
    assert!(first["predicted"].get("existing").is_none());
    assert!(first.get("extend_session").is_none());

    let other = session_with_joints(&app, "PLAN-5", &shot[..CAL_POSES], &[]).await;
    let only_val = session_with_joints(&app, "PLAN-4", &[], &shot[CAL_POSES..]).await;
    let tracker = app
        .new_session("PLAN-4", &json!({"instrument": "tracker"}))
        .await;
    for id in [
        "00000000-0000-0000-0000-000000000000".to_string(),
        other,
        only_val,
        tracker,
    ] {
        let mut b = extend.clone();
        b["extend_session"] = json!(id);
        let r = app.post_json(url, &b).await;
        assert_eq!(r.status(), 422, "{id}");
        let p: Value = r.json().await.unwrap();
        assert_eq!(p["errors"][0]["field"], "extend_session", "{p}");
    }
}
