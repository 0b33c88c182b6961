//! The image-level fit with non-geometric terms: its analytic Jacobian
//! and normal equations against finite differences.

use super::*;
use crate::kinematics::image_fit::ImageTerms;
use crate::kinematics::image_test_campaign::{image_campaign, ImageCampaign};
use crate::kinematics::nongeometric::CandidateOptions;
use crate::sim::campaign::CampaignSpec;
use crate::solver::{finite_difference_jacobian, LeastSquaresProblem};

#[test]
fn jacobian_with_terms_matches_finite_differences() {
    let mut spec = CampaignSpec::standard("puma560", 7).unwrap();
    spec.cal_poses = 6;
    spec.val_poses = 0;
    spec.non_geometric = true;
    let ImageCampaign {
        campaign: c,
        truth,
        poses,
        layout,
        free,
    } = image_campaign(&spec);
    let mut terms =
        NonGeometric::candidates(&truth, &CandidateOptions::for_robot(&truth.robot)).unwrap();
    terms.values = (0..terms.terms.len())
        .map(|t| 1e-5 * (t as f64 - 10.0))
        .collect();
    let bases: Vec<Vec<f64>> = poses
        .iter()
        .map(|p| terms.basis(&p.joints_rad).unwrap())
        .collect();
    let fit = ImageFit {
        layout: &layout,
        reference: &truth,
        intrinsics: &c.truth.intrinsics,
        free: &free,
        poses: &poses,
        noise: ImageNoise {
            sigma_px: 0.5,
            joint: JointNoise::Known { sigma_rad: 1e-5 },
        },
        hold_intrinsics: false,
        extra_bases: &[],
        session_of: &[],
        terms: Some(ImageTerms {
            terms: &terms,
            bases: &bases,
        }),
        prior: None,
    };
    assert_eq!(fit.nk(), free.len() + terms.terms.len());
    let x = DVector::from_fn(fit.params(), |i, _| 1e-5 * ((i % 5) as f64 - 2.0));
    let analytic = fit.jacobian(&x).unwrap();
    let fd = finite_difference_jacobian(|x| fit.residuals(x), &x).unwrap();
    assert!(
        (&analytic - &fd).amax() < 1e-4 * fd.amax(),
        "{}",
        (&analytic - &fd).amax()
    );
    let r = fit.residuals(&x).unwrap();
    let (a, g) = fit.arrow_normal_equations(&x).unwrap();
    let (dense_a, dense_g) = (analytic.transpose() * &analytic, analytic.transpose() * &r);
    assert!((&a.to_dense() - &dense_a).amax() < 1e-9 * dense_a.amax());
    assert!((&g - &dense_g).amax() < 1e-9 * (1.0 + dense_g.amax()));
    // The terms at x are the start plus x's term entries.
    let at = fit.terms_at(&x).unwrap();
    for t in 0..terms.terms.len() {
        assert!((at.values[t] - terms.values[t] - x[fit.term_start() + t]).abs() < 1e-18);
    }
}
