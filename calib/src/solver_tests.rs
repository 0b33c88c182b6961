use super::*;
use rand::{rngs::StdRng, Rng, SeedableRng};
use rand_distr::{Distribution, Normal};

/// Rosenbrock as least squares: r = [10 (x2 - x1^2), 1 - x1], minimum (1, 1).
struct Rosenbrock;
impl LeastSquaresProblem for Rosenbrock {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        Some(DVector::from_vec(vec![
            10.0 * (x[1] - x[0] * x[0]),
            1.0 - x[0],
        ]))
    }
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        Some(DMatrix::from_row_slice(
            2,
            2,
            &[-20.0 * x[0], 10.0, -1.0, 0.0],
        ))
    }
}

/// y = a exp(-b t) + c, with `a` in thousands and `b` tiny: badly scaled.
struct ExpDecay {
    t: Vec<f64>,
    y: Vec<f64>,
}
impl LeastSquaresProblem for ExpDecay {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        Some(DVector::from_iterator(
            self.t.len(),
            self.t
                .iter()
                .zip(&self.y)
                .map(|(t, y)| x[0] * (-x[1] * t).exp() + x[2] - y),
        ))
    }
}

fn exp_data(truth: [f64; 3], sigma: f64, seed: u64) -> ExpDecay {
    let mut rng = StdRng::seed_from_u64(seed);
    let noise = Normal::new(0.0, sigma).unwrap();
    let t: Vec<f64> = (0..200).map(|i| i as f64 * 50.0).collect();
    let y = t
        .iter()
        .map(|t| truth[0] * (-truth[1] * t).exp() + truth[2] + noise.sample(&mut rng))
        .collect();
    ExpDecay { t, y }
}

#[test]
fn rosenbrock_converges_with_both_schedules() {
    for options in [LmOptions::default(), LmOptions::paper()] {
        let report = solve(&Rosenbrock, DVector::from_vec(vec![-1.2, 1.0]), &options).unwrap();
        assert!(
            (report.x[0] - 1.0).abs() < 1e-8,
            "{options:?}: {}",
            report.x
        );
        assert!(
            (report.x[1] - 1.0).abs() < 1e-8,
            "{options:?}: {}",
            report.x
        );
        assert!(report.cost < 1e-16);
    }
}

#[test]
fn finite_difference_jacobian_matches_analytic() {
    let x = DVector::from_vec(vec![0.7, -0.3]);
    let numeric = finite_difference_jacobian(|x| Rosenbrock.residuals(x), &x).unwrap();
    let analytic = Rosenbrock.jacobian(&x).unwrap();
    assert!((numeric - analytic).amax() < 1e-6);
}

/// Reconstruction property: with Gaussian noise of known sigma the estimate
/// lies within 3 standard deviations of the truth, and the estimated residual
/// variance matches sigma^2.
#[test]
fn noisy_fit_recovers_truth_within_three_sigma() {
    let truth = [2500.0, 1.3e-3, 40.0];
    let sigma = 0.5;
    let mut rng = StdRng::seed_from_u64(7);
    for _ in 0..5 {
        let problem = exp_data(truth, sigma, rng.random());
        let x0 = DVector::from_vec(vec![1000.0, 1e-3, 0.0]);
        let report = solve(&problem, x0, &LmOptions::default()).unwrap();
        let sd = report.standard_deviations();
        for k in 0..3 {
            let z = (report.x[k] - truth[k]) / sd[k];
            assert!(z.abs() < 3.0, "param {k}: z = {z}, x = {}", report.x);
        }
        let ratio = report.residual_variance().sqrt() / sigma;
        assert!((0.8..1.2).contains(&ratio), "sigma ratio {ratio}");
    }
}

#[test]
fn paper_schedule_also_fits_badly_scaled_problem() {
    let truth = [2500.0, 1.3e-3, 40.0];
    let problem = exp_data(truth, 0.0, 1);
    let options = LmOptions {
        max_iterations: 2000,
        ..LmOptions::paper()
    };
    let report = solve(
        &problem,
        DVector::from_vec(vec![2000.0, 1.0e-3, 0.0]),
        &options,
    )
    .unwrap();
    assert!((report.x[1] - truth[1]).abs() < 1e-9, "{}", report.x);
}

#[test]
fn redundant_parameters_converge_and_covariance_stays_finite() {
    // r = x0 + x1 - 3 (twice): only the sum is identifiable.
    struct Redundant;
    impl LeastSquaresProblem for Redundant {
        fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
            Some(DVector::from_vec(vec![
                x[0] + x[1] - 3.0,
                2.0 * (x[0] + x[1]) - 6.0,
            ]))
        }
    }
    let report = solve(
        &Redundant,
        DVector::from_vec(vec![0.0, 0.0]),
        &LmOptions::default(),
    )
    .unwrap();
    assert!(report.cost < 1e-20);
    assert!(report.covariance().iter().all(|v| v.is_finite()));
}

