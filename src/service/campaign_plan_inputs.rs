//! What a campaign plan is computed from (issue 16): the robot's
//! kinematics (its latest parameter set's, else nominal), the camera (a
//! reused calibration's intrinsics, else the nominal camera's), the board's
//! points, and the body's ranges, typed into the numerics' plan request.

use nalgebra::{Point3, Vector3};
use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::{CalibratedModel, RobotModel};
use robocal_calib::plan::{KeepOutBox, PlanPurpose, PlanRequest};

use super::camera_reuse;
use super::error::{ServiceError, ServiceResult};
use super::report_camera::report_camera;
use super::results::typed;
use crate::domain::Target;
use crate::schema::campaign_plan::{CampaignPlanBody, PlanPurposeDoc};
use crate::schema::robot::{doc_to_model, KinematicsDoc};
use crate::schema::session::{CameraDoc, Instrument};
use crate::schema::Checker;
use crate::store::DynStore;

/// Micrometres per millimetre (pixel pitch to focal length in pixels).
const UM_PER_MM: f64 = 1000.0;

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

/// What the plan starts from: the kinematics (the latest parameter set's,
/// else nominal), what they are called, and the latest set's calibrated
/// frames (the guesses a request may omit).
pub struct PlanningRobot {
    pub robot: RobotModel,
    pub model_name: String,
    /// The latest set's `target_to_base` and `flange_to_camera`.
    pub latest: Option<CalibratedModel>,
}

/// The robot a plan is computed for (404 for an unknown serial).
pub async fn planning_robot(store: &DynStore, serial: &str) -> ServiceResult<PlanningRobot> {
    let robot = store
        .get_robot(serial)
        .await?
        .ok_or_else(|| ServiceError::not_found("robot", serial))?;
    if let Some(set) = store.get_parameter_set(serial, None).await? {
        if let Ok(typed) = typed(&set) {
            if let Ok(model) = typed.model() {
                // A tracker set's frames are the tracker's, not a board's.
                let camera = typed.instrument == Instrument::Camera;
                return Ok(PlanningRobot {
                    robot: model.robot.clone(),
                    model_name: format!("{serial}/{}", set.version),
                    latest: camera.then_some(model),
                });
            }
        }
    }
    let doc: KinematicsDoc =
        serde_json::from_value(robot.kinematics).map_err(ServiceError::internal)?;
    Ok(PlanningRobot {
        robot: doc_to_model(&doc),
        model_name: "nominal".to_string(),
        latest: None,
    })
}

/// Intrinsics and image size: the reused calibration's, else the nominal camera's.
pub async fn camera_of(
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
            report_camera(store, &serial, version)
                .await?
                .map(|c| c.image_size())
                .ok_or_else(|| {
                    ServiceError::invalid(
                        "camera",
                        "the calibration does not record its image size: give camera",
                    )
                })?
        }
    };
    Ok((fixed.intrinsics, size, true))
}

/// The numerics' request from the checked body.
pub fn plan_request(
    body: &CampaignPlanBody,
    model: CalibratedModel,
    intrinsics: Intrinsics,
    size: (u32, u32),
    hold_intrinsics: bool,
    sigma_px: f64,
) -> ServiceResult<PlanRequest> {
    let target = Target::from_doc(
        body.target
            .as_ref()
            .ok_or_else(|| ServiceError::invalid("target", "required"))?,
    )?;
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
    r.sigma_px = sigma_px;
    r.hold_intrinsics = hold_intrinsics;
    match body.purpose {
        Some(PlanPurposeDoc::Calibration) => r.purpose = PlanPurpose::Calibration,
        Some(PlanPurposeDoc::QuickCheck) => r.purpose = PlanPurpose::QuickCheck,
        // An extension adds to a calibration campaign whatever its size.
        None if body.extend_session.is_some() => r.purpose = PlanPurpose::Calibration,
        None => {}
    }
    Ok(r)
}
