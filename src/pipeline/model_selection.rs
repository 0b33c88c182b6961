//! Part of stage "identify" for camera jobs: how much of the kinematics
//! the campaign can carry, chosen by how each model predicts arm
//! configurations it was not fitted to (docs/method.md §6.8 "Model selection
//! by held-out groups", calib's `model_ladder`).
//!
//! The poses are grouped by configuration (a pose's `group` as uploaded,
//! else joints 1–3 within a few degrees). When the validation poses repeat
//! calibration configurations, they cannot show a model that bent weakly
//! determined links to those configurations: the comparison then pools
//! calibration and validation poses, and the headline before/after become
//! the held-out predictions (the nominal-kinematics rung and the kept one).

use nalgebra::Vector3;
use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::config_groups::{
    configuration_groups, group_count, shares_configurations,
};
use robocal_calib::kinematics::identifiability::structural_redundancies;
use robocal_calib::kinematics::identify::{IdentifyError, JointNoise, Measurement};
use robocal_calib::kinematics::joint_refine::{ImageNoise, ImagePose, JointRefinement};
use robocal_calib::kinematics::model_ladder::{
    climb, errors_mm, fit_rung, heldout_score, LadderInput, Rung, RungScore,
};
use robocal_calib::kinematics::nongeometric::CandidateOptions;
use robocal_calib::kinematics::prior::KinematicPrior;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::{CalibratedModel, ParamLayout, RobotModel};

use super::camera_stage::CameraStep;
use super::measuring::Measuring;
use super::position_selection::PositionHeldOut;
use super::PoseInput;
use crate::report::model_selection::{validation_basis, ModelSelectionReport, RungReport};

/// What the model selection needs of the job.
pub struct SelectionInput<'a> {
    pub poses: &'a [PoseInput],
    pub camera: &'a CameraStep,
    pub measuring: Measuring,
    pub cal: &'a [usize],
    pub val: &'a [usize],
    /// The robot's nominal kinematics.
    pub nominal: &'a RobotModel,
    /// The full model fitted on the calibration poses (its frames start
    /// every rung, its noise weighs them).
    pub full: &'a JointRefinement,
    /// Layout indices the campaign determines (the identifiability's).
    pub campaign_free: &'a [usize],
    pub prior: KinematicPrior,
    pub hold_intrinsics: bool,
    /// Term candidates when the job selects terms (`full` is then the
    /// refinement with the kept terms; the ladder gains `full_terms`).
    pub candidates: Option<&'a CandidateOptions>,
}

/// A held-out comparison that can judge other kinematics the same way
/// (the release gate's approved set): on image points (camera jobs) or
/// tool positions (tracker jobs).
#[derive(Debug, Clone)]
pub enum HeldOut {
    Images(ImageHeldOut),
    Positions(PositionHeldOut),
}

impl HeldOut {
    /// Mean held-out position error (mm) of `held`'s kinematics and kept
    /// terms, held, with only the frames (and the camera) fitted per fold.
    pub fn mean_mm_of(&self, held: &TermModel) -> Result<f64, String> {
        match self {
            HeldOut::Images(h) => h.mean_mm_of(held),
            HeldOut::Positions(h) => h.mean_mm_of(held),
        }
    }
}

/// The camera jobs' held-out comparison, on image points.
#[derive(Debug, Clone)]
pub struct ImageHeldOut {
    pub nominal_frames: CalibratedModel,
    pub intrinsics: Intrinsics,
    pub images: Vec<ImagePose>,
    pub groups: Vec<usize>,
    pub measured: Vec<Option<Measurement>>,
    pub identifiable: Vec<usize>,
    pub noise: ImageNoise,
    pub hold_intrinsics: bool,
}

