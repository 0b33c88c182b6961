//! Results of a robot: its versioned parameter sets, and the calibrated
//! model of one of them evaluated (forward kinematics, compensation).

use futures_util::Stream;
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::RobotModel;

use super::compensate::{self, CompensateRequest, CompensateResponse, Compensation};
use super::error::{ServiceError, ServiceResult};
use super::evaluate::{ForwardRequest, ForwardResponse};
use super::filter::{self, FilterRequest, FilterResponse, Filtering};
use super::target_stream;
use super::uncertainty::{self, Uncertainty, UncertaintyMapRequest, UncertaintyMapResponse};
use crate::domain::{check_controller, CalibratedSet, ControllerIdentity, ParameterSet};
use crate::schema::robot::{doc_to_model, KinematicsDoc};
use crate::store::DynStore;
use crate::store::ParameterSetRecord;

/// The path word that names a robot's newest parameter set.
pub const LATEST: &str = "latest";

/// `latest` (`None`) or a positive integer.
fn parse_version(version: &str) -> ServiceResult<Option<i64>> {
    if version == LATEST {
        return Ok(None);
    }
    match version.parse::<i64>() {
        Ok(v) if v >= 1 => Ok(Some(v)),
        _ => Err(ServiceError::invalid(
            "version",
            "a positive integer or \"latest\"",
        )),
    }
}

/// Parameter set `version` (`latest` allowed) of robot `serial`, or 404.
pub async fn find_parameter_set(
    store: &DynStore,
    serial: &str,
    version: &str,
) -> ServiceResult<ParameterSetRecord> {
    let v = parse_version(version)?;
    store
        .get_parameter_set(serial, v)
        .await?
        .ok_or_else(|| ServiceError::not_found("parameter set", &format!("{serial}/{version}")))
}

/// A stored parameter set's robot model (409 when the set holds none: a
/// hand–eye or stage camera set).
pub fn typed(record: &ParameterSetRecord) -> ServiceResult<ParameterSet> {
    record.parameters.kinematic().cloned().ok_or_else(no_model)
}

fn no_model() -> ServiceError {
    ServiceError::Conflict("this parameter set holds no calibrated model".into())
}

/// 409 for a hand–eye set (a flange-pose session's): it holds no
/// identified kinematics, and evaluating the robot's nominal joint table
/// under its name would pass uncalibrated kinematics off as calibrated.
pub fn refuse_hand_eye(set: &ParameterSetRecord) -> ServiceResult<()> {
    if let CalibratedSet::HandEye(_) = set.parameters {
        return Err(ServiceError::Conflict(format!(
            "parameter set {}/{} is a hand–eye calibration from controller flange poses: \
             it identified no kinematics, so it has no model to evaluate or export; \
             use a set calibrated from joint angles",
            set.serial, set.version
        )));
    }
    Ok(())
}

/// The calibrated model of a parameter set with its kept terms (409 when
/// it holds none).
async fn model(
    store: &DynStore,
    serial: &str,
    version: &str,
    session_id: Option<&str>,
    expect_controller: Option<&ControllerIdentity>,
) -> ServiceResult<TermModel> {
    let record = find_parameter_set(store, serial, version).await?;
    refuse_hand_eye(&record)?;
    let set = typed(&record)?;
    check_controller(expect_controller, set.controller.as_ref())
        .map_err(ServiceError::controller("the parameter set"))?;
    in_session(set, session_id)?
        .term_model()
        .map_err(|_| no_model())
}

/// The set in session `session_id`'s board frame; 422 naming
/// `session_id` when the set knows no such session.
fn in_session(set: ParameterSet, session_id: Option<&str>) -> ServiceResult<ParameterSet> {
    let Some(id) = session_id else {
        return Ok(set);
    };
    set.in_session(id).ok_or_else(|| {
        ServiceError::Invalid(vec![crate::schema::FieldError::new(
            "session_id",
            format!(
                "this parameter set has no session {id}: it knows {}",
                set.session_ids().join(", ")
            ),
        )])
    })
}

/// A parameter set's calibrated model and its stored covariance (`None`
/// for sets stored without one).
async fn model_and_uncertainty(
    store: &DynStore,
    serial: &str,
    version: &str,
    session_id: Option<&str>,
) -> ServiceResult<(TermModel, Option<Uncertainty>)> {
    let record = find_parameter_set(store, serial, version).await?;
    refuse_hand_eye(&record)?;
    let doc = in_session(typed(&record)?, session_id)?;
    let model = doc.term_model().map_err(|_| no_model())?;
    let uncertainty = Uncertainty::of(&doc, &model)
        .transpose()
        .map_err(ServiceError::internal)?;
    Ok((model, uncertainty))
}

