//! Non-geometric terms selected, not imposed (issue 19, method.md §6).
//!
//! 1. The geometric identification ([`identify`]) fixes the geometric free
//!    set, the weights and the starting point.
//! 2. **Identifiability**: the whitened Jacobian columns of every candidate,
//!    scaled to unit norm, are projected out of the span of the free
//!    geometric columns and of the candidates accepted before them; a term
//!    whose remainder is below [`TERM_IDENTIFIABLE_TOL`] (the sine of its
//!    angle to that span) is reported as not identifiable and never fitted;
//!    so is every term of a joint whose turning moves the measured point by
//!    less than [`MIN_LEVER_MM`] per radian (rms over the poses).
//! 3. **Joint fit + backward elimination**: the identifiable terms are
//!    fitted jointly with the geometry, base and tool; σ from the Jacobian
//!    at the solution scaled by the residual variance. The least significant
//!    term is dropped while its `|value| / σ` is below the Bonferroni
//!    threshold `z = Φ⁻¹(1 − α / 2m)` (family-wise false-positive rate
//!    [`FAMILY_FALSE_POSITIVE`] over the `m` identifiable candidates).
//! 4. **Region cross-validation**: each joint's surviving terms stay only
//!    if they lower the whitened error on held-out contiguous regions of
//!    that joint's covered range ([`super::term_cv::region_folds`]); a
//!    term that fits the covered region and nothing beyond it is reported
//!    as not generalising. The rest are refitted (step 3 again).
//! 5. **Information criterion**: the kept set stays only if it lowers the
//!    Bayesian information criterion `N ln(RSS/N) + k ln N` against the
//!    geometric fit (same weights), and lowers the error on held-out poses
//!    in a [`FOLDS`]-fold cross-validation ([`super::term_cv`]); otherwise
//!    every term is rejected.

use nalgebra::{DMatrix, DVector};

use super::identify::{identify, Identification, IdentifyError, IdentifyOptions};
use super::measurement::Measurement;
use super::nongeometric::{CandidateOptions, NonGeometric};
use super::params::{CalibratedModel, Instrument, PARAMS_PER_JOINT};
use super::refined_terms::RefinedTerms;
use super::term_cv::{held_out_costs, interleaved_folds, region_folds, FOLDS};
use super::term_elimination::{bonferroni_z, probe_like, stack, Elimination};
use super::term_fit::TermFit;
use super::term_report::line;
pub use super::term_report::{TermReport, Verdict};
use super::weights::PoseCovariances;
use crate::covariance::covariance_from_jacobian;
use crate::solver::LeastSquaresProblem;

/// Sine of a candidate's angle to the span of the geometry and the earlier
/// candidates below which it is not identifiable from the campaign.
pub const TERM_IDENTIFIABLE_TOL: f64 = 3e-2;
/// A joint whose turning moves the measured point less than this (mm/rad,
/// rms over the poses: a point within a millimetre of its axis) is not seen
/// turning, so none of its deflection terms is identifiable.
pub const MIN_LEVER_MM: f64 = 1.0;
/// Family-wise probability of keeping at least one term on a robot that has
/// none: issue 19 allows 5% of campaigns; 1% leaves room for the
/// optimism of backward elimination (the survivors' `z` is the largest).
pub const FAMILY_FALSE_POSITIVE: f64 = 0.01;
/// How the selection decides, for reports.
pub const CRITERION: &str = "Bonferroni-corrected Wald test (family-wise 1%) with backward elimination, each joint's terms cross-validated on held-out regions of that joint's range, then BIC and 5-fold cross-validation against the geometric fit";

/// Geometry plus the selected non-geometric terms.
#[derive(Debug, Clone)]
pub struct TermIdentification {
    pub geometric: Identification,
    /// Geometry, base and tool refitted jointly with the kept terms.
    pub model: CalibratedModel,
    /// The kept terms with their values.
    pub terms: NonGeometric,
    /// σ of each kept term's value, in `terms` order.
    pub term_std_devs: Vec<f64>,
    /// The kept terms' covariance with the geometry (`None` when none is
    /// kept).
    pub term_covariance: Option<super::term_model::TermCovariance>,
    /// The geometry's layout-sized covariance marginal over the kept terms
    /// (`None` when none is kept: the geometric fit's is it).
    pub geometric_covariance: Option<DMatrix<f64>>,
    pub report: Vec<TermReport>,
    pub z_threshold: f64,
    pub bic_geometric: f64,
    pub bic_with_terms: f64,
    /// How this selection decided ([`CRITERION`] at pose level,
    /// [`super::image_term_selection::IMAGE_CRITERION`] on the images).
    pub criterion: &'static str,
}

impl TermIdentification {
    /// Drops every kept term (`why`: the reason each line then states):
    /// the geometric fit becomes the model, as when the selection keeps
    /// none. The model ladder does this when the terms do not predict held-out
    /// configurations better (method.md §6.8).
    pub fn drop_terms(&mut self, why: &str) {
        for line in &mut self.report {
            if line.verdict == Verdict::Kept {
                line.verdict = Verdict::NoInformationGain;
                line.why = why.to_string();
            }
        }
        self.model = self.geometric.model.clone();
        self.terms = self.terms.subset(&[]);
        self.term_std_devs.clear();
        self.term_covariance = None;
        self.geometric_covariance = None;
    }
}

