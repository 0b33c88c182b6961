//! The one Levenberg–Marquardt solver used by the camera and the kinematics
//! stages (method.md §6, paper eqs. 8–18).
//!
//! Minimises `F(x) = |r(x)|^2` for a residual vector `r` with a dense
//! Jacobian. Two damping schedules:
//! - [`Damping::Marquardt`]: the paper's eq. 18, `(J^T J + mu I) dx = -J^T r`,
//!   `mu_0 = 0.001`, `mu <- lambda mu` when a step does not reduce `|r|` (the
//!   step is rejected), `mu <- mu / lambda` when it does;
//! - [`Damping::Nielsen`] (the default, **beyond** the paper): gain-ratio
//!   control of `mu` (Nielsen 1999, as in Madsen–Nielsen–Tingleff), which
//!   needs far fewer rejected steps on badly scaled problems.
//!
//! With `column_scaling` (default on) the problem is solved in the variables
//! `D x`, `D = diag(|J_j|)` kept at its running maximum (MINPACK), so that
//! millimetres, radians and pixels become commensurable; near-redundant
//! parameters stay bounded by the damping and show up as tiny singular values
//! in [`LmReport::covariance`].

use nalgebra::{DMatrix, DVector};

pub use crate::covariance::{covariance_from_jacobian, covariance_from_normal, COVARIANCE_RCOND};
pub use crate::normal_matrix::NormalMatrix;

/// Relative step of the forward/central finite-difference Jacobian.
pub const FINITE_DIFFERENCE_STEP: f64 = 1e-6;
/// Damping above this means no step can reduce the cost any more.
const MAX_DAMPING: f64 = 1e32;
/// Nielsen's initial damping, relative to the largest diagonal of `J^T J`.
const NIELSEN_TAU: f64 = 1e-3;

/// A non-linear least-squares problem.
pub trait LeastSquaresProblem {
    /// Residuals at `x`, or `None` where the model is undefined there (a
    /// point behind the camera, say): the solver then treats the step as
    /// rejected.
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>>;

    /// Jacobian `d r / d x` at `x`. The default is central differences;
    /// override it with the analytic Jacobian where one exists.
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        finite_difference_jacobian(|x| self.residuals(x), x)
    }

    /// Solve `A d = g` for the (column-scaled, damped) dense normal matrix
    /// `A` of this problem, exploiting its structure (e.g. a Schur
    /// complement over block-diagonal pose blocks); `None` falls back to
    /// dense Cholesky. A [`NormalMatrix::Arrow`] is always solved by its
    /// Schur complement.
    fn solve_normal(&self, _a: &DMatrix<f64>, _g: &DVector<f64>) -> Option<DVector<f64>> {
        None
    }

    /// `(J^T J, J^T r)` at `x` (with `r` = residuals at `x`) assembled by
    /// the problem itself. Block-sparse problems (bundle-style camera
    /// calibration: each image row touches the intrinsics and one pose)
    /// override this so that the solver never forms the dense Jacobian
    /// (not even for the report: [`LmReport::jacobian`] is then `None` and
    /// the covariance comes from [`LmReport::normal_matrix`]); returned as
    /// a [`NormalMatrix::Arrow`], not even the dense normal matrix is
    /// formed. The default `None` lets the solver use [`Self::jacobian`].
    fn normal_equations(
        &self,
        _x: &DVector<f64>,
        _residuals: &DVector<f64>,
    ) -> Option<(NormalMatrix, DVector<f64>)> {
        None
    }
}

/// How the damping `mu` evolves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Damping {
    /// The paper's schedule (method.md §6): `2.5 < lambda < 10`.
    Marquardt { mu0: f64, lambda: f64 },
    /// Gain-ratio control (the default).
    Nielsen,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmOptions {
    pub damping: Damping,
    pub max_iterations: usize,
    /// Stop when an accepted step reduces the cost by less than this fraction.
    pub cost_tolerance: f64,
    /// Stop when the scaled step is below this fraction of the scaled `x`.
    pub step_tolerance: f64,
    /// Stop when the largest scaled gradient component is below this.
    pub gradient_tolerance: f64,
    pub column_scaling: bool,
}

impl Default for LmOptions {
    fn default() -> Self {
        Self {
            damping: Damping::Nielsen,
            max_iterations: 200,
            cost_tolerance: 1e-12,
            step_tolerance: 1e-12,
            gradient_tolerance: 1e-12,
            column_scaling: true,
        }
    }
}

