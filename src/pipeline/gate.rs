//! The release gate at the end of a job (issue 17): a set is approved
//! automatically only when it predicts this session's validation poses
//! better than the robot's currently approved set does on the same poses
//! (or than the nominal model, for the first set) and no hard warning
//! fired; otherwise it stays a `candidate`, with the reason, until a
//! person approves or rejects it. `latest` serves approved sets only.
//!
//! The approved set is evaluated as the nominal "before" is (method.md §7):
//! its kinematics held, the base and hand–eye frames re-fitted on this
//! session's calibration poses (the board may have moved between the two
//! sessions, the camera may have been re-mounted), then its mean 3-D error
//! at this session's validation poses. A set with kept non-geometric
//! terms (issue 19) is evaluated with them, held at their values (its
//! frames re-fitted through them): the candidate's own figure
//! (`Identified::after`) uses its terms, so both sides are judged as
//! they would be served. Two sets of one tracker, one fitted with a 6-DoF
//! probe's orientation, are compared on the tool point's position.
//!
//! Both sides of that comparison are figured by one rule: this job's set
//! is put through exactly what the approved set goes through (its stored
//! form read back, its kinematics and terms held, the frames re-fitted on
//! these poses), so identical parameters give identical figures and never
//! read as "better than before". The report's gate section shows both,
//! with the figure the approved set's own report gave and why the two
//! may differ.

use std::borrow::Cow;

use robocal_calib::kinematics::identify::{
    fit_parameters, frame_indices, validate, IdentifyMode, IdentifyOptions, JointNoise, Measurement,
};
use robocal_calib::kinematics::{CalibratedModel, Instrument, ParamLayout};

use super::identify_stage::Identified;
use super::input::ApprovedSet;
use crate::domain::{ParameterSet, Release, ReleaseStatus};
use crate::report::GateReport;
use crate::schema::session::Instrument as SessionInstrument;

/// What [`GateReport::compared_with`] says for the nominal model.
const NOMINAL: &str = "nominal";
/// The model-selection rung that keeps the nominal kinematics.
const HAND_EYE_RUNG: &str = "hand_eye";
/// Two figures of the same poses closer than this are the same (mm): a
/// nanometre is below any robot's repeatability by three orders, so a
/// smaller gain is arithmetic, not a better set.
const SAME_WITHIN_MM: f64 = 1e-6;

/// The gate's decision and what the report shows of it.
pub struct Gate {
    pub release: Release,
    pub report: GateReport,
}

/// `set`'s mean 3-D error at `id`'s validation poses, its kinematics and
/// terms held and its frames re-fitted on `id`'s calibration poses (from
/// `id`'s own frames, close to the truth whatever happened to the cell
/// since).
fn refit_mean_mm(
    set: &ParameterSet,
    session: SessionInstrument,
    id: &Identified,
) -> Result<f64, String> {
    let instrument = id.identification.layout.instrument;
    // The job's own measurements, borrowed; converted only when needed.
    type Data<'a> = Cow<'a, [Measurement]>;
    let (instrument, cal_data, val_data): (_, Data, Data) = if set.layout_instrument() == instrument
    {
        (
            instrument,
            Cow::Borrowed(&id.cal_data),
            Cow::Borrowed(&id.val_data),
        )
    } else if !session.has_camera() && !set.instrument.has_camera() {
        // One tracker, one of the two sets fitted with a 6-DoF probe's
        // orientation: compared on the tool point, the figure both have.
        let positions = |data: &[Measurement]| -> Data {
            Cow::Owned(data.iter().map(Measurement::position_only).collect())
        };
        (
            Instrument::Tracker,
            positions(&id.cal_data),
            positions(&id.val_data),
        )
    } else {
        return Err("it was calibrated with another instrument".into());
    };
    let held = set.term_model()?;
    let model = held.model.clone();
    let (theirs, ours) = (model.robot.joints.len(), id.model.robot.joints.len());
    if theirs != ours {
        return Err(format!(
            "its joint table has {theirs} joints, this job's {ours}"
        ));
    }
    let start = CalibratedModel {
        world_to_base: id.model.world_to_base,
        flange_to_tool: id.model.flange_to_tool,
        ..model
    };
    let layout = ParamLayout::new(&start.robot, instrument);
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::default(),
    };
    let which = frame_indices(&layout, true);
    // With the terms held, a geometric fit of the deflected joints is the
    // fit through the terms (`TermModel::deflect_measurements`).
    let deflect = |data| held.deflect_measurements(data).map_err(|e| e.to_string());
    let (cal_data, val_data) = (deflect(&cal_data)?, deflect(&val_data)?);
    let (refit, _) = fit_parameters(&start, instrument, &cal_data, &which, options)
        .map_err(|e| e.to_string())?;
    let (stats, _) = validate(&refit, &val_data).map_err(|e| e.to_string())?;
    Ok(stats.norm.mean_mm)
}