/// Forward kinematics of a parameter set's calibrated model, with each
/// row's predicted σ when the set holds a covariance.
pub async fn forward(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: &ForwardRequest,
) -> ServiceResult<ForwardResponse> {
    let (model, uncertainty) =
        model_and_uncertainty(store, serial, version, request.session_id.as_deref()).await?;
    Ok(uncertainty::forward(&model, uncertainty.as_ref(), request)?)
}

/// Predicted σ over the workspace (`uncertainty-map`), on a blocking
/// thread (a box is solved by inverse kinematics).
pub async fn uncertainty_map(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: UncertaintyMapRequest,
) -> ServiceResult<UncertaintyMapResponse> {
    let (model, uncertainty) =
        model_and_uncertainty(store, serial, version, request.session_id.as_deref()).await?;
    let uncertainty = uncertainty.ok_or_else(|| {
        ServiceError::Conflict(
            "this parameter set was stored without its covariance: calibrate again to predict uncertainties"
                .into(),
        )
    })?;
    let answer = tokio::task::spawn_blocking(move || {
        uncertainty::uncertainty_map(&model, &uncertainty, &request)
    })
    .await
    .map_err(ServiceError::internal)?;
    Ok(answer?)
}

/// Joints that put the tool on each target by a parameter set's calibrated
/// model (inverse kinematics on a blocking thread).
pub async fn compensate(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: CompensateRequest,
) -> ServiceResult<CompensateResponse> {
    let model = model(
        store,
        serial,
        version,
        request.session_id.as_deref(),
        request.expect_controller.as_ref(),
    )
    .await?;
    let answer = tokio::task::spawn_blocking(move || compensate::compensate(&model, &request))
        .await
        .map_err(ServiceError::internal)?;
    Ok(answer?)
}

/// [`compensate`] as one JSON line per target, solved as the client reads
/// (`target_stream::ndjson`); the request is checked whole first, so a bad
/// field is still a 422.
pub async fn compensate_stream(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: CompensateRequest,
) -> ServiceResult<impl Stream<Item = Vec<u8>>> {
    let model = model(
        store,
        serial,
        version,
        request.session_id.as_deref(),
        request.expect_controller.as_ref(),
    )
    .await?;
    let plan = Compensation::check(&model, &request)?;
    Ok(target_stream::ndjson(plan.len(), move |i| plan.solve(i)))
}

/// The robot's nominal chain (what its controller runs), for `filter`.
async fn nominal_chain(store: &DynStore, serial: &str) -> ServiceResult<RobotModel> {
    let robot = store
        .get_robot(serial)
        .await?
        .ok_or_else(|| ServiceError::not_found("robot", serial))?;
    let doc: KinematicsDoc =
        serde_json::from_value(robot.kinematics).map_err(ServiceError::internal)?;
    Ok(doc_to_model(&doc))
}

/// A filter request checked against a parameter set's calibrated model and
/// the robot's nominal chain.
async fn filtering(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: &FilterRequest,
) -> ServiceResult<Filtering> {
    let model = model(
        store,
        serial,
        version,
        request.session_id.as_deref(),
        request.expect_controller.as_ref(),
    )
    .await?;
    let nominal = nominal_chain(store, serial).await?;
    Ok(Filtering::check(&model, nominal, request)?)
}

/// Filtered targets for the nominal controller (`filter`), on a blocking
/// thread: the calibrated model of the set, the robot's nominal chain.
pub async fn filter(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: FilterRequest,
) -> ServiceResult<FilterResponse> {
    let plan = filtering(store, serial, version, &request).await?;
    drop(request);
    tokio::task::spawn_blocking(move || filter::filter(&plan))
        .await
        .map_err(ServiceError::internal)
}

/// [`filter`] as one JSON line per target, solved as the client reads.
pub async fn filter_stream(
    store: &DynStore,
    serial: &str,
    version: &str,
    request: FilterRequest,
) -> ServiceResult<impl Stream<Item = Vec<u8>>> {
    let plan = filtering(store, serial, version, &request).await?;
    drop(request);
    Ok(target_stream::ndjson(plan.len(), move |i| plan.solve(i)))
}
