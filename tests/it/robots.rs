use serde_json::{json, Value};

use crate::support::*;

#[tokio::test]
async fn put_get_list_delete_robot() {
    let app = spawn_app().await;
    let r = app.put_json("/v1/robots/SN-1", &robot_body()).await;
    assert_eq!(r.status(), 201);
    let created: Value = r.json().await.unwrap();
    assert_eq!(created["serial"], "SN-1");
    assert_eq!(created["kinematics"]["joints"].as_array().unwrap().len(), 6);

    let r = app.put_json("/v1/robots/SN-1", &robot_body()).await;
    assert_eq!(r.status(), 200, "a second PUT replaces");

    let got: Value = app.get("/v1/robots/SN-1").await.json().await.unwrap();
    assert_eq!(got["model"], "Test arm");

    for s in ["SN-2", "SN-3"] {
        assert_eq!(
            app.put_json(&format!("/v1/robots/{s}"), &robot_body())
                .await
                .status(),
            201
        );
    }
    let page: Value = app.get("/v1/robots?limit=2").await.json().await.unwrap();
    assert_eq!(page["items"].as_array().unwrap().len(), 2);
    let cursor = page["next_cursor"].as_str().unwrap().to_string();
    let rest: Value = app
        .get(&format!("/v1/robots?limit=2&cursor={cursor}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(rest["items"][0]["serial"], "SN-3");
    assert!(rest["next_cursor"].is_null());

    let r = app
        .client
        .delete(app.url("/v1/robots/SN-1"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 204);
    assert_eq!(app.get("/v1/robots/SN-1").await.status(), 404);
}

#[tokio::test]
async fn convention_is_chosen_for_parallel_axes() {
    let app = spawn_app().await;
    let got: Value = app
        .put_json("/v1/robots/P1", &robot_body())
        .await
        .json()
        .await
        .unwrap();
    let joints = got["kinematics"]["joints"].as_array().unwrap();
    // Joint 2 (alpha = 0) links two parallel axes: Hayati; joint 1: DH.
    assert_eq!(joints[1]["convention"], "hayati");
    assert_eq!(joints[0]["convention"], "dh");
    // An explicit convention is kept.
    let mut body = robot_body();
    body["kinematics"]["joints"][1]["convention"] = json!("dh");
    let got: Value = app
        .put_json("/v1/robots/P2", &body)
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(got["kinematics"]["joints"][1]["convention"], "dh");
}

#[tokio::test]
async fn presets_expand_to_joint_tables() {
    let app = spawn_app().await;
    for preset in ["irb2400", "puma560"] {
        let r = app
            .put_json(
                &format!("/v1/robots/{preset}-1"),
                &json!({"model": preset, "preset": preset}),
            )
            .await;
        assert_eq!(r.status(), 201);
        let got: Value = r.json().await.unwrap();
        assert_eq!(got["preset"], preset);
        assert_eq!(
            got["kinematics"]["joints"].as_array().unwrap().len(),
            6,
            "{got}"
        );
        assert_eq!(
            got["kinematics"]["joints"][1]["convention"], "hayati",
            "{preset}: {got}"
        );
    }
}

#[tokio::test]
async fn sessions_create_get_list() {
    let app = spawn_app().await;
    let id = app.robot_and_session("S1").await;
    let got: Value = app
        .get(&format!("/v1/sessions/{id}"))
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(got["serial"], "S1");
    assert_eq!(got["instrument"], "camera");
    assert_eq!(got["target"]["rows"], 7);
    assert_eq!(got["pose_count"], 0);
    let tracker = app
        .post_json("/v1/robots/S1/sessions", &json!({"instrument": "tracker"}))
        .await;
    assert_eq!(tracker.status(), 201);
    let list: Value = app
        .get("/v1/robots/S1/sessions")
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(list["items"].as_array().unwrap().len(), 2);
}

/// The robot document's `prior` (docs/method.md §6.7): stored, served,
/// replaced with the robot, and refused with a 422 naming the field when
/// it is not a usable σ.
#[tokio::test]
async fn the_kinematic_prior_is_part_of_the_robot_document() {
    let app = spawn_app().await;
    let mut body = robot_body();
    body["prior"] = json!({"joint_offset_deg": 0.05, "length_mm": 0.3, "twist_deg": 0.02});
    let r = app.put_json("/v1/robots/PRIOR-1", &body).await;
    assert_eq!(r.status(), 201);
    let got: Value = app.get("/v1/robots/PRIOR-1").await.json().await.unwrap();
    assert_eq!(got["prior"]["length_mm"], 0.3, "{got}");
    assert_eq!(got["prior"]["joint_offset_deg"], 0.05);
    // Replaced without it: manufacturing tolerances again (not served).
    let r = app.put_json("/v1/robots/PRIOR-1", &robot_body()).await;
    assert_eq!(r.status(), 200);
    let got: Value = app.get("/v1/robots/PRIOR-1").await.json().await.unwrap();
    assert!(got.get("prior").is_none(), "{got}");
    for (field, bad) in [
        (
            "prior.length_mm",
            json!({"joint_offset_deg": 0.1, "length_mm": 0.0, "twist_deg": 0.1}),
        ),
        (
            "prior.twist_deg",
            json!({"joint_offset_deg": 0.1, "length_mm": 1.0, "twist_deg": 45.0}),
        ),
    ] {
        let mut body = robot_body();
        body["prior"] = bad;
        let r = app.put_json("/v1/robots/PRIOR-2", &body).await;
        assert_eq!(r.status(), 422);
        let problem: Value = r.json().await.unwrap();
        assert_eq!(problem["errors"][0]["field"], field, "{problem}");
    }
    assert_eq!(app.get("/v1/robots/PRIOR-2").await.status(), 404);
}
