use nalgebra::{DMatrix, DVector};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

use super::*;
use crate::geometry::{pose_error, pose_from_xyz_rpy_deg};
use crate::kinematics::params::Instrument;
use crate::kinematics::presets;

/// Monte-Carlo draws of the parameters; the RMS of their pose errors
/// matches the first-order prediction to a few per cent at this size.
const DRAWS: usize = 4000;
const TOLERANCE: f64 = 0.06;

fn model() -> CalibratedModel {
    CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: pose_from_xyz_rpy_deg([100.0, -800.0, 300.0], [10.0, -20.0, 170.0]).unwrap(),
        flange_to_tool: pose_from_xyz_rpy_deg([30.0, -20.0, 110.0], [5.0, 3.0, 80.0]).unwrap(),
    }
}

/// A dense covariance with realistic sizes: 0.05 mm and 1e-4 rad, correlated.
fn covariance(layout: &ParamLayout, rng: &mut StdRng) -> DMatrix<f64> {
    let n = layout.len();
    let scale = DMatrix::from_fn(n, n, |i, j| {
        if i == j {
            if layout.is_angle(i) {
                1e-4
            } else {
                0.05
            }
        } else {
            0.0
        }
    });
    let mix = DMatrix::from_fn(n, n, |i, j| {
        if i == j {
            1.0
        } else {
            let z: f64 = StandardNormal.sample(rng);
            0.3 * z / (n as f64).sqrt()
        }
    });
    let l = &scale * mix;
    &l * l.transpose()
}

fn monte_carlo(frame: PoseFrame, q: &[f64]) -> (PoseStd, f64, f64) {
    let m = model();
    let layout = ParamLayout::new(&m.robot, Instrument::Camera);
    let mut rng = StdRng::seed_from_u64(7);
    let cov = covariance(&layout, &mut rng);
    let predicted = pose_std(&layout, &m, &cov, q, frame).unwrap();
    let chol = cov.clone().cholesky().unwrap().l();
    let pose_of = |model: &CalibratedModel| match frame {
        PoseFrame::FlangeInBase => model.robot.base_to_flange(q).unwrap(),
        PoseFrame::ToolInWorld => model.world_to_tool(q).unwrap(),
        PoseFrame::GivenToolInWorld(t) => model.with_tool(t).world_to_tool(q).unwrap(),
    };
    let nominal = pose_of(&m);
    let (mut pos, mut rot) = (0.0, 0.0);
    for _ in 0..DRAWS {
        let z = DVector::from_fn(layout.len(), |_, _| -> f64 {
            StandardNormal.sample(&mut rng)
        });
        let drawn = layout.apply(&m, &(&chol * z));
        let e = pose_error(&pose_of(&drawn), &nominal);
        pos += e.rows(0, 3).norm_squared();
        rot += e.rows(3, 3).norm_squared();
    }
    let n = DRAWS as f64;
    (predicted, (pos / n).sqrt(), (rot / n).sqrt())
}

#[test]
fn propagated_sigma_matches_monte_carlo_in_every_frame() {
    let q = [0.3, -0.4, 0.2, 1.1, -0.7, 2.0];
    let tool = pose_from_xyz_rpy_deg([0.0, 50.0, 200.0], [0.0, 10.0, 0.0]).unwrap();
    for frame in [
        PoseFrame::FlangeInBase,
        PoseFrame::ToolInWorld,
        PoseFrame::GivenToolInWorld(tool),
    ] {
        let (predicted, pos, rot) = monte_carlo(frame, &q);
        assert!(
            (predicted.position_mm / pos - 1.0).abs() < TOLERANCE,
            "{frame:?}: predicted {} mm, drawn {pos} mm",
            predicted.position_mm
        );
        assert!(
            (predicted.rotation_rad / rot - 1.0).abs() < TOLERANCE,
            "{frame:?}: predicted {} rad, drawn {rot} rad",
            predicted.rotation_rad
        );
    }
}

