//! Stages "measure_poses" and "identify": the measured camera (or tracker)
//! poses (`measuring`), the kinematic identification (method.md §5–6) and, for camera
//! sessions, the joint refinement on the raw image points; then the
//! before/after accuracy at the validation poses (method.md §7).

use nalgebra::Vector3;
use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::identify::{
    holdout_split, identify, validate, Identification, IdentifyMode, IdentifyOptions, JointNoise,
    Measurement,
};
use robocal_calib::kinematics::image_term_selection::select_terms_on_images;
use robocal_calib::kinematics::initial::{initial_frames_from_poses, initial_world_to_base};
use robocal_calib::kinematics::joint_covariance::joint_refine_covariance;
use robocal_calib::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose};
use robocal_calib::kinematics::nongeometric::CandidateOptions;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::term_selection::{identify_with_terms, TermIdentification};
use robocal_calib::kinematics::term_validate::validate_with_terms;
use robocal_calib::kinematics::{CalibratedModel, Instrument, RobotModel};
use robocal_calib::stats::AccuracyStats;

use super::camera_stage::CameraStep;
use super::measuring::Measuring;
use super::model_selection::{select, HeldOut, PoseErrors, SelectionInput};
use super::position_selection::{
    apply_choice, select_positions, PositionSelectionInput, TERMS_DO_NOT_PREDICT,
};
use super::{PipelineError, PoseInput, Stage};
use crate::domain::TermsDoc;
use crate::report::model_selection::ModelSelectionReport;
use crate::schema::job::{Measurement as MeasurementKind, Validation};
use crate::schema::session::PoseSet;
use robocal_calib::kinematics::model_ladder::Rung;
use robocal_calib::kinematics::prior::KinematicPrior;

/// The identified model and the numbers the report needs.
pub struct Identified {
    pub identification: Identification,
    /// The final model (joint refinement when it ran, else the pose-level fit).
    pub model: CalibratedModel,
    /// Standard deviations of `model`'s parameters (layout order, internal
    /// units): the joint refinement's when it ran. The pose-level fit's
    /// would describe a different, less precise estimate.
    pub std_devs: nalgebra::DVector<f64>,
    /// The full covariance behind `std_devs` (layout order, internal
    /// units, zero where fixed): stored with the set for predicted
    /// uncertainties.
    pub covariance: nalgebra::DMatrix<f64>,
    /// Refined intrinsics and their standard deviations, when the joint
    /// refinement ran.
    pub refined_intrinsics: Option<(Intrinsics, [f64; 8], f64)>,
    /// Joint noise (rad) the joint refinement estimated from the images.
    pub joint_noise_rad: Option<f64>,
    /// Indices (into the session's poses) of the calibration and validation poses.
    pub cal: Vec<usize>,
    pub val: Vec<usize>,
    pub before: AccuracyStats,
    pub after: AccuracyStats,
    /// Per validation pose: position error before and after (mm, world frame).
    pub val_errors: Vec<PoseErrors>,
    /// The same for each pose left out by the screening (how far its joints
    /// and its image disagree), where its image gives a camera pose.
    pub outlier_errors: Vec<PoseErrors>,
    /// The calibration and validation measurements (the release gate
    /// compares the approved set on the same poses).
    pub cal_data: Vec<Measurement>,
    pub val_data: Vec<Measurement>,
    /// The selection of non-geometric terms, when it ran.
    pub selection: Option<TermIdentification>,
    /// The kept terms as the set stores them (`None`: none kept).
    pub terms: Option<TermsDoc>,
    /// How much of the kinematics the campaign carried (camera jobs with a
    /// joint refinement and enough configurations).
    pub model_selection: Option<ModelSelectionReport>,
    /// The held-out comparison, when the headline figures are held-out
    /// predictions: the gate judges the approved set the same way.
    pub held_out: Option<HeldOut>,
}

