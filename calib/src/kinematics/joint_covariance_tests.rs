use super::*;
use crate::kinematics::identify::JointNoise;
use crate::kinematics::image_pose::ImageNoise;
use crate::kinematics::image_test_campaign::{image_campaign, ImageCampaign};
use crate::kinematics::joint_refine::joint_refine;
use crate::sim::campaign::CampaignSpec;

/// The recomputed diagonal against the refinement's own standard
/// deviations (different inversions of the same matrix).
const RELATIVE: f64 = 1e-6;

#[test]
fn the_full_covariance_reproduces_the_refinements_standard_deviations() {
    let mut spec = CampaignSpec::standard("puma560", 3).unwrap();
    spec.cal_poses = 20;
    spec.val_poses = 0;
    let ImageCampaign {
        campaign: c,
        truth,
        poses,
        layout,
        free,
    } = image_campaign(&spec);
    let mut start = truth.clone();
    start.robot.joints[2].a_mm += 0.5;
    for (hold_intrinsics, joint) in [
        (false, JointNoise::Estimate),
        (true, JointNoise::Known { sigma_rad: 0.0 }),
    ] {
        let noise = ImageNoise {
            sigma_px: 0.1,
            joint,
        };
        let r = joint_refine(
            &start,
            &c.truth.intrinsics,
            &poses,
            &free,
            noise,
            hold_intrinsics,
        )
        .unwrap();
        let cov = joint_refine_covariance(&r, &poses, &free, hold_intrinsics).unwrap();
        assert!((&cov - cov.transpose()).amax() < 1e-12 * cov.amax());
        for i in 0..layout.len() {
            let sd = cov[(i, i)].max(0.0).sqrt();
            let want = r.std_devs[i];
            assert!(
                (sd - want).abs() <= RELATIVE * want.max(f64::MIN_POSITIVE),
                "{} (hold {hold_intrinsics}): {sd} vs {want}",
                layout.params[i].name
            );
        }
        // Off-diagonal terms are there: the correlations the σ alone lose.
        assert!(cov.iter().filter(|v| **v != 0.0).count() > free.len());
    }
    let empty = joint_refine(
        &start,
        &c.truth.intrinsics,
        &poses,
        &free,
        ImageNoise {
            sigma_px: 0.1,
            joint: JointNoise::Estimate,
        },
        false,
    )
    .unwrap();
    assert!(joint_refine_covariance(&empty, &[], &free, false).is_err());
}