#[test]
fn degenerate_input_is_an_error_not_a_panic() {
    struct Undefined;
    impl LeastSquaresProblem for Undefined {
        fn residuals(&self, _x: &DVector<f64>) -> Option<DVector<f64>> {
            None
        }
    }
    let x0 = DVector::from_vec(vec![1.0]);
    assert_eq!(
        solve(&Undefined, x0.clone(), &LmOptions::default()).unwrap_err(),
        SolverError::InvalidStart
    );
    let problem = exp_data([1.0, 1.0, 1.0], 0.0, 1);
    let short = ExpDecay {
        t: problem.t[..2].to_vec(),
        y: problem.y[..2].to_vec(),
    };
    assert!(matches!(
        solve(
            &short,
            DVector::from_vec(vec![1.0, 1.0, 1.0]),
            &LmOptions::default()
        ),
        Err(SolverError::Underdetermined { .. })
    ));
    assert_eq!(
        solve(&Rosenbrock, DVector::zeros(0), &LmOptions::default()).unwrap_err(),
        SolverError::Empty
    );
}

#[test]
fn undefined_regions_are_stepped_around() {
    // sqrt(x) - 2 is undefined for x < 0: the first full step overshoots there.
    struct Sqrt;
    impl LeastSquaresProblem for Sqrt {
        fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
            (x[0] >= 0.0).then(|| DVector::from_vec(vec![x[0].sqrt() - 2.0]))
        }
    }
    let report = solve(&Sqrt, DVector::from_vec(vec![0.01]), &LmOptions::default()).unwrap();
    assert!((report.x[0] - 4.0).abs() < 1e-8);
}

#[test]
fn covariance_equals_inverse_normal_matrix_when_well_conditioned() {
    let problem = exp_data([2500.0, 1.3e-3, 40.0], 0.5, 3);
    let x = DVector::from_vec(vec![2500.0, 1.3e-3, 40.0]);
    let jac = problem.jacobian(&x).unwrap();
    let direct = jac.tr_mul(&jac).try_inverse().unwrap() * 2.0;
    let ours = covariance_from_jacobian(&jac, 2.0);
    for (a, b) in direct.iter().zip(ours.iter()) {
        assert!((a - b).abs() <= 1e-8 * a.abs().max(1e-30), "{a} vs {b}");
    }
}

/// A problem that assembles its normal equations itself converges to the
/// same answer as the dense default.
#[test]
fn assembled_normal_equations_match_dense_path() {
    struct Assembled(ExpDecay);
    impl LeastSquaresProblem for Assembled {
        fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
            self.0.residuals(x)
        }
        fn normal_equations(
            &self,
            x: &DVector<f64>,
            r: &DVector<f64>,
        ) -> Option<(NormalMatrix, DVector<f64>)> {
            let (mut jtj, mut jtr) = (DMatrix::zeros(3, 3), DVector::zeros(3));
            for (k, t) in self.0.t.iter().enumerate() {
                let e = (-x[1] * t).exp();
                let row = nalgebra::Vector3::new(e, -x[0] * t * e, 1.0);
                for i in 0..3 {
                    jtr[i] += row[i] * r[k];
                    for j in 0..3 {
                        jtj[(i, j)] += row[i] * row[j];
                    }
                }
            }
            Some((jtj.into(), jtr))
        }
    }
    let truth = [2500.0, 1.3e-3, 40.0];
    let x0 = DVector::from_vec(vec![1000.0, 1e-3, 0.0]);
    let dense = solve(&exp_data(truth, 0.5, 9), x0.clone(), &LmOptions::default()).unwrap();
    let fast = solve(
        &Assembled(exp_data(truth, 0.5, 9)),
        x0,
        &LmOptions::default(),
    )
    .unwrap();
    assert!((&dense.x - &fast.x).amax() < 1e-6 * dense.x.amax());
    // No dense Jacobian is formed; the covariance from the normal matrix
    // is the one from the Jacobian's SVD.
    assert!(fast.jacobian.is_none() && dense.jacobian.is_some());
    let (a, b) = (dense.covariance(), fast.covariance());
    for i in 0..3 {
        for j in 0..3 {
            let scale = (a[(i, i)] * a[(j, j)]).sqrt();
            assert!((a[(i, j)] - b[(i, j)]).abs() < 1e-4 * scale, "{a} vs {b}");
        }
    }
}
