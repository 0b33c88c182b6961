//! Issue 19 through the service: a simulated laser-tracker campaign of a
//! UR10 whose true joints have compliance and periodic errors (the
//! simulator's switch, `calib::sim::tracker_campaign`) calibrated by a job:
//! the terms are kept, and `forward` with them beats the same campaign's
//! geometric-only set at the validation poses; `compensate` answers the
//! commanded joints through them; the exports carry them; a robot without
//! them keeps none; a bad payload is a 422 naming `payload_kg`.

use std::time::Duration;

use robocal_calib::kinematics::presets;
use robocal_calib::sim::tracker_campaign::{simulate_tracker, TrackerCampaign, TrackerSpec};
use serde_json::{json, Value};

use crate::support::{spawn_app_with, TestApp};

const CAL_POSES: usize = 300;
const VAL_POSES: usize = 60;
const NOISE_MM: f64 = 0.01;
const JOB_WAIT: Duration = Duration::from_secs(600);

fn campaign(seed: u64, switch: bool) -> TrackerCampaign {
    simulate_tracker(
        &presets::ur10(),
        &TrackerSpec {
            poses: CAL_POSES + VAL_POSES,
            noise_mm: NOISE_MM,
            seed,
            non_geometric: switch,
            orientation_noise_rad: None,
        },
    )
}

fn deg(q: &[f64]) -> Vec<f64> {
    q.iter().map(|r| r.to_degrees()).collect()
}

/// A UR10 robot `serial`, a tracker session with `c`'s poses; returns the session.
async fn upload(app: &TestApp, serial: &str, c: &TrackerCampaign) -> String {
    app.put_kinematics(serial, "UR10", &presets::ur10()).await;
    let poses = c.measurements.iter().enumerate().map(|(i, m)| {
        let p = m.observed.position_mm();
        let set = if i < CAL_POSES { "cal" } else { "val" };
        (deg(&m.joints_rad), [p.x, p.y, p.z], set)
    });
    let body = json!({"instrument": "tracker", "payload_kg": 0.0});
    app.tracker_session(serial, &body, poses).await
}

async fn calibrate(app: &TestApp, session: &str, options: Value) {
    let path = format!("/v1/sessions/{session}/calibrations");
    let done = app.finished_job(&path, &options, JOB_WAIT).await;
    eprintln!("job: {done}");
}

/// RMS (mm) of `forward`'s tool position against the validation poses'
/// measured positions, for parameter set `version`.
async fn forward_rms_mm(app: &TestApp, serial: &str, version: u32, c: &TrackerCampaign) -> f64 {
    let val = &c.measurements[CAL_POSES..];
    let rows: Vec<Vec<f64>> = val.iter().map(|m| deg(&m.joints_rad)).collect();
    let r = app
        .post_json(
            &format!("/v1/robots/{serial}/parameter-sets/{version}/forward"),
            &json!({"joints_deg": rows}),
        )
        .await;
    assert_eq!(r.status(), 200);
    let answer: Value = r.json().await.unwrap();
    let sum: f64 = val
        .iter()
        .zip(answer["poses"].as_array().unwrap())
        .map(|(m, pose)| {
            let t = &pose["camera_in_target"]["translation_mm"];
            let p = m.observed.position_mm();
            (0..3)
                .map(|k| (t[k].as_f64().unwrap() - p[k]).powi(2))
                .sum::<f64>()
        })
        .sum();
    (sum / val.len() as f64).sqrt()
}

