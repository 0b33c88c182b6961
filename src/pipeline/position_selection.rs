//! Part of stage "identify" for tracker jobs: how much of the kinematics
//! the campaign can carry, and whether its non-geometric terms predict,
//! chosen by how each model predicts the tool positions of arm
//! configurations it was not fitted to (docs/method.md §6.8, calib's
//! `position_ladder`). As for camera jobs (`model_selection.rs`):
//! poses are grouped by their `group`, else joints 1–3; when the validation
//! poses repeat calibration configurations the comparison pools both and
//! the headline before/after are the held-out predictions.

use nalgebra::{DMatrix, DVector, Vector3};
use robocal_calib::kinematics::config_groups::{
    configuration_groups, group_count, shares_configurations,
};
use robocal_calib::kinematics::identifiability::structural_redundancies;
use robocal_calib::kinematics::identify::{
    Identification, IdentifyError, IdentifyOptions, Measurement,
};
use robocal_calib::kinematics::model_ladder::Rung;
use robocal_calib::kinematics::nongeometric::CandidateOptions;
use robocal_calib::kinematics::position_ladder::{
    climb_positions, fit_position_rung, heldout_position_score, PositionFit, PositionLadderInput,
    PositionRungScore,
};
use robocal_calib::kinematics::prior::KinematicPrior;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::term_selection::TermIdentification;
use robocal_calib::kinematics::{CalibratedModel, Instrument};

use super::measuring::Measuring;
use super::pose_errors::PoseErrors;
use super::PoseInput;
use crate::report::model_selection::{validation_basis, ModelSelectionReport, RungReport};

/// What the tracker model selection needs of the job.
pub struct PositionSelectionInput<'a> {
    pub poses: &'a [PoseInput],
    pub measuring: Measuring,
    pub instrument: Instrument,
    pub cal: &'a [usize],
    pub val: &'a [usize],
    /// The pose-level identification on the calibration poses (its
    /// "before" frames start every rung, its free set is the campaign's).
    pub identification: &'a Identification,
    /// Term candidates (`None`: terms off, no `full_terms` rung).
    pub candidates: Option<&'a CandidateOptions>,
    pub prior: KinematicPrior,
    pub options: IdentifyOptions,
}

/// A held-out comparison of tool positions that can judge other
/// kinematics the same way (the release gate's approved set).
#[derive(Debug, Clone)]
pub struct PositionHeldOut {
    pub nominal_frames: CalibratedModel,
    pub instrument: Instrument,
    pub data: Vec<Measurement>,
    pub groups: Vec<usize>,
    pub identifiable: Vec<usize>,
    pub options: IdentifyOptions,
}

impl PositionHeldOut {
    /// Mean held-out tool position error (mm) of `held`'s kinematics,
    /// held, with only the base and tool frames fitted per fold; its kept
    /// terms held at their values (every pose's joints deflected through
    /// them first, as the set would be served).
    pub fn mean_mm_of(&self, held: &TermModel) -> Result<f64, String> {
        let deflected;
        let data = if held.has_terms() {
            deflected = held
                .deflect_measurements(&self.data)
                .map_err(|e| e.to_string())?;
            &deflected
        } else {
            &self.data
        };
        let nominal = CalibratedModel {
            robot: held.model.robot.clone(),
            ..self.nominal_frames.clone()
        };
        let prior = KinematicPrior::default();
        let input = PositionLadderInput {
            nominal: &nominal,
            instrument: self.instrument,
            data,
            groups: &self.groups,
            campaign_free: &self.identifiable,
            identifiable: &self.identifiable,
            prior: &prior,
            options: self.options,
            candidates: None,
        };
        let score = heldout_position_score(Rung::HandEye, &input);
        if let Some(why) = score.failed {
            return Err(why);
        }
        mean_mm(&score).ok_or_else(|| "no held-out pose could be measured".into())
    }
}

/// The model kept, and what the report and the gate need of the choice.
pub struct PositionSelected {
    pub chosen: Rung,
    /// The kept rung refitted on the calibration poses, when it is a
    /// geometric rung other than `full` (`None`: the pose-level fit, or
    /// its term selection, stands).
    pub refit: Option<PositionFit>,
    pub heldout_errors: Option<Vec<PoseErrors>>,
    pub held_out: PositionHeldOut,
    pub report: ModelSelectionReport,
}

fn mean_mm(score: &PositionRungScore) -> Option<f64> {
    let e = &score.heldout_errors_mm;
    (!e.is_empty())
        .then(|| e.iter().map(|(_, v)| Vector3::from(*v).norm()).sum::<f64>() / e.len() as f64)
}

