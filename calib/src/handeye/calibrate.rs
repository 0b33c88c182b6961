//! The flange-pose hand–eye end to end (issue 14): PnP and a robust
//! AX = XB start, the consensus of per-pose board estimates for a first
//! inlier set, then the bundle on image points ([`super::bundle`]) refitted
//! until the residual screening ([`super::screen`]) stops changing the set.

use nalgebra::{DVector, Matrix6, Vector6};

use super::bundle::{
    fit_bundle, BundleFit, BundleFreedom, BundleModel, Pairs, BUNDLE_INTRINSICS, PINHOLE_INTRINSICS,
};
use super::error::HandEyeError;
use super::noise::{fit_with_flange_noise, FlangeNoise};
use super::result::{FlangeCalibration, JackknifeSigma, PoseSigma, PoseVerdict};
use super::robust::robust_limit;
use super::start::{board_consensus, board_estimates, board_probe, robust_hand_eye};
use super::view::FlangeView;
use crate::camera::estimate_pose;
use crate::camera::model::{Intrinsics, IntrinsicsStdDev};
use crate::camera::observations::MIN_DOTS_PER_VIEW;
use crate::geometry::{perturb_left, pose_error, Pose};
use crate::solver::finite_difference_jacobian;

/// Fewest poses that agree with their images for a hand–eye (two motions
/// with distinct rotation axes).
pub const MIN_POSES: usize = 3;
/// Fit / re-screen rounds before the inlier set is taken as it stands.
const MAX_ROUNDS: usize = 6;

/// How to run [`calibrate_flange`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlangeOptions {
    /// The camera guess the bundle starts from (and PnP uses).
    pub start_intrinsics: Intrinsics,
    /// Refine k1, k2, p1, p2 (k3 stays at the guess); else the pinhole only.
    pub distortion: bool,
    /// Hold every intrinsic at `start_intrinsics` (a camera calibrated from
    /// the images alone): the robot poses then cannot bend the camera.
    pub hold_intrinsics: bool,
    /// Refine the board scale (a printed pitch in doubt).
    pub fit_board_scale: bool,
    /// Let the flange poses carry noise, estimated from the data
    /// ([`super::noise`]), in the final fit; else they are exact.
    pub estimate_flange_noise: bool,
}

/// Hand–eye, board and intrinsics from controller flange poses.
pub fn calibrate_flange(
    views: &[FlangeView],
    options: &FlangeOptions,
) -> Result<FlangeCalibration, HandEyeError> {
    let flanges: Vec<Pose> = views.iter().map(|v| v.base_to_flange).collect();
    let pairs: Vec<_> = views.iter().map(FlangeView::pairs).collect();
    let refs: Vec<&Pairs> = pairs.iter().map(Vec::as_slice).collect();
    calibrate_pairs(&flanges, &refs, options)
}

/// [`calibrate_flange`] on `(target point, pixel)` pairs per pose.
pub fn calibrate_pairs(
    flanges: &[Pose],
    pairs: &[&Pairs],
    options: &FlangeOptions,
) -> Result<FlangeCalibration, HandEyeError> {
    let Screened {
        fit,
        freedom,
        inliers,
        per_pose,
        rounds,
    } = screen_pairs(flanges, pairs, options)?;
    let views: Vec<(Pose, &Pairs)> = inliers.iter().map(|&k| (flanges[k], pairs[k])).collect();
    let (fit, freedom, noise) = if options.estimate_flange_noise {
        let (fit, noise) = fit_with_flange_noise(
            &views,
            &fit.model,
            &freedom,
            FlangeNoise::start(fit.sigma_px),
        )?;
        let freedom = fit.freedom.clone();
        (fit, freedom, Some(noise))
    } else {
        (fit, freedom, None)
    };
    let jackknife = jackknife(&views, &fit, &freedom);
    let mut result = report(&fit, per_pose, rounds, jackknife);
    result.flange_noise = noise;
    Ok(result)
}

/// The screened bundle: the fit on the inliers and every pose's verdict.
pub(super) struct Screened {
    pub(super) fit: BundleFit,
    pub(super) freedom: BundleFreedom,
    /// Indices of the poses the fit used.
    pub(super) inliers: Vec<usize>,
    pub(super) per_pose: Vec<PoseVerdict>,
    pub(super) rounds: usize,
}

