//! Loads a claimed job's inputs from the store into a [`pipeline::Input`].

use std::sync::Arc;
use std::time::Duration;

use crate::domain::{label_or_number, FlangePose, JobKind, PoseGroup};
use crate::imaging::DecodeGate;
use crate::pipeline::{
    ApprovedSet, FixedCamera, ImageSource, Input, PoseImage, PoseInput, RegionInput,
};
use crate::report::regions::LocalModel;
use crate::report::Report;
use crate::schema::job::CalibrationOptions;
use crate::schema::robot::KinematicsDoc;
use crate::service::camera_reuse::{self, ReuseError};
use crate::store::{ClaimedJob, DynStore, StoreError};

/// Poses read per store call.
const PAGE: i64 = 500;

#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The job's session or robot is gone, or a stored document is unusable.
    #[error("{0}")]
    Gone(String),
    #[error(transparent)]
    Store(#[from] StoreError),
}

pub async fn load_input(
    store: &DynStore,
    job: &ClaimedJob,
    test_stage_delay: Duration,
    gate: Arc<DecodeGate>,
) -> Result<Input, LoadError> {
    let session = store
        .get_session(&job.session_id)
        .await?
        .ok_or_else(|| LoadError::Gone(format!("session {} was deleted", job.session_id)))?;
    let robot = store
        .get_robot(&session.serial)
        .await?
        .ok_or_else(|| LoadError::Gone(format!("robot {} was deleted", session.serial)))?;
    let bad = |what: &str, e: serde_json::Error| LoadError::Gone(format!("stored {what}: {e}"));
    let kinematics: KinematicsDoc =
        serde_json::from_value(robot.kinematics).map_err(|e| bad("kinematics", e))?;
    let spec = session.spec;
    let options: CalibrationOptions = job.options.calibration();
    let approved = approved_set(store, &session.serial).await?;
    let fixed_camera = match &spec.camera_calibration_id {
        Some(id) => Some(
            camera_reuse::resolve(store, id, spec.camera.as_ref())
                .await
                .map_err(|e| match e {
                    ReuseError::Store(e) => LoadError::Store(e),
                    e => LoadError::Gone(format!("{}: {e}", camera_reuse::FIELD)),
                })?,
        ),
        // A re-check or a partial scope holds the approved set's camera.
        None if job.kind == JobKind::Check || !options.scope.is_full() => {
            approved.as_ref().and_then(|a| {
                Some(FixedCamera {
                    calibration_id: a.id.clone(),
                    intrinsics: a.set.camera?,
                })
            })
        }
        None => None,
    };
    let poses = load_poses(store, &session.id).await?;
    let mut regions = Vec::new();
    for id in options.sessions.iter().filter(|id| **id != session.id) {
        let further = store
            .get_session(id)
            .await?
            .ok_or_else(|| LoadError::Gone(format!("session {id} was deleted")))?;
        regions.push(RegionInput {
            poses: load_poses(store, &further.id).await?,
            session_id: further.id,
            session: further.spec,
        });
    }
    let local_models = if regions.is_empty() {
        Vec::new()
    } else {
        let ids: Vec<&str> = std::iter::once(session.id.as_str())
            .chain(regions.iter().map(|r| r.session_id.as_str()))
            .collect();
        local_models(store, &session.serial, &ids).await?
    };
    Ok(Input {
        session_id: session.id.clone(),
        serial: session.serial,
        robot: crate::schema::robot::doc_to_model(&kinematics),
        prior: robot.prior.unwrap_or_default(),
        kinematics,
        session: spec,
        poses,
        options,
        fixed_camera,
        images: store_images(store, gate),
        test_stage_delay,
        validate_only: false,
        approved,
        kind: job.kind,
        local_models,
        regions,
    })
}

/// Sets looked at for the local models of a multi-session job (newest
/// first): one page.
const LOCAL_SETS_SCANNED: i64 = 200;

