//! Joint refinement, the default final stage (method.md §6 **beyond**):
//! kinematics, `target_to_base`, `flange_to_camera` and the camera
//! intrinsics fitted together directly to the raw image points of every
//! pose. With independent pixel noise this is the statistically efficient
//! estimator: no information is lost in a per-image pose and its
//! approximate covariance.
//!
//! Residual per dot: `(project(camera_to_target * P) - observed) / sigma_px`,
//! with `target_to_camera = target_to_base * base_to_flange(q + e) *
//! flange_to_camera`. The Jacobian is analytic: the projection's derivative
//! with respect to the camera pose ([`project_with_jacobians`]) times the
//! identification Jacobian ([`tool_pose_jacobian`]), plus the intrinsics'.
//!
//! Joint noise: the recorded joints `q` of a pose are off by an unknown
//! `e ~ N(0, sigma_q^2)` that moves every dot of that image together, so the
//! dots of one image are correlated. Each pose gets its own joint
//! correction `e` as a nuisance unknown with the prior residual
//! `e / sigma_q` (errors in variables): for the linearised problem this is
//! exactly the weighting by the marginal covariance `sigma_px^2 I +
//! J_e sigma_q^2 J_e^T`, without ever forming it. The normal equations are
//! assembled per pose from 6x6 sums over its dots, so the corrections cost
//! little.

use nalgebra::{DMatrix, DVector};

use super::identify_error::IdentifyError;
use super::identify_options::JointNoise;
use super::image_fit::{ImageFit, ImageTerms};
pub use super::image_pose::{ImageNoise, ImagePose};
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, Instrument, ParamLayout};
use super::prior::PriorRows;
use super::refined_terms::RefinedTerms;
use crate::camera::model::Intrinsics;
use crate::geometry::Pose;
use crate::solver::{solve, LmOptions, LmReport, Termination};

#[derive(Debug, Clone)]
pub struct JointRefinement {
    pub model: CalibratedModel,
    pub intrinsics: Intrinsics,
    pub layout: ParamLayout,
    /// Standard deviation of every layout parameter (zero where fixed).
    pub std_devs: DVector<f64>,
    /// Standard deviations of [`INTRINSIC_NAMES`].
    pub intrinsics_std: [f64; 8],
    pub reprojection_rms_px: f64,
    /// Dot noise (px) and joint noise (rad) the final fit was weighted
    /// with: as given, or estimated.
    pub sigma_px: f64,
    pub joint_sigma_rad: f64,
    /// `target_to_base` of every session (board placement), session 0's
    /// first (equal to `model.world_to_base`); one entry for one session.
    pub session_target_to_base: Vec<Pose>,
    /// Estimated joint corrections per pose (rad), empty without joint noise.
    pub joint_corrections_rad: Vec<Vec<f64>>,
    /// The non-geometric terms refined with the geometry, with their
    /// covariance ([`joint_refine_with_terms`]); `None` for geometry only.
    pub terms: Option<RefinedTerms>,
    /// Weight `1/σ` of the kinematic prior per free parameter (empty: no
    /// prior, a maximum-likelihood fit): the covariance is the posterior.
    pub prior_weights: Vec<f64>,
    pub iterations: usize,
    pub termination: Termination,
}

/// Starting joint noise (rad, about 0.0006 deg) when it is estimated.
const JOINT_SIGMA_START_RAD: f64 = 1e-5;
/// Below this the joint noise is negligible (rad).
const JOINT_SIGMA_FLOOR_RAD: f64 = 1e-9;
/// Variance-component rounds at most, and their convergence tolerance on
/// the variance factors.
const VARIANCE_ROUNDS: usize = 8;
const VARIANCE_TOLERANCE: f64 = 0.02;
/// Largest change of `ln sigma_q` in one round (a factor of 10).
const MAX_LOG_STEP: f64 = std::f64::consts::LN_10;

