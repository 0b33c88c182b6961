//! Non-geometric terms selected in the image-level joint refinement
//! (issue 19, method.md §6 "beyond"): for a camera campaign the pose-level
//! selection ([`super::term_selection`]) sees each image only through a
//! pose measured with the camera step's intrinsics, whose error is shared
//! by every pose; terms of a few tens of µrad drown in it (on the
//! simulator: σ of a periodic term 2–4x its size). On the image points,
//! with the intrinsics refined together, the same terms stand out.
//!
//! 1. **Candidates**: every candidate the pose-level analysis found
//!    identifiable (its geometric span and lever tests, step 2 there).
//! 2. **Joint fit**: all candidates refined with geometry, hand–eye and
//!    intrinsics on the image points ([`joint_refine_with_terms`]); the
//!    covariance of the term values, marginal over everything else, from
//!    that fit's inverse normal matrix.
//! 3. **Backward elimination**: the least significant term is dropped
//!    while its `|value| / σ` is below the Bonferroni threshold
//!    (family-wise [`FAMILY_FALSE_POSITIVE`]); each drop conditions the
//!    others on it being zero (`v_r -= C_rj v_j / C_jj`, `C_rr -= C_rj C_jr
//!    / C_jj`: the constrained least-squares solution of the linearised
//!    fit), so only one image-level fit is needed for the whole path.
//! 4. **Refit and information criterion**: the survivors are refined again
//!    (geometry from the geometric fit's), re-tested, and kept only if they
//!    lower the Bayesian information criterion `χ² + k ln n` against the
//!    geometric refinement, both weighted with the dot and joint noise the
//!    refit with the terms estimated (`n` image rows). With the noise
//!    re-estimated per fit the two would not compare: without the terms the
//!    joint corrections soak up their effect and the estimated joint noise
//!    grows, which lowers the image residual instead of the cost.

use nalgebra::{DMatrix, DVector};

use super::identify_error::IdentifyError;
use super::identify_options::JointNoise;
use super::image_pose::{ImageNoise, ImagePose};
use super::joint_refine::{joint_refine, joint_refine_with_terms, JointRefinement};
use super::nongeometric::NonGeometric;
use super::term_elimination::bonferroni_z;
use super::term_report::{line, TermReport, Verdict};
use super::term_selection::{TermIdentification, FAMILY_FALSE_POSITIVE};
use crate::camera::model::Intrinsics;

/// How the image-level selection decides, for reports.
pub const IMAGE_CRITERION: &str = "identifiable at pose level, then a Bonferroni-corrected Wald test (family-wise 1%) with backward elimination in the image-level joint refinement (geometry, hand–eye, intrinsics and terms together), then BIC (χ² + k ln n, both fits weighted with the noise the refit with the terms estimated) against the geometric refinement";
/// Refits of the survivors at most (each may drop one more term).
const MAX_REFITS: usize = 4;

/// The image-level selection and the refinement it ends with.
#[derive(Debug, Clone)]
pub struct ImageTermSelection {
    /// The selection as a report reads it: values, σ and verdicts from the
    /// image-level fits, `model` the final refinement's.
    pub selection: TermIdentification,
    /// The final refinement: with the kept terms (its `terms` set) or the
    /// geometric one when none is kept.
    pub refinement: JointRefinement,
}

