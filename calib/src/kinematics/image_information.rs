//! The Fisher information of a camera campaign's image points (method.md
//! §6.9 "The Cramér–Rao bound"): the joint refinement's own normal matrix
//! ([`super::image_fit`]) evaluated at given (true) parameters with the
//! noise known, each pose's joint corrections eliminated by their Schur
//! complement.
//!
//! With Gaussian dot noise the Fisher information of the unknowns is
//! `Jᵀ R⁻¹ J`; the joint refinement's residuals are already whitened, and
//! its per-pose joint corrections with the prior `e / σ_q` are, for the
//! linearised problem, exactly the marginal covariance `σ_px² I + J_e σ_q²
//! J_eᵀ` of that pose's dots (method.md §6.4). Eliminating them therefore
//! gives the information with the encoder noise marginalised, without
//! forming the dense per-pose covariance. The observed pixels do not enter
//! (only the gradient would use them).

use nalgebra::{DMatrix, DVector};

use super::identify_error::IdentifyError;
use super::identify_options::JointNoise;
use super::image_fit::{ImageFit, ImageTerms};
use super::image_pose::{ImageNoise, ImagePose};
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, Instrument, ParamLayout};
use crate::camera::model::Intrinsics;

/// Where the information is evaluated and what is unknown.
#[derive(Debug, Clone, Copy)]
pub struct InformationInput<'a> {
    /// The parameters (usually the truth) and their layout's reference.
    pub model: &'a CalibratedModel,
    pub intrinsics: &'a Intrinsics,
    /// Non-geometric terms whose values are unknowns too (with their values
    /// at `model`); `None` or no terms: geometry only.
    pub terms: Option<&'a NonGeometric>,
    /// Recorded joints and the board points each image sees (the pixels
    /// are not used).
    pub poses: &'a [ImagePose],
    /// Layout indices that are unknowns.
    pub free: &'a [usize],
    /// Dot noise per image axis (px) and joint-encoder noise (rad), known.
    pub sigma_px: f64,
    pub joint_sigma_rad: f64,
    /// The intrinsics are known (not unknowns).
    pub hold_intrinsics: bool,
}

/// The Fisher information of the head unknowns, in the order of the joint
/// refinement's head: `free` layout values, the term values, then the
/// intrinsics ([`super::projection::INTRINSIC_NAMES`], unless held).
pub fn image_information(input: &InformationInput) -> Result<DMatrix<f64>, IdentifyError> {
    if input.poses.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    let layout = ParamLayout::new(&input.model.robot, Instrument::Camera);
    let mut bases = Vec::with_capacity(input.poses.len());
    for (pose, p) in input.poses.iter().enumerate() {
        input
            .model
            .robot
            .base_to_flange(&p.joints_rad)
            .map_err(|source| IdentifyError::Pose { pose, source })?;
        if let Some(t) = input.terms {
            bases.push(
                t.basis(&p.joints_rad)
                    .map_err(|source| IdentifyError::Pose { pose, source })?,
            );
        }
    }
    let sigma_px = if input.sigma_px.is_finite() && input.sigma_px > 0.0 {
        input.sigma_px
    } else {
        return Err(IdentifyError::BadCovariance { pose: 0 });
    };
    let problem = ImageFit {
        layout: &layout,
        reference: input.model,
        intrinsics: input.intrinsics,
        free: input.free,
        poses: input.poses,
        noise: ImageNoise {
            sigma_px,
            joint: JointNoise::Known {
                sigma_rad: input.joint_sigma_rad.abs(),
            },
        },
        hold_intrinsics: input.hold_intrinsics,
        extra_bases: &[],
        session_of: &[],
        terms: input.terms.map(|terms| ImageTerms {
            terms,
            bases: &bases,
        }),
        prior: None,
    };
    let x = DVector::zeros(problem.params());
    let (normal, _) = problem
        .arrow_normal_equations(&x)
        .ok_or(IdentifyError::NoPoses)?;
    normal
        .schur_complement()
        .ok_or(IdentifyError::BadCovariance { pose: 0 })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::joint_covariance::joint_refine_covariance;
    use crate::kinematics::joint_refine::joint_refine;
    use crate::sim::campaign::{simulate_campaign, CampaignSpec};
    use crate::sim::campaign_io::PoseSet;

    /// At a refinement's own solution, with its noise, the information is
    /// the inverse of the covariance `joint_refine_covariance` reports
    /// (which scales by the residual variance: compared up to that factor).
    #[test]
    fn information_inverts_the_refinements_covariance() {
        let mut spec = CampaignSpec::standard("puma560", 5).unwrap();
        spec.cal_poses = 12;
        spec.val_poses = 1;
        spec.encoder_sigma_deg = 0.002;
        let campaign = simulate_campaign(&spec).unwrap();
        let truth = campaign.truth.model().unwrap();
        let poses: Vec<ImagePose> = campaign
            .poses
            .iter()
            .filter(|p| p.set == PoseSet::Cal)
            .map(|p| ImagePose {
                joints_rad: p.joints_rad.clone(),
                observations: p.observations(&campaign.truth.board),
            })
            .collect();
        let layout = ParamLayout::new(&truth.robot, Instrument::Camera);
        let free: Vec<usize> = (layout.base_start()..layout.len()).collect();
        let noise = ImageNoise {
            sigma_px: spec.pixel_sigma_px,
            joint: JointNoise::Known {
                sigma_rad: spec.encoder_sigma_deg.to_radians(),
            },
        };
        let fit = joint_refine(&truth, &spec.intrinsics, &poses, &free, noise, true).unwrap();
        let covariance = joint_refine_covariance(&fit, &poses, &free, true).unwrap();
        let information = image_information(&InformationInput {
            model: &fit.model,
            intrinsics: &fit.intrinsics,
            terms: None,
            poses: &poses,
            free: &free,
            sigma_px: spec.pixel_sigma_px,
            joint_sigma_rad: spec.encoder_sigma_deg.to_radians(),
            hold_intrinsics: true,
        })
        .unwrap();
        let block = DMatrix::from_fn(free.len(), free.len(), |r, c| {
            covariance[(free[r], free[c])]
        });
        let bound = crate::bound::cramer_rao::invert_information(&information).0;
        // The residual variance factor, common to every entry.
        let factor = block.trace() / bound.trace();
        assert!((0.5..2.0).contains(&factor), "variance factor {factor}");
        // Compared as correlations-scaled entries (the units differ).
        let n = free.len();
        let off = DMatrix::from_fn(n, n, |r, c| {
            let scale = (block[(r, r)] * block[(c, c)]).sqrt();
            (block[(r, c)] - factor * bound[(r, c)]) / scale
        })
        .amax();
        assert!(off < 1e-3, "the covariances differ by {off} (scaled)");
    }
}
