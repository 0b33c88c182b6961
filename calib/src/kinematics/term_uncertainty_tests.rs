use nalgebra::DMatrix;

use super::*;
use crate::kinematics::params::Instrument;
use crate::kinematics::term_model::TermModel;
use crate::kinematics::uncertainty::CovarianceFactor;
use crate::sim::tracker_campaign::{simulate_tracker, TrackerSpec};

const Q: [f64; 6] = [0.3, -1.1, 1.2, -0.7, 1.4, 0.2];

fn model() -> TermModel {
    let c = simulate_tracker(
        &crate::kinematics::presets::ur10(),
        &TrackerSpec {
            poses: 1,
            noise_mm: 0.0,
            seed: 3,
            non_geometric: true,
            orientation_noise_rad: None,
        },
    );
    let n = c.true_terms.terms.len();
    TermModel {
        model: c.truth,
        terms: c.true_terms,
        term_std_devs: vec![0.0; n],
        covariance: None,
        ranges: Vec::new(),
    }
}

/// A dense positive definite covariance over `n` entries (sizes ~1e-3).
fn random_spd(n: usize, seed: u64) -> DMatrix<f64> {
    let mut state = seed;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    let a = DMatrix::from_fn(n, n, |_, _| next() * 1e-3);
    &a * a.transpose() + DMatrix::identity(n, n) * 1e-8
}

#[test]
fn independent_terms_give_the_sum_of_the_two_variances() {
    let m = model();
    let layout = ParamLayout::new(&m.model.robot, Instrument::Camera);
    let n = layout.len();
    let geometric = DMatrix::identity(n, n) * 1e-6;
    let sds: Vec<f64> = (0..m.terms.terms.len())
        .map(|t| 1e-5 * (t + 1) as f64)
        .collect();
    let with = TermCovariance {
        cross: DMatrix::zeros(n, sds.len()),
        terms: DMatrix::from_diagonal(&nalgebra::DVector::from_iterator(
            sds.len(),
            sds.iter().map(|s| s * s),
        )),
    };
    let m = TermModel {
        term_std_devs: sds,
        ..m
    };
    let joint = TermCovarianceFactor::new(&layout, &geometric, &with).unwrap();
    let plain = CovarianceFactor::new(&layout, &geometric).unwrap();
    let bent = m.deflected(&Q).unwrap();
    for frame in [PoseFrame::ToolInWorld, PoseFrame::FlangeInBase] {
        let both = joint.pose_std(&m, &Q, frame).unwrap();
        let g = plain.pose_std(&m.model, &bent, frame).unwrap();
        let end = match frame {
            PoseFrame::FlangeInBase => crate::kinematics::CalibratedModel {
                robot: m.model.robot.clone(),
                world_to_base: crate::geometry::Pose::identity(),
                flange_to_tool: crate::geometry::Pose::identity(),
            },
            _ => m.model.clone(),
        };
        let t = m.term_variance(&end, &Q).unwrap();
        let expected = (g.position_mm.powi(2) + t.position_mm2).sqrt();
        assert!(
            (both.position_mm - expected).abs() < 1e-9 * expected,
            "{frame:?}"
        );
        let expected = (g.rotation_rad.powi(2) + t.rotation_rad2).sqrt();
        assert!(
            (both.rotation_rad - expected).abs() < 1e-9 * expected,
            "{frame:?}"
        );
    }
}

/// The extended Jacobian against finite differences of the tool position:
/// `trace(J Σ J^T)` of a dense joint covariance, terms and geometry
/// correlated.
#[test]
fn correlated_terms_match_finite_differences() {
    let m = model();
    let layout = ParamLayout::new(&m.model.robot, Instrument::Camera);
    let (n, nt) = (layout.len(), m.terms.terms.len());
    let full = random_spd(n + nt, 11);
    let with = TermCovariance {
        cross: full.view((0, n), (n, nt)).into_owned(),
        terms: full.view((n, n), (nt, nt)).into_owned(),
    };
    let geometric = full.view((0, 0), (n, n)).into_owned();
    let predicted = TermCovarianceFactor::new(&layout, &geometric, &with)
        .unwrap()
        .pose_std(&m, &Q, PoseFrame::ToolInWorld)
        .unwrap();
    let position = |x: &nalgebra::DVector<f64>| {
        let mut terms = m.terms.clone();
        for t in 0..nt {
            terms.values[t] += x[n + t];
        }
        let geo = layout.apply(&m.model, &x.rows(0, n).into_owned());
        terms.world_to_tool(&geo, &Q).unwrap().translation.vector
    };
    let h = 1e-7;
    let zero = nalgebra::DVector::zeros(n + nt);
    let p0 = position(&zero);
    let jac = DMatrix::from_fn(3, n + nt, |r, c| {
        let mut x = zero.clone();
        x[c] = h;
        (position(&x) - p0)[r] / h
    });
    let trace = (&jac * &full * jac.transpose()).trace();
    assert!(
        (predicted.position_mm.powi(2) - trace).abs() < 1e-4 * trace,
        "{} vs {trace}",
        predicted.position_mm.powi(2)
    );
}