/// Refine `start` (usually the pose-level identification) and `intrinsics`
/// (the camera step's) on the image points. `free` are the layout indices
/// identified (the identifiability analysis's); `noise` weighs the data;
/// `hold_intrinsics` keeps `intrinsics` as they are (a reused camera).
///
/// With [`JointNoise::Estimate`] the dot noise and the joint noise are
/// estimated with the fit (Förstner's variance-component estimation, two
/// groups): each group's variance is scaled by its weighted residual sum
/// over its redundancy `r_k = n_k - tr(N^-1 N_k)` until both factors are 1.
pub fn joint_refine(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    poses: &[ImagePose],
    free: &[usize],
    noise: ImageNoise,
    hold_intrinsics: bool,
) -> Result<JointRefinement, IdentifyError> {
    refine_sessions(
        start,
        intrinsics,
        poses,
        free,
        noise,
        hold_intrinsics,
        Extras::default(),
    )
}

/// [`joint_refine`] with non-geometric terms (issue 19, method.md §6
/// "beyond"): every term of `terms` is refined with the geometry, hand–eye
/// and intrinsics on the image points, starting from its value there (the
/// pose-level selection's). The result's `terms` holds the refined values
/// and their covariance with the geometry; its `std_devs` are marginal over
/// the terms.
pub fn joint_refine_with_terms(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    poses: &[ImagePose],
    free: &[usize],
    terms: &NonGeometric,
    noise: ImageNoise,
    hold_intrinsics: bool,
) -> Result<JointRefinement, IdentifyError> {
    refine_sessions(
        start,
        intrinsics,
        poses,
        free,
        noise,
        hold_intrinsics,
        Extras {
            terms: Some(terms),
            ..Extras::default()
        },
    )
}

/// [`joint_refine`] as a maximum a posteriori fit (method.md §6
/// "Priors"): every free kinematic parameter is held towards nominal by
/// `prior` ([`PriorRows::new`] for `free` around `start`). A parameter the
/// images cannot determine then keeps σ near its prior.
pub fn joint_refine_with_prior(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    poses: &[ImagePose],
    free: &[usize],
    prior: &PriorRows,
    noise: ImageNoise,
    hold_intrinsics: bool,
) -> Result<JointRefinement, IdentifyError> {
    refine_sessions(
        start,
        intrinsics,
        poses,
        free,
        noise,
        hold_intrinsics,
        Extras {
            prior: Some(prior),
            ..Extras::default()
        },
    )
}

/// What a refinement fits beyond one board and the geometry (see
/// [`super::image_fit`]): the reference `target_to_base` of sessions 1..
/// and the session of every pose; the non-geometric terms; the kinematic
/// prior.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Extras<'a> {
    pub(super) extra_bases: &'a [Pose],
    pub(super) session_of: &'a [usize],
    pub(super) terms: Option<&'a NonGeometric>,
    pub(super) prior: Option<&'a PriorRows>,
}

