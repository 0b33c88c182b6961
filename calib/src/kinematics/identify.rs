//! Kinematic identification by Levenberg–Marquardt (method.md §6) and the
//! before/after accuracy at validation poses (method.md §7).
//!
//! Stages: (1) "before": nominal kinematics, only the world-to-base and
//! flange-to-tool transforms fitted; (2) identifiability analysis at that
//! model (structural redundancies fixed, the campaign checked);
//! (3) every free parameter fitted. Residuals are measured minus predicted
//! tool poses (6 rows: mm and small-angle rad) or positions (3 rows).
//! [`IdentifyMode::Paper`] is the paper's eq. 18 with Marquardt's schedule on
//! the plain residual; [`IdentifyMode::Weighted`] (the default, **beyond**)
//! whitens each pose's residual with its covariance from the camera step and
//! uses column scaling with gain-ratio damping.

use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, Vector3};
use serde::{Deserialize, Serialize};

use super::identifiability::{analyse, IdentifiabilityError, IdentifiabilityReport};
use super::jacobian::tool_pose_jacobian;
use super::model::{KinematicsError, RobotModel};
use super::params::{CalibratedModel, Instrument, ParamKind, ParamLayout};
use crate::geometry::{pose_error, Pose};
use crate::solver::{solve, LeastSquaresProblem, LmOptions, SolverError, Termination};
use crate::stats::AccuracyStats;

/// Position standard deviation assumed for a pose given without covariance.
pub const DEFAULT_POSITION_SIGMA_MM: f64 = 0.1;
/// Orientation standard deviation assumed for a pose given without covariance.
pub const DEFAULT_ROTATION_SIGMA_RAD: f64 = 1e-4;

/// What was measured at one pose, in the world (target or instrument) frame.
// A few thousand measurements at most: the 6x6 covariance stays inline.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Observed {
    /// Full tool pose with an optional 6x6 covariance in the
    /// [`pose_error`] parameterisation (`[dp mm; dr rad]`, world frame).
    Pose {
        world_to_tool: Pose,
        covariance: Option<Matrix6<f64>>,
    },
    /// Tool position with an optional 3x3 covariance (mm^2).
    Position {
        position_mm: Vector3<f64>,
        covariance: Option<Matrix3<f64>>,
    },
}

