//! The `full_terms` rung of the camera model ladder (method.md §6.8): the
//! non-geometric terms a camera job with terms on selects (method.md §6.6,
//! decision 0024), fitted on the training groups alone so that the terms
//! are judged by the same held-out prediction as the geometric rungs.

use super::identify::{IdentifyError, IdentifyMode, Measurement};
use super::image_pose::{ImageNoise, ImagePose};
use super::image_term_selection::{select_terms_on_images, ImageTermSelection};
use super::joint_refine::JointRefinement;
use super::model_ladder::{fit_rung, LadderInput, Rung};
use super::term_selection::identify_with_terms;

/// The `full_terms` rung on `poses` (with `measurements`, the same poses'
/// measured camera poses): the pose-level term selection, then the
/// selection on the image points ([`select_terms_on_images`]), as a camera
/// job with terms on runs them.
pub fn fit_terms_rung(
    input: &LadderInput,
    poses: &[ImagePose],
    measurements: &[Measurement],
    noise: ImageNoise,
) -> Result<ImageTermSelection, IdentifyError> {
    let candidates = input.candidates.ok_or(IdentifyError::NoPoses)?;
    let pose_level = identify_with_terms(
        input.nominal,
        super::Instrument::Camera,
        measurements,
        IdentifyMode::Weighted.into(),
        candidates,
    )?;
    select_terms_on_images(
        &pose_level,
        input.intrinsics,
        poses,
        noise,
        input.hold_intrinsics,
    )
}

/// Fit `rung` on the poses `train` (indices into `input.poses`); the fit
/// and its number of free parameters (kept terms included).
pub(super) fn fit_on(
    rung: Rung,
    input: &LadderInput,
    train: &[usize],
) -> Result<(JointRefinement, usize), IdentifyError> {
    let poses: Vec<ImagePose> = train.iter().map(|&i| input.poses[i].clone()).collect();
    if rung != Rung::FullTerms {
        let (fit, free) = fit_rung(rung, input, &poses, input.noise)?;
        return Ok((fit, free.len()));
    }
    let measured: Vec<Measurement> = train
        .iter()
        .filter_map(|&i| input.measured.get(i).cloned().flatten())
        .collect();
    let s = fit_terms_rung(input, &poses, &measured, input.noise)?;
    let count = s.selection.geometric.identifiability.free.len() + s.selection.terms.terms.len();
    Ok((s.refinement, count))
}
