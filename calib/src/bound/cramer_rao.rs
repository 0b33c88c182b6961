//! The Cramér–Rao bound of a camera campaign (method.md §6.9): the inverse
//! of the Fisher information of every dot over all unknowns, the encoder
//! noise of each pose marginalised ([`image_information`]), propagated to
//! the camera positions at the validation poses together with those
//! poses' own encoder noise.

use nalgebra::{DMatrix, Matrix3, Vector3};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

use crate::kinematics::identify_error::IdentifyError;
use crate::kinematics::image_information::{image_information, InformationInput};
use crate::kinematics::jacobian::tool_pose_jacobian;
use crate::kinematics::nongeometric::NonGeometric;
use crate::kinematics::{Instrument, ParamLayout};

/// Eigenvalues of the (Jacobi-scaled) information below this fraction of
/// the largest count as undetermined directions: the bound says nothing
/// about them (they are cut off, not made infinite).
pub const UNDETERMINED_RCOND: f64 = 1e-12;
/// Draws per validation pose for the expected 3-D error norm (the mean of
/// a Gaussian vector's length has no closed form for an anisotropic
/// covariance); fixed seed, so the bound is deterministic. Relative
/// sampling error about 1 % per pose, far less over a campaign.
pub const MEAN_NORM_DRAWS: usize = 4000;
const MEAN_NORM_SEED: u64 = 0x00c4_b0b0;

/// What the bound needs: where the information is evaluated, and the
/// recorded joints of the validation poses.
#[derive(Debug, Clone, Copy)]
pub struct BoundInput<'a> {
    pub information: InformationInput<'a>,
    pub val_joints: &'a [Vec<f64>],
}

/// One validation pose's predicted position error covariance (mm²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseBound {
    /// From the parameters' bound: `J Σ Jᵀ`.
    pub parameters: Matrix3<f64>,
    /// From the pose's own encoder noise: `σ_q² J_q J_qᵀ`.
    pub encoder: Matrix3<f64>,
}

impl PoseBound {
    pub fn total(&self) -> Matrix3<f64> {
        self.parameters + self.encoder
    }
}

/// The bound at the validation poses: what a perfect unbiased estimator
/// with the correct model would reach there, against the true camera.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidationBound {
    pub poses: Vec<PoseBound>,
    /// RMS of the 3-D position error over the poses (mm).
    pub rms_mm: f64,
    /// Its parts: the parameters' and the encoders' (squares add).
    pub parameters_rms_mm: f64,
    pub encoder_rms_mm: f64,
    /// Expected mean 3-D error (mm): the mean of `E|e|` over the poses.
    pub mean_mm: f64,
}

/// The bound of a campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct CramerRao {
    /// Layout indices that were unknowns, then this many term values and
    /// intrinsics: the order of `covariance`.
    pub free: Vec<usize>,
    pub terms: usize,
    pub intrinsics: usize,
    /// The bound on the unknowns' covariance (internal units).
    pub covariance: DMatrix<f64>,
    /// Directions the campaign does not determine (cut off).
    pub undetermined: usize,
    pub validation: ValidationBound,
}

/// The bound of `input` (module doc).
pub fn cramer_rao(input: &BoundInput) -> Result<CramerRao, IdentifyError> {
    let info = &input.information;
    let information = image_information(info)?;
    let (covariance, undetermined) = invert_information(&information);
    let terms = info.terms.map_or(0, |t| t.terms.len());
    let intrinsics = information.nrows() - info.free.len() - terms;
    let validation = validation_bound(info, terms, &covariance, input.val_joints)?;
    Ok(CramerRao {
        free: info.free.to_vec(),
        terms,
        intrinsics,
        covariance,
        undetermined,
        validation,
    })
}