/// Identify geometry and the candidate terms of `candidates`, keeping only
/// identifiable and significant ones (see the module doc).
pub fn identify_with_terms(
    reference: &CalibratedModel,
    instrument: Instrument,
    cal: &[Measurement],
    options: IdentifyOptions,
    candidates: &CandidateOptions,
) -> Result<TermIdentification, IdentifyError> {
    let geo = identify(reference, instrument, cal, options)?;
    let all = NonGeometric::candidates(&geo.model, candidates)?;
    let w = PoseCovariances::new(&geo.layout, &geo.before, cal)?
        .whitening(geo.joint_sigma_rad, options.mode)?;
    let free = geo.identifiability.free.clone();
    let x_geo = DVector::from_iterator(free.len(), free.iter().map(|&i| geo.correction[i]));
    let every: Vec<usize> = (0..all.terms.len()).collect();
    let probe = TermFit {
        layout: &geo.layout,
        reference: &geo.before,
        free: &free,
        terms: &all,
        free_terms: &every,
        data: cal,
        whitening: &w,
    };
    let x0 = stack(&x_geo, &DVector::zeros(every.len()));
    let (r_geo, jac) = probe.evaluate(&x0, true).ok_or(IdentifyError::NoPoses)?;
    let mut report: Vec<Option<TermReport>> = vec![None; all.terms.len()];
    let remainders = remainders(&jac, free.len());
    let levers_mm = joint_levers_mm(&geo.model, &geo.layout, cal)?;
    let mut active = Vec::new();
    for (t, &sine) in remainders.iter().enumerate() {
        let joint = all.terms[t].joint();
        if levers_mm[joint] < MIN_LEVER_MM {
            report[t] = Some(line(&all, t, Verdict::NotIdentifiable, 0.0, 0.0,
                format!("not identifiable from this campaign: turning joint {} moves the measured point {:.1e} mm/rad (rms)", joint + 1, levers_mm[joint])));
        } else if sine < TERM_IDENTIFIABLE_TOL {
            report[t] = Some(line(&all, t, Verdict::NotIdentifiable, 0.0, 0.0,
                format!("not identifiable from this campaign: sine {sine:.1e} to the geometry and earlier terms")));
        } else {
            active.push(t);
        }
    }
    let z_threshold = bonferroni_z(FAMILY_FALSE_POSITIVE, active.len().max(1));
    let n_res = r_geo.len() as f64;
    let cost_geo = r_geo.norm_squared();
    let mut x_terms: Vec<f64> = vec![0.0; all.terms.len()];
    let mut geo_x = x_geo.clone();
    let mut elimination = Elimination {
        probe: &probe,
        x_terms: &mut x_terms,
        geo_x: &mut geo_x,
        report: &mut report,
        z_threshold,
    };
    let (mut active, mut final_x, mut final_sd, mut final_cost) = elimination.run(active, &all)?;
    // Region cross-validation, one joint at a time: a joint's terms stay
    // only if they lower the error on held-out regions of that joint's
    // covered range (term_cv's module doc).
    let mut dropped_any = false;
    let significant = active.clone();
    for joint in 0..reference.robot.dof() {
        let group: Vec<usize> = active
            .iter()
            .copied()
            .filter(|&t| all.terms[t].joint() == joint)
            .collect();
        if group.is_empty() {
            continue;
        }
        let rest: Vec<usize> = active
            .iter()
            .copied()
            .filter(|t| !group.contains(t))
            .collect();
        let folds = region_folds(cal, joint);
        let (cv_without, cv_with) = held_out_costs(
            &geo.layout,
            &geo.before,
            &free,
            &all,
            (&rest, &active),
            &x_geo,
            cal,
            &w,
            &folds,
        )?;
        if cv_with >= cv_without {
            for &t in &group {
                report[t] = Some(line(
                    &all,
                    t,
                    Verdict::DoesNotGeneralise,
                    x_terms[t],
                    significant
                        .iter()
                        .position(|&a| a == t)
                        .map_or(f64::NAN, |k| final_sd[k]),
                    format!(
                        "held-out regions of joint {}'s range: error {:.4} with the joint's terms, {:.4} without (rms, whitened)",
                        joint + 1,
                        (cv_with / n_res).sqrt(),
                        (cv_without / n_res).sqrt()
                    ),
                ));
            }
            active = rest;
            dropped_any = true;
        }
    }
    if dropped_any {
        let mut elimination = Elimination {
            probe: &probe,
            x_terms: &mut x_terms,
            geo_x: &mut geo_x,
            report: &mut report,
            z_threshold,
        };
        (active, final_x, final_sd, final_cost) = elimination.run(active, &all)?;
    }
    let k = active.len() as f64;
    let bic_geometric = n_res * (cost_geo / n_res).ln();
    let bic_with_terms = n_res * (final_cost / n_res).ln() + k * n_res.ln();
    let mut gain = bic_with_terms < bic_geometric;
    let mut why_not = format!("BIC {bic_with_terms:.1} not below the geometric {bic_geometric:.1}");
    if gain && !active.is_empty() {
        let (cv_geo, cv_terms) = held_out_costs(
            &geo.layout,
            &geo.before,
            &free,
            &all,
            (&[], &active),
            &x_geo,
            cal,
            &w,
            &interleaved_folds(cal.len()),
        )?;
        if cv_terms >= cv_geo {
            gain = false;
            why_not = format!(
                "{FOLDS}-fold held-out error not lowered: {:.4} vs geometric {:.4} (rms, whitened)",
                (cv_terms / n_res).sqrt(),
                (cv_geo / n_res).sqrt()
            );
        }
    }
    let fit = TermFit {
        free_terms: &active,
        ..probe_like(&probe)
    };
    let (mut model, terms) = fit.split(&final_x);
    let mut kept = terms.subset(&active);
    for (k, &t) in active.iter().enumerate() {
        report[t] = Some(if gain {
            line(
                &all,
                t,
                Verdict::Kept,
                x_terms[t],
                final_sd[k],
                format!(
                    "identifiable, |value|/σ = {:.1}, BIC {bic_with_terms:.1} < {bic_geometric:.1}",
                    x_terms[t].abs() / final_sd[k]
                ),
            )
        } else {
            line(
                &all,
                t,
                Verdict::NoInformationGain,
                x_terms[t],
                final_sd[k],
                why_not.clone(),
            )
        });
    }
    let mut term_std_devs = final_sd;
    if !gain {
        model = geo.model.clone();
        kept = kept.subset(&[]);
        term_std_devs.clear();
    }
    // The kept terms' covariance with the geometry, and the geometry's
    // marginal over them, from the final joint fit.
    let joint = if kept.terms.is_empty() {
        None
    } else {
        let jac = fit.jacobian(&final_x).ok_or(IdentifyError::NoPoses)?;
        let dof = (jac.nrows() as f64 - fit.unknowns() as f64).max(1.0);
        let cov = covariance_from_jacobian(&jac, final_cost / dof);
        Some(RefinedTerms::from_head(
            kept.clone(),
            &cov,
            geo.layout.len(),
            &free,
            free.len(),
        ))
    };
    Ok(TermIdentification {
        model,
        terms: kept,
        term_std_devs,
        term_covariance: joint.as_ref().map(|j| j.covariance.clone()),
        geometric_covariance: joint.map(|j| j.geometric_covariance),
        report: report.into_iter().flatten().collect(),
        z_threshold,
        bic_geometric,
        bic_with_terms,
        criterion: CRITERION,
        geometric: geo,
    })
}

