//! Joint fit and backward elimination of non-geometric terms (step 3 of
//! [`super::term_selection`]'s module doc): the terms are fitted jointly
//! with the geometry, base and tool, σ from the Jacobian at the solution
//! scaled by the residual variance, and the least significant term is
//! dropped while its `|value| / σ` is below the Bonferroni threshold.

use nalgebra::DVector;

use super::identify::IdentifyError;
use super::nongeometric::NonGeometric;
use super::term_fit::TermFit;
use super::term_report::{line, TermReport, Verdict};
use crate::covariance::covariance_from_jacobian;
use crate::solver::{solve, LeastSquaresProblem, LmOptions};

/// Terms below this `|value| / σ` are all dropped in one round (speed only:
/// they could never reach the threshold).
const HOPELESS_Z: f64 = 1.0;
const MAX_ITERATIONS: usize = 500;
/// The surviving terms, the solution (geometry then terms), the terms' σ
/// and the cost.
pub(super) type Eliminated = (Vec<usize>, DVector<f64>, Vec<f64>, f64);

/// Joint fit and backward elimination (step 3 of the module doc) of the
/// terms `active`: the survivors, the solution, their σ and the cost.
/// Values of the fitted terms land in `x_terms`, the geometry in `geo_x`
/// (the next fit's start), dropped terms in `report`.
pub(super) struct Elimination<'a, 'b> {
    pub probe: &'b TermFit<'a>,
    pub x_terms: &'b mut Vec<f64>,
    pub geo_x: &'b mut DVector<f64>,
    pub report: &'b mut Vec<Option<TermReport>>,
    pub z_threshold: f64,
}

impl Elimination<'_, '_> {
    pub fn run(
        &mut self,
        mut active: Vec<usize>,
        all: &NonGeometric,
    ) -> Result<Eliminated, IdentifyError> {
        let free = self.probe.free;
        let z_threshold = self.z_threshold;
        let lm = LmOptions {
            max_iterations: MAX_ITERATIONS,
            ..LmOptions::default()
        };
        loop {
            let fit = TermFit {
                free_terms: &active,
                ..probe_like(self.probe)
            };
            let start = stack(
                self.geo_x,
                &DVector::from_iterator(active.len(), active.iter().map(|&t| self.x_terms[t])),
            );
            let sol = solve(&fit, start, &lm)?;
            let jac = fit.jacobian(&sol.x).ok_or(IdentifyError::NoPoses)?;
            let dof = (sol.residuals.len() as f64 - fit.unknowns() as f64).max(1.0);
            let cov = covariance_from_jacobian(&jac, sol.cost / dof);
            let sd: Vec<f64> = (0..active.len())
                .map(|k| cov[(free.len() + k, free.len() + k)].max(0.0).sqrt())
                .collect();
            *self.geo_x = sol.x.rows(0, free.len()).into_owned();
            for (k, &t) in active.iter().enumerate() {
                self.x_terms[t] = sol.x[free.len() + k];
            }
            let z: Vec<f64> = (0..active.len())
                .map(|k| self.x_terms[active[k]].abs() / sd[k].max(f64::MIN_POSITIVE))
                .collect();
            let weakest = (0..active.len()).min_by(|&a, &b| z[a].total_cmp(&z[b]));
            let Some(weakest) = weakest.filter(|&k| z[k] < z_threshold) else {
                return Ok((active, sol.x, sd, sol.cost));
            };
            let drop: Vec<usize> = if z[weakest] < HOPELESS_Z {
                (0..active.len()).filter(|&k| z[k] < HOPELESS_Z).collect()
            } else {
                vec![weakest]
            };
            for &k in &drop {
                let t = active[k];
                self.report[t] = Some(line(
                    all,
                    t,
                    Verdict::NotSignificant,
                    self.x_terms[t],
                    sd[k],
                    format!(
                        "|value|/σ = {:.2} below the threshold {z_threshold:.2}",
                        z[k]
                    ),
                ));
            }
            active = active
                .iter()
                .enumerate()
                .filter(|(k, _)| !drop.contains(k))
                .map(|(_, &t)| t)
                .collect();
        }
    }
}

pub(super) fn probe_like<'a>(p: &TermFit<'a>) -> TermFit<'a> {
    TermFit {
        layout: p.layout,
        reference: p.reference,
        free: p.free,
        terms: p.terms,
        free_terms: p.free_terms,
        data: p.data,
        whitening: p.whitening,
    }
}

pub(super) fn stack(a: &DVector<f64>, b: &DVector<f64>) -> DVector<f64> {
    DVector::from_iterator(a.len() + b.len(), a.iter().chain(b.iter()).copied())
}

/// `z` with two-sided normal tail `α / m` (Bonferroni over `m` tests).
pub fn bonferroni_z(alpha: f64, m: usize) -> f64 {
    let target = alpha / m as f64;
    let (mut lo, mut hi) = (0.0_f64, 40.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if erfc(mid / std::f64::consts::SQRT_2) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Complementary error function (Numerical Recipes' Chebyshev fit,
/// relative error < 1.2e-7 everywhere).
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * poly.exp();
    if x >= 0.0 {
        r
    } else {
        2.0 - r
    }
}
