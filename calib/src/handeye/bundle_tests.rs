use nalgebra::{DVector, Point2, Point3, Vector6};

use super::*;
use crate::geometry::pose_from_xyz_rpy_deg;
use crate::solver::finite_difference_jacobian;

#[test]
fn analytic_jacobian_matches_finite_differences_away_from_the_reference() {
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
    let views: Vec<(Pose, &Pairs)> = flanges.iter().map(|f| (*f, pairs.as_slice())).collect();
    let freedom = BundleFreedom {
        intrinsics: (0..BUNDLE_INTRINSICS).collect(),
        board_scale: true,
        flange_weights: Some(Vector6::new(0.5, 0.7, 0.9, 300.0, 400.0, 500.0)),
    };
    let problem = Bundle {
        views: &views,
        reference,
        freedom: &freedom,
    };
    let mut x = DVector::zeros(problem.params());
    for (i, v) in x.iter_mut().enumerate() {
        *v = 1e-3 * ((i * 7 % 5) as f64 - 2.0);
    }
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
