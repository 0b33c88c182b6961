//! Tests of the identifiability analysis.

use super::*;
use crate::geometry::Pose;
use crate::kinematics::{presets, Instrument, RobotModel};

fn model(robot: crate::kinematics::RobotModel) -> CalibratedModel {
    CalibratedModel {
        robot,
        world_to_base: Pose::translation(200.0, -900.0, 100.0),
        flange_to_tool: Pose::translation(0.0, 40.0, 100.0),
    }
}

#[test]
fn structural_redundancies_are_the_known_ones() {
    for robot in [presets::irb2400(), presets::puma560()] {
        let m = model(robot);
        let layout = ParamLayout::new(&m.robot, Instrument::Camera);
        let fixed: Vec<String> = structural_redundancies(&layout, &m)
            .unwrap()
            .iter()
            .map(|&i| layout.params[i].name.clone())
            .collect();
        assert_eq!(
            fixed,
            ["dtheta_1", "d_1", "dtheta_6", "a_6", "d_6", "alpha_6"],
            "30 = 36 - 6 independent parameters (method.md §5)"
        );
        let tracker = ParamLayout::new(&m.robot, Instrument::Tracker);
        assert_eq!(structural_redundancies(&tracker, &m).unwrap().len(), 6);
    }
}

#[test]
fn too_few_or_too_similar_poses_are_named_errors() {
    let m = model(presets::irb2400());
    let layout = ParamLayout::new(&m.robot, Instrument::Camera);
    let few: Vec<Vec<f64>> = (0..3).map(|k| vec![0.1 * k as f64; 6]).collect();
    let jac = stacked_jacobian(&layout, &m, &few).unwrap();
    assert!(matches!(
        analyse(&layout, &m, &jac),
        Err(IdentifiabilityError::TooFewPoses { poses: 3, .. })
    ));
    // Only joint 1 moves: the other joints' terms are not determined.
    let similar: Vec<Vec<f64>> = (0..20)
        .map(|k| vec![0.05 * k as f64, 0.2, 0.1, 0.3, 0.4, 0.5])
        .collect();
    let jac = stacked_jacobian(&layout, &m, &similar).unwrap();
    match analyse(&layout, &m, &jac) {
        Err(IdentifiabilityError::Unidentifiable { parameters }) => {
            assert!(parameters.iter().any(|p| p == "dtheta_2"), "{parameters:?}");
        }
        other => panic!("expected Unidentifiable, got {other:?}"),
    }
}

/// The real Aubo i10 campaign (calib/tests/data/aubo_i10_hkclr): the
/// authors' DH table and the 24 joint vectors, 6 groups of 4 with joints
/// 1-3 fixed within a group.
fn aubo() -> (RobotModel, Vec<Vec<f64>>) {
    use crate::kinematics::model::{choose_conventions, Joint};
    let dh: [(f64, f64, f64, f64); 6] = [
        (163.2, 0.0, 90.0, 0.0),
        (0.0, 647.0, 180.0, 90.0),
        (0.0, 600.5, 180.0, 0.0),
        (201.3, 0.0, -90.0, -90.0),
        (102.5, 0.0, 90.0, 0.0),
        (94.0, 0.0, 0.0, 0.0),
    ];
    let joints: Vec<(Option<crate::kinematics::Convention>, Joint)> = dh
        .iter()
        .map(|&(d, a, alpha, off)| (None, Joint::dh(a, alpha, d, off, (-360.0, 360.0))))
        .collect();
    let robot = RobotModel {
        joints: choose_conventions(&joints),
    };
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/aubo_i10_hkclr/joints"
    );
    let poses = (1..=6)
        .flat_map(|g| {
            std::fs::read_to_string(format!("{dir}/group{g}.txt"))
                .unwrap()
                .lines()
                .filter(|l| !l.trim().is_empty())
                .map(|l| l.split(',').map(|v| v.trim().parse().unwrap()).collect())
                .collect::<Vec<Vec<f64>>>()
        })
        .collect();
    (robot, poses)
}

/// `n` joint vectors spread over +-1.5 rad on every joint.
fn spread_poses(n: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n)
        .map(|_| (0..6).map(|_| rng.random_range(-1.5..1.5)).collect())
        .collect()
}

#[test]
fn links_whose_joints_barely_move_are_reported_poorly_determined() {
    let (robot, poses) = aubo();
    let m = model(robot);
    let layout = ParamLayout::new(&m.robot, Instrument::Camera);
    let jac = stacked_jacobian(&layout, &m, &poses).unwrap();
    let r = analyse(&layout, &m, &jac).unwrap();
    let named = |r: &IdentifiabilityReport| -> Vec<String> {
        r.free
            .iter()
            .zip(&r.excitation)
            .map(|(&i, e)| format!("{} {e:.3}", layout.params[i].name))
            .collect()
    };
    eprintln!("aubo: rank {} fixed {:?}\n{:?}", r.rank, r.fixed, named(&r));
    // Nothing is undetermined (rank 28 of 36, the 8 fixed are structural)...
    assert!(r.weak.is_empty(), "{:?}", r.weak);
    assert_eq!(r.free.len(), 28);
    // ...but joints 1-3 take six values only: their links are identified
    // poorly, the wrist's (joint 5 moves in every pose) well.
    let poor = &r.poorly_determined;
    for p in ["dtheta_2", "a_2", "dtheta_3", "a_3"] {
        assert!(poor.iter().any(|q| q == p), "{p} not in {poor:?}");
    }
    assert!(poor.iter().all(|q| !q.ends_with("_5")), "{poor:?}");
    // The same robot over 24 poses spread on every joint: none.
    let jac = stacked_jacobian(&layout, &m, &spread_poses(24, 7)).unwrap();
    let r = analyse(&layout, &m, &jac).unwrap();
    assert!(r.poorly_determined.is_empty(), "{:?}", named(&r));
}