/// Run the ladder on the tool positions; `None` when the campaign has too
/// few configurations to hold any out (the pose-level fit stands).
pub fn select_positions(
    s: &PositionSelectionInput,
) -> Result<Option<PositionSelected>, IdentifyError> {
    let measured = |ids: &[usize]| -> Vec<(usize, Measurement)> {
        ids.iter()
            .filter_map(|&i| Some((i, s.measuring.of(&s.poses[i], i, None, None)?)))
            .collect()
    };
    let (cal, val) = (measured(s.cal), measured(s.val));
    let all: Vec<&(usize, Measurement)> = cal.iter().chain(&val).collect();
    let joints: Vec<Vec<f64>> = all.iter().map(|(_, m)| m.joints_rad.clone()).collect();
    let labels: Vec<Option<String>> = all.iter().map(|(i, _)| s.poses[*i].group.clone()).collect();
    let groups_all = configuration_groups(&joints, &labels);
    let cal_at: Vec<usize> = (0..cal.len()).collect();
    let val_at: Vec<usize> = (cal.len()..all.len()).collect();
    let shared = shares_configurations(&groups_all, &cal_at, &val_at);
    let (pool, groups): (Vec<&(usize, Measurement)>, Vec<usize>) = if shared {
        (all, groups_all)
    } else {
        let n = cal.len();
        (
            all[..n].to_vec(),
            configuration_groups(&joints[..n], &labels[..n]),
        )
    };
    // Nominal kinematics with the frames fitted on the calibration poses.
    let nominal_frames = s.identification.before.clone();
    let layout = &s.identification.layout;
    let structural = structural_redundancies(layout, &nominal_frames)
        .map_err(|source| IdentifyError::Pose { pose: 0, source })?;
    let identifiable: Vec<usize> = (0..layout.len())
        .filter(|i| !structural.contains(i))
        .collect();
    let held_out = PositionHeldOut {
        nominal_frames,
        instrument: s.instrument,
        data: pool.iter().map(|(_, m)| m.clone()).collect(),
        groups,
        identifiable,
        options: s.options,
    };
    let input = PositionLadderInput {
        nominal: &held_out.nominal_frames,
        instrument: s.instrument,
        data: &held_out.data,
        groups: &held_out.groups,
        campaign_free: &s.identification.identifiability.free,
        identifiable: &held_out.identifiable,
        prior: &s.prior,
        options: s.options,
        candidates: s.candidates,
    };
    let Some(ladder) = climb_positions(&input, &Rung::WITH_TERMS) else {
        return Ok(None);
    };
    let refit = match ladder.chosen {
        Rung::Full | Rung::FullTerms => None,
        rung => {
            let cal_data: Vec<Measurement> = cal.iter().map(|(_, m)| m.clone()).collect();
            Some(fit_position_rung(rung, &input, &cal_data)?)
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
                Some((pool[*k].0, Vector3::from(*b), Vector3::from(a)))
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
                heldout_rms_px: None,
                heldout_rms_mm: sc.heldout_rms_mm.is_finite().then_some(sc.heldout_rms_mm),
                heldout_mean_mm: mean_mm(sc),
                failed: sc.failed.clone(),
            })
            .collect(),
        chosen: ladder.chosen.as_str().to_string(),
        reason: ladder.reason.clone(),
        undetermined: Vec::new(),
    };
    Ok(Some(PositionSelected {
        chosen: ladder.chosen,
        refit,
        heldout_errors,
        held_out,
        report,
    }))
}

/// Why the terms' lines say they were not kept when a geometric rung won.
pub const TERMS_DO_NOT_PREDICT: &str =
    "kept by the selection on all calibration poses, but the model without terms predicts held-out configurations as well (model ladder)";

/// The kept rung applied to the pose-level outcome: the model with its σ
/// and covariance when they change (a geometric rung kept over the
/// pose-level fit or its terms), with the free set of `identification` and
/// the terms of `selection` following. `None`: the outcome stands.
pub fn apply_choice(
    chosen: Rung,
    refit: Option<PositionFit>,
    identification: &mut Identification,
    selection: &mut Option<TermIdentification>,
) -> Option<(CalibratedModel, DVector<f64>, DMatrix<f64>)> {
    if chosen == Rung::FullTerms {
        return None;
    }
    let had_terms = selection
        .as_ref()
        .is_some_and(|s| !s.terms.terms.is_empty());
    if let Some(s) = selection.as_mut() {
        s.drop_terms(TERMS_DO_NOT_PREDICT);
    }
    match refit {
        Some(PositionFit::Geometric(fit)) => {
            let layout = &identification.layout;
            let ident = &mut identification.identifiability;
            ident.fixed = (0..layout.len())
                .filter(|i| !fit.free.contains(i))
                .map(|i| layout.params[i].name.clone())
                .collect();
            ident.free = fit.free.clone();
            let fit = *fit;
            Some((fit.model, fit.std_devs, fit.covariance))
        }
        // `full` (the pose-level fit itself).
        _ => had_terms.then(|| {
            (
                identification.model.clone(),
                identification.std_devs.clone(),
                identification.covariance.clone(),
            )
        }),
    }
}