impl Identified {
    /// `model` with the kept terms, as the stored set evaluates it.
    pub fn term_model(&self) -> Result<TermModel, String> {
        match &self.terms {
            Some(t) => t.term_model(self.model.clone(), self.identification.layout.instrument),
            None => Ok(TermModel::geometric(self.model.clone())),
        }
    }
}

fn numerical(stage: Stage, message: impl std::fmt::Display) -> PipelineError {
    PipelineError::Numerical {
        stage: stage.as_str(),
        message: message.to_string(),
    }
}

/// The parameters the campaign could not determine (weak or poorly
/// determined), for the model selection's report.
fn undetermined(identification: &Identification) -> Vec<String> {
    let ident = &identification.identifiability;
    ident
        .weak
        .iter()
        .chain(&ident.poorly_determined)
        .cloned()
        .collect()
}

/// The calibration and validation split (indices into `usable`).
pub(super) fn split(
    poses: &[PoseInput],
    usable: &[usize],
    validation: Validation,
) -> (Vec<usize>, Vec<usize>) {
    match validation {
        Validation::Holdout(h) => {
            let (cal, val) = holdout_split(usable.len(), h.holdout_fraction);
            (
                cal.into_iter().map(|i| usable[i]).collect(),
                val.into_iter().map(|i| usable[i]).collect(),
            )
        }
        Validation::Named(_) => usable.iter().partition(|&&i| poses[i].set == PoseSet::Cal),
    }
}

