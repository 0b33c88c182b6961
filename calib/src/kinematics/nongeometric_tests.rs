use super::*;
use crate::kinematics::presets;

fn model() -> CalibratedModel {
    CalibratedModel {
        robot: presets::ur10(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::translation(0.0, 0.0, 100.0),
    }
}

#[test]
fn candidates_cover_periodic_and_compliance_terms() {
    let m = model();
    let c = NonGeometric::candidates(&m, &CandidateOptions::for_robot(&m.robot)).unwrap();
    let periodic = c
        .terms
        .iter()
        .filter(|t| matches!(t, TermKind::Periodic { .. }))
        .count();
    assert_eq!(periodic, 6 * 2 * 2);
    assert!(c.terms.contains(&TermKind::ComplianceTool { joint: 1 }));
    assert!(c.terms.contains(&TermKind::ComplianceTool { joint: 2 }));
    assert!(c.values.iter().all(|&v| v == 0.0));
}

#[test]
fn gravity_torque_basis_matches_a_hand_computation() {
    // Arm stretched horizontally (UR: q2 = 0 puts the upper arm level): the
    // tool's torque about the shoulder is m g times its horizontal reach.
    let m = model();
    let mut t = NonGeometric::none(&m);
    t.terms = vec![TermKind::ComplianceTool { joint: 1 }];
    t.values = vec![1.0];
    let q = [0.0; 6];
    let flange = m.robot.base_to_flange(&q).unwrap();
    let tool = flange * nalgebra::Point3::new(0.0, 0.0, 100.0);
    let frame1 = m.robot.joints[0].link_transform(0.0);
    let axis = frame1.rotation * nalgebra::Vector3::z();
    // Horizontal lever across the (horizontal) shoulder axis.
    let mut lever = tool.coords - frame1.translation.vector;
    lever.z = 0.0;
    lever -= axis * axis.dot(&lever);
    let reach_m = lever.norm() / 1000.0;
    let f = t.basis(&q).unwrap()[0];
    assert!(
        (f.abs() - GRAVITY_M_PER_S2 * reach_m).abs() < 1e-9,
        "{f} vs {reach_m}"
    );
    // Arm vertical: no lever.
    let up = [
        0.0,
        -std::f64::consts::FRAC_PI_2,
        0.0,
        -std::f64::consts::FRAC_PI_2,
        0.0,
        0.0,
    ];
    assert!(t.basis(&up).unwrap()[0].abs() < 0.2 * f.abs());
}

#[test]
fn periodic_terms_deflect_their_joint() {
    let m = model();
    let mut t = NonGeometric::none(&m);
    t.terms = vec![TermKind::Periodic {
        joint: 2,
        harmonic: 2,
        cosine: false,
    }];
    t.values = vec![1e-3];
    let q = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
    let d = t.deflected(&q).unwrap();
    assert!((d[2] - 0.3 - 1e-3 * (0.6f64).sin()).abs() < 1e-15);
    assert_eq!(d[0], 0.1);
}

#[test]
fn bad_payload_and_joint_are_refused() {
    let m = model();
    let mut o = CandidateOptions::for_robot(&m.robot);
    o.payload_kg = f64::NAN;
    assert!(matches!(
        NonGeometric::candidates(&m, &o),
        Err(NonGeometricError::BadPayload(_))
    ));
    o.payload_kg = 2.0;
    let c = NonGeometric::candidates(&m, &o).unwrap();
    assert!(c.terms.contains(&TermKind::CompliancePayload { joint: 2 }));
    o.compliant_joints = vec![9];
    assert!(matches!(
        NonGeometric::candidates(&m, &o),
        Err(NonGeometricError::NoSuchJoint { .. })
    ));
}