/// PnP, the robust start, the board consensus and the bundle refitted
/// until the residual screening stops changing the inliers (module doc);
/// no jackknife (its leave-one-out refits cost `O(n^2)`), no flange noise.
pub(super) fn screen_pairs(
    flanges: &[Pose],
    pairs: &[&Pairs],
    options: &FlangeOptions,
) -> Result<Screened, HandEyeError> {
    let n = flanges.len();
    if pairs.len() != n {
        return Err(HandEyeError::BadPose {
            pose: n.min(pairs.len()),
            reason: format!("{n} flange poses but {} images", pairs.len()),
        });
    }
    let mut reasons: Vec<Option<String>> = vec![None; n];
    let mut cameras: Vec<Option<Pose>> = vec![None; n];
    for k in 0..n {
        let h = flanges[k].to_homogeneous();
        if h.iter().any(|v| !v.is_finite()) {
            reasons[k] = Some("the flange pose is not finite".into());
            continue;
        }
        if pairs[k].len() < MIN_DOTS_PER_VIEW {
            reasons[k] = Some(format!(
                "only {} board points, at least {MIN_DOTS_PER_VIEW} are needed",
                pairs[k].len()
            ));
            continue;
        }
        match estimate_pose(&options.start_intrinsics, pairs[k], None) {
            Ok(e) => cameras[k] = Some(e.target_to_camera),
            Err(e) => reasons[k] = Some(format!("no camera pose from the image: {e}")),
        }
    }
    let usable: Vec<usize> = (0..n).filter(|&k| cameras[k].is_some()).collect();
    if usable.len() < MIN_POSES {
        return Err(HandEyeError::TooFewPoses {
            usable: usable.len(),
            required: MIN_POSES,
        });
    }
    // Consensus of the per-pose board estimates.
    let b: Vec<Pose> = usable.iter().map(|&k| flanges[k]).collect();
    let c: Vec<Pose> = usable.iter().filter_map(|&k| cameras[k]).collect();
    let hand_eye = robust_hand_eye(&b, &c)?;
    let estimates = board_estimates(&b, &c, &hand_eye);
    let probe = board_probe(
        usable
            .iter()
            .flat_map(|&k| pairs[k].iter().map(|(p, _)| *p)),
    );
    let (medoid, dev) =
        board_consensus(&estimates, &probe).ok_or(HandEyeError::DegenerateMotion)?;
    let mut deviation_mm = vec![f64::NAN; n];
    for (i, &k) in usable.iter().enumerate() {
        deviation_mm[k] = dev[i];
    }
    let limit_mm = robust_limit(&dev);
    let mut inliers: Vec<usize> = usable
        .iter()
        .copied()
        .filter(|&k| deviation_mm[k] <= limit_mm)
        .collect();
    let freedom = BundleFreedom {
        intrinsics: if options.hold_intrinsics {
            Vec::new()
        } else if options.distortion {
            (0..BUNDLE_INTRINSICS).collect()
        } else {
            PINHOLE_INTRINSICS.to_vec()
        },
        board_scale: options.fit_board_scale,
        flange_weights: None,
    };
    let mut model = BundleModel {
        intrinsics: options.start_intrinsics,
        target_to_base: estimates[medoid],
        flange_to_camera: hand_eye,
        board_scale: 1.0,
    };
    let mut rounds = 0;
    let (fit, rms, limit_px) = loop {
        rounds += 1;
        if inliers.len() < MIN_POSES {
            return Err(HandEyeError::TooFewPoses {
                usable: inliers.len(),
                required: MIN_POSES,
            });
        }
        let views: Vec<(Pose, &Pairs)> = inliers.iter().map(|&k| (flanges[k], pairs[k])).collect();
        let fit = fit_bundle(&views, &model, &freedom)?;
        model = fit.model;
        let rms: Vec<f64> = (0..n)
            .map(|k| model.view_rms_px(&flanges[k], pairs[k]))
            .collect();
        let in_rms: Vec<f64> = inliers.iter().map(|&k| rms[k]).collect();
        let limit_px = robust_limit(&in_rms);
        let next: Vec<usize> = usable
            .iter()
            .copied()
            .filter(|&k| rms[k] <= limit_px)
            .collect();
        if next == inliers || rounds >= MAX_ROUNDS {
            break (fit, rms, limit_px);
        }
        inliers = next;
    };
    let mut is_inlier = vec![false; n];
    for &k in &inliers {
        is_inlier[k] = true;
    }
    let per_pose = (0..n)
        .map(|k| {
            let outlier = !is_inlier[k];
            let reason = reasons[k].clone().or_else(|| {
                outlier.then(|| {
                    format!(
                        "reprojection RMS {:.2} px predicted from its robot pose by the fit of the \
                         other poses (limit {limit_px:.2} px); its own board estimate lies {:.1} mm \
                         from the consensus (limit {limit_mm:.1} mm): the robot pose contradicts the image",
                        rms[k], deviation_mm[k]
                    )
                })
            });
            PoseVerdict {
                outlier,
                reason,
                rms_px: rms[k],
                board_deviation_mm: deviation_mm[k],
            }
        })
        .collect();
    Ok(Screened {
        fit,
        freedom,
        inliers,
        per_pose,
        rounds,
    })
}

/// One leave-one-out refit, relative to the full fit.
struct LeaveOneOut {
    flange_to_camera: Vector6<f64>,
    target_to_base: Vector6<f64>,
    board_scale: f64,
}