/// Select `pose_level`'s identifiable candidates on the image points (see
/// the module doc); `intrinsics`, `poses`, `noise` and `hold_intrinsics`
/// as for [`joint_refine`].
pub fn select_terms_on_images(
    pose_level: &TermIdentification,
    intrinsics: &Intrinsics,
    poses: &[ImagePose],
    noise: ImageNoise,
    hold_intrinsics: bool,
) -> Result<ImageTermSelection, IdentifyError> {
    let geo = &pose_level.geometric;
    let free = &geo.identifiability.free;
    // The geometric refinement at its own noise: needed only when no term
    // is kept (the result) or none survives (the BIC's baseline).
    let refine_geometric =
        || joint_refine(&geo.model, intrinsics, poses, free, noise, hold_intrinsics);
    let mut geometric = None;
    // Report lines in the pose-level order; the candidates keep their line.
    let mut report: Vec<Option<TermReport>> = pose_level
        .report
        .iter()
        .map(|l| (l.verdict == Verdict::NotIdentifiable).then(|| l.clone()))
        .collect();
    let line_of: Vec<usize> = (0..report.len()).filter(|&i| report[i].is_none()).collect();
    let mut candidates = pose_level.terms.subset(&[]);
    candidates.terms = line_of.iter().map(|&i| pose_level.report[i].term).collect();
    candidates.values = vec![0.0; line_of.len()];
    let z_threshold = bonferroni_z(FAMILY_FALSE_POSITIVE, line_of.len().max(1));
    let n = image_rows(poses);
    let mut outcome = Outcome {
        candidates: &candidates,
        report: &mut report,
        line_of: &line_of,
        z_threshold,
    };
    let mut active: Vec<usize> = (0..candidates.terms.len()).collect();
    let mut values = DVector::zeros(0);
    if !active.is_empty() {
        let all = joint_refine_with_terms(
            &geo.model,
            intrinsics,
            poses,
            free,
            &candidates,
            noise,
            hold_intrinsics,
        )?;
        let fitted = all.terms.as_ref().ok_or(IdentifyError::NoPoses)?;
        values = DVector::from_column_slice(&fitted.terms.values);
        let covariance = fitted.covariance.terms.clone();
        outcome.eliminate(&mut active, &mut values, covariance);
    }
    let mut last = None;
    for _ in 0..MAX_REFITS {
        if active.is_empty() {
            break;
        }
        let mut kept = candidates.subset(&active);
        kept.values = values.iter().copied().collect();
        let refit = joint_refine_with_terms(
            &geo.model,
            intrinsics,
            poses,
            free,
            &kept,
            noise,
            hold_intrinsics,
        )?;
        let fitted = refit.terms.as_ref().ok_or(IdentifyError::NoPoses)?;
        values = DVector::from_column_slice(&fitted.terms.values);
        let before = active.len();
        outcome.eliminate(&mut active, &mut values, fitted.covariance.terms.clone());
        if active.len() == before {
            last = Some(refit);
            break;
        }
    }
    let (bic_geometric, bic_with_terms) = match &last {
        Some(r) => {
            // The geometric refinement at the noise the terms' refit found.
            let same_noise = ImageNoise {
                sigma_px: r.sigma_px,
                joint: JointNoise::Known {
                    sigma_rad: r.joint_sigma_rad,
                },
            };
            let plain = joint_refine(
                &geo.model,
                intrinsics,
                poses,
                free,
                same_noise,
                hold_intrinsics,
            )?;
            let k = active.len() as f64;
            (whitened_cost(&plain, n), whitened_cost(r, n) + k * n.ln())
        }
        None => {
            let g = refine_geometric()?;
            let cost = whitened_cost(&g, n);
            geometric = Some(g);
            (cost, cost)
        }
    };
    let gain = last.is_some() && bic_with_terms < bic_geometric;
    let (refinement, kept, term_std_devs, joint) = match last {
        Some(r) if gain => {
            let fitted = r.terms.clone().ok_or(IdentifyError::NoPoses)?;
            for (a, &c) in active.iter().enumerate() {
                let (v, sd) = (fitted.terms.values[a], fitted.std_devs[a]);
                outcome.set(c, Verdict::Kept, v, sd, format!(
                    "identifiable, |value|/σ = {:.1} in the image-level joint refinement, BIC {bic_with_terms:.1} < {bic_geometric:.1}",
                    v.abs() / sd
                ));
            }
            let (terms, std_devs) = (fitted.terms.clone(), fitted.std_devs.clone());
            (r, terms, std_devs, Some(fitted))
        }
        other => {
            if let Some(r) = &other {
                let fitted = r.terms.as_ref().ok_or(IdentifyError::NoPoses)?;
                for (a, &c) in active.iter().enumerate() {
                    outcome.set(c, Verdict::NoInformationGain, fitted.terms.values[a], fitted.std_devs[a],
                        format!("BIC {bic_with_terms:.1} of the image residuals not below the geometric {bic_geometric:.1}"));
                }
            }
            let g = match geometric {
                Some(g) => g,
                None => refine_geometric()?,
            };
            (g, candidates.subset(&[]), Vec::new(), None)
        }
    };
    let selection = TermIdentification {
        geometric: geo.clone(),
        model: refinement.model.clone(),
        terms: kept,
        term_std_devs,
        term_covariance: joint.as_ref().map(|j| j.covariance.clone()),
        geometric_covariance: joint.map(|j| j.geometric_covariance),
        report: report.into_iter().flatten().collect(),
        z_threshold,
        bic_geometric,
        bic_with_terms,
        criterion: IMAGE_CRITERION,
    };
    Ok(ImageTermSelection {
        selection,
        refinement,
    })
}

