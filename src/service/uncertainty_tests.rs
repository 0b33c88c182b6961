use super::*;
use robocal_calib::kinematics::{presets, Instrument};
use serde_json::json;

fn model() -> CalibratedModel {
    CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    }
}

/// Every parameter uncertain by 0.01 (mm or rad), uncorrelated.
fn uncertainty() -> Uncertainty {
    let layout = ParamLayout::new(&model().robot, Instrument::Camera);
    let n = layout.len();
    Uncertainty {
        layout,
        covariance: DMatrix::identity(n, n) * 1e-4,
    }
}

fn fields(errors: Vec<FieldError>) -> Vec<String> {
    errors.into_iter().map(|e| e.field).collect()
}

fn request(v: serde_json::Value) -> UncertaintyMapRequest {
    serde_json::from_value(v).unwrap()
}

#[test]
fn bad_requests_name_their_field() {
    let (m, u) = (model(), uncertainty());
    let both = request(json!({"joints_deg": [[0, 0, 0, 0, 0, 0]],
        "box": {"min_mm": [0, 0, 0], "max_mm": [1, 1, 1], "step_mm": 1}}));
    assert_eq!(fields(uncertainty_map(&m, &u, &both).unwrap_err()), ["box"]);
    let neither = request(json!({}));
    assert_eq!(
        fields(uncertainty_map(&m, &u, &neither).unwrap_err()),
        ["box"]
    );
    let inverted =
        request(json!({"box": {"min_mm": [0, 0, 0], "max_mm": [1, -1, 1], "step_mm": 1}}));
    assert_eq!(
        fields(uncertainty_map(&m, &u, &inverted).unwrap_err()),
        ["box.max_mm[1]"]
    );
    let huge =
        request(json!({"box": {"min_mm": [0, 0, 0], "max_mm": [1000, 1000, 1000], "step_mm": 1}}));
    assert_eq!(
        fields(uncertainty_map(&m, &u, &huge).unwrap_err()),
        ["box.step_mm"]
    );
    let zero_step =
        request(json!({"box": {"min_mm": [0, 0, 0], "max_mm": [1, 1, 1], "step_mm": 0}}));
    assert_eq!(
        fields(uncertainty_map(&m, &u, &zero_step).unwrap_err()),
        ["box.step_mm"]
    );
    let short = request(json!({"joints_deg": [[0, 0, 0]]}));
    assert_eq!(
        fields(uncertainty_map(&m, &u, &short).unwrap_err()),
        ["joints_deg[0]"]
    );
    let nan_tool = request(json!({"joints_deg": [[0, 0, 0, 0, 0, 0]],
        "tool": {"translation_mm": [0, 0, 0], "rotation_deg": [0, 0, 0],
                 "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 2]]}}));
    assert!(fields(uncertainty_map(&m, &u, &nan_tool).unwrap_err())[0].starts_with("tool"));
}

#[test]
fn a_box_is_walked_x_fastest_and_each_point_reached() {
    let (m, u) = (model(), uncertainty());
    // Around the IRB-2400's zero-joint flange (940, 0, 1455), pointing forward.
    let req = request(
        json!({"box": {"min_mm": [900, -20, 1400], "max_mm": [940, 20, 1400],
        "step_mm": 20}, "rotation_deg": [0, 90, 0]}),
    );
    let map = uncertainty_map(&m, &u, &req).unwrap();
    assert_eq!(map.points.len(), 9);
    assert!(map.errors.is_empty(), "{:?}", map.errors);
    let at = |i: usize| map.points[i].as_ref().unwrap().flange_position_mm;
    assert!((at(1)[0] - 920.0).abs() < 1e-6 && (at(1)[1] + 20.0).abs() < 1e-6);
    assert!((at(3)[1] - 0.0).abs() < 1e-6 && (at(3)[0] - 900.0).abs() < 1e-6);
    // Uncorrelated equal variances: σ grows with the lever arm to the base.
    assert!(map
        .points
        .iter()
        .flatten()
        .all(|p| p.std.position_std_mm > 0.0));
    let far = request(
        json!({"box": {"min_mm": [900, 0, 1400], "max_mm": [9900, 0, 1400],
        "step_mm": 9000}, "rotation_deg": [0, 90, 0]}),
    );
    let map = uncertainty_map(&m, &u, &far).unwrap();
    assert!(map.points[0].is_some() && map.points[1].is_none());
    assert_eq!(map.errors[0].index, 1);
}

#[test]
fn forward_fills_sigma_only_with_a_covariance() {
    let m = model();
    let req: ForwardRequest =
        serde_json::from_value(json!({"joints_deg": [[0, 10, 20, 0, 30, 0]]})).unwrap();
    let without = forward(&m, None, &req).unwrap();
    assert!(without.poses[0].position_std_mm.is_none());
    let with = forward(&m, Some(&uncertainty()), &req).unwrap();
    let p = &with.poses[0];
    assert!(p.position_std_mm.unwrap() > p.flange_position_std_mm.unwrap());
    assert!(p.rotation_std_deg.unwrap() > 0.0);
}
