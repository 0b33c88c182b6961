//! Stage "report": the parameter set (what `forward` and `compensate`
//! evaluate) and the accuracy report (api.md "Results"), from the stages'
//! outcomes.

use robocal_calib::kinematics::{ParamKind, ParamLayout};

use super::camera_stage::{camera_mode, camera_report, CameraStep};
use super::identify_stage::Identified;
use super::measure::Measured;
use super::measuring::Measuring;
use super::screen_stage::Outlier;
use super::{PoseInput, Summary};
use crate::domain::{CovarianceDoc, ParameterSet};
use crate::report::{
    CameraStd, IdentifiabilityReport, ParameterReport, PoseReport, Report, ResidualSample,
    TermsReport,
};
use crate::schema::robot::model_to_doc;
use crate::schema::session::Instrument as SessionInstrument;
use crate::schema::PoseOut;

/// Most residual arrows kept in a report (the plot averages them anyway).
const MAX_RESIDUAL_SAMPLES: usize = 6000;

fn display_value(layout: &ParamLayout, i: usize, value: f64) -> (f64, String) {
    if layout.is_angle(i) {
        (value.to_degrees(), "deg".into())
    } else {
        (value, "mm".into())
    }
}

/// Nominal (the "before" model) against identified values, per parameter.
fn parameter_rows(id: &Identified) -> Vec<ParameterReport> {
    let layout = &id.identification.layout;
    let correction = layout.difference(&id.model, &id.identification.before);
    let std = &id.std_devs;
    let fixed = &id.identification.identifiability.fixed;
    layout
        .params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let nominal = match (p.kind, p.joint) {
                (ParamKind::JointOffset, Some(j)) => {
                    id.identification.before.robot.joints[j].theta_offset_rad
                }
                (ParamKind::Length, Some(j)) => id.identification.before.robot.joints[j].a_mm,
                (ParamKind::Offset, Some(j)) => id.identification.before.robot.joints[j].d_mm,
                (ParamKind::Tilt, Some(j)) => id.identification.before.robot.joints[j].beta_rad,
                (ParamKind::Twist, Some(j)) => id.identification.before.robot.joints[j].alpha_rad,
                _ => 0.0,
            };
            let (nominal_out, unit) = display_value(layout, i, nominal);
            let (identified_out, _) = display_value(layout, i, nominal + correction[i]);
            let (std_out, _) = display_value(layout, i, std[i]);
            ParameterReport {
                name: p.name.clone(),
                unit,
                nominal: nominal_out,
                identified: identified_out,
                std: std_out,
                fixed: fixed.contains(&p.name),
            }
        })
        .collect()
}

pub struct Context<'a> {
    pub serial: &'a str,
    pub session_id: &'a str,
    /// The controller the session was measured on: the set
    /// inherits it.
    pub controller: Option<&'a crate::domain::ControllerIdentity>,
    /// The session's instrument (the set's frame names follow it).
    pub instrument: SessionInstrument,
    /// What each pose measured: a tracker's set records it (a 6-DoF
    /// probe's identifies the tool's frame).
    pub measuring: Measuring,
    pub poses: &'a [PoseInput],
    pub measured: Option<&'a Measured>,
    pub camera: Option<&'a CameraStep>,
    /// Poses the screening left out (`screen_stage`).
    pub outliers: &'a [Outlier],
    pub notes: Vec<String>,
}

pub fn parameter_set(ctx: &Context, id: &Identified) -> ParameterSet {
    let rows = parameter_rows(id);
    ParameterSet {
        instrument: if ctx.instrument.has_camera() {
            SessionInstrument::Camera
        } else {
            SessionInstrument::Tracker
        },
        measurement: (!ctx.instrument.has_camera()).then_some(ctx.measuring.kind),
        session_id: ctx.session_id.to_string(),
        kinematics: model_to_doc(&id.model.robot),
        world_to_base: PoseOut::new(&id.model.world_to_base),
        flange_to_tool: PoseOut::new(&id.model.flange_to_tool),
        camera: id
            .refined_intrinsics
            .as_ref()
            .map(|r| r.0)
            .or_else(|| ctx.camera.map(|c| c.intrinsics())),
        camera_mode: ctx.camera.map(|c| camera_mode(c).to_string()),
        camera_calibration_id: ctx.camera.and_then(|c| c.fixed_from.clone()),
        fixed: id.identification.identifiability.fixed.clone(),
        parameters: rows,
        covariance: Some(CovarianceDoc::from_layout(
            &id.identification.layout,
            &id.covariance,
            &id.identification.identifiability.free,
        )),
        joint_noise_deg: id.joint_noise_rad.map(f64::to_degrees),
        terms: id.terms.clone(),
        session_target_to_base: Vec::new(),
        controller: ctx.controller.cloned(),
    }
}

pub(super) fn residual_field(step: &CameraStep) -> Vec<ResidualSample> {
    let intr = step.calibration.intrinsics;
    let mut out = Vec::new();
    for (view, obs) in step.calibration.views.iter().zip(&step.observations) {
        for (p, px) in obs {
            if let Some(pred) = intr.project(&(view.camera_to_target * p)) {
                out.push(ResidualSample {
                    x_px: px.x,
                    y_px: px.y,
                    dx_px: px.x - pred.x,
                    dy_px: px.y - pred.y,
                });
            }
        }
    }
    let stride = out.len().div_ceil(MAX_RESIDUAL_SAMPLES).max(1);
    out.into_iter().step_by(stride).collect()
}