fn image_rows(poses: &[ImagePose]) -> f64 {
    (2 * poses.iter().map(|p| p.observations.len()).sum::<usize>()) as f64
}

/// `χ²` of a refinement over `rows` image rows: its image residuals over
/// the dot noise and its joint corrections over the joint noise.
fn whitened_cost(r: &JointRefinement, rows: f64) -> f64 {
    let image = (r.reprojection_rms_px / r.sigma_px).powi(2) * rows;
    let joints: f64 = match r.joint_sigma_rad {
        s if s > 0.0 => r
            .joint_corrections_rad
            .iter()
            .flatten()
            .map(|e| (e / s).powi(2))
            .sum(),
        _ => 0.0,
    };
    image + joints
}

/// The report lines being written and the test they use.
struct Outcome<'a> {
    candidates: &'a NonGeometric,
    report: &'a mut Vec<Option<TermReport>>,
    /// Report line of each candidate.
    line_of: &'a [usize],
    z_threshold: f64,
}

impl Outcome<'_> {
    fn set(&mut self, candidate: usize, verdict: Verdict, value: f64, sd: f64, why: String) {
        self.report[self.line_of[candidate]] =
            Some(line(self.candidates, candidate, verdict, value, sd, why));
    }

    /// Backward elimination on the linearised fit (module doc, step 3):
    /// `active` (candidate indices) with `values` and their `covariance` in
    /// the same order; the dropped are reported.
    fn eliminate(
        &mut self,
        active: &mut Vec<usize>,
        values: &mut DVector<f64>,
        mut covariance: DMatrix<f64>,
    ) {
        while !active.is_empty() {
            let z = |a: usize| {
                let var = covariance[(a, a)];
                if var > 0.0 {
                    values[a].abs() / var.sqrt()
                } else {
                    0.0
                }
            };
            let (a, z_min) = (0..active.len())
                .map(|a| (a, z(a)))
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .unwrap_or((0, f64::INFINITY));
            if z_min >= self.z_threshold {
                return;
            }
            let var = covariance[(a, a)];
            let why = if var > 0.0 {
                format!(
                    "|value|/σ = {z_min:.2} below the threshold {:.2} in the image-level joint refinement",
                    self.z_threshold
                )
            } else {
                "not identifiable in the image-level joint refinement (no variance)".to_string()
            };
            let verdict = if var > 0.0 {
                Verdict::NotSignificant
            } else {
                Verdict::NotIdentifiable
            };
            self.set(active[a], verdict, values[a], var.max(0.0).sqrt(), why);
            if var > 0.0 {
                let column = covariance.column(a).into_owned();
                *values -= &column * (values[a] / var);
                covariance -= &column * column.transpose() / var;
            }
            *values = values.clone().remove_row(a);
            covariance = covariance.remove_row(a).remove_column(a);
            active.remove(a);
        }
    }
}

#[cfg(test)]
#[path = "image_term_selection_tests.rs"]
mod tests;