/// The newest local (one-session) set of each of `sessions`, with its
/// report's validation figures: the side by side of local and global
/// models in each region.
async fn local_models(
    store: &DynStore,
    serial: &str,
    sessions: &[&str],
) -> Result<Vec<(String, LocalModel)>, LoadError> {
    let page = store
        .list_parameter_sets(serial, LOCAL_SETS_SCANNED, None)
        .await?;
    let mut found: Vec<(String, LocalModel)> = Vec::new();
    for record in page.items {
        let Some(set) = record.parameters.into_kinematic() else {
            continue;
        };
        let wanted = sessions.contains(&set.session_id.as_str())
            && set.session_target_to_base.is_empty()
            && !found.iter().any(|(id, _)| *id == set.session_id);
        if !wanted || !full_scope(store, record.job_id.as_deref()).await? {
            continue;
        }
        let report = store.get_report(serial, record.version).await?;
        let after = report
            .map(serde_json::from_value::<Report>)
            .transpose()
            .map_err(|e| {
                LoadError::Gone(format!("stored report {serial}/{}: {e}", record.version))
            })?
            .map(|r| r.after);
        if let Some(after) = after {
            found.push((
                set.session_id,
                LocalModel {
                    version: record.version,
                    after,
                },
            ));
        }
    }
    Ok(found)
}

/// The serial's newest approved set, typed; `None` when it has none, or
/// when that set holds no robot model (a hand–eye or stage camera set):
/// the gate then compares with the nominal model.
async fn approved_set(store: &DynStore, serial: &str) -> Result<Option<ApprovedSet>, LoadError> {
    let Some(record) = store.get_parameter_set(serial, None).await? else {
        return Ok(None);
    };
    // Its own report's headline, which the gate's report shows beside
    // the gate's own figure of it.
    let report = store.get_report(serial, record.version).await?;
    let report_mean_mm = report
        .as_ref()
        .and_then(|r| r.pointer("/after/mean_mm"))
        .and_then(serde_json::Value::as_f64);
    let report_session_id = report
        .as_ref()
        .and_then(|r| r.get("session_id"))
        .and_then(serde_json::Value::as_str)
        .map(str::to_string);
    Ok(record.parameters.into_kinematic().map(|set| ApprovedSet {
        id: format!("{serial}/{}", record.version),
        version: record.version,
        set,
        report_mean_mm,
        report_session_id,
    }))
}

/// Whether the job that made a set was a full calibration (a `scope:
/// base` set carries another session's model over: not a local model).
async fn full_scope(store: &DynStore, job_id: Option<&str>) -> Result<bool, LoadError> {
    let Some(id) = job_id else {
        return Ok(true);
    };
    let Some(job) = store.get_job(id).await? else {
        return Ok(true);
    };
    Ok(job.options.calibration().scope.is_full())
}

/// Reads images from the store's blobs, from the job's blocking thread.
fn store_images(store: &DynStore, gate: Arc<DecodeGate>) -> ImageSource {
    let (store, runtime) = (store.clone(), tokio::runtime::Handle::current());
    ImageSource {
        read: Arc::new(move |sha256: &str| {
            runtime
                .block_on(store.get_blob(sha256))
                .map_err(|e| format!("reading image {sha256}: {e}"))?
                .ok_or_else(|| format!("image {sha256} is missing from the store"))
        }),
        gate,
    }
}

/// Every pose of a session, in upload order.
async fn load_poses(store: &DynStore, session_id: &str) -> Result<Vec<PoseInput>, LoadError> {
    let mut poses = Vec::new();
    let mut cursor: Option<String> = None;
    loop {
        let page = store
            .list_poses(session_id, PAGE, cursor.as_deref())
            .await?;
        for p in page.items {
            // A reference only: the detect stage reuses the stored detection,
            // or reads the image itself when it has none.
            let image = p.image.as_ref().map(|meta| PoseImage {
                key: meta.sha256.clone(),
                width: meta.width,
                height: meta.height,
                detection: p.image_detection.clone(),
            });
            let measured = p.measured.unwrap_or_default();
            let flange_pose = match &p.flange_pose {
                Some(doc) => Some(FlangePose::stored(doc).ok_or_else(|| {
                    LoadError::Gone(format!("stored flange_pose of pose {} is not a pose", p.id))
                })?),
                None => None,
            };
            let label = label_or_number(p.label.as_deref(), poses.len());
            poses.push(PoseInput {
                id: p.id,
                label,
                joints_deg: p.joints_deg,
                flange_pose,
                set: p.set,
                image,
                image_points: p.points,
                measured_position_mm: measured.measured_position_mm,
                measured_pose: measured.measured_pose,
                stage_reading: p.stage_reading,
                group: p.group.map(PoseGroup::into_string),
            });
        }
        match page.next_cursor {
            Some(c) => cursor = Some(c),
            None => break,
        }
    }
    Ok(poses)
}