/// Leave each pose out in turn and refit from the solution (see
/// [`JackknifeSigma`]); `None` when fewer than `MIN_POSES + 1` poses.
fn jackknife(
    views: &[(Pose, &Pairs)],
    fit: &BundleFit,
    freedom: &BundleFreedom,
) -> Option<JackknifeSigma> {
    let n = views.len();
    if n <= MIN_POSES {
        return None;
    }
    let mut samples = Vec::with_capacity(n);
    for drop in 0..n {
        let kept: Vec<(Pose, &Pairs)> = views
            .iter()
            .enumerate()
            .filter(|(k, _)| *k != drop)
            .map(|(_, v)| *v)
            .collect();
        let m = fit_bundle(&kept, &fit.model, freedom).ok()?.model;
        let x = pose_error(&m.flange_to_camera, &fit.model.flange_to_camera);
        let t = pose_error(&m.target_to_base, &fit.model.target_to_base);
        samples.push(LeaveOneOut {
            flange_to_camera: x,
            target_to_base: t,
            board_scale: m.board_scale,
        });
    }
    let nf = n as f64;
    let factor = (nf - 1.0) / nf;
    let spread6 = |pick: &dyn Fn(&LeaveOneOut) -> Vector6<f64>| {
        let mean = samples.iter().map(pick).sum::<Vector6<f64>>() / nf;
        let cov = samples
            .iter()
            .map(|s| (pick(s) - mean) * (pick(s) - mean).transpose())
            .sum::<Matrix6<f64>>()
            * factor;
        PoseSigma::from_covariance(&cov)
    };
    let mean_scale = samples.iter().map(|s| s.board_scale).sum::<f64>() / nf;
    let var_scale = factor
        * samples
            .iter()
            .map(|s| (s.board_scale - mean_scale).powi(2))
            .sum::<f64>();
    Some(JackknifeSigma {
        flange_to_camera: spread6(&|s| s.flange_to_camera),
        target_to_base: spread6(&|s| s.target_to_base),
        board_scale: freedom.board_scale.then(|| var_scale.sqrt()),
    })
}

/// Standard deviations of the intrinsics from the bundle's covariance.
fn intrinsics_sigma(fit: &BundleFit) -> IntrinsicsStdDev {
    let mut s = [0.0; BUNDLE_INTRINSICS];
    let mut cov_fx_fy = 0.0;
    let idx = |name: usize| fit.freedom.intrinsics.iter().position(|&i| i == name);
    for (k, &i) in fit.freedom.intrinsics.iter().enumerate() {
        s[i] = fit.covariance[(k, k)].max(0.0).sqrt();
    }
    if let (Some(a), Some(b)) = (idx(0), idx(1)) {
        cov_fx_fy = fit.covariance[(a, b)];
    }
    let cam = &fit.model.intrinsics;
    // m = fy / fx, first-order propagation.
    let (dfx, dfy) = (-cam.fy / (cam.fx * cam.fx), 1.0 / cam.fx);
    let var_m = dfx * dfx * s[0] * s[0] + dfy * dfy * s[1] * s[1] + 2.0 * dfx * dfy * cov_fx_fy;
    IntrinsicsStdDev {
        fx: s[0],
        fy: s[1],
        scale_ratio: var_m.max(0.0).sqrt(),
        cx: s[2],
        cy: s[3],
        k1: s[4],
        k2: s[5],
        p1: s[6],
        p2: s[7],
        k3: 0.0,
    }
}

/// Covariance of `base_to_target = target_to_base^-1` from that of
/// `target_to_base` (both in `pose_error` coordinates).
fn inverse_covariance(target_to_base: &Pose, cov: &Matrix6<f64>) -> Matrix6<f64> {
    let inv = target_to_base.inverse();
    let map = |d: &DVector<f64>| {
        let moved = perturb_left(target_to_base, &Vector6::from_column_slice(d.as_slice()));
        Some(DVector::from_column_slice(
            pose_error(&moved.inverse(), &inv).as_slice(),
        ))
    };
    let j = finite_difference_jacobian(map, &DVector::zeros(6))
        .map(|j| Matrix6::from_fn(|r, c| j[(r, c)]))
        .unwrap_or_else(Matrix6::identity);
    j * cov * j.transpose()
}

fn report(
    fit: &BundleFit,
    per_pose: Vec<PoseVerdict>,
    rounds: usize,
    jackknife: Option<JackknifeSigma>,
) -> FlangeCalibration {
    let m = &fit.model;
    let t_cov = fit.block6(fit.target_to_base_offset());
    let x_cov = fit.block6(fit.flange_to_camera_offset());
    let b_cov = inverse_covariance(&m.target_to_base, &t_cov);
    FlangeCalibration {
        intrinsics: m.intrinsics,
        intrinsics_sigma: intrinsics_sigma(fit),
        flange_to_camera: m.flange_to_camera,
        flange_to_camera_sigma: PoseSigma::from_covariance(&x_cov),
        flange_to_camera_covariance: x_cov,
        target_to_base: m.target_to_base,
        target_to_base_sigma: PoseSigma::from_covariance(&t_cov),
        base_to_target: m.target_to_base.inverse(),
        base_to_target_sigma: PoseSigma::from_covariance(&b_cov),
        board_scale: m.board_scale,
        board_scale_sigma: fit.board_scale_sigma(),
        jackknife,
        flange_noise: None,
        rms_px: fit.rms_px,
        sigma_px: fit.sigma_px,
        points: fit.points,
        per_pose,
        rounds,
    }
}