impl LmOptions {
    /// The paper's variant: Marquardt's schedule with `mu_0 = 0.001`,
    /// `lambda = 10`, no column scaling.
    pub fn paper() -> Self {
        Self {
            damping: Damping::Marquardt {
                mu0: 1e-3,
                lambda: 10.0,
            },
            column_scaling: false,
            ..Self::default()
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Termination {
    CostConverged,
    StepConverged,
    GradientConverged,
    /// The damping grew without bound: no step reduces the cost.
    NoFurtherProgress,
    MaxIterations,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolverError {
    #[error("the problem has no parameters or no residuals")]
    Empty,
    #[error("{residuals} residuals cannot determine {parameters} parameters")]
    Underdetermined { residuals: usize, parameters: usize },
    #[error("the model is undefined at the starting point")]
    InvalidStart,
    #[error("the residuals or Jacobian contain non-finite values")]
    NonFinite,
}

#[derive(Debug, Clone)]
pub struct LmReport {
    pub x: DVector<f64>,
    pub residuals: DVector<f64>,
    /// Jacobian at `x` (unscaled); `None` when the problem assembled its
    /// own normal equations ([`LeastSquaresProblem::normal_equations`]):
    /// the dense Jacobian of a block-sparse problem (tens of thousands of
    /// rows) would cost more than the whole solve.
    pub jacobian: Option<DMatrix<f64>>,
    /// `J^T J` at `x` (unscaled).
    pub normal_matrix: NormalMatrix,
    /// Sum of squared residuals at `x`.
    pub cost: f64,
    pub initial_cost: f64,
    pub iterations: usize,
    pub termination: Termination,
}

impl LmReport {
    /// `sigma^2 = |r|^2 / (m - n)`: the residual variance of unit weight.
    pub fn residual_variance(&self) -> f64 {
        let dof = self.residuals.len().saturating_sub(self.x.len()).max(1);
        self.cost / dof as f64
    }

    /// Parameter covariance `sigma^2 (J^T J)^+` (method.md §6 **beyond**),
    /// of every parameter (dense; see [`NormalMatrix::covariance`]).
    pub fn covariance(&self) -> DMatrix<f64> {
        match &self.jacobian {
            Some(j) => covariance_from_jacobian(j, self.residual_variance()),
            None => self.normal_matrix.covariance(self.residual_variance()),
        }
    }

    /// Standard deviation of each parameter.
    pub fn standard_deviations(&self) -> DVector<f64> {
        self.covariance().diagonal().map(|v| v.max(0.0).sqrt())
    }
}

/// Central-difference Jacobian of `f` at `x`.
pub fn finite_difference_jacobian(
    f: impl Fn(&DVector<f64>) -> Option<DVector<f64>>,
    x: &DVector<f64>,
) -> Option<DMatrix<f64>> {
    let r0 = f(x)?;
    let mut jac = DMatrix::zeros(r0.len(), x.len());
    let mut probe = x.clone();
    for j in 0..x.len() {
        let h = FINITE_DIFFERENCE_STEP * x[j].abs().max(1.0);
        probe[j] = x[j] + h;
        let plus = f(&probe)?;
        probe[j] = x[j] - h;
        let minus = f(&probe)?;
        probe[j] = x[j];
        if plus.len() != r0.len() || minus.len() != r0.len() {
            return None;
        }
        jac.set_column(j, &((plus - minus) / (2.0 * h)));
    }
    Some(jac)
}

fn all_finite(v: impl IntoIterator<Item = f64>) -> bool {
    v.into_iter().all(f64::is_finite)
}

/// The Jacobian (when the solver forms the normal equations itself) and
/// the unscaled `(J^T J, J^T r)` at `x`.
#[allow(clippy::type_complexity)]
fn linearise<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    x: &DVector<f64>,
    r: &DVector<f64>,
) -> Result<(Option<DMatrix<f64>>, NormalMatrix, DVector<f64>), SolverError> {
    if let Some((a, g)) = problem.normal_equations(x, r) {
        if a.dim() != x.len() || !a.is_finite() || !all_finite(g.iter().copied()) {
            return Err(SolverError::NonFinite);
        }
        return Ok((None, a, g));
    }
    let jac = problem.jacobian(x).ok_or(SolverError::InvalidStart)?;
    if !all_finite(jac.iter().copied()) {
        return Err(SolverError::NonFinite);
    }
    let a = jac.transpose() * &jac;
    let g = jac.transpose() * r;
    Ok((Some(jac), a.into(), g))
}

/// Minimise `|r(x)|^2` from `x0`.
pub fn solve<P: LeastSquaresProblem + ?Sized>(
    problem: &P,
    x0: DVector<f64>,
    options: &LmOptions,
) -> Result<LmReport, SolverError> {
    let n = x0.len();
    if n == 0 {
        return Err(SolverError::Empty);
    }
    let mut x = x0;
    let mut r = problem.residuals(&x).ok_or(SolverError::InvalidStart)?;
    if r.is_empty() {
        return Err(SolverError::Empty);
    }
    if r.len() < n {
        return Err(SolverError::Underdetermined {
            residuals: r.len(),
            parameters: n,
        });
    }
    if !all_finite(r.iter().copied()) {
        return Err(SolverError::NonFinite);
    }
    let (mut jac, mut a_raw, mut g_raw) = linearise(problem, &x, &r)?;
    let initial_cost = r.norm_squared();
    let mut cost = initial_cost;
    let mut scale: DVector<f64> = DVector::from_element(n, 1.0);
    let mut scale_initialised = false;
    let mut mu = match options.damping {
        Damping::Marquardt { mu0, .. } => mu0,
        Damping::Nielsen => 0.0,
    };
    let mut nu = 2.0;
    let mut iterations = 0;
    let mut termination = Termination::MaxIterations;

    'outer: while iterations < options.max_iterations {
        iterations += 1;
        if options.column_scaling {
            let diagonal = a_raw.diagonal();
            for j in 0..n {
                let norm = diagonal[j].max(0.0).sqrt();
                let previous = if scale_initialised { scale[j] } else { 0.0 };
                scale[j] = previous.max(norm);
                if scale[j] == 0.0 {
                    scale[j] = 1.0;
                }
            }
            scale_initialised = true;
        }
        // Scaled system: J_s = J D^-1, unknown dx_s = D dx.
        let mut a = a_raw.clone();
        a.scale_symmetric(&scale);
        let g = g_raw.component_div(&scale);
        if g.amax() <= options.gradient_tolerance * cost.sqrt().max(f64::MIN_POSITIVE) {
            termination = Termination::GradientConverged;
            break;
        }
        if iterations == 1 && options.damping == Damping::Nielsen {
            mu = NIELSEN_TAU * a.diagonal().max();
        }
        let xs_norm = x.component_mul(&scale).norm();
        // Inner loop: raise the damping until a step reduces the cost.
        loop {
            if mu > MAX_DAMPING {
                termination = Termination::NoFurtherProgress;
                break 'outer;
            }
            let mut damped = a.clone();
            damped.add_to_diagonal(mu);
            let solved = match damped {
                NormalMatrix::Dense(damped) => problem
                    .solve_normal(&damped, &g)
                    .or_else(|| damped.cholesky().map(|c| c.solve(&g))),
                NormalMatrix::Arrow(damped) => damped.solve(&g),
            };
            let Some(solution) = solved else {
                mu = (mu * 10.0).max(1e-12);
                continue;
            };
            let step_s = -solution;
            let step = step_s.component_div(&scale);
            let candidate = &x + &step;
            let new_r = problem
                .residuals(&candidate)
                .filter(|v| v.len() == r.len() && all_finite(v.iter().copied()));
            let new_cost = new_r.as_ref().map_or(f64::INFINITY, |v| v.norm_squared());
            let accepted = new_cost < cost;
            match options.damping {
                Damping::Marquardt { lambda, .. } => {
                    mu = if accepted { mu / lambda } else { mu * lambda };
                }
                Damping::Nielsen => {
                    // Predicted reduction of the linear model: -2 g.dx - dx^T A dx.
                    let predicted = -(2.0 * g.dot(&step_s) + step_s.dot(&a.mul_vector(&step_s)));
                    let rho = (cost - new_cost) / predicted.max(f64::MIN_POSITIVE);
                    if accepted && rho > 0.0 {
                        mu *= (1.0f64 / 3.0).max(1.0 - (2.0 * rho - 1.0).powi(3));
                        nu = 2.0;
                    } else {
                        mu *= nu;
                        nu *= 2.0;
                    }
                }
            }
            let step_small =
                step_s.norm() <= options.step_tolerance * (xs_norm + options.step_tolerance);
            if !accepted {
                if step_small {
                    termination = Termination::StepConverged;
                    break 'outer;
                }
                continue;
            }
            let reduction = (cost - new_cost) / cost.max(f64::MIN_POSITIVE);
            x = candidate;
            r = new_r.expect("accepted steps have residuals");
            cost = new_cost;
            (jac, a_raw, g_raw) = linearise(problem, &x, &r).map_err(|_| SolverError::NonFinite)?;
            if reduction <= options.cost_tolerance {
                termination = Termination::CostConverged;
                break 'outer;
            }
            if step_small {
                termination = Termination::StepConverged;
                break 'outer;
            }
            break;
        }
    }
    Ok(LmReport {
        x,
        residuals: r,
        jacobian: jac,
        normal_matrix: a_raw,
        cost,
        initial_cost,
        iterations,
        termination,
    })
}

#[cfg(test)]
#[path = "solver_tests.rs"]
mod tests;
