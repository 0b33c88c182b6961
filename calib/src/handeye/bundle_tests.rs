use nalgebra::{DVector, Point2, Point3, Vector6};

use super::*;
use crate::camera::model::Intrinsics;
use crate::geometry::pose_from_xyz_rpy_deg;
use crate::handeye::bundle_problem::Bundle;
use crate::normal_matrix::NormalMatrix;
use crate::solver::finite_difference_jacobian;

/// A two-view problem with every unknown free and flange corrections, at
/// a point away from the reference, with its views (kept alive by the
/// caller through the returned vectors).
/// The reference model, the views' flange poses and their (shared) point pairs.
type TwoViews = (BundleModel, Vec<Pose>, Vec<(Point3<f64>, Point2<f64>)>);

fn two_views() -> TwoViews {
    let intrinsics = Intrinsics {
        fx: 1500.0,
        fy: 1490.0,
        cx: 640.0,
        cy: 480.0,
        k1: -0.1,
        k2: 0.05,
        p1: 2e-4,
        p2: -3e-4,
        k3: 0.0,
    };
    let reference = BundleModel {
        intrinsics,
        target_to_base: pose_from_xyz_rpy_deg([-900.0, 40.0, 700.0], [170.0, 5.0, -30.0]).unwrap(),
        flange_to_camera: pose_from_xyz_rpy_deg([5.0, 60.0, 110.0], [2.0, -1.0, 90.0]).unwrap(),
        board_scale: 1.0,
    };
    // Flange poses chosen so that the camera sees the board from ~700 mm.
    let want = [
        pose_from_xyz_rpy_deg([60.0, 50.0, -700.0], [5.0, -8.0, 20.0]).unwrap(),
        pose_from_xyz_rpy_deg([40.0, 90.0, -650.0], [-10.0, 6.0, -40.0]).unwrap(),
    ];
    let flanges: Vec<Pose> = want
        .iter()
        .map(|c| reference.target_to_base.inverse() * c * reference.flange_to_camera.inverse())
        .collect();
    let pairs: Vec<(Point3<f64>, Point2<f64>)> = (0..4)
        .flat_map(|r| (0..5).map(move |c| Point3::new(25.0 * c as f64, 25.0 * r as f64, 0.0)))
        .map(|p| (p, Point2::new(600.0, 500.0)))
        .collect();
    (reference, flanges, pairs)
}

fn freedom(flange_weights: bool) -> BundleFreedom {
    BundleFreedom {
        intrinsics: (0..BUNDLE_INTRINSICS).collect(),
        board_scale: true,
        flange_weights: flange_weights.then(|| Vector6::new(0.5, 0.7, 0.9, 300.0, 400.0, 500.0)),
    }
}

fn away_from_reference(n: usize) -> DVector<f64> {
    DVector::from_fn(n, |i, _| 1e-3 * ((i * 7 % 5) as f64 - 2.0))
}

#[test]
fn analytic_jacobian_matches_finite_differences_away_from_the_reference() {
    let (reference, flanges, pairs) = two_views();
    let views: Vec<(Pose, &Pairs)> = flanges.iter().map(|f| (*f, pairs.as_slice())).collect();
    let freedom = freedom(true);
    let problem = Bundle {
        views: &views,
        reference,
        freedom: &freedom,
    };
    let x = away_from_reference(problem.params());
    let analytic = problem.jacobian(&x).unwrap();
    let numeric = finite_difference_jacobian(|x| problem.residuals(x), &x).unwrap();
    for c in 0..analytic.ncols() {
        let (a, n) = (analytic.column(c), numeric.column(c));
        assert!(
            (a - n).norm() <= 1e-5 * n.norm().max(1.0),
            "column {c}: {} vs {}",
            a.norm(),
            n.norm()
        );
    }
}

/// The point-by-point normal equations are `J^T J`, `J^T r` of the dense
/// Jacobian, with and without flange corrections (arrowhead and dense).
#[test]
fn normal_equations_equal_those_of_the_dense_jacobian() {
    let (reference, flanges, pairs) = two_views();
    let views: Vec<(Pose, &Pairs)> = flanges.iter().map(|f| (*f, pairs.as_slice())).collect();
    for corrected in [false, true] {
        let freedom = freedom(corrected);
        let problem = Bundle {
            views: &views,
            reference,
            freedom: &freedom,
        };
        let x = away_from_reference(problem.params());
        let r = problem.residuals(&x).unwrap();
        let jac = problem.jacobian(&x).unwrap();
        let (a, g) = problem.normal_equations(&x, &r).unwrap();
        assert_eq!(matches!(a, NormalMatrix::Arrow(_)), corrected);
        let (want_a, want_g) = (jac.transpose() * &jac, jac.transpose() * &r);
        let err_a = (a.to_dense() - &want_a).amax() / want_a.amax();
        let err_g = (&g - &want_g).amax() / want_g.amax();
        assert!(err_a < 1e-12 && err_g < 1e-12, "{err_a} {err_g}");
    }
}