impl ImageHeldOut {
    fn input<'a>(
        &'a self,
        nominal: &'a CalibratedModel,
        prior: &'a KinematicPrior,
    ) -> LadderInput<'a> {
        LadderInput {
            nominal,
            intrinsics: &self.intrinsics,
            poses: &self.images,
            groups: &self.groups,
            measured: &self.measured,
            campaign_free: &self.identifiable,
            identifiable: &self.identifiable,
            prior,
            noise: self.noise,
            hold_intrinsics: self.hold_intrinsics,
            candidates: None,
        }
    }

    /// Mean held-out camera position error (mm) of `held`'s kinematics,
    /// held, with only the board, hand–eye and camera fitted per fold. Its
    /// kept non-geometric terms are held at their values: every pose's
    /// joints deflected through them first (`TermModel::deflected`), as the
    /// set would be served.
    pub fn mean_mm_of(&self, held: &TermModel) -> Result<f64, String> {
        let deflected: ImageHeldOut;
        let this = if held.has_terms() {
            deflected = self.deflected(held)?;
            &deflected
        } else {
            self
        };
        let nominal = CalibratedModel {
            robot: held.model.robot.clone(),
            ..self.nominal_frames.clone()
        };
        let prior = KinematicPrior::default();
        let score = heldout_score(Rung::HandEye, &this.input(&nominal, &prior));
        if let Some(why) = score.failed {
            return Err(why);
        }
        let errors = errors_mm(&score);
        if errors.is_empty() {
            return Err("no held-out pose could be measured".into());
        }
        Ok(errors.iter().map(Vector3::norm).sum::<f64>() / errors.len() as f64)
    }

    /// The same comparison with every pose's joints deflected by `held`'s terms.
    fn deflected(&self, held: &TermModel) -> Result<ImageHeldOut, String> {
        let images = self
            .images
            .iter()
            .map(|p| {
                Ok(ImagePose {
                    joints_rad: held.deflected(&p.joints_rad).map_err(|e| e.to_string())?,
                    observations: p.observations.clone(),
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        let measured = self
            .measured
            .iter()
            .map(|m| match m {
                Some(m) => held
                    .deflect_measurements(std::slice::from_ref(m))
                    .map(|mut d| d.pop())
                    .map_err(|e| e.to_string()),
                None => Ok(None),
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok(ImageHeldOut {
            images,
            measured,
            ..self.clone()
        })
    }
}

pub use super::pose_errors::PoseErrors;

/// The model kept, and what the report and the gate need of the choice.
pub struct Selected {
    pub chosen: Rung,
    /// The kept rung refitted on the calibration poses (`None`: the full
    /// model given is kept).
    pub refit: Option<(JointRefinement, Vec<usize>)>,
    /// Held-out errors per pose (session index, nominal rung, kept rung)
    /// when the headline is leave-group-out.
    pub heldout_errors: Option<Vec<PoseErrors>>,
    pub held_out: ImageHeldOut,
    pub report: ModelSelectionReport,
}

fn mean_mm(score: &RungScore) -> Option<f64> {
    let e = errors_mm(score);
    (!e.is_empty()).then(|| e.iter().map(Vector3::norm).sum::<f64>() / e.len() as f64)
}

/// The image points of `poses` (session indices; every one has a view,
/// `select` keeps only those).
fn image_poses(s: &SelectionInput, poses: &[usize]) -> Vec<ImagePose> {
    poses
        .iter()
        .filter_map(|&i| {
            Some(ImagePose {
                joints_rad: s.poses[i].joints_deg.to_radians(),
                observations: s.camera.observations_of(i)?.to_vec(),
            })
        })
        .collect()
}

/// Run the ladder; `None` when the campaign has too few configurations to
/// hold any out (the full model is kept, as before).
pub fn select(s: &SelectionInput) -> Result<Option<Selected>, IdentifyError> {
    let usable = |i: &&usize| s.camera.observations_of(**i).is_some();
    let cal: Vec<usize> = s.cal.iter().filter(usable).copied().collect();
    let val: Vec<usize> = s.val.iter().filter(usable).copied().collect();
    let all: Vec<usize> = cal.iter().chain(&val).copied().collect();
    let joints: Vec<Vec<f64>> = all
        .iter()
        .map(|&i| s.poses[i].joints_deg.to_radians())
        .collect();
    // A pose's explicit `group` wins; the others are clustered on joints 1–3.
    let labels: Vec<Option<String>> = all.iter().map(|&i| s.poses[i].group.clone()).collect();
    let groups_all = configuration_groups(&joints, &labels);
    let cal_at: Vec<usize> = (0..cal.len()).collect();
    let val_at: Vec<usize> = (cal.len()..all.len()).collect();
    let shared = shares_configurations(&groups_all, &cal_at, &val_at);
    let pool: Vec<usize> = if shared { all.clone() } else { cal.clone() };
    let groups: Vec<usize> = if shared {
        groups_all
    } else {
        configuration_groups(&joints[..cal.len()], &labels[..cal.len()])
    };
    let intrinsics = s.full.intrinsics;
    let images = image_poses(s, &pool);
    let measured: Vec<Option<Measurement>> = pool
        .iter()
        .map(|&i| {
            s.measuring
                .of(&s.poses[i], i, Some(s.camera), Some(&intrinsics))
        })
        .collect();
    let nominal_frames = CalibratedModel {
        robot: s.nominal.clone(),
        ..s.full.model.clone()
    };
    let layout = ParamLayout::new(s.nominal, robocal_calib::kinematics::Instrument::Camera);
    let structural = structural_redundancies(&layout, &nominal_frames)
        .map_err(|source| IdentifyError::Pose { pose: 0, source })?;
    let identifiable: Vec<usize> = (0..layout.len())
        .filter(|i| !structural.contains(i))
        .collect();
    let noise = ImageNoise {
        sigma_px: s.full.sigma_px,
        joint: JointNoise::Known {
            sigma_rad: s.full.joint_sigma_rad,
        },
    };
    let held_out = ImageHeldOut {
        nominal_frames: nominal_frames.clone(),
        intrinsics,
        images,
        groups,
        measured,
        identifiable: identifiable.clone(),
        noise,
        hold_intrinsics: s.hold_intrinsics,
    };
    let input = LadderInput {
        campaign_free: s.campaign_free,
        candidates: s.candidates,
        ..held_out.input(&nominal_frames, &s.prior)
    };
    let Some(ladder) = climb(&input, &Rung::WITH_TERMS) else {
        return Ok(None);
    };
    let refit = match ladder.chosen {
        // The job's own fit: the full model, or with terms on its
        // refinement with the kept terms.
        Rung::FullTerms => None,
        Rung::Full if s.candidates.is_none() => None,
        rung => {
            // The kept rung on the calibration poses, its noise estimated.
            let cal_images = image_poses(s, &cal);
            let estimate = ImageNoise {
                sigma_px: s.full.sigma_px,
                joint: JointNoise::Estimate,
            };
            Some(fit_rung(rung, &input, &cal_images, estimate)?)
        }
    };
    let heldout_errors = shared.then(|| {
        let of = |rung| {
            ladder
                .score(rung)
                .map(|sc| sc.heldout_errors_mm.clone())
                .unwrap_or_default()
        };
        let (before, after) = (of(Rung::HandEye), of(ladder.chosen));
        before
            .iter()
            .filter_map(|(k, b)| {
                let a = after.iter().find(|(j, _)| j == k)?.1;
                Some((pool[*k], Vector3::from(*b), Vector3::from(a)))
            })
            .collect()
    });
    let report = ModelSelectionReport {
        configurations: group_count(&held_out.groups),
        val_shares_configurations: shared,
        validation: validation_basis(shared),
        folds: ladder.folds,
        rungs: ladder
            .scores
            .iter()
            .map(|sc| RungReport {
                rung: sc.rung.as_str().to_string(),
                description: sc.rung.describe().to_string(),
                parameters: sc.parameters,
                heldout_rms_px: sc.heldout_rms_px.is_finite().then_some(sc.heldout_rms_px),
                heldout_rms_mm: None,
                heldout_mean_mm: mean_mm(sc),
                failed: sc.failed.clone(),
            })
            .collect(),
        chosen: ladder.chosen.as_str().to_string(),
        reason: ladder.reason.clone(),
        undetermined: Vec::new(),
    };
    Ok(Some(Selected {
        chosen: ladder.chosen,
        refit,
        heldout_errors,
        held_out,
        report,
    }))
}
