//! The full calibration of one session: screen the poses, identify the
//! robot (with the model ladder and the non-geometric terms), then the set,
//! its report and the release gate's decision (method.md §6–7).

use std::sync::atomic::AtomicBool;

use robocal_calib::kinematics::nongeometric::CandidateOptions;

use crate::domain::CalibratedSet;
use crate::pipeline::prelude::{check_cancelled, flange_guess, Prelude};
use crate::pipeline::{
    detections, gate, identify_stage, measuring, output, results, screen_stage, Input, Output,
    PipelineError, Stage,
};

/// Identifies the robot of a camera or tracker session from what the
/// prelude measured.
pub fn run(
    input: &Input,
    prelude: Prelude,
    within: &dyn Fn(Stage, &str, f64),
    cancel: &AtomicBool,
) -> Result<Output, PipelineError> {
    let Prelude {
        mut notes,
        measured,
        camera,
    } = prelude;
    let intrinsics_held = input.fixed_camera.is_some() || !input.options.refine_intrinsics;
    let usable: Vec<usize> = (0..input.poses.len())
        .filter(|&i| camera.as_ref().is_none_or(|c| c.view_pose.contains(&i)))
        .collect();
    let (usable, outliers) = match &camera {
        Some(step) => {
            let (kept, outliers, note) =
                screen_stage::screen_poses(&input.robot, &input.poses, step, &usable);
            notes.extend(note);
            (kept, outliers)
        }
        None => (usable, Vec::new()),
    };
    let measuring =
        measuring::Measuring::for_job(&input.session, input.options.measurement, &input.poses)?;
    let guess = flange_guess(input);
    // Paper mode keeps the paper's pipeline: its Tsai intrinsics are not
    // the joint refinement's camera model, so refining on the image points
    // with them held fits the model error instead (tens of px). A reused
    // camera is held fixed.
    let paper_camera = !input.options.refine_intrinsics && input.fixed_camera.is_none();
    let joint_refinement = input.options.joint_refinement && !paper_camera;
    if camera.is_some() && input.options.joint_refinement && intrinsics_held {
        notes.push(if paper_camera {
            "Joint refinement skipped: paper mode (refine_intrinsics: false) keeps the paper's pose-level identification.".to_string()
        } else {
            "Joint refinement held the camera intrinsics fixed at the reused calibration's.".to_string()
        });
    }
    within(Stage::Identify, "kinematic identification", 0.0);
    // Term selection: default on for trackers, opt-in for cameras (there
    // the terms are selected again on the image points; see
    // `CalibrationOptions::non_geometric_for`).
    let candidates = input
        .options
        .non_geometric_for(input.session.instrument)
        .then(|| CandidateOptions {
            payload_kg: input.session.payload_kg.unwrap_or(0.0),
            ..CandidateOptions::for_robot(&input.robot)
        });
    let identify = |usable: &[usize], outliers: &[screen_stage::Outlier]| {
        identify_stage::identify_robot(
            &input.robot,
            &input.poses,
            camera.as_ref(),
            guess,
            measuring,
            input.options.validation,
            joint_refinement,
            intrinsics_held,
            usable,
            &outliers.iter().map(|o| o.pose).collect::<Vec<_>>(),
            candidates.as_ref(),
            input.prior,
        )
    };
    let (identified, outliers) = screen_stage::identify_confirmed(usable, outliers, identify)?;
    notes.extend(screen_stage::note(&input.poses, &outliers));
    notes.extend(identified.terms.as_ref().and_then(|t| t.range_note()));
    if let Some(sigma) = identified.joint_noise_rad {
        notes.push(format!(
            "Joint noise (encoders, repeatability) estimated from the images: {:.1e} deg per joint; the parameter standard deviations include it.",
            sigma.to_degrees()
        ));
    }
    check_cancelled(cancel)?;
    within(Stage::Report, "building the report", 0.0);
    if let Some(m) = &measured {
        if !m.failures.is_empty() {
            notes.push(format!(
                "{} of {} images were not used (see detection failures).",
                m.failures.len(),
                m.points.len()
            ));
        }
    }
    let context = results::Context {
        serial: &input.serial,
        session_id: &input.session_id,
        controller: input.session.controller.as_ref(),
        instrument: input.session.instrument,
        measuring,
        poses: &input.poses,
        measured: measured.as_ref(),
        camera: camera.as_ref(),
        outliers: &outliers,
        notes,
    };
    let set = results::parameter_set(&context, &identified);
    let mut report = results::report(&context, &identified, &set);
    let gate = gate::decide(
        &identified,
        &set,
        context.instrument,
        input.approved.as_ref(),
        paper_camera && camera.is_some(),
    );
    report.gate = Some(gate.report);
    let detections = match (&measured, &camera) {
        (Some(m), Some(step)) => detections::with_residuals(
            &input.poses,
            m,
            step,
            &identified
                .term_model()
                .map_err(|e| PipelineError::numerical(Stage::Report, e))?,
            &set.camera.unwrap_or(step.intrinsics()),
            measuring.kind == crate::schema::job::Measurement::Pose,
        ),
        _ => Vec::new(),
    };
    within(Stage::Report, "done", 1.0);
    Ok(Output {
        parameter_set: Some(output::new_set(
            CalibratedSet::Kinematic(set),
            &report,
            gate.release,
        )?),
        summary: results::summary(&identified),
        detections,
        check: None,
    })
}
