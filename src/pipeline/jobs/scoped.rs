//! A partial recalibration (issue 17): `scope: "base"` re-fits only the
//! board's (tracker's) transform in the robot base frame, `"hand_eye"` only
//! the camera's (tool's) in the flange frame, from a few poses, holding the
//! kinematics, the other frame and the camera intrinsics at the robot's
//! latest approved set (the paper recalibrated the base in each region).
//! "Before" is that set as it was; the gate approves the result when it
//! predicts the validation poses better. The approved set's kept
//! non-geometric terms (issue 19) stay in the result and are held at their
//! values through the fit and both validations.

use robocal_calib::kinematics::identify::{
    fit_parameters, validate, IdentifyMode, IdentifyOptions, JointNoise,
};
use robocal_calib::kinematics::initial::initial_world_to_base;
use robocal_calib::kinematics::{ParamKind, ParamLayout};

use crate::domain::{CalibratedSet, ParameterSet};
use crate::pipeline::camera_stage::{camera_report, CameraStep};
use crate::pipeline::identify_stage::split;
use crate::pipeline::measure::Measured;
use crate::pipeline::measuring::Measuring;
use crate::pipeline::results::residual_field;
use crate::pipeline::{Input, Output, PipelineError, Stage, Summary};
use crate::report::{DetectionReport, IdentifiabilityReport, PoseReport, Report};
use crate::schema::job::CalibrationScope;
use crate::schema::PoseOut;

fn numerical(message: impl std::fmt::Display) -> PipelineError {
    PipelineError::numerical(Stage::Identify, message)
}

/// The layout indices a scope re-fits.
fn refitted(layout: &ParamLayout, scope: CalibrationScope) -> Vec<usize> {
    (0..layout.len())
        .filter(|&i| {
            matches!(
                (layout.params[i].kind, scope),
                (ParamKind::Base(_), CalibrationScope::Base)
                    | (ParamKind::Tool(_), CalibrationScope::HandEye)
            )
        })
        .collect()
}

