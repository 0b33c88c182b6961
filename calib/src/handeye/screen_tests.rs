//! Poses that lie (issue 14): 2–3 wrong poses in a 20-pose campaign are
//! flagged, no good pose is, and the fit equals the clean fit within noise.

use nalgebra::{Translation3, Vector6};

use super::test_campaign::FlangeCampaign;
use super::*;
use crate::geometry::pose_error;
use crate::kinematics::image_pose::ImagePose;
use crate::kinematics::CalibratedModel;

/// The lying poses and the lie told at each.
const SWAPPED: (usize, usize) = (3, 11);
const JOINT_OFF: usize = 7;
const JOINT_OFF_DEG: f64 = 2.0;
const SHIFTED: usize = 15;
const SHIFT_MM: f64 = 20.0;
/// How far (in sigmas of the clean fit) the screened fit may be from it.
const SAME_FIT_SIGMAS: f64 = 3.0;

fn flagged(per_pose: &[PoseVerdict]) -> Vec<usize> {
    per_pose
        .iter()
        .enumerate()
        .filter(|(_, p)| p.outlier)
        .map(|(k, _)| k)
        .collect()
}

fn sigma6(s: &PoseSigma) -> Vector6<f64> {
    let r = s.rotation_deg.map(f64::to_radians);
    let t = s.translation_mm;
    Vector6::new(t[0], t[1], t[2], r[0], r[1], r[2])
}

#[test]
fn lying_flange_poses_are_flagged_and_do_not_bend_the_fit() {
    let sim = FlangeCampaign::new(21);
    let clean = calibrate_flange(&sim.views(None), &sim.options()).unwrap();
    let mut views = sim.views(None);
    // Pose SWAPPED.0 carries pose SWAPPED.1's flange pose (wrong file).
    views[SWAPPED.0].base_to_flange = sim.flanges[SWAPPED.1];
    // A pose 2 degrees off in joint 2 (recorded before the robot settled).
    let robot = &sim.campaign.truth.robot;
    let mut q = sim.campaign.poses[JOINT_OFF].true_joints_rad.clone();
    q[1] += JOINT_OFF_DEG.to_radians();
    views[JOINT_OFF].base_to_flange = robot.base_to_flange(&q).unwrap();
    // A flange pose shifted by 20 mm.
    views[SHIFTED].base_to_flange =
        Translation3::new(SHIFT_MM, 0.0, 0.0) * views[SHIFTED].base_to_flange;
    let fit = calibrate_flange(&views, &sim.options()).unwrap();
    let rms: Vec<String> = fit
        .per_pose
        .iter()
        .map(|p| format!("{:.2}", p.rms_px))
        .collect();
    eprintln!("flange liars: per-pose RMS px {rms:?}");
    assert_eq!(flagged(&fit.per_pose), vec![SWAPPED.0, JOINT_OFF, SHIFTED]);
    for k in flagged(&fit.per_pose) {
        let reason = fit.per_pose[k].reason.as_deref().unwrap();
        assert!(reason.contains("contradicts"), "{reason}");
    }
    let sx = sigma6(&clean.flange_to_camera_sigma);
    let st = sigma6(&clean.target_to_base_sigma);
    let dx = pose_error(&fit.flange_to_camera, &clean.flange_to_camera);
    let dt = pose_error(&fit.target_to_base, &clean.target_to_base);
    for k in 0..6 {
        assert!(
            dx[k].abs() < SAME_FIT_SIGMAS * sx[k],
            "hand-eye {k}: {} vs {}",
            dx[k],
            sx[k]
        );
        assert!(
            dt[k].abs() < SAME_FIT_SIGMAS * st[k],
            "board {k}: {} vs {}",
            dt[k],
            st[k]
        );
    }
    assert!((fit.rms_px - clean.rms_px).abs() < 0.1 * clean.rms_px);
}

#[test]
fn lying_joint_poses_of_a_kinematic_campaign_are_flagged() {
    let sim = FlangeCampaign::new(22);
    let truth = &sim.campaign.truth;
    let board = truth.board;
    let mut poses: Vec<ImagePose> = sim
        .campaign
        .poses
        .iter()
        .map(|p| ImagePose {
            joints_rad: p.joints_rad.clone(),
            observations: p.observations(&board),
        })
        .collect();
    // Two joint files swapped, and one pose 2 degrees off in joint 2.
    let (a, b) = SWAPPED;
    let qa = poses[a].joints_rad.clone();
    poses[a].joints_rad = poses[b].joints_rad.clone();
    poses[b].joints_rad = qa;
    poses[JOINT_OFF].joints_rad[1] += JOINT_OFF_DEG.to_radians();
    // The nominal robot with the user's rough guesses (only its forward
    // kinematics matter).
    let model = CalibratedModel {
        robot: truth.nominal.clone(),
        world_to_base: sim.target_to_base,
        flange_to_tool: crate::geometry::pose_from_matrix_rows(&truth.flange_to_camera_guess)
            .unwrap(),
    };
    let verdicts = screen_joint_poses(&model, &truth.intrinsics, &poses).unwrap();
    let rms: Vec<String> = verdicts
        .iter()
        .map(|p| format!("{:.1}", p.rms_px))
        .collect();
    eprintln!("joint liars: per-pose RMS px {rms:?}");
    let mut expected = vec![a, b, JOINT_OFF];
    expected.sort();
    assert_eq!(flagged(&verdicts), expected, "{verdicts:#?}");
}