#[tokio::test]
async fn terms_are_kept_used_and_exported_and_absent_terms_are_not_kept() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    // Bad payloads name the field.
    let r = app
        .put_json("/v1/robots/P1", &crate::support::robot_body())
        .await;
    assert_eq!(r.status(), 201);
    for bad in [json!(-1.0), json!(1e9)] {
        let r = app
            .post_json(
                "/v1/robots/P1/sessions",
                &json!({"instrument": "tracker", "payload_kg": bad}),
            )
            .await;
        assert_eq!(r.status(), 422);
        let problem: Value = r.json().await.unwrap();
        assert!(problem.to_string().contains("payload_kg"), "{problem}");
    }

    // With the switch: terms kept; the geometric-only set of the same poses
    // (`non_geometric: false`) is version 2.
    let c = campaign(7, true);
    let session = upload(&app, "UR10-T", &c).await;
    calibrate(&app, &session, json!({})).await;
    calibrate(&app, &session, json!({"non_geometric": false})).await;
    let set = app.get_ok("/v1/robots/UR10-T/parameter-sets/1").await;
    let kept: Vec<&str> = set["terms"]["terms"]
        .as_array()
        .unwrap_or_else(|| panic!("no terms kept: {set}"))
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    for truth in &c.true_terms.terms {
        assert!(kept.contains(&truth.name().as_str()), "{kept:?}");
    }
    for t in set["terms"]["terms"].as_array().unwrap() {
        assert!(t["std_dev"].as_f64().unwrap() > 0.0 && t["unit"].is_string());
    }
    let report = app
        .get_ok("/v1/robots/UR10-T/parameter-sets/1/report")
        .await;
    let lines = report["terms"]["lines"].as_array().unwrap();
    assert_eq!(
        report["terms"]["kept"].as_u64().unwrap() as usize,
        kept.len()
    );
    assert!(lines
        .iter()
        .all(|l| l["why"].as_str().is_some_and(|w| !w.is_empty())));
    assert!(
        lines.len() > kept.len(),
        "rejected candidates are named too"
    );
    assert!(app.get_ok("/v1/robots/UR10-T/parameter-sets/2").await["terms"].is_null());

    let with = forward_rms_mm(&app, "UR10-T", 1, &c).await;
    let without = forward_rms_mm(&app, "UR10-T", 2, &c).await;
    let floor_mm = 3f64.sqrt() * NOISE_MM;
    eprintln!("forward at validation poses: with terms {with:.4} mm, without {without:.4} mm, floor {floor_mm:.4}");
    assert!(with < 1.3 * floor_mm, "{with} vs floor {floor_mm}");
    assert!(without > 3.0 * with, "{without} vs {with}");

    // compensate answers the commanded joints: the validation joints back
    // from their own forward pose (the geometry alone would miss them by
    // the deflections, ~1e-2 deg).
    let q = deg(&c.measurements[CAL_POSES].joints_rad);
    let fwd = app
        .post_json(
            "/v1/robots/UR10-T/parameter-sets/1/forward",
            &json!({"joints_deg": [q]}),
        )
        .await
        .json::<Value>()
        .await
        .unwrap();
    let target = &fwd["poses"][0]["camera_in_target"];
    let r = app
        .post_json(
            "/v1/robots/UR10-T/parameter-sets/1/compensate",
            &json!({"targets": [target], "seed_joints_deg": q}),
        )
        .await;
    assert_eq!(r.status(), 200);
    let comp: Value = r.json().await.unwrap();
    for (k, want) in q.iter().enumerate() {
        let got = comp["joints_deg"][0][k].as_f64().unwrap();
        assert!((got - want).abs() < 1e-5, "joint {k}: {got} vs {want}");
    }
    // The streamed answer (ndjson) goes through the terms too: its line
    // equals the whole answer.
    let streamed = app
        .client
        .post(app.url("/v1/robots/UR10-T/parameter-sets/1/compensate"))
        .header("accept", "application/x-ndjson")
        .json(&json!({"targets": [target], "seed_joints_deg": q}))
        .send()
        .await
        .unwrap();
    assert_eq!(streamed.status(), 200);
    let text = streamed.text().await.unwrap();
    let line: Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    assert_eq!(line["joints_deg"], comp["joints_deg"][0], "{text}");

    // Exports: a terms table in dh-json and csv; URDF says it cannot hold them.
    let base = "/v1/robots/UR10-T/parameter-sets/1/export";
    let dh = app.get_ok(&format!("{base}?format=dh-json")).await;
    assert_eq!(dh["terms"], set["terms"]);
    let csv = app
        .get(&format!("{base}?format=csv"))
        .await
        .text()
        .await
        .unwrap();
    assert!(csv.contains(robocal::export::table::CSV_TERMS_HEADER));
    assert!(kept.iter().all(|name| csv.contains(name)));
    let urdf = app
        .get(&format!("{base}?format=urdf"))
        .await
        .text()
        .await
        .unwrap();
    assert!(urdf.contains("URDF cannot hold"), "{urdf}");

    // The kept periodic terms' joints carry their identified span, and
    // `forward` says where a pose leaves it.
    let ranges = set["terms"]["joint_ranges_deg"].as_array().unwrap();
    let joint_1 = ranges
        .iter()
        .find(|r| r["joint"] == 1)
        .expect("periodic_1 kept");
    let (lo, hi) = (
        joint_1["min_deg"].as_f64().unwrap(),
        joint_1["max_deg"].as_f64().unwrap(),
    );
    assert!(lo < -140.0 && hi > 140.0 && hi < 150.0, "{joint_1}");
    let inside = deg(&c.measurements[0].joints_rad);
    let mut outside = inside.clone();
    outside[0] = hi + 20.0;
    let answer = app
        .post_ok(
            "/v1/robots/UR10-T/parameter-sets/1/forward",
            &json!({"joints_deg": [inside, outside]}),
        )
        .await;
    let notes = app
        .get_ok("/v1/robots/UR10-T/parameter-sets/1/report")
        .await["notes"]
        .to_string();
    assert!(notes.contains("identified over joint 1"), "{notes}");
    let warnings = |k: usize| answer["poses"][k]["warnings"].to_string();
    assert!(!warnings(0).contains("extrapolate"), "{}", warnings(0));
    assert!(
        warnings(1).contains("joint 1") && warnings(1).contains("extrapolate"),
        "{}",
        warnings(1)
    );

    // `compensate` and `filter` say it of the joints they answer.
    let target = &answer["poses"][1]["camera_in_target"];
    for (kind, extra) in [
        ("compensate", json!({})),
        (
            "filter",
            json!({"tool": {"translation_mm": [0, 0, 0], "rotation_deg": [0, 0, 0]}}),
        ),
    ] {
        let mut body = json!({"targets": [target], "seed_joints_deg": outside});
        body.as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        let solved = app
            .post_ok(&format!("/v1/robots/UR10-T/parameter-sets/1/{kind}"), &body)
            .await;
        let said = solved["warnings"][0].to_string();
        assert!(
            said.contains("joint 1") && said.contains("extrapolate"),
            "{kind}: {solved}"
        );
    }

    // Without the switch: the selection runs and keeps nothing.
    let c = campaign(8, false);
    let session = upload(&app, "UR10-G", &c).await;
    calibrate(&app, &session, json!({})).await;
    let set = app.get_ok("/v1/robots/UR10-G/parameter-sets/1").await;
    assert!(set["terms"].is_null(), "{}", set["terms"]);
    let report = app
        .get_ok("/v1/robots/UR10-G/parameter-sets/1/report")
        .await;
    assert_eq!(report["terms"]["kept"], 0);
}
