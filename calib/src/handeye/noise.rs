//! The noise of the controller's flange poses, estimated from the data
//! (issue 14 **beyond**): the bundle with per-pose flange corrections
//! ([`super::bundle::BundleFreedom::flange_weights`]) is refitted while
//! the pixel, flange-translation and flange-rotation variances are
//! re-estimated from their residuals and redundancies (variance-component
//! estimation, as the joint noise in `kinematics::weights`). The images
//! then keep their own weight for the camera, and the formal covariance
//! includes the robot's pose errors.

use nalgebra::Vector6;
use serde::{Deserialize, Serialize};

use super::bundle::{fit_bundle, BundleFit, BundleFreedom, BundleModel, Pairs};
use crate::geometry::Pose;
use crate::kinematics::measurement::{DEFAULT_POSITION_SIGMA_MM, DEFAULT_ROTATION_SIGMA_RAD};
use crate::solver::SolverError;

/// Re-estimation rounds at most.
const MAX_ROUNDS: usize = 12;
/// Stop when every variance factor is this close to one.
const FACTOR_TOLERANCE: f64 = 0.02;
/// Noise floors: exact flange poses drive the estimate towards zero.
const MIN_TRANSLATION_MM: f64 = 1e-4;
const MIN_ROTATION_RAD: f64 = 1e-7;
/// Redundancy below this leaves a variance as it is.
const MIN_REDUNDANCY: f64 = 1e-3;

/// Noise of the data as estimated.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FlangeNoise {
    /// Dot-centre noise per image axis (px).
    pub pixel_px: f64,
    /// Flange-pose noise per axis: translation (mm) and rotation (rad).
    pub translation_mm: f64,
    pub rotation_rad: f64,
}

impl FlangeNoise {
    /// The starting guess: the pixel noise given, the flange noise of a
    /// pose given without covariance (`kinematics::measurement`).
    pub fn start(pixel_px: f64) -> Self {
        Self {
            pixel_px,
            translation_mm: DEFAULT_POSITION_SIGMA_MM,
            rotation_rad: DEFAULT_ROTATION_SIGMA_RAD,
        }
    }

    fn weights(&self) -> Vector6<f64> {
        let (t, r) = (
            self.pixel_px / self.translation_mm,
            self.pixel_px / self.rotation_rad,
        );
        Vector6::new(t, t, t, r, r, r)
    }
}

/// Fit with flange corrections and estimated noise (module doc).
pub fn fit_with_flange_noise(
    views: &[(Pose, &Pairs)],
    start: &BundleModel,
    freedom: &BundleFreedom,
    initial: FlangeNoise,
) -> Result<(BundleFit, FlangeNoise), SolverError> {
    let mut noise = initial;
    let mut model = *start;
    let mut round = 0;
    loop {
        round += 1;
        let with_prior = BundleFreedom {
            flange_weights: Some(noise.weights()),
            ..freedom.clone()
        };
        let fit = fit_bundle(views, &model, &with_prior)?;
        model = fit.model;
        let Some(c) = fit.components else {
            return Ok((fit, noise));
        };
        let variance =
            |(ss, redundancy): (f64, f64)| (redundancy > MIN_REDUNDANCY).then(|| ss / redundancy);
        let Some(pixel_var) = variance(c.pixel) else {
            return Ok((fit, noise));
        };
        // Prior rows are in pixel units: their variance over the pixel
        // variance is the factor by which the flange sigma was wrong.
        let factor = |g: (f64, f64)| variance(g).map_or(1.0, |v| v / pixel_var);
        let (ft, fr) = (factor(c.translation), factor(c.rotation));
        let converged = round > 1
            && (ft - 1.0).abs() < FACTOR_TOLERANCE
            && (fr - 1.0).abs() < FACTOR_TOLERANCE
            && (pixel_var.sqrt() / noise.pixel_px - 1.0).abs() < FACTOR_TOLERANCE;
        if converged || round >= MAX_ROUNDS {
            return Ok((fit, noise));
        }
        noise = FlangeNoise {
            pixel_px: pixel_var.sqrt(),
            translation_mm: (noise.translation_mm * ft.sqrt()).max(MIN_TRANSLATION_MM),
            rotation_rad: (noise.rotation_rad * fr.sqrt()).max(MIN_ROTATION_RAD),
        };
    }
}