/// Identification, joint refinement and validation.
#[allow(clippy::too_many_arguments)]
pub fn identify_robot(
    robot: &RobotModel,
    poses: &[PoseInput],
    camera: Option<&CameraStep>,
    flange_to_tool_guess: nalgebra::Isometry3<f64>,
    measuring: Measuring,
    validation: Validation,
    joint_refinement: bool,
    hold_intrinsics: bool,
    usable: &[usize],
    outliers: &[usize],
    candidates: Option<&CandidateOptions>,
    prior: KinematicPrior,
) -> Result<Identified, PipelineError> {
    let instrument = measuring.layout(camera.is_some());
    let (cal, val) = split(poses, usable, validation);
    let cal_data: Vec<Measurement> = cal
        .iter()
        .filter_map(|&i| measuring.of(&poses[i], i, camera, None))
        .collect();
    let mut start = CalibratedModel {
        robot: robot.clone(),
        world_to_base: nalgebra::Isometry3::identity(),
        flange_to_tool: flange_to_tool_guess,
    };
    if camera.is_none() && instrument == Instrument::Camera {
        // A 6-DoF probe: its frame on the flange is found from the poses,
        // whatever the bracket's rotation.
        (start.world_to_base, start.flange_to_tool) = initial_frames_from_poses(&start, &cal_data)
            .map_err(|e| numerical(Stage::Identify, e))?;
    } else {
        start.world_to_base =
            initial_world_to_base(&start, &cal_data).map_err(|e| numerical(Stage::Identify, e))?;
    }
    // The pose-level fit takes the measurement covariances as they are; the
    // joint noise is estimated where the data can separate it from the dot
    // noise: in the joint refinement on the image points (a paper-mode
    // camera's biased poses would otherwise be read as joint noise).
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::default(),
    };
    // The term selection refits the geometry itself first (calib's
    // `identify_with_terms`), so the geometric fit is its `geometric`.
    let (identification, selection) = match candidates {
        Some(c) => {
            let s = identify_with_terms(&start, instrument, &cal_data, options, c)
                .map_err(|e| numerical(Stage::Identify, e))?;
            (s.geometric.clone(), Some(s))
        }
        None => (
            identify(&start, instrument, &cal_data, options)
                .map_err(|e| numerical(Stage::Identify, e))?,
            None,
        ),
    };
    let mut selection = selection;
    let mut model = identification.model.clone();
    let mut std_devs = identification.std_devs.clone();
    let mut covariance = identification.covariance.clone();
    let mut refined_intrinsics = None;
    let mut joint_noise_rad = None;
    let mut identification = identification;
    let mut model_selection = None;
    let mut held_out = None;
    let mut heldout_errors = None;
    if let Some(s) = &selection {
        // Pose level only (a tracker, or no joint refinement): geometry
        // refitted jointly with the kept terms, its covariance marginal
        // over them.
        model = s.model.clone();
        if let Some(c) = &s.geometric_covariance {
            std_devs = c.diagonal().map(|v| v.max(0.0).sqrt());
            covariance = c.clone();
        }
    }
    if camera.is_none() {
        // A tracker: how much of the kinematics, and whether the terms,
        // the campaign carries, judged on configurations held out
        // (docs/method.md §6.8).
        let chosen = select_positions(&PositionSelectionInput {
            poses,
            measuring,
            instrument,
            cal: &cal,
            val: &val,
            identification: &identification,
            candidates,
            prior,
            options,
        })
        .map_err(|e| numerical(Stage::Identify, e))?;
        if let Some(mut chosen) = chosen {
            let refit = chosen.refit.take();
            let changed = apply_choice(chosen.chosen, refit, &mut identification, &mut selection);
            if let Some((m, sd, cov)) = changed {
                (model, std_devs, covariance) = (m, sd, cov);
            }
            chosen.report.undetermined = undetermined(&identification);
            heldout_errors = chosen.heldout_errors.take();
            if heldout_errors.is_some() {
                held_out = Some(HeldOut::Positions(chosen.held_out));
            }
            model_selection = Some(chosen.report);
        }
    }
    if let (Some(step), true) = (
        camera,
        joint_refinement && measuring.kind == MeasurementKind::Pose,
    ) {
        let images: Vec<ImagePose> = cal
            .iter()
            .filter_map(|&i| {
                Some(ImagePose {
                    joints_rad: poses[i].joints_deg.to_radians(),
                    observations: step.observations_of(i)?.to_vec(),
                })
            })
            .collect();
        let noise = ImageNoise {
            sigma_px: step.calibration.rms_px.max(1e-3),
            joint: JointNoise::Estimate,
        };
        let free = &identification.identifiability.free;
        let intrinsics = step.intrinsics();
        let joint = match &selection {
            // Terms selected again on the image points, refined with the
            // geometry, hand–eye and intrinsics (calib's
            // `image_term_selection`).
            Some(s) => {
                let on_images =
                    select_terms_on_images(s, &intrinsics, &images, noise, hold_intrinsics)
                        .map_err(|e| numerical(Stage::Identify, e))?;
                selection = Some(on_images.selection);
                on_images.refinement
            }
            None => joint_refine(
                &identification.model,
                &intrinsics,
                &images,
                free,
                noise,
                hold_intrinsics,
            )
            .map_err(|e| numerical(Stage::Identify, e))?,
        };
        let mut joint = joint;
        let mut free = free.clone();
        {
            // How much of the kinematics (and whether the terms) the
            // campaign carries, judged on configurations held out
            // (docs/method.md §6.8).
            let chosen = select(&SelectionInput {
                poses,
                camera: step,
                measuring,
                cal: &cal,
                val: &val,
                nominal: robot,
                full: &joint,
                campaign_free: &free,
                prior,
                hold_intrinsics,
                candidates,
            })
            .map_err(|e| numerical(Stage::Identify, e))?;
            if let Some(mut chosen) = chosen {
                if chosen.chosen != Rung::FullTerms {
                    if let Some(s) = selection.as_mut() {
                        s.drop_terms(TERMS_DO_NOT_PREDICT);
                    }
                }
                if let Some((refit, kept)) = chosen.refit.take() {
                    joint = refit;
                    free = kept;
                    let ident = &mut identification.identifiability;
                    ident.fixed = (0..identification.layout.len())
                        .filter(|i| !free.contains(i))
                        .map(|i| identification.layout.params[i].name.clone())
                        .collect();
                    ident.free = free.clone();
                }
                chosen.report.undetermined = undetermined(&identification);
                heldout_errors = chosen.heldout_errors.take();
                if heldout_errors.is_some() {
                    held_out = Some(HeldOut::Images(chosen.held_out));
                }
                model_selection = Some(chosen.report);
            }
        }
        covariance = match &joint.terms {
            // Marginal over the terms: read from the refinement itself.
            Some(t) => t.geometric_covariance.clone(),
            None => joint_refine_covariance(&joint, &images, &free, hold_intrinsics)
                .map_err(|e| numerical(Stage::Identify, e))?,
        };
        model = joint.model.clone();
        std_devs = joint.std_devs.clone();
        joint_noise_rad = Some(joint.joint_sigma_rad);
        refined_intrinsics = Some((
            joint.intrinsics,
            joint.intrinsics_std,
            joint.reprojection_rms_px,
        ));
    }
    let terms = selection.as_ref().and_then(|s| {
        TermsDoc::of(
            s,
            &identification.layout,
            &identification.identifiability.free,
            &cal_data,
        )
    });
    let evaluated = match &terms {
        Some(t) => t.term_model(model.clone(), instrument),
        None => Ok(TermModel::geometric(model.clone())),
    }
    .map_err(|e| numerical(Stage::Identify, e))?;
    // Validation: every val pose measured with the final intrinsics.
    let final_intrinsics = refined_intrinsics
        .as_ref()
        .map(|r| r.0)
        .or_else(|| camera.map(|c| c.intrinsics()));
    let (mut val_index, mut val_data) = (Vec::new(), Vec::new());
    for &i in &val {
        if let Some(m) = measuring.of(&poses[i], i, camera, final_intrinsics.as_ref()) {
            val_index.push(i);
            val_data.push(m);
        }
    }
    if val_data.is_empty() {
        return Err(numerical(
            Stage::Identify,
            "no validation pose could be measured: upload poses with set \"val\" or use {\"validation\":{\"holdout_fraction\":0.3}}",
        ));
    }
    let (mut before, before_errors) =
        validate(&identification.before, &val_data).map_err(|e| numerical(Stage::Identify, e))?;
    let (mut after, after_errors) =
        validate_with_terms(&evaluated.model, &evaluated.terms, &val_data)
            .map_err(|e| numerical(Stage::Identify, e))?;
    let mut val_errors: Vec<PoseErrors> = val_index
        .iter()
        .zip(before_errors.iter().zip(&after_errors))
        .map(|(&i, (b, a))| (i, *b, *a))
        .collect();
    if let Some(errors) = heldout_errors.filter(|e| !e.is_empty()) {
        // The validation poses repeat calibration configurations: the
        // headline is the held-out configurations' prediction, nominal
        // kinematics against the kept model (docs/method.md §7).
        let pick = |f: fn(&PoseErrors) -> Vector3<f64>| errors.iter().map(f).collect::<Vec<_>>();
        before = AccuracyStats::from_errors(&pick(|e| e.1));
        after = AccuracyStats::from_errors(&pick(|e| e.2));
        val_errors = errors;
    }
    let mut outlier_errors = Vec::new();
    for &o in outliers {
        let measured = measuring.of(&poses[o], o, camera, final_intrinsics.as_ref());
        if let Some(m) = measured {
            let one = std::slice::from_ref(&m);
            if let (Ok((_, b)), Ok((_, a))) = (
                validate(&identification.before, one),
                validate_with_terms(&evaluated.model, &evaluated.terms, one),
            ) {
                outlier_errors.push((o, b[0], a[0]));
            }
        }
    }
    Ok(Identified {
        identification,
        model,
        std_devs,
        covariance,
        refined_intrinsics,
        joint_noise_rad,
        cal,
        val: val_index,
        before,
        after,
        val_errors,
        outlier_errors,
        cal_data,
        val_data,
        selection,
        terms,
        model_selection,
        held_out,
    })
}