/// `set`'s figure on `id`'s poses by the gate's one rule: held-out
/// configurations when the job's headline is leave-group-out (its
/// kinematics and terms held, board, hand–eye and camera re-fitted per
/// fold, docs/method.md §7), the validation poses otherwise.
fn gate_mean_mm(
    set: &ParameterSet,
    session: SessionInstrument,
    id: &Identified,
) -> Result<f64, String> {
    match &id.held_out {
        Some(held_out) => held_out.mean_mm_of(&set.term_model()?),
        None => refit_mean_mm(set, session, id),
    }
}

/// How [`gate_mean_mm`] figured both sides, for the report.
fn basis(id: &Identified) -> &'static str {
    if id.held_out.is_some() {
        "both sets' kinematics (and kept terms) held, board, hand–eye and camera re-fitted per held-out arm configuration of this session; a set's own headline re-fits its kinematics per configuration too, so it can be lower"
    } else {
        "both sets' kinematics (and kept terms) held, base and hand–eye frames re-fitted on this session's calibration poses, then measured at its validation poses"
    }
}

/// `set` as the next job will read it back from the store (the same
/// serialisation as the approved set it is compared with went through).
fn as_stored(set: &ParameterSet) -> Result<ParameterSet, String> {
    serde_json::to_value(set)
        .and_then(serde_json::from_value)
        .map_err(|e| e.to_string())
}