#[test]
fn the_base_frame_ignores_the_board_and_a_given_tool_the_hand_eye() {
    let m = model();
    let layout = ParamLayout::new(&m.robot, Instrument::Camera);
    let q = [0.1, 0.2, -0.3, 0.4, 0.5, 0.6];
    // Only the board (world-to-base) and hand–eye are uncertain.
    let frames: Vec<usize> = (layout.base_start()..layout.len()).collect();
    let cov = embed_covariance(
        layout.len(),
        &frames,
        &(DMatrix::identity(frames.len(), frames.len()) * 0.01),
    );
    let flange = pose_std(&layout, &m, &cov, &q, PoseFrame::FlangeInBase).unwrap();
    assert_eq!(flange.position_mm, 0.0);
    assert_eq!(flange.rotation_rad, 0.0);
    let camera = pose_std(&layout, &m, &cov, &q, PoseFrame::ToolInWorld).unwrap();
    let given = pose_std(
        &layout,
        &m,
        &cov,
        &q,
        PoseFrame::GivenToolInWorld(m.flange_to_tool),
    )
    .unwrap();
    assert!(camera.position_mm > given.position_mm && given.position_mm > 0.0);
}

#[test]
fn a_misshapen_or_non_finite_covariance_is_refused() {
    let m = model();
    let layout = ParamLayout::new(&m.robot, Instrument::Camera);
    let q = [0.0; 6];
    let small = DMatrix::zeros(3, 3);
    assert!(matches!(
        pose_std(&layout, &m, &small, &q, PoseFrame::ToolInWorld),
        Err(UncertaintyError::Shape { .. })
    ));
    let mut nan = DMatrix::zeros(layout.len(), layout.len());
    nan[(0, 0)] = f64::NAN;
    assert_eq!(
        pose_std(&layout, &m, &nan, &q, PoseFrame::ToolInWorld),
        Err(UncertaintyError::NotFinite)
    );
    let zero = DMatrix::zeros(layout.len(), layout.len());
    assert!(matches!(
        pose_std(&layout, &m, &zero, &[0.0; 3], PoseFrame::ToolInWorld),
        Err(UncertaintyError::Kinematics(_))
    ));
}

/// The precomputed factor answers what `J Σ J^T` answers, for a dense
/// correlated covariance with fixed parameters (zero rows and columns, so
/// singular) in every frame.
#[test]
fn the_covariance_factor_propagates_as_the_full_matrix() {
    let m = model();
    let layout = ParamLayout::new(&m.robot, Instrument::Camera);
    let mut rng = StdRng::seed_from_u64(11);
    let mut cov = covariance(&layout, &mut rng);
    for fixed in [3, layout.tool_start() + 2] {
        cov.row_mut(fixed).fill(0.0);
        cov.column_mut(fixed).fill(0.0);
    }
    let factor = CovarianceFactor::new(&layout, &cov).unwrap();
    let tool = pose_from_xyz_rpy_deg([10.0, 0.0, 200.0], [0.0, 90.0, 0.0]).unwrap();
    for q in [
        [0.1, -0.3, 0.4, 1.0, -0.7, 2.0],
        [-1.2, 0.5, -0.2, -2.0, 1.1, 0.3],
    ] {
        for frame in [
            PoseFrame::FlangeInBase,
            PoseFrame::ToolInWorld,
            PoseFrame::GivenToolInWorld(tool),
        ] {
            let full = pose_std(&layout, &m, &cov, &q, frame).unwrap();
            let fast = factor.pose_std(&m, &q, frame).unwrap();
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b;
            assert!(
                close(fast.position_mm, full.position_mm),
                "{frame:?}: {fast:?} vs {full:?}"
            );
            assert!(
                close(fast.rotation_rad, full.rotation_rad),
                "{frame:?}: {fast:?} vs {full:?}"
            );
            assert!(
                (fast.position_covariance - full.position_covariance).norm()
                    <= 1e-9 * full.position_covariance.norm()
            );
        }
    }
    let nan = DMatrix::from_element(layout.len(), layout.len(), f64::NAN);
    assert_eq!(
        CovarianceFactor::new(&layout, &nan).unwrap_err(),
        UncertaintyError::NotFinite
    );
}
