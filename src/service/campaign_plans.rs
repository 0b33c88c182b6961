//! Campaign plans (issue 16): which poses to shoot and how good the result
//! will be. The request is typed here into the numerics' plan request
//! (`robocal_calib::plan`), the plan is computed on a blocking thread and
//! stored; the stored plan is served as JSON or as a cell program.

use std::collections::BTreeMap;

use nalgebra::{Point3, Vector3};
use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::CalibratedModel;
use robocal_calib::plan::planner::PlannedSet;
use robocal_calib::plan::{
    plan_campaign, CampaignPlan, KeepOutBox, PlanError, PlanPurpose, PlanRequest,
};

use super::camera_reuse;
use super::error::{ServiceError, ServiceResult};
use super::evaluate::pose_of;
use super::export::Exported;
use super::results::typed;
use crate::domain::{now_rfc3339, Target};
use crate::export::campaign_program::{
    write_csv, write_krl, write_rapid, write_urscript, ProgramFormat, KRL_PROGRAM,
};
use crate::schema::campaign_plan::{
    CampaignPlanBody, CampaignPlanOut, FilterCountDoc, PlanPurposeDoc, PlannedPoseDoc, PredictedDoc,
};
use crate::schema::robot::{doc_to_model, KinematicsDoc};
use crate::schema::session::{CameraDoc, PoseSet};
use crate::schema::{Checker, FieldError};
use crate::store::{CampaignPlanRecord, DynStore};

/// Micrometres per millimetre (pixel pitch to focal length in pixels).
const UM_PER_MM: f64 = 1000.0;
/// Decimals of the joint values served (1e-6 deg).
const JOINT_DECIMALS: f64 = 1e6;

fn round_deg(rad: f64) -> f64 {
    (rad.to_degrees() * JOINT_DECIMALS).round() / JOINT_DECIMALS
}

/// A pinhole camera from the session's nominal camera: principal point at
/// the image centre, no distortion (the job calibrates them).
fn nominal_intrinsics(camera: &CameraDoc) -> Intrinsics {
    let f_px = camera.nominal_focal_mm * UM_PER_MM / camera.pixel_size_um;
    Intrinsics::pinhole(
        f_px,
        f_px,
        0.5 * f64::from(camera.width),
        0.5 * f64::from(camera.height),
    )
}

/// Every feature of the board in the target frame (mm).
fn board_points(target: &Target) -> Vec<Point3<f64>> {
    let (rows, cols) = match target {
        Target::Dots(t) => (t.rows, t.cols),
        Target::Charuco(t) => (
            t.squares[1].saturating_sub(1),
            t.squares[0].saturating_sub(1),
        ),
        Target::Chessboard(t) => (t.rows(), t.cols()),
        Target::AsymmetricCircles(t) => (t.rows, t.cols),
    };
    (0..rows as u32)
        .flat_map(|r| (0..cols as u32).map(move |c| (r, c)))
        .map(|(r, c)| Point3::from(target.point_mm(r, c)))
        .collect()
}

/// The kinematics the plan uses: the latest parameter set's, else nominal.
async fn planning_robot(
    store: &DynStore,
    serial: &str,
) -> ServiceResult<(robocal_calib::kinematics::RobotModel, String)> {
    let robot = store
        .get_robot(serial)
        .await?
        .ok_or_else(|| ServiceError::not_found("robot", serial))?;
    if let Some(set) = store.get_parameter_set(serial, None).await? {
        if let Ok(model) = typed(&set).and_then(|t| t.model().map_err(ServiceError::internal)) {
            return Ok((model.robot, format!("{serial}/{}", set.version)));
        }
    }
    let doc: KinematicsDoc =
        serde_json::from_value(robot.kinematics).map_err(ServiceError::internal)?;
    Ok((doc_to_model(&doc), "nominal".to_string()))
}

/// Intrinsics and image size: the reused calibration's, else the nominal camera's.
async fn camera_of(
    store: &DynStore,
    body: &CampaignPlanBody,
) -> ServiceResult<(Intrinsics, (u32, u32), bool)> {
    let Some(id) = &body.camera_calibration_id else {
        let camera = body
            .camera
            .as_ref()
            .ok_or_else(|| ServiceError::invalid("camera", "required"))?;
        return Ok((
            nominal_intrinsics(camera),
            (camera.width, camera.height),
            false,
        ));
    };
    let fixed = camera_reuse::resolve(store, id, body.camera.as_ref())
        .await
        .map_err(|e| match e {
            camera_reuse::ReuseError::NotFound(message) => ServiceError::NotFoundField {
                field: camera_reuse::FIELD,
                message,
            },
            camera_reuse::ReuseError::Store(e) => e.into(),
            other => ServiceError::invalid(camera_reuse::FIELD, other.to_string()),
        })?;
    let size = match &body.camera {
        Some(c) => (c.width, c.height),
        None => {
            let (serial, version) = fixed
                .calibration_id
                .split_once('/')
                .and_then(|(s, v)| Some((s.to_string(), v.parse::<i64>().ok()?)))
                .ok_or_else(|| ServiceError::internal("resolved calibration id"))?;
            let report = store.get_report(&serial, version).await?;
            let side = |key: &str| {
                report
                    .as_ref()
                    .and_then(|r| r.pointer(&format!("/camera/{key}")))
                    .and_then(serde_json::Value::as_u64)
                    .and_then(|v| u32::try_from(v).ok())
            };
            match (side("image_width"), side("image_height")) {
                (Some(w), Some(h)) => (w, h),
                _ => {
                    return Err(ServiceError::invalid(
                        "camera",
                        "the calibration does not record its image size: give camera",
                    ))
                }
            }
        }
    };
    Ok((fixed.intrinsics, size, true))
}

