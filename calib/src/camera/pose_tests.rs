//! Pose estimation and its covariance (method.md §4).

use nalgebra::{Point2, Point3};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, Normal};

use super::*;
use crate::sim::point_views::{simulate_views, ViewCampaignSpec};

/// Noise realisations for the covariance check.
const REALISATIONS: usize = 200;

#[test]
fn pose_covariance_matches_the_scatter_of_repeated_estimates() {
    let spec = ViewCampaignSpec {
        views: 1,
        noise_px: 0.0,
        ..ViewCampaignSpec::modern_1280x1024(21)
    };
    let sim = &simulate_views(&spec).unwrap()[0];
    let truth = sim.camera_to_target.inverse();
    let exact: Vec<(Point3<f64>, Point2<f64>)> = sim
        .observations
        .dots
        .iter()
        .zip(&sim.true_centre_images)
        .map(|(d, c)| (d.target_mm, *c))
        .collect();
    let sigma = 0.02;
    let noise = Normal::new(0.0, sigma).unwrap();
    let mut rng = StdRng::seed_from_u64(5);
    let mut errors = Vec::new();
    let mut predicted = None;
    for _ in 0..REALISATIONS {
        let noisy: Vec<_> = exact
            .iter()
            .map(|(t, p)| {
                (
                    *t,
                    p + nalgebra::Vector2::new(noise.sample(&mut rng), noise.sample(&mut rng)),
                )
            })
            .collect();
        let est = estimate_pose(&spec.intrinsics, &noisy, None).unwrap();
        assert!((est.rms_px / (sigma * std::f64::consts::SQRT_2) - 1.0).abs() < 0.25);
        errors.push(pose_error(&est.target_to_camera, &truth));
        predicted = Some(est.covariance_6x6);
    }
    let cov = predicted.unwrap();
    for k in 0..6 {
        let empirical =
            (errors.iter().map(|e| e[k] * e[k]).sum::<f64>() / REALISATIONS as f64).sqrt();
        let model = cov[(k, k)].sqrt();
        println!("component {k}: empirical sd {empirical:.3e} predicted {model:.3e}");
        assert!((empirical / model - 1.0).abs() < 0.2, "component {k}");
    }
}

#[test]
fn degenerate_pose_input_is_refused() {
    let cam = Intrinsics::pinhole(1000.0, 1000.0, 640.0, 512.0);
    let line: Vec<_> = (0..10)
        .map(|i| (Point3::new(i as f64, 0.0, 0.0), Point2::new(i as f64, 0.0)))
        .collect();
    assert!(matches!(
        estimate_pose(&cam, &line, None),
        Err(CameraError::CollinearPoints { .. })
    ));
    assert!(matches!(
        estimate_pose(&cam, &line[..3], None),
        Err(CameraError::TooFewPoints { .. })
    ));
}