pub fn report(ctx: &Context, id: &Identified, set: &ParameterSet) -> Report {
    let camera = ctx.camera.map(|step| {
        let std = id.refined_intrinsics.as_ref().map(|(_, s, _)| CameraStd {
            fx: s[0],
            fy: s[1],
            cx: s[2],
            cy: s[3],
            k1: s[4],
            k2: s[5],
            p1: s[6],
            p2: s[7],
            ..CameraStd::default()
        });
        let intr = set.camera.unwrap_or(step.intrinsics());
        camera_report(step, &intr, std, ctx.poses)
    });
    let detection = ctx.measured.map(Measured::report);
    let per_view_rms = |i: usize| {
        let step = ctx.camera?;
        let view = step.view_pose.iter().position(|&p| p == i)?;
        Some(step.calibration.views[view].rms_px)
    };
    let reason_of = |i: usize| {
        ctx.outliers
            .iter()
            .find(|o| o.pose == i)
            .map(|o| o.reason.clone())
    };
    let per_pose = id
        .val_errors
        .iter()
        .chain(&id.outlier_errors)
        .map(|(i, before, after)| PoseReport {
            pose_id: ctx.poses[*i].id.clone(),
            label: ctx.poses[*i].label.clone(),
            // Validation poses (uploaded or held out) are "val"; an outlier
            // keeps the set it was uploaded in.
            set: match reason_of(*i) {
                Some(_) => ctx.poses[*i].set.as_str().into(),
                None => "val".into(),
            },
            joints_deg: ctx.poses[*i].joints_deg.as_deg().to_vec(),
            before_error_mm: [before.x, before.y, before.z],
            after_error_mm: [after.x, after.y, after.z],
            before_mm: before.norm(),
            after_mm: after.norm(),
            reprojection_rms_px: per_view_rms(*i),
            outlier: reason_of(*i).is_some(),
            reason: reason_of(*i),
            camera_in_target: None,
        })
        .collect();
    let ident = &id.identification.identifiability;
    let mut notes = ctx.notes.clone();
    if id.after.norm.mean_mm > id.before.norm.mean_mm {
        notes.push(format!(
            "Warning: this set predicts the validation poses worse than the nominal model ({:.3} mm against {:.3} mm mean): do not send it to production. {}",
            id.after.norm.mean_mm,
            id.before.norm.mean_mm,
            if set.camera_mode.as_deref() == Some("paper") {
                "The paper's camera model (one radial term) does not fit this lens well enough; calibrate with refine_intrinsics: true."
            } else {
                "Check the validation poses and the board description, or add calibration poses."
            }
        ));
    }
    if id.terms.is_some() {
        notes.push(if id.refined_intrinsics.is_some() {
            "Non-geometric terms kept (see terms): selected and refined with the geometry, hand–eye and intrinsics on the image points; the parameter σ are marginal over the terms."
        } else {
            "Non-geometric terms kept (see terms): the geometry was refitted with them at pose level; the parameter σ are marginal over the terms."
        }.to_string());
    }
    if !ident.weak.is_empty() {
        notes.push(format!(
            "The poses did not determine {}: held at nominal. Add poses that move these joints more widely to identify them.",
            ident.weak.join(", ")
        ));
    }
    if !ident.poorly_determined.is_empty() {
        notes.push(format!(
            "The poses determine {} poorly (little excitation: their joints take few distinct values, or they trade against other parameters); they are identified but their σ is large. Add poses that move these joints more widely.",
            ident.poorly_determined.join(", ")
        ));
    }
    Report {
        serial: ctx.serial.to_string(),
        version: 0,
        job_id: String::new(),
        session_id: ctx.session_id.to_string(),
        created_at: crate::domain::now_rfc3339(),
        instrument: set.instrument.as_str().to_string(),
        measurement: ctx.measuring.kind.as_str().to_string(),
        camera,
        detection,
        before: id.before,
        after: id.after,
        per_pose,
        parameters: set.parameters.clone(),
        identifiability: IdentifiabilityReport {
            parameters: id.identification.layout.len(),
            rank: ident.rank,
            condition_number: ident.condition_number,
            observability_index: ident.observability_index,
            fixed: ident.fixed.clone(),
            weak: ident
                .weak
                .iter()
                .chain(&ident.poorly_determined)
                .cloned()
                .collect(),
        },
        residual_field: ctx.camera.map(residual_field).unwrap_or_default(),
        hand_eye: None,
        notes,
        uncertainty_map: super::uncertainty_map::workspace_map(id, ctx.poses),
        gate: None,
        model_selection: id.model_selection.clone(),
        release: Default::default(),
        measurement_accuracy: None,
        regions: Vec::new(),
        terms: id
            .selection
            .as_ref()
            .map(|s| TermsReport::of(s, s.terms.payload_kg)),
    }
}

/// The summary stored as the job's result document.
pub fn summary(id: &Identified) -> Summary {
    Summary {
        stage: None,
        calibration_poses: id.cal.len(),
        validation_poses: id.val.len(),
        joints: None,
        before_mean_mm: Some(id.before.norm.mean_mm),
        after_mean_mm: Some(id.after.norm.mean_mm),
        ..Summary::default()
    }
}