fn plan_error(e: PlanError) -> ServiceError {
    match e {
        PlanError::Invalid { field, message } => ServiceError::invalid(field, message),
        PlanError::Infeasible {
            constraint,
            feasible,
            wanted,
            filters,
        } => {
            let mut errors = vec![FieldError::new(
                constraint,
                format!(
                    "this constraint bound: {feasible} feasible poses for {wanted} asked (survivors per filter follow)"
                ),
            )];
            errors.extend(filters.iter().map(|f| {
                FieldError::new(
                    format!("candidates.{}", f.constraint),
                    format!("{} survived", f.survivors),
                )
            }));
            ServiceError::Invalid(errors)
        }
        PlanError::Unidentifiable { parameters } => ServiceError::invalid(
            "view_angle_deg",
            format!("the feasible poses do not determine {parameters:?}: widen the ranges"),
        ),
        PlanError::Model(message) => ServiceError::invalid("kinematics", message),
    }
}

/// The numerics' request from the checked body.
fn plan_request(
    body: &CampaignPlanBody,
    model: CalibratedModel,
    intrinsics: Intrinsics,
    size: (u32, u32),
    hold_intrinsics: bool,
) -> ServiceResult<PlanRequest> {
    let target = Target::from_doc(&body.target)?;
    let dof = model.robot.dof();
    let mut c = Checker::default();
    if let Some(limits) = &body.joint_limits_deg {
        if limits.len() != dof {
            c.fail(
                "joint_limits_deg",
                format!("{} ranges for a {dof}-joint robot", limits.len()),
            );
        }
    }
    if let Some(q) = &body.start_joints_deg {
        if q.len() != dof {
            c.fail(
                "start_joints_deg",
                format!("{} values for a {dof}-joint robot", q.len()),
            );
        }
    }
    c.finish()?;
    let mut r = PlanRequest::new(
        model,
        intrinsics,
        size,
        board_points(&target),
        body.poses as usize,
    );
    r.validation_poses = body.validation_poses as usize;
    r.distance_mm = (body.distance_mm[0], body.distance_mm[1]);
    r.view_angle_deg = (body.view_angle_deg[0], body.view_angle_deg[1]);
    r.joint_limits_rad = body.joint_limits_deg.as_ref().map(|l| {
        l.iter()
            .map(|[lo, hi]| (lo.to_radians(), hi.to_radians()))
            .collect()
    });
    r.keep_out = body
        .keep_out
        .iter()
        .flatten()
        .map(|b| KeepOutBox {
            min_mm: Vector3::from(b.min_mm),
            max_mm: Vector3::from(b.max_mm),
        })
        .collect();
    r.start_joints_rad = body
        .start_joints_deg
        .as_ref()
        .map(|q| q.iter().map(|d| d.to_radians()).collect());
    if let Some(s) = body.sigma_px {
        r.sigma_px = s;
    }
    r.hold_intrinsics = hold_intrinsics;
    match body.purpose {
        Some(PlanPurposeDoc::Calibration) => r.purpose = PlanPurpose::Calibration,
        Some(PlanPurposeDoc::QuickCheck) => r.purpose = PlanPurpose::QuickCheck,
        None => {}
    }
    Ok(r)
}