/// [`joint_refine`] over several sessions: `start.world_to_base` is
/// session 0's board.
pub(super) fn refine_sessions(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    poses: &[ImagePose],
    free: &[usize],
    noise: ImageNoise,
    hold_intrinsics: bool,
    sessions: Extras,
) -> Result<JointRefinement, IdentifyError> {
    if poses.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    let mut term_bases = Vec::new();
    for (pose, p) in poses.iter().enumerate() {
        start
            .robot
            .base_to_flange(&p.joints_rad)
            .map_err(|source| IdentifyError::Pose { pose, source })?;
        if let Some(t) = sessions.terms {
            let basis = t
                .basis(&p.joints_rad)
                .map_err(|source| IdentifyError::Pose { pose, source })?;
            term_bases.push(basis);
        }
    }
    let terms = sessions.terms.map(|terms| ImageTerms {
        terms,
        bases: &term_bases,
    });
    let layout = ParamLayout::new(&start.robot, Instrument::Camera);
    let estimate = noise.joint == JointNoise::Estimate;
    let mut sigma_px = if noise.sigma_px > 0.0 {
        noise.sigma_px
    } else {
        1.0
    };
    let mut joint_sigma_rad = match noise.joint {
        JointNoise::Known { sigma_rad } => sigma_rad.abs(),
        JointNoise::Estimate => JOINT_SIGMA_START_RAD,
    };
    // Unknowns kept from round to round: kinematics, bases, intrinsics.
    let kinematic = ImageFit {
        layout: &layout,
        reference: start,
        intrinsics,
        free,
        poses,
        noise,
        hold_intrinsics,
        extra_bases: sessions.extra_bases,
        session_of: sessions.session_of,
        terms,
        prior: sessions.prior,
    }
    .head();
    let mut x0: Option<DVector<f64>> = None;
    let mut previous: Option<(f64, f64)> = None;
    let mut round = 0;
    loop {
        round += 1;
        let problem = ImageFit {
            layout: &layout,
            reference: start,
            intrinsics,
            free,
            poses,
            noise: ImageNoise {
                sigma_px,
                joint: JointNoise::Known {
                    sigma_rad: joint_sigma_rad,
                },
            },
            hold_intrinsics,
            extra_bases: sessions.extra_bases,
            session_of: sessions.session_of,
            terms,
            prior: sessions.prior,
        };
        let n = problem.params();
        let x_start = match x0.take() {
            Some(x) if x.len() == n => x,
            Some(x) => DVector::from_fn(n, |i, _| if i < kinematic { x[i] } else { 0.0 }),
            None => DVector::zeros(n),
        };
        let report = solve(&problem, x_start, &LmOptions::default())?;
        let solution = Solution::at(&problem, &report)?;
        let done = !estimate || round >= VARIANCE_ROUNDS || joint_sigma_rad == 0.0;
        let (lambda_px, lambda_q) = solution.variance_factors(&problem, &report);
        let converged = (lambda_px - 1.0).abs() < VARIANCE_TOLERANCE
            && (joint_sigma_rad == 0.0 || (lambda_q - 1.0).abs() < VARIANCE_TOLERANCE);
        if done || converged {
            return Ok(solution.into_refinement(&problem, &report, layout.clone()));
        }
        sigma_px *= lambda_px.sqrt();
        // Förstner's update `sigma^2 *= lambda` converges linearly (slowly
        // when the corrections are poorly redundant); a secant on
        // `log lambda_q(log sigma_q) = 0` instead.
        let log_sigma = joint_sigma_rad.ln();
        let log_lambda = lambda_q.max(f64::MIN_POSITIVE).ln();
        let step = match previous.replace((log_sigma, log_lambda)) {
            Some((s0, l0)) if (log_lambda - l0).abs() > f64::EPSILON => {
                -log_lambda * (log_sigma - s0) / (log_lambda - l0)
            }
            // First round: `sigma_q *= lambda_q`, which lands close when
            // the start is far off (the factor falls with sigma_q^-2 there).
            _ => log_lambda,
        };
        joint_sigma_rad = (log_sigma + step.clamp(-MAX_LOG_STEP, MAX_LOG_STEP)).exp();
        if joint_sigma_rad < JOINT_SIGMA_FLOOR_RAD {
            joint_sigma_rad = 0.0;
        }
        x0 = Some(report.x);
    }
}

/// A solved round: the model and intrinsics found, and the parts of the
/// unit-variance inverse normal matrix at them that the covariance and the
/// variance components need.
struct Solution {
    model: CalibratedModel,
    intrinsics: Intrinsics,
    /// `target_to_base` of every session, session 0 first.
    bases: Vec<Pose>,
    /// The terms at their solved values.
    terms: Option<NonGeometric>,
    /// Kinematics and intrinsics block.
    head_inverse: DMatrix<f64>,
    /// Diagonal of the joint corrections' block.
    tail_diagonal: DVector<f64>,
}