/// For each column after the first `geometric` ones: the norm of its
/// unit-scaled copy left after projecting out the geometric columns and the
/// earlier accepted candidate columns (modified Gram–Schmidt, twice).
fn remainders(jac: &DMatrix<f64>, geometric: usize) -> Vec<f64> {
    let mut basis: Vec<DVector<f64>> = Vec::new();
    let project = |col: DVector<f64>, basis: &mut Vec<DVector<f64>>, accept_tol: f64| {
        let norm = col.norm();
        if norm == 0.0 {
            return 0.0;
        }
        let mut v = col / norm;
        for _ in 0..2 {
            for b in basis.iter() {
                let d = b.dot(&v);
                v -= b * d;
            }
        }
        let rest = v.norm();
        if rest >= accept_tol {
            basis.push(v / rest);
        }
        rest
    };
    for c in 0..geometric {
        project(jac.column(c).into_owned(), &mut basis, 1e-12);
    }
    (geometric..jac.ncols())
        .map(|c| {
            project(
                jac.column(c).into_owned(),
                &mut basis,
                TERM_IDENTIFIABLE_TOL,
            )
        })
        .collect()
}

/// RMS over the poses of the measured point's motion per radian of each
/// joint (the `dtheta_i` columns of the tool Jacobian, position rows).
fn joint_levers_mm(
    model: &CalibratedModel,
    layout: &super::params::ParamLayout,
    cal: &[Measurement],
) -> Result<Vec<f64>, IdentifyError> {
    let mut sums = vec![0.0; model.robot.dof()];
    for (pose, m) in cal.iter().enumerate() {
        let (_, jac) = super::jacobian::tool_pose_jacobian(layout, model, &m.joints_rad)
            .map_err(|source| IdentifyError::Pose { pose, source })?;
        for (j, sum) in sums.iter_mut().enumerate() {
            *sum += jac
                .fixed_view::<3, 1>(0, j * PARAMS_PER_JOINT)
                .norm_squared();
        }
    }
    let n = cal.len().max(1) as f64;
    Ok(sums.into_iter().map(|s| (s / n).sqrt()).collect())
}