/// `I⁻¹` through Jacobi scaling (the unknowns mix mm, rad, px and
/// distortion coefficients); the pseudo-inverse with its count of cut
/// directions when the scaled information is not positive definite.
pub fn invert_information(information: &DMatrix<f64>) -> (DMatrix<f64>, usize) {
    let n = information.nrows();
    let scale: Vec<f64> = (0..n)
        .map(|i| {
            let d = information[(i, i)];
            if d > 0.0 {
                1.0 / d.sqrt()
            } else {
                0.0
            }
        })
        .collect();
    let scaled = DMatrix::from_fn(n, n, |r, c| information[(r, c)] * scale[r] * scale[c]);
    let unscale = |m: DMatrix<f64>| DMatrix::from_fn(n, n, |r, c| m[(r, c)] * scale[r] * scale[c]);
    if let Some(ch) = scaled.clone().cholesky() {
        let smallest = scaled.symmetric_eigenvalues().min();
        if smallest > UNDETERMINED_RCOND * n as f64 {
            return (unscale(ch.inverse()), 0);
        }
    }
    let eigen = scaled.symmetric_eigen();
    let largest = eigen.eigenvalues.max();
    let mut inverse = DMatrix::zeros(n, n);
    let mut cut = 0;
    for (k, &l) in eigen.eigenvalues.iter().enumerate() {
        if l > UNDETERMINED_RCOND * largest {
            let v = eigen.eigenvectors.column(k);
            inverse += (v * v.transpose()) / l;
        } else {
            cut += 1;
        }
    }
    (unscale(inverse), cut)
}

/// Each validation pose's position error covariance: the parameters'
/// bound through the camera position's Jacobian (geometry and terms; the
/// intrinsics do not move the camera), plus the pose's own encoder noise
/// through the joint columns.
fn validation_bound(
    info: &InformationInput,
    terms: usize,
    covariance: &DMatrix<f64>,
    val_joints: &[Vec<f64>],
) -> Result<ValidationBound, IdentifyError> {
    if val_joints.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    let layout = ParamLayout::new(&info.model.robot, Instrument::Camera);
    let offsets = layout.joint_offset_indices();
    let none = NonGeometric::none(info.model);
    let deflection = info.terms.unwrap_or(&none);
    let nk = info.free.len() + terms;
    let kinematic = covariance.view((0, 0), (nk, nk)).into_owned();
    let sigma_q = info.joint_sigma_rad.abs();
    let mut poses = Vec::with_capacity(val_joints.len());
    for (pose, q) in val_joints.iter().enumerate() {
        let at = |source| IdentifyError::Pose { pose, source };
        let deflected = deflection.deflected(q).map_err(at)?;
        let basis = deflection.basis(q).map_err(at)?;
        let (_, jt) = tool_pose_jacobian(&layout, info.model, &deflected).map_err(at)?;
        let mut j = DMatrix::zeros(3, nk);
        for (c, &i) in info.free.iter().enumerate() {
            j.set_column(c, &jt.fixed_view::<3, 1>(0, i));
        }
        for (t, kind) in deflection.terms.iter().enumerate().take(terms) {
            let column = jt.fixed_view::<3, 1>(0, offsets[kind.joint()]) * basis[t];
            j.set_column(info.free.len() + t, &column);
        }
        let jq = DMatrix::from_fn(3, offsets.len(), |r, c| jt[(r, offsets[c])]);
        let to3 = |m: DMatrix<f64>| Matrix3::from_fn(|r, c| m[(r, c)]);
        poses.push(PoseBound {
            parameters: to3(&j * &kinematic * j.transpose()),
            encoder: to3(&jq * jq.transpose() * (sigma_q * sigma_q)),
        });
    }
    let n = poses.len() as f64;
    let ms = |f: &dyn Fn(&PoseBound) -> f64| poses.iter().map(f).sum::<f64>() / n;
    let parameters = ms(&|p| p.parameters.trace());
    let encoder = ms(&|p| p.encoder.trace());
    let rng = StdRng::seed_from_u64(MEAN_NORM_SEED);
    let mean_mm = ms(&|p| expected_norm(&p.total(), &mut rng.clone()));
    Ok(ValidationBound {
        rms_mm: (parameters + encoder).sqrt(),
        parameters_rms_mm: parameters.sqrt(),
        encoder_rms_mm: encoder.sqrt(),
        mean_mm,
        poses,
    })
}

/// `E|e|` for `e ~ N(0, c)`, by [`MEAN_NORM_DRAWS`] draws.
pub fn expected_norm(c: &Matrix3<f64>, rng: &mut StdRng) -> f64 {
    let eigen = c.symmetric_eigen();
    let root =
        eigen.eigenvectors * Matrix3::from_diagonal(&eigen.eigenvalues.map(|l| l.max(0.0).sqrt()));
    let sum: f64 = (0..MEAN_NORM_DRAWS)
        .map(|_| {
            let z = Vector3::from_fn(|_, _| StandardNormal.sample(rng));
            (root * z).norm()
        })
        .sum();
    sum / MEAN_NORM_DRAWS as f64
}