impl Observed {
    pub fn position_mm(&self) -> Vector3<f64> {
        match self {
            Observed::Pose { world_to_tool, .. } => world_to_tool.translation.vector,
            Observed::Position { position_mm, .. } => *position_mm,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    pub joints_rad: Vec<f64>,
    pub observed: Observed,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IdentifyMode {
    /// Paper eq. 18: Marquardt schedule, plain residuals, no scaling.
    Paper,
    /// Covariance weights, column scaling, gain-ratio damping.
    #[default]
    Weighted,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IdentifyError {
    #[error("no calibration poses")]
    NoPoses,
    #[error("pose {pose}: {source}")]
    Pose {
        pose: usize,
        source: KinematicsError,
    },
    #[error("pose {pose}: a {instrument:?} session needs {expected} measurements")]
    WrongMeasurement {
        pose: usize,
        instrument: Instrument,
        expected: &'static str,
    },
    #[error("pose {pose}: covariance is not positive definite")]
    BadCovariance { pose: usize },
    #[error(transparent)]
    Identifiability(#[from] IdentifiabilityError),
    #[error("solver: {0}")]
    Solver(#[from] SolverError),
}

/// The identified model with its uncertainty.
#[derive(Debug, Clone)]
pub struct Identification {
    /// Nominal kinematics with only world-to-base and tool fitted.
    pub before: CalibratedModel,
    pub model: CalibratedModel,
    pub layout: ParamLayout,
    /// `model = layout.apply(before, correction)`; zero at fixed parameters.
    pub correction: DVector<f64>,
    /// Standard deviation of every parameter (zero where fixed).
    pub std_devs: DVector<f64>,
    pub identifiability: IdentifiabilityReport,
    /// RMS of the (weighted) calibration residual.
    pub residual_rms: f64,
    pub iterations: usize,
    pub termination: Termination,
}

/// Whitened residuals `W (measured - predicted)` over the free parameters.
struct PoseFit<'a> {
    layout: &'a ParamLayout,
    reference: &'a CalibratedModel,
    free: &'a [usize],
    data: &'a [Measurement],
    whitening: &'a [DMatrix<f64>],
}

impl PoseFit<'_> {
    fn full(&self, x: &DVector<f64>) -> DVector<f64> {
        let mut full = DVector::zeros(self.layout.len());
        for (k, &i) in self.free.iter().enumerate() {
            full[i] = x[k];
        }
        full
    }

    fn rows(&self) -> usize {
        self.layout.instrument.rows()
    }

    /// Residual and full-column Jacobian at model `m` (x = 0 around it).
    fn evaluate(
        &self,
        m: &CalibratedModel,
        with_jac: bool,
    ) -> Option<(DVector<f64>, DMatrix<f64>)> {
        let rows = self.rows();
        let cols = if with_jac { self.layout.len() } else { 0 };
        let mut r = DVector::zeros(rows * self.data.len());
        let mut jac = DMatrix::zeros(rows * self.data.len(), cols);
        for (k, (meas, w)) in self.data.iter().zip(self.whitening).enumerate() {
            let (pred, j) = if with_jac {
                tool_pose_jacobian(self.layout, m, &meas.joints_rad).ok()?
            } else {
                (
                    m.world_to_tool(&meas.joints_rad).ok()?,
                    DMatrix::zeros(0, 0),
                )
            };
            let e = match &meas.observed {
                Observed::Pose { world_to_tool, .. } => pose_error(world_to_tool, &pred),
                Observed::Position { position_mm, .. } => {
                    let d = position_mm - pred.translation.vector;
                    nalgebra::Vector6::new(d.x, d.y, d.z, 0.0, 0.0, 0.0)
                }
            };
            r.rows_mut(k * rows, rows).copy_from(&(w * e.rows(0, rows)));
            if with_jac {
                jac.rows_mut(k * rows, rows)
                    .copy_from(&(-(w * j.rows(0, rows))));
            }
        }
        Some((r, jac))
    }
}

impl LeastSquaresProblem for PoseFit<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let m = self.layout.apply(self.reference, &self.full(x));
        Some(self.evaluate(&m, false)?.0)
    }

    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let m = self.layout.apply(self.reference, &self.full(x));
        let (_, jac) = self.evaluate(&m, true)?;
        Some(DMatrix::from_fn(jac.nrows(), self.free.len(), |r, c| {
            jac[(r, self.free[c])]
        }))
    }
}

/// Check the measurements and build each pose's whitening matrix `W`
/// (`W^T W = Sigma^-1`); identity in paper mode.
fn whitening(
    instrument: Instrument,
    robot: &RobotModel,
    data: &[Measurement],
    mode: IdentifyMode,
) -> Result<Vec<DMatrix<f64>>, IdentifyError> {
    let rows = instrument.rows();
    data.iter()
        .enumerate()
        .map(|(pose, m)| {
            robot
                .base_to_flange(&m.joints_rad)
                .map_err(|source| IdentifyError::Pose { pose, source })?;
            let cov: DMatrix<f64> = match (&m.observed, instrument) {
                (Observed::Pose { covariance, .. }, Instrument::Camera) => match covariance {
                    Some(c) => DMatrix::from_column_slice(6, 6, c.as_slice()),
                    None => default_covariance(6),
                },
                (Observed::Pose { .. }, Instrument::Tracker) => default_covariance(3),
                (Observed::Position { covariance, .. }, Instrument::Tracker) => match covariance {
                    Some(c) => DMatrix::from_column_slice(3, 3, c.as_slice()),
                    None => default_covariance(3),
                },
                (Observed::Position { .. }, Instrument::Camera) => {
                    return Err(IdentifyError::WrongMeasurement {
                        pose,
                        instrument,
                        expected: "full-pose",
                    })
                }
            };
            if mode == IdentifyMode::Paper {
                return Ok(DMatrix::identity(rows, rows));
            }
            let chol = cov
                .cholesky()
                .ok_or(IdentifyError::BadCovariance { pose })?;
            chol.l()
                .try_inverse()
                .ok_or(IdentifyError::BadCovariance { pose })
        })
        .collect()
}

fn default_covariance(rows: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows, rows, |i, j| match (i == j, i < 3) {
        (false, _) => 0.0,
        (true, true) => DEFAULT_POSITION_SIGMA_MM.powi(2),
        (true, false) => DEFAULT_ROTATION_SIGMA_RAD.powi(2),
    })
}

fn options(mode: IdentifyMode) -> LmOptions {
    match mode {
        IdentifyMode::Paper => LmOptions::paper(),
        IdentifyMode::Weighted => LmOptions::default(),
    }
}

