use super::*;
use crate::kinematics::image_test_campaign::{image_campaign, ImageCampaign};
use crate::kinematics::prior::{KinematicPrior, PriorRows};
use crate::sim::campaign::CampaignSpec;
use crate::solver::finite_difference_jacobian;
use crate::solver::LeastSquaresProblem;

fn noise(sigma_px: f64) -> ImageNoise {
    ImageNoise {
        sigma_px,
        joint: JointNoise::default(),
    }
}

#[test]
fn jacobian_matches_finite_differences_and_exact_points_are_fitted() {
    let mut spec = CampaignSpec::standard("puma560", 5).unwrap();
    spec.cal_poses = 25;
    spec.val_poses = 0;
    spec.pixel_sigma_px = 0.0;
    spec.encoder_sigma_deg = 0.0;
    let ImageCampaign {
        campaign: c,
        truth,
        poses,
        layout,
        free,
    } = image_campaign(&spec);
    let fit = ImageFit {
        layout: &layout,
        reference: &truth,
        intrinsics: &c.truth.intrinsics,
        free: &free,
        poses: &poses[..3],
        noise: ImageNoise {
            sigma_px: 0.5,
            joint: JointNoise::Known { sigma_rad: 1e-5 },
        },
        hold_intrinsics: false,
        extra_bases: &[],
        session_of: &[],
        terms: None,
        prior: None,
    };
    let x = DVector::from_fn(
        fit.params(),
        |i, _| if i < free.len() { 1e-4 } else { 1e-3 },
    );
    let analytic = fit.jacobian(&x).unwrap();
    let fd = finite_difference_jacobian(|x| fit.residuals(x), &x).unwrap();
    assert!(
        (&analytic - &fd).amax() < 1e-4 * fd.amax(),
        "{}",
        (&analytic - &fd).amax()
    );
    // The assembled normal equations are J^T J and J^T r, with and without
    // the intrinsics among the unknowns, with and without a kinematic prior
    // (centred off the reference, so that its residuals are not zero).
    let mut off = truth.clone();
    off.robot.joints[1].a_mm += 0.7;
    off.robot.joints[2].theta_offset_rad += 1e-3;
    let prior = PriorRows::new(&KinematicPrior::default(), &layout, &free, &truth, &off);
    assert!(prior.weight.iter().any(|&w| w > 0.0));
    for (hold_intrinsics, prior) in [(false, None), (true, None), (false, Some(&prior))] {
        let fit = ImageFit {
            hold_intrinsics,
            prior,
            ..fit
        };
        if prior.is_some() {
            let analytic = fit.jacobian(&x).unwrap();
            let fd = finite_difference_jacobian(|x| fit.residuals(x), &x).unwrap();
            assert!((&analytic - &fd).amax() < 1e-4 * fd.amax());
        }
        let x = DVector::from_fn(fit.params(), |i, _| 1e-4 * ((i % 3) as f64 - 1.0));
        let j = fit.jacobian(&x).unwrap();
        let r = fit.residuals(&x).unwrap();
        let (a, g) = fit.arrow_normal_equations(&x).unwrap();
        let a = a.to_dense();
        let (dense_a, dense_g) = (j.transpose() * &j, j.transpose() * &r);
        assert!((&a - &dense_a).amax() < 1e-9 * dense_a.amax());
        assert!((&g - &dense_g).amax() < 1e-9 * (1.0 + dense_g.amax()));
    }
    // Start off the truth (intrinsics and kinematics), recover it.
    let mut cam = c.truth.intrinsics;
    cam.fx *= 1.001;
    cam.cx += 2.0;
    let mut start = truth.clone();
    start.robot.joints[2].a_mm += 0.5;
    let r = joint_refine(&start, &cam, &poses, &free, noise(0.1), false).unwrap();
    assert!(r.reprojection_rms_px < 1e-6, "{}", r.reprojection_rms_px);
    assert!((r.intrinsics.fx - c.truth.intrinsics.fx).abs() < 1e-4);
    assert!((r.model.robot.joints[2].a_mm - truth.robot.joints[2].a_mm).abs() < 1e-6);
    assert!(joint_refine(&start, &cam, &[], &free, noise(0.1), false).is_err());
}