fn plan_doc(
    id: String,
    serial: &str,
    model_name: String,
    plan: &CampaignPlan,
    sigma_px: f64,
    layout_angles: &dyn Fn(&str) -> bool,
) -> CampaignPlanOut {
    CampaignPlanOut {
        id,
        serial: serial.to_string(),
        poses: plan
            .poses
            .iter()
            .map(|p| PlannedPoseDoc {
                joints_deg: p.joints_rad.iter().map(|q| round_deg(*q)).collect(),
                set: match p.set {
                    PlannedSet::Cal => PoseSet::Cal,
                    PlannedSet::Val => PoseSet::Val,
                },
            })
            .collect(),
        predicted: PredictedDoc {
            validation_error_mean_mm: plan.prediction.validation_error_mean_mm,
            parameter_std_devs: plan
                .prediction
                .parameter_std_devs
                .iter()
                .map(|(name, sd)| {
                    let v = if layout_angles(name) {
                        sd.to_degrees()
                    } else {
                        *sd
                    };
                    (name.clone(), v)
                })
                .collect::<BTreeMap<_, _>>(),
            condition_number: plan.prediction.condition_number,
            sigma_px,
        },
        purpose: match plan.purpose {
            PlanPurpose::Calibration => PlanPurposeDoc::Calibration,
            PlanPurpose::QuickCheck => PlanPurposeDoc::QuickCheck,
        },
        start_joints_deg: plan
            .start_joints_rad
            .iter()
            .map(|q| round_deg(*q))
            .collect(),
        path_length_deg: plan.path_length_rad.to_degrees(),
        candidates: plan
            .filters
            .iter()
            .map(|f| FilterCountDoc {
                constraint: f.constraint.to_string(),
                survivors: f.survivors,
            })
            .collect(),
        model: model_name,
        created_at: now_rfc3339(),
    }
}

/// `POST /v1/robots/{serial}/campaign-plans`: plan, store, return the plan.
pub async fn create_plan(
    store: &DynStore,
    serial: &str,
    body: CampaignPlanBody,
) -> ServiceResult<CampaignPlanOut> {
    body.check()?;
    let (robot, model_name) = planning_robot(store, serial).await?;
    let mut c = Checker::default();
    let target_to_base = pose_of(&body.target_to_base_guess, "target_to_base_guess", &mut c);
    let flange_to_camera = pose_of(
        &body.flange_to_camera_guess,
        "flange_to_camera_guess",
        &mut c,
    );
    c.finish()?;
    let (Some(world_to_base), Some(flange_to_tool)) = (target_to_base, flange_to_camera) else {
        return Err(ServiceError::invalid("target_to_base_guess", "not a pose"));
    };
    let (intrinsics, size, hold) = camera_of(store, &body).await?;
    let model = CalibratedModel {
        robot,
        world_to_base,
        flange_to_tool,
    };
    let request = plan_request(&body, model, intrinsics, size, hold)?;
    let sigma_px = request.sigma_px;
    let layout = robocal_calib::kinematics::ParamLayout::new(
        &request.model.robot,
        robocal_calib::kinematics::Instrument::Camera,
    );
    let plan = tokio::task::spawn_blocking(move || plan_campaign(&request))
        .await
        .map_err(ServiceError::internal)?
        .map_err(plan_error)?;
    let is_angle = |name: &str| layout.index_of(name).is_some_and(|i| layout.is_angle(i));
    let id = uuid::Uuid::now_v7().to_string();
    let out = plan_doc(id, serial, model_name, &plan, sigma_px, &is_angle);
    let record = CampaignPlanRecord {
        id: out.id.clone(),
        serial: serial.to_string(),
        request: serde_json::to_value(&body).map_err(ServiceError::internal)?,
        plan: serde_json::to_value(&out).map_err(ServiceError::internal)?,
        created_at: out.created_at.clone(),
    };
    store.insert_campaign_plan(&record).await?;
    Ok(out)
}

/// `GET /v1/robots/{serial}/campaign-plans/{id}?format=`.
pub async fn get_plan(
    store: &DynStore,
    serial: &str,
    id: &str,
    format: Option<&str>,
) -> ServiceResult<Exported> {
    let format = match format {
        None => ProgramFormat::Json,
        Some(name) => ProgramFormat::parse(name).ok_or_else(|| {
            ServiceError::invalid(
                "format",
                format!("must be one of {}", ProgramFormat::NAMES.join(", ")),
            )
        })?,
    };
    let record = store
        .get_campaign_plan(serial, id)
        .await?
        .ok_or_else(|| ServiceError::not_found("campaign plan", id))?;
    let plan: CampaignPlanOut =
        serde_json::from_value(record.plan).map_err(ServiceError::internal)?;
    let joints = plan.poses.first().map_or(0, |p| p.joints_deg.len());
    if let Some(max) = format.max_joints().filter(|&m| joints > m) {
        return Err(ServiceError::invalid(
            "format",
            format!(
                "a {} program carries at most {max} axes; this robot has {joints}",
                ProgramFormat::NAMES[format as usize]
            ),
        ));
    }
    let body = match format {
        ProgramFormat::Json => serde_json::to_vec_pretty(&plan).map_err(ServiceError::internal)?,
        ProgramFormat::Csv => write_csv(&plan).into_bytes(),
        ProgramFormat::Urscript => write_urscript(&plan).into_bytes(),
        ProgramFormat::Rapid => write_rapid(&plan).into_bytes(),
        ProgramFormat::Krl => write_krl(&plan).into_bytes(),
    };
    Ok(Exported {
        content_type: format.content_type(),
        // KRL wants the file named as its DEF.
        file_name: match format {
            ProgramFormat::Krl => format!("{KRL_PROGRAM}.src"),
            _ => format!("{serial}-plan-{id}.{}", format.extension()),
        },
        body,
    })
}