/// Fit only the parameters selected by `which` (layout indices) of
/// `reference` to `data`; returns the fitted model and the solver's report.
pub fn fit_parameters(
    reference: &CalibratedModel,
    instrument: Instrument,
    data: &[Measurement],
    which: &[usize],
    mode: IdentifyMode,
) -> Result<(CalibratedModel, crate::solver::LmReport), IdentifyError> {
    if data.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    let layout = ParamLayout::new(&reference.robot, instrument);
    let w = whitening(instrument, &reference.robot, data, mode)?;
    let problem = PoseFit {
        layout: &layout,
        reference,
        free: which,
        data,
        whitening: &w,
    };
    let report = solve(&problem, DVector::zeros(which.len()), &options(mode))?;
    let model = layout.apply(reference, &problem.full(&report.x));
    Ok((model, report))
}

/// Indices of the world-to-base (and, with `tool`, flange-to-tool) values.
pub fn frame_indices(layout: &ParamLayout, tool: bool) -> Vec<usize> {
    (0..layout.len())
        .filter(|&i| match layout.params[i].kind {
            ParamKind::Base(_) => true,
            ParamKind::Tool(_) => tool,
            _ => false,
        })
        .collect()
}

/// Identify kinematics, base and tool from `reference` (nominal kinematics
/// with a rough world-to-base and tool, see [`super::initial::initial_world_to_base`]).
pub fn identify(
    reference: &CalibratedModel,
    instrument: Instrument,
    cal: &[Measurement],
    mode: IdentifyMode,
) -> Result<Identification, IdentifyError> {
    let layout = ParamLayout::new(&reference.robot, instrument);
    let (before, _) = fit_parameters(
        reference,
        instrument,
        cal,
        &frame_indices(&layout, true),
        IdentifyMode::Weighted,
    )?;
    let w = whitening(instrument, &reference.robot, cal, mode)?;
    let all: Vec<usize> = (0..layout.len()).collect();
    let probe = PoseFit {
        layout: &layout,
        reference: &before,
        free: &all,
        data: cal,
        whitening: &w,
    };
    let (_, jac_all) = probe
        .evaluate(&before, true)
        .ok_or(IdentifyError::NoPoses)?;
    let identifiability = analyse(&layout, &before, &jac_all)?;
    let free = identifiability.free.clone();
    let problem = PoseFit {
        free: &free,
        ..probe
    };
    let report = solve(&problem, DVector::zeros(free.len()), &options(mode))?;
    let correction = problem.full(&report.x);
    let model = layout.apply(&before, &correction);
    // Covariance from the Jacobian at the solution itself (x = 0 around it).
    let at_solution = PoseFit {
        reference: &model,
        ..problem
    };
    let jac = at_solution
        .jacobian(&DVector::zeros(free.len()))
        .ok_or(IdentifyError::NoPoses)?;
    let dof = (report.residuals.len() - free.len()).max(1) as f64;
    let cov = crate::solver::covariance_from_jacobian(&jac, report.cost / dof);
    let mut std_devs = DVector::zeros(layout.len());
    for (k, &i) in free.iter().enumerate() {
        std_devs[i] = cov[(k, k)].max(0.0).sqrt();
    }
    Ok(Identification {
        before,
        model,
        correction,
        std_devs,
        identifiability,
        residual_rms: (report.cost / report.residuals.len() as f64).sqrt(),
        iterations: report.iterations,
        termination: report.termination,
        layout,
    })
}

/// Position errors (measured minus predicted tool position, world frame)
/// of `model` at `data`, and their statistics (method.md §7).
pub fn validate(
    model: &CalibratedModel,
    data: &[Measurement],
) -> Result<(AccuracyStats, Vec<Vector3<f64>>), IdentifyError> {
    let errors = data
        .iter()
        .enumerate()
        .map(|(pose, m)| {
            let pred = model
                .world_to_tool(&m.joints_rad)
                .map_err(|source| IdentifyError::Pose { pose, source })?;
            Ok(m.observed.position_mm() - pred.translation.vector)
        })
        .collect::<Result<Vec<_>, IdentifyError>>()?;
    Ok((AccuracyStats::from_errors(&errors), errors))
}

/// Deterministic hold-out split when a campaign has no `val` poses: every
/// k-th pose (k = round(1 / fraction)) goes to validation.
pub fn holdout_split(count: usize, fraction: f64) -> (Vec<usize>, Vec<usize>) {
    if !(fraction > 0.0 && fraction < 1.0) {
        return ((0..count).collect(), Vec::new());
    }
    let every = (1.0 / fraction).round().max(2.0) as usize;
    (0..count).partition(|i| (i + 1) % every != 0)
}

#[cfg(test)]
#[path = "identify_tests.rs"]
mod tests;
