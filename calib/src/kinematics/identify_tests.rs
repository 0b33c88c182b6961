use super::*;
use crate::geometry::Pose;
use crate::kinematics::initial::initial_world_to_base;
use crate::sim::campaign::{perturb_robot, CampaignSpec};
use nalgebra::Matrix6;
use rand::{rngs::StdRng, Rng, SeedableRng};

/// Noise-free data recovers the model to round-off.
const EXACT_TOL_MM: f64 = 1e-6;

fn setup(instrument: Instrument) -> (CalibratedModel, CalibratedModel, Vec<Measurement>) {
    let spec = CampaignSpec::standard("irb2400", 3).unwrap();
    let mut rng = StdRng::seed_from_u64(11);
    let truth = CalibratedModel {
        robot: perturb_robot(&spec.nominal, &spec, &mut rng),
        world_to_base: crate::geometry::pose_from_xyz_rpy_deg(
            [1500.0, -200.0, 300.0],
            [5.0, -3.0, 170.0],
        )
        .unwrap(),
        flange_to_tool: crate::geometry::pose_from_xyz_rpy_deg(
            [2.0, 58.0, 113.0],
            [0.5, -0.8, 1.0],
        )
        .unwrap(),
    };
    let data: Vec<Measurement> = (0..40)
        .map(|_| {
            let q: Vec<f64> = truth
                .robot
                .joints
                .iter()
                .map(|j| rng.random_range(0.6 * j.min_rad..0.6 * j.max_rad))
                .collect();
            let pose = truth.world_to_tool(&q).unwrap();
            let observed = match instrument {
                Instrument::Camera => Observed::Pose {
                    world_to_tool: pose,
                    covariance: None,
                },
                Instrument::Tracker => Observed::Position {
                    position_mm: pose.translation.vector,
                    covariance: None,
                },
            };
            Measurement {
                joints_rad: q,
                observed,
            }
        })
        .collect();
    let mut start = CalibratedModel {
        robot: spec.nominal.clone(),
        world_to_base: Pose::identity(),
        flange_to_tool: match instrument {
            Instrument::Camera => spec.flange_to_camera_guess,
            Instrument::Tracker => Pose::translation(0.0, 60.0, 110.0),
        },
    };
    start.world_to_base = initial_world_to_base(&start, &data).unwrap();
    (truth, start, data)
}

#[test]
fn noise_free_campaigns_are_recovered_exactly_in_both_modes() {
    for instrument in [Instrument::Camera, Instrument::Tracker] {
        let (_, start, data) = setup(instrument);
        for mode in [IdentifyMode::Weighted, IdentifyMode::Paper] {
            let id = identify(&start, instrument, &data, mode.into()).unwrap();
            let (before, _) = validate(&id.before, &data).unwrap();
            let (after, _) = validate(&id.model, &data).unwrap();
            assert!(
                before.norm.mean_mm > 0.3,
                "{instrument:?} {mode:?}: {before:?}"
            );
            assert!(
                after.norm.max_mm < EXACT_TOL_MM,
                "{instrument:?} {mode:?}: {after:?}"
            );
            assert_eq!(id.identifiability.fixed.len(), 6);
            let free_std: Vec<f64> = id
                .identifiability
                .free
                .iter()
                .map(|&i| id.std_devs[i])
                .collect();
            assert!(
                free_std.iter().all(|s| *s < 1e-6),
                "exact data, no uncertainty"
            );
        }
    }
}

#[test]
fn bad_input_is_an_error_value() {
    let (_, start, mut data) = setup(Instrument::Camera);
    assert!(matches!(
        identify(
            &start,
            Instrument::Camera,
            &[],
            IdentifyMode::Weighted.into()
        ),
        Err(IdentifyError::NoPoses)
    ));
    let good = data.clone();
    data[3].joints_rad.pop();
    assert!(matches!(
        identify(
            &start,
            Instrument::Camera,
            &data,
            IdentifyMode::Weighted.into()
        ),
        Err(IdentifyError::Pose { pose: 3, .. })
    ));
    let mut data = good.clone();
    data[5].observed = Observed::Position {
        position_mm: Vector3::zeros(),
        covariance: None,
    };
    assert!(matches!(
        identify(
            &start,
            Instrument::Camera,
            &data,
            IdentifyMode::Weighted.into()
        ),
        Err(IdentifyError::WrongMeasurement { pose: 5, .. })
    ));
    let mut data = good;
    if let Observed::Pose { covariance, .. } = &mut data[2].observed {
        *covariance = Some(-Matrix6::identity());
    }
    assert!(matches!(
        identify(
            &start,
            Instrument::Camera,
            &data,
            IdentifyMode::Weighted.into()
        ),
        Err(IdentifyError::BadCovariance { pose: 2 })
    ));
}

#[test]
fn holdout_takes_every_kth_pose() {
    let (cal, val) = holdout_split(10, 0.3);
    assert_eq!(val, [2, 5, 8]);
    assert_eq!(cal.len(), 7);
    assert_eq!(holdout_split(4, 0.0).1.len(), 0);
}

/// Joint noise added to the recorded joints is estimated from the
/// pose-level residuals (variance components) when the measurement
/// covariances are right.
#[test]
fn joint_noise_is_estimated_from_the_pose_residuals() {
    const JOINT_SIGMA_RAD: f64 = 2e-4;
    const POSITION_SIGMA_MM: f64 = 0.01;
    const ROTATION_SIGMA_RAD: f64 = 2e-5;
    const REL_TOL: f64 = 0.35;
    let (_, start, mut data) = setup(Instrument::Camera);
    let mut rng = StdRng::seed_from_u64(5);
    let mut gauss = |s: f64| -> f64 {
        // Box–Muller from two uniforms.
        let (u, v): (f64, f64) = (rng.random_range(1e-12..1.0), rng.random_range(0.0..1.0));
        s * (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    };
    let cov = Matrix6::from_diagonal(&nalgebra::Vector6::new(
        POSITION_SIGMA_MM.powi(2),
        POSITION_SIGMA_MM.powi(2),
        POSITION_SIGMA_MM.powi(2),
        ROTATION_SIGMA_RAD.powi(2),
        ROTATION_SIGMA_RAD.powi(2),
        ROTATION_SIGMA_RAD.powi(2),
    ));
    for m in &mut data {
        for q in &mut m.joints_rad {
            *q += gauss(JOINT_SIGMA_RAD);
        }
        if let Observed::Pose {
            world_to_tool,
            covariance,
        } = &mut m.observed
        {
            let d = nalgebra::Vector6::new(
                gauss(POSITION_SIGMA_MM),
                gauss(POSITION_SIGMA_MM),
                gauss(POSITION_SIGMA_MM),
                gauss(ROTATION_SIGMA_RAD),
                gauss(ROTATION_SIGMA_RAD),
                gauss(ROTATION_SIGMA_RAD),
            );
            *world_to_tool = crate::geometry::perturb_left(world_to_tool, &d);
            *covariance = Some(cov);
        }
    }
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::Estimate,
    };
    let id = identify(&start, Instrument::Camera, &data, options).unwrap();
    let rel = id.joint_sigma_rad / JOINT_SIGMA_RAD - 1.0;
    assert!(
        rel.abs() < REL_TOL,
        "estimated {:e} rad",
        id.joint_sigma_rad
    );
    // Told there is none, the fit leaves it at zero.
    let id = identify(
        &start,
        Instrument::Camera,
        &data,
        IdentifyMode::Weighted.into(),
    )
    .unwrap();
    assert_eq!(id.joint_sigma_rad, 0.0);
}