/// The gate's decision for a job's identified set (`candidate`: the set
/// the job stores). `paper_camera`: the set's intrinsics are the paper's
/// Tsai sequence (`refine_intrinsics: false`), a hard warning: its one
/// radial term does not fit a real lens (method.md §4), and its
/// validation poses are measured through that same camera, so its
/// figures flatter it.
pub fn decide(
    id: &Identified,
    candidate: &ParameterSet,
    instrument: SessionInstrument,
    approved: Option<&ApprovedSet>,
    paper_camera: bool,
) -> Gate {
    let (mut mean, nominal) = (id.after.norm.mean_mm, id.before.norm.mean_mm);
    let mut blockers = Vec::new();
    if paper_camera {
        blockers.push(
            "hard warning: the paper's camera model (refine_intrinsics: false) measured its own validation poses"
                .to_string(),
        );
    }
    if let Some(m) = &id.model_selection {
        // Camera rungs are judged on image points, tracker rungs on positions.
        let rms = |rung: &str| {
            let r = m.rungs.iter().find(|r| r.rung == rung)?;
            r.heldout_rms_px
                .map(|v| (v, "px"))
                .or(r.heldout_rms_mm.map(|v| (v, "mm")))
        };
        if let (Some((kept, unit)), Some((nominal, _))) = (rms(&m.chosen), rms(HAND_EYE_RUNG)) {
            if kept > nominal {
                blockers.push(format!(
                    "hard warning: predicts held-out configurations worse than the nominal kinematics ({kept:.3} {unit} against {nominal:.3} {unit})"
                ));
            }
        }
    }
    let nominal_kept = id
        .model_selection
        .as_ref()
        .is_some_and(|m| m.chosen == HAND_EYE_RUNG);
    let mut earlier = None;
    let compared = match approved.map(|a| (a, gate_mean_mm(&a.set, instrument, id))) {
        Some((a, Ok(theirs))) => {
            // This set by the same rule, read back as the approved one was.
            match as_stored(candidate).and_then(|c| gate_mean_mm(&c, instrument, id)) {
                Ok(ours) => mean = ours,
                Err(why) => blockers.push(format!(
                    "this set could not be evaluated as {} was ({why})",
                    a.id
                )),
            }
            earlier = Some(EarlierSet {
                own_report_mean_mm: a.report_mean_mm,
                own_report_session_id: a.report_session_id.clone(),
                basis: basis(id).to_string(),
            });
            Some((a.id.clone(), theirs))
        }
        Some((a, Err(why))) => {
            blockers.push(format!(
                "the approved set {} could not be evaluated on these poses ({why})",
                a.id
            ));
            None
        }
        None => None,
    };
    let (compared_with, compared_mean) = compared.unwrap_or_else(|| (NOMINAL.to_string(), nominal));
    let mut gate = outcome(
        mean,
        nominal,
        compared_with,
        compared_mean,
        blockers,
        nominal_kept,
    );
    if let Some(e) = earlier {
        gate.report.basis = Some(e.basis);
        gate.report.compared_own_mean_mm = e.own_report_mean_mm;
        gate.report.compared_own_session_id = e.own_report_session_id;
    }
    gate
}

/// What the report says of the approved set beside the gate's figure.
struct EarlierSet {
    own_report_mean_mm: Option<f64>,
    own_report_session_id: Option<String>,
    basis: String,
}

