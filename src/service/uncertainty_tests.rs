use super::*;
use robocal_calib::kinematics::{presets, Instrument};

fn model() -> TermModel {
    TermModel::geometric(CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    })
}

/// Every parameter uncertain by 0.01 (mm or rad), uncorrelated.
fn uncertainty() -> Uncertainty {
    let layout = ParamLayout::new(&model().model.robot, Instrument::Camera);
    let n = layout.len();
    Uncertainty::from_covariance(layout, DMatrix::identity(n, n) * 1e-4).unwrap()
}

fn fields(errors: Vec<FieldError>) -> Vec<String> {
    errors.into_iter().map(|e| e.field).collect()
}

/// A request naming nothing; the tests fill in what they send.
fn request() -> UncertaintyMapRequest {
    UncertaintyMapRequest {
        joints_deg: None,
        region: None,
        rotation_deg: None,
        seed_joints_deg: None,
        tool: None,
        session_id: None,
    }
}

/// A request for the joint rows `rows`.
fn at_joints(rows: &[&[f64]]) -> UncertaintyMapRequest {
    UncertaintyMapRequest {
        joints_deg: Some(rows.iter().map(|r| r.to_vec()).collect()),
        ..request()
    }
}

/// A request for the box from `min_mm` to `max_mm` every `step_mm`.
fn in_box(min_mm: [f64; 3], max_mm: [f64; 3], step_mm: f64) -> UncertaintyMapRequest {
    UncertaintyMapRequest {
        region: Some(BoxDoc {
            min_mm,
            max_mm,
            step_mm,
        }),
        ..request()
    }
}

const ZERO_JOINTS: [f64; 6] = [0.0; 6];

#[test]
fn bad_requests_name_their_field() {
    let (m, u) = (model(), uncertainty());
    let both = UncertaintyMapRequest {
        joints_deg: Some(vec![ZERO_JOINTS.to_vec()]),
        ..in_box([0.0; 3], [1.0; 3], 1.0)
    };
    assert_eq!(fields(uncertainty_map(&m, &u, &both).unwrap_err()), ["box"]);
    let neither = request();
    assert_eq!(
        fields(uncertainty_map(&m, &u, &neither).unwrap_err()),
        ["box"]
    );
    let inverted = in_box([0.0; 3], [1.0, -1.0, 1.0], 1.0);
    assert_eq!(
        fields(uncertainty_map(&m, &u, &inverted).unwrap_err()),
        ["box.max_mm[1]"]
    );
    let huge = in_box([0.0; 3], [1000.0; 3], 1.0);
    assert_eq!(
        fields(uncertainty_map(&m, &u, &huge).unwrap_err()),
        ["box.step_mm"]
    );
    let zero_step = in_box([0.0; 3], [1.0; 3], 0.0);
    assert_eq!(
        fields(uncertainty_map(&m, &u, &zero_step).unwrap_err()),
        ["box.step_mm"]
    );
    let short = at_joints(&[&[0.0; 3]]);
    assert_eq!(
        fields(uncertainty_map(&m, &u, &short).unwrap_err()),
        ["joints_deg[0]"]
    );
    let nan_tool = UncertaintyMapRequest {
        tool: Some(PoseDoc {
            translation_mm: [0.0; 3],
            rotation_deg: [0.0; 3],
            matrix: Some([
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 2.0],
            ]),
        }),
        ..at_joints(&[&ZERO_JOINTS])
    };
    assert!(fields(uncertainty_map(&m, &u, &nan_tool).unwrap_err())[0].starts_with("tool"));
}

#[test]
fn a_box_is_walked_x_fastest_and_each_point_reached() {
    let (m, u) = (model(), uncertainty());
    // Around the IRB-2400's zero-joint flange (940, 0, 1455), pointing forward.
    let req = UncertaintyMapRequest {
        rotation_deg: Some([0.0, 90.0, 0.0]),
        ..in_box([900.0, -20.0, 1400.0], [940.0, 20.0, 1400.0], 20.0)
    };
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
    let far = UncertaintyMapRequest {
        rotation_deg: Some([0.0, 90.0, 0.0]),
        ..in_box([900.0, 0.0, 1400.0], [9900.0, 0.0, 1400.0], 9000.0)
    };
    let map = uncertainty_map(&m, &u, &far).unwrap();
    assert!(map.points[0].is_some() && map.points[1].is_none());
    assert_eq!(map.errors[0].index, 1);
}

#[test]
fn forward_fills_sigma_only_with_a_covariance() {
    let m = model();
    let req = ForwardRequest {
        joints_deg: vec![vec![0.0, 10.0, 20.0, 0.0, 30.0, 0.0]],
        tool: None,
        session_id: None,
    };
    let without = forward(&m, None, &req).unwrap();
    assert!(without.poses[0].position_std_mm.is_none());
    let with = forward(&m, Some(&uncertainty()), &req).unwrap();
    let p = &with.poses[0];
    assert!(p.position_std_mm.unwrap() > p.flange_position_std_mm.unwrap());
    assert!(p.rotation_std_deg.unwrap() > 0.0);
}

#[test]
fn a_kept_terms_sigma_adds_to_the_forward_sigma() {
    use robocal_calib::kinematics::nongeometric::TermKind;
    let m = model();
    let req = ForwardRequest {
        joints_deg: vec![vec![30.0, 10.0, 20.0, 0.0, 30.0, 0.0]],
        tool: None,
        session_id: None,
    };
    let u = uncertainty();
    let plain = forward(&m, Some(&u), &req).unwrap().poses[0].clone();
    // A base-joint gear eccentricity of 0 ± 1e-2 rad: sin(30°) = 0.5, so the
    // flange gains 0.5e-2 rad times its lever.
    let mut with_term = m.clone();
    with_term.terms.terms = vec![TermKind::Periodic {
        joint: 0,
        harmonic: 1,
        cosine: false,
    }];
    with_term.terms.values = vec![0.0];
    with_term.term_std_devs = vec![1e-2];
    let bent = forward(&with_term, Some(&u), &req).unwrap().poses[0].clone();
    let lever_mm = {
        let p = bent.flange_in_base.translation_mm;
        (p[0] * p[0] + p[1] * p[1]).sqrt()
    };
    let expected =
        (plain.flange_position_std_mm.unwrap().powi(2) + (0.5e-2 * lever_mm).powi(2)).sqrt();
    let got = bent.flange_position_std_mm.unwrap();
    assert!(
        (got - expected).abs() < 1e-6 * expected,
        "{got} vs {expected}"
    );
    // A zero-valued term moves nothing.
    assert_eq!(
        bent.flange_in_base.translation_mm,
        plain.flange_in_base.translation_mm
    );
}