impl Solution {
    fn at(problem: &ImageFit, report: &LmReport) -> Result<Self, IdentifyError> {
        let (model, intrinsics) = problem.unpack(&report.x);
        let bases = problem.session_bases(&report.x, &model);
        let terms = problem.terms_at(&report.x);
        // Linearised at the solution itself (x = 0 around it, the joint
        // corrections kept as found).
        let at = ImageFit {
            reference: &model,
            intrinsics: &intrinsics,
            extra_bases: &bases[1..],
            terms: problem
                .terms
                .zip(terms.as_ref())
                .map(|(t, solved)| ImageTerms {
                    terms: solved,
                    bases: t.bases,
                }),
            ..*problem
        };
        let kinematic = problem.head();
        let x_at = DVector::from_fn(
            at.params(),
            |i, _| {
                if i < kinematic {
                    0.0
                } else {
                    report.x[i]
                }
            },
        );
        let (normal, _) = at
            .arrow_normal_equations(&x_at)
            .ok_or(IdentifyError::NoPoses)?;
        // An unidentifiable combination gets no variance (the
        // pseudo-inverse of the Schur complement), never the dense matrix;
        // without joint corrections the head is the whole (small) matrix
        // and its pseudo-inverse is taken directly.
        let parts = match normal.block_count() {
            0 => normal.pseudo_invert(),
            _ => normal.invert().unwrap_or_else(|| normal.pseudo_invert()),
        };
        Ok(Self {
            head_inverse: parts.head,
            tail_diagonal: parts.tail_diagonal,
            model,
            intrinsics,
            bases,
            terms,
        })
    }

    /// Förstner's factors `(lambda_px, lambda_q)`: each group's weighted
    /// residual sum over its redundancy.
    fn variance_factors(&self, problem: &ImageFit, report: &LmReport) -> (f64, f64) {
        let kinematic = problem.head();
        let n = problem.params();
        let rows = problem.image_rows();
        let prior_weight = problem.noise.joint_sigma_rad().powi(-2);
        let trace_q = self.tail_diagonal.sum() * prior_weight;
        let image_cost: f64 = report.residuals.rows(0, rows).norm_squared();
        let prior_cost: f64 = report.residuals.rows(rows, n - kinematic).norm_squared();
        let r_q = (n - kinematic) as f64 - trace_q;
        let r_px = rows as f64 - n as f64 + trace_q;
        let lambda_q = if r_q > 0.0 { prior_cost / r_q } else { 1.0 };
        (image_cost / r_px.max(1.0), lambda_q)
    }

    fn into_refinement(
        self,
        problem: &ImageFit,
        report: &LmReport,
        layout: ParamLayout,
    ) -> JointRefinement {
        let free = problem.free;
        let nj = problem.joints();
        let kinematic = problem.head();
        let joint_corrections_rad = (0..problem.poses.len())
            .map(|k| report.x.as_slice()[kinematic + k * nj..kinematic + (k + 1) * nj].to_vec())
            .filter(|c| !c.is_empty())
            .collect();
        let variance = report.residual_variance();
        let sd = |i: usize| (self.head_inverse[(i, i)] * variance).max(0.0).sqrt();
        let mut std_devs = DVector::zeros(layout.len());
        for (k, &i) in free.iter().enumerate() {
            std_devs[i] = sd(k);
        }
        let rows = problem.image_rows();
        let image_cost = report.residuals.rows(0, rows).norm_squared();
        let terms = self.terms.map(|t| {
            RefinedTerms::from_head(
                t,
                &(&self.head_inverse * variance),
                layout.len(),
                free,
                problem.term_start(),
            )
        });
        JointRefinement {
            model: self.model,
            intrinsics: self.intrinsics,
            std_devs,
            intrinsics_std: std::array::from_fn(|k| {
                if k < problem.ni() {
                    sd(problem.nk() + k)
                } else {
                    0.0
                }
            }),
            reprojection_rms_px: (image_cost / rows as f64).sqrt() * problem.noise.sigma_px,
            sigma_px: problem.noise.sigma_px,
            joint_sigma_rad: problem.noise.joint_sigma_rad(),
            joint_corrections_rad,
            terms,
            prior_weights: problem.prior.map(|p| p.weight.clone()).unwrap_or_default(),
            session_target_to_base: self.bases,
            iterations: report.iterations,
            termination: report.termination,
            layout,
        }
    }
}

#[cfg(test)]
#[path = "joint_refine_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "joint_refine_terms_tests.rs"]
mod terms_tests;