/// The decision from the figures: approved only when the set is better
/// than `compared_with` and than nominal, and nothing in `blockers` (hard
/// warnings, a comparison that could not be made) holds it back.
/// `nominal_kept`: the model selection kept the nominal kinematics (only
/// board, hand–eye and camera identified); a first such set equal to the
/// nominal model is what the campaign supports, and is approved.
pub fn outcome(
    mean_mm: f64,
    nominal_mm: f64,
    compared_with: String,
    compared_mean_mm: f64,
    mut blockers: Vec<String>,
    nominal_kept: bool,
) -> Gate {
    // NaN-safe: anything not shown better is worse.
    let first_nominal = nominal_kept
        && compared_with == NOMINAL
        && mean_mm.partial_cmp(&compared_mean_mm) != Some(std::cmp::Ordering::Greater);
    // A set that predicts the poses as the approved one does (re-running a
    // job on the same images) is the same set, not a better one.
    let same = compared_with != NOMINAL && (mean_mm - compared_mean_mm).abs() <= SAME_WITHIN_MM;
    let worse = !first_nominal
        && !same
        && mean_mm.partial_cmp(&compared_mean_mm) != Some(std::cmp::Ordering::Less);
    let worse_than_nominal =
        mean_mm.partial_cmp(&nominal_mm) == Some(std::cmp::Ordering::Greater) || mean_mm.is_nan();
    if worse_than_nominal && compared_with != NOMINAL {
        blockers.push(format!(
            "hard warning: worse than the nominal model ({mean_mm:.3} mm against {nominal_mm:.3} mm)"
        ));
    }
    let approved = !same && !worse && !worse_than_nominal && blockers.is_empty();
    let comparison = if compared_mean_mm.is_finite() {
        format!(
            "{mean_mm:.3} mm mean 3-D validation error against {compared_mean_mm:.3} mm for {compared_with} on the same poses"
        )
    } else {
        format!("{mean_mm:.3} mm mean 3-D error; {compared_with}")
    };
    let mut reason = if approved && first_nominal {
        format!("approved by the gate: the kinematics stay nominal, no identified model predicted held-out configurations better; board, hand–eye and camera identified ({comparison})")
    } else if approved {
        format!("approved by the gate: better than before ({comparison})")
    } else if same {
        format!("held as a candidate: the same as before, nothing gained ({comparison})")
    } else if worse {
        format!("held as a candidate: not better than before ({comparison})")
    } else {
        format!("held as a candidate ({comparison})")
    };
    if !blockers.is_empty() {
        reason = format!("{reason}; {}", blockers.join("; "));
    }
    let status = if approved {
        ReleaseStatus::Approved
    } else {
        ReleaseStatus::Candidate
    };
    Gate {
        release: Release {
            status,
            reason: Some(reason.clone()),
        },
        report: GateReport {
            status: status.as_str().to_string(),
            reason,
            compared_with,
            compared_mean_mm: compared_mean_mm.is_finite().then_some(compared_mean_mm),
            mean_mm: mean_mm.is_finite().then_some(mean_mm),
            worse: worse || worse_than_nominal,
            basis: None,
            compared_own_mean_mm: None,
            compared_own_session_id: None,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The case: a paper-mode set worse than nominal (11.36 → 11.75 mm).
    #[test]
    fn a_set_worse_than_nominal_is_a_candidate() {
        let gate = outcome(11.75, 11.36, NOMINAL.into(), 11.36, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
        assert!(gate.report.worse);
        assert!(gate.release.reason.unwrap().contains("11.360"));
    }

    #[test]
    fn better_than_the_approved_set_but_worse_than_nominal_is_a_candidate() {
        let gate = outcome(2.0, 1.5, "R/1".into(), 3.0, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
        assert!(gate.release.reason.unwrap().contains("hard warning"));
    }

    #[test]
    fn better_than_before_is_approved_and_nan_never_is() {
        let gate = outcome(0.1, 5.0, "R/1".into(), 0.2, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Approved);
        assert!(!gate.report.worse);
        let gate = outcome(f64::NAN, 5.0, NOMINAL.into(), 5.0, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
        // A hard warning (a paper-mode camera) holds back even a better set.
        let gate = outcome(0.1, 5.0, NOMINAL.into(), 5.0, vec!["paper".into()], false);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
    }

    /// Re-running a job on the same images: equal figures are the same
    /// set, held as a candidate, not "better than before" and not worse.
    #[test]
    fn the_same_figure_as_the_approved_set_is_not_better() {
        let gate = outcome(0.011, 5.0, "R/1".into(), 0.011, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
        assert!(!gate.report.worse);
        let reason = gate.release.reason.unwrap();
        assert!(reason.contains("the same as before"), "{reason}");
        assert!(!reason.contains("better than before"), "{reason}");
        let gate = outcome(0.011 - 1e-9, 5.0, "R/1".into(), 0.011, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
        let gate = outcome(0.010, 5.0, "R/1".into(), 0.011, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Approved);
    }

    /// Identification did not pay: the nominal kinematics kept, equal to
    /// the nominal model, is approved as a first set; never over an
    /// approved set it does not beat, never with a blocker.
    #[test]
    fn a_first_set_that_keeps_the_nominal_kinematics_is_approved() {
        let gate = outcome(1.2, 1.2, NOMINAL.into(), 1.2, Vec::new(), true);
        assert_eq!(gate.release.status, ReleaseStatus::Approved);
        assert!(gate.release.reason.unwrap().contains("stay nominal"));
        let gate = outcome(1.2, 1.2, NOMINAL.into(), 1.2, Vec::new(), false);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
        let gate = outcome(1.2, 1.2, "R/1".into(), 1.2, Vec::new(), true);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
        let gate = outcome(1.2, 1.2, NOMINAL.into(), 1.2, vec!["x".into()], true);
        assert_eq!(gate.release.status, ReleaseStatus::Candidate);
    }
}