/// Runs the partial recalibration after the camera stage.
pub fn run(
    input: &Input,
    measured: Option<&Measured>,
    camera: Option<&CameraStep>,
    mut notes: Vec<String>,
    within: &dyn Fn(Stage, &str, f64),
) -> Result<Output, PipelineError> {
    let scope = input.options.scope;
    let approved = input.approved.as_ref().ok_or_else(|| {
        PipelineError::invalid(
            "scope",
            format!(
                "scope {:?} holds the latest approved set, and robot {} has none",
                scope.as_str(),
                input.serial
            ),
        )
    })?;
    let (instrument, measuring) =
        Measuring::for_approved(approved, &input.session, &input.poses, "scope")?;
    let terms = approved.set.term_model().map_err(numerical)?;
    let held = terms.model.clone();
    within(Stage::Identify, "re-fitting the scope's frame", 0.0);
    let usable: Vec<usize> = (0..input.poses.len())
        .filter(|&i| camera.is_none_or(|c| c.view_pose.contains(&i)))
        .collect();
    let (cal, val) = split(&input.poses, &usable, input.options.validation);
    let measure = |indices: &[usize]| -> (Vec<usize>, Vec<_>) {
        indices
            .iter()
            .filter_map(|&i| Some((i, measuring.of(&input.poses[i], i, camera, None)?)))
            .unzip()
    };
    // With the terms held, the geometric fit and validation of the
    // deflected joints are those through the terms.
    let deflect = |data: Vec<_>| terms.deflect_measurements(&data).map_err(numerical);
    let cal_data = deflect(measure(&cal).1)?;
    let (val_index, val_data) = measure(&val);
    let val_data = deflect(val_data)?;
    if val_data.is_empty() {
        return Err(numerical(
            "no validation pose could be measured: upload poses with set \"val\" or use {\"validation\":{\"holdout_fraction\":0.3}}",
        ));
    }
    let layout = ParamLayout::new(&held.robot, instrument);
    let which = refitted(&layout, scope);
    let mut start = held.clone();
    if scope == CalibrationScope::Base {
        // The board may have moved far: start from a registration of the
        // measured poses, as a full calibration does.
        start.world_to_base = initial_world_to_base(&held, &cal_data).map_err(numerical)?;
    }
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::default(),
    };
    let (model, _) =
        fit_parameters(&start, instrument, &cal_data, &which, options).map_err(numerical)?;
    let (before, before_errors) = validate(&held, &val_data).map_err(numerical)?;
    let (after, after_errors) = validate(&model, &val_data).map_err(numerical)?;
    let set = ParameterSet {
        session_id: input.session_id.clone(),
        world_to_base: PoseOut::new(&model.world_to_base),
        flange_to_tool: PoseOut::new(&model.flange_to_tool),
        // The camera is the approved set's, held fixed.
        camera_mode: camera.map(|_| "fixed".to_string()),
        camera_calibration_id: camera.map(|_| approved.id.clone()),
        // One session's board: the approved set's other placements are
        // not this set's.
        session_target_to_base: Vec::new(),
        // The controller this session was measured on, not the held set's.
        controller: input.session.controller.clone(),
        ..approved.set.clone()
    };
    let frame = match scope {
        CalibrationScope::HandEye => set.frame_names().flange_to_end,
        _ => set.frame_names().world_to_base,
    };
    notes.push(format!(
        "Only {frame} was re-fitted (scope {:?}) from {} poses; the kinematics, the other frame{}{} \
         and the covariance are those of the approved set {}. Before: that set as it was.",
        scope.as_str(),
        cal_data.len(),
        if camera.is_some() {
            ", the camera intrinsics"
        } else {
            ""
        },
        if terms.has_terms() {
            ", its non-geometric terms (held through the fit)"
        } else {
            ""
        },
        approved.id
    ));
    // No nominal model takes part in a partial scope: "before" is the
    // approved set, the only comparison.
    let gate = crate::pipeline::gate::outcome(
        after.norm.mean_mm,
        f64::INFINITY,
        approved.id.clone(),
        before.norm.mean_mm,
        Vec::new(),
        false,
    );
    let per_pose = val_index
        .iter()
        .zip(before_errors.iter().zip(&after_errors))
        .map(|(&i, (b, a))| PoseReport {
            pose_id: input.poses[i].id.clone(),
            label: input.poses[i].label.clone(),
            set: "val".into(),
            joints_deg: input.poses[i].joints_deg.as_deg().to_vec(),
            before_error_mm: [b.x, b.y, b.z],
            after_error_mm: [a.x, a.y, a.z],
            before_mm: b.norm(),
            after_mm: a.norm(),
            reprojection_rms_px: None,
            outlier: false,
            reason: None,
            camera_in_target: None,
        })
        .collect();
    let report = Report {
        serial: input.serial.clone(),
        version: 0,
        job_id: String::new(),
        session_id: input.session_id.clone(),
        created_at: crate::domain::now_rfc3339(),
        instrument: set.instrument.as_str().to_string(),
        measurement: measuring.kind.as_str().into(),
        camera: camera.map(|step| camera_report(step, &step.intrinsics(), None, &input.poses)),
        detection: measured.map(|m| DetectionReport {
            images: m.points.len(),
            images_detected: m.points.iter().filter(|p| p.is_some()).count(),
            dots_per_image: m.points.iter().flatten().map(Vec::len).max().unwrap_or(0),
            failures: m.failures.clone(),
        }),
        before,
        after,
        per_pose,
        parameters: set.parameters.clone(),
        // A frame's 6 (or 3) components from a few poses: no
        // identifiability analysis ran (0 = not computed).
        identifiability: IdentifiabilityReport {
            parameters: which.len(),
            rank: which.len(),
            condition_number: 0.0,
            observability_index: 0.0,
            fixed: Vec::new(),
            weak: Vec::new(),
        },
        residual_field: camera.map(residual_field).unwrap_or_default(),
        hand_eye: None,
        notes,
        uncertainty_map: None,
        terms: None,
        gate: Some(gate.report),
        model_selection: None,
        release: Default::default(),
        measurement_accuracy: None,
        regions: Vec::new(),
    };
    let summary = Summary {
        calibration_poses: cal_data.len(),
        validation_poses: val_data.len(),
        before_mean_mm: Some(before.norm.mean_mm),
        after_mean_mm: Some(after.norm.mean_mm),
        ..Summary::default()
    };
    within(Stage::Report, "done", 1.0);
    Ok(Output {
        parameter_set: Some(crate::pipeline::output::new_set(
            CalibratedSet::Kinematic(set),
            &report,
            gate.release,
        )?),
        summary,
        detections: Vec::new(),
        check: None,
    })
}
