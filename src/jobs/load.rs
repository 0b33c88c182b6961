//! Loads a claimed job's inputs from the store into a [`pipeline::Input`].

use std::time::Duration;

use crate::camera_reuse::{self, ReuseError};
use crate::domain::{label_or_number, ClaimedJob};
use crate::pipeline::{Input, PoseInput};
use crate::schema::job::CalibrationOptions;
use crate::schema::robot::KinematicsDoc;
use crate::schema::session::{ImagePointDoc, PoseSet, SessionBody};
use crate::schema::PoseDoc;
use crate::store::{DynStore, StoreError};

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
    let spec: SessionBody = serde_json::from_value(session.spec).map_err(|e| bad("session", e))?;
    let options: CalibrationOptions =
        serde_json::from_value(job.options.clone()).map_err(|e| bad("options", e))?;
    let fixed_camera = match &spec.camera_calibration_id {
        Some(id) => Some(
            camera_reuse::resolve(store, id, spec.camera.as_ref())
                .await
                .map_err(|e| match e {
                    ReuseError::Store(e) => LoadError::Store(e),
                    e => LoadError::Gone(format!("{}: {e}", camera_reuse::FIELD)),
                })?,
        ),
        None => None,
    };
    let mut poses = Vec::new();
    let mut cursor: Option<String> = None;
    loop {
        let page = store
            .list_poses(&session.id, PAGE, cursor.as_deref())
            .await?;
        for p in page.items {
            let image = match &p.image {
                Some(meta) => Some(store.get_blob(&meta.sha256).await?.ok_or_else(|| {
                    LoadError::Gone(format!("image {} of pose {} missing", meta.sha256, p.id))
                })?),
                None => None,
            };
            let image_points: Vec<ImagePointDoc> =
                serde_json::from_value(p.points).map_err(|e| bad("points", e))?;
            let measured = p.measured.unwrap_or_default();
            let measured_position_mm: Option<[f64; 3]> =
                serde_json::from_value(measured["measured_position_mm"].clone())
                    .map_err(|e| bad("measured_position_mm", e))?;
            let measured_pose: Option<PoseDoc> =
                serde_json::from_value(measured["measured_pose"].clone())
                    .map_err(|e| bad("measured_pose", e))?;
            let label = label_or_number(p.label.as_deref(), poses.len());
            poses.push(PoseInput {
                id: p.id,
                label,
                joints_deg: p.joints_deg,
                set: PoseSet::parse(&p.set).unwrap_or_default(),
                image,
                image_points,
                measured_position_mm,
                measured_pose,
            });
        }
        match page.next_cursor {
            Some(c) => cursor = Some(c),
            None => break,
        }
    }
    Ok(Input {
        session_id: session.id.clone(),
        serial: session.serial,
        robot: crate::robot_model::doc_to_model(&kinematics),
        kinematics,
        session: spec,
        poses,
        options,
        fixed_camera,
        test_stage_delay,
        validate_only: false,
    })
}
