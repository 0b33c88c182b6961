//! Pose ingestion: a session that takes poses, one at a time (JSON image
//! points or a tracker measurement, or an image) or as a dataset archive
//! ([`super::dataset_intake`]). Every pose's joints are checked against the
//! robot's joint count before anything is stored.

use std::sync::Arc;

use super::error::{ServiceError, ServiceResult};
use super::images::{ingest_image, ImageCheck};
use crate::domain::{check_robot_pose, JointsDeg, PoseGroup, PoseKind, StageReading};
use crate::imaging::DecodeGate;
use crate::schema::flange_pose::FlangePoseDoc;
use crate::schema::pose_body::PoseJsonBody;
use crate::schema::session::{Instrument, PoseSet, SessionBody};
use crate::schema::Checker;
use crate::store::{DynStore, NewPose, PoseRecord, SessionRecord, TrackerMeasurement};

/// A session about to take poses: its stored spec and its robot's joint
/// count, looked up once.
pub struct PoseIntake {
    pub store: DynStore,
    pub gate: Arc<DecodeGate>,
    pub session: SessionRecord,
    pub spec: SessionBody,
    pub joint_count: usize,
    /// What the session's poses so far carry (`None` before its first).
    pub pose_kind: Option<PoseKind>,
}

/// One image pose as the client sent it (the multipart parts, read).
pub struct ImagePose {
    /// The joint angles, or (instead) the controller's `flange_pose`.
    pub joints_deg: Option<Vec<f64>>,
    pub flange_pose: Option<FlangePoseDoc>,
    pub set: PoseSet,
    pub image: Vec<u8>,
    /// The image's file name, as a label.
    pub label: Option<String>,
    /// The `group` part, checked by the HTTP edge.
    pub group: Option<PoseGroup>,
    /// A stage session's parts: the stage's reading and the
    /// sequence, as sent (checked by [`StageReading::check`]).
    pub stage_position_mm: Option<[f64; 3]>,
    pub sequence: Option<u32>,
}

/// The stored session `id`, or 404.
pub async fn find_session(store: &DynStore, id: &str) -> ServiceResult<SessionRecord> {
    store
        .get_session(id)
        .await?
        .ok_or_else(|| ServiceError::not_found("session", id))
}

/// The controller identity robot `serial` records: what a new
/// session records unless it names its own. 404 when there is no robot.
pub async fn robot_controller(
    store: &DynStore,
    serial: &str,
) -> ServiceResult<Option<crate::domain::ControllerIdentity>> {
    let robot = store
        .get_robot(serial)
        .await?
        .ok_or_else(|| ServiceError::not_found("robot", serial))?;
    Ok(robot.controller)
}

/// Number of joints of the robot `serial` (0 for a joint table that is not a list).
pub async fn robot_joint_count(store: &DynStore, serial: &str) -> ServiceResult<usize> {
    let robot = store
        .get_robot(serial)
        .await?
        .ok_or_else(|| ServiceError::not_found("robot", serial))?;
    Ok(robot.kinematics["joints"]
        .as_array()
        .map(Vec::len)
        .unwrap_or(0))
}

impl PoseIntake {
    /// Session `id` ready to take poses (404 when there is no such session).
    pub async fn open(store: &DynStore, gate: Arc<DecodeGate>, id: &str) -> ServiceResult<Self> {
        let session = find_session(store, id).await?;
        let spec = session.spec.clone();
        let joint_count = robot_joint_count(store, &session.serial).await?;
        let first = store.list_poses(&session.id, 1, None).await?;
        let pose_kind = first
            .items
            .first()
            .map(|p| PoseKind::of_stored(p.flange_pose.as_ref()));
        Ok(PoseIntake {
            store: store.clone(),
            gate,
            session,
            spec,
            joint_count,
            pose_kind,
        })
    }

    /// Refuses images for a tracker session (checked before the body is read).
    pub fn check_takes_images(&self) -> ServiceResult<()> {
        if !self.spec.instrument.has_camera() {
            return Err(ServiceError::invalid(
                "image",
                "a tracker session takes JSON measurements",
            ));
        }
        Ok(())
    }

    /// What an image of this session is checked against.
    pub fn image_check(&self) -> ImageCheck {
        ImageCheck::of(&self.session.id, &self.spec, self.gate.clone())
    }

    /// Stores one JSON pose (image points or a tracker measurement).
    pub async fn add_json(self, body: PoseJsonBody) -> ServiceResult<PoseRecord> {
        if self.spec.instrument == Instrument::Stage {
            return Err(ServiceError::invalid(
                "image",
                "a stage session takes multipart poses: image, stage_position_mm, sequence",
            ));
        }
        let checked = body.check(
            self.spec.instrument,
            self.spec.camera.as_ref(),
            self.joint_count,
        );
        let mut c = Checker::default();
        if let Some(kind) = kind_of(body.joints_deg.as_deref(), body.flange_pose.as_ref()) {
            kind.check_same(&mut c, "", self.pose_kind);
        }
        let (joints_deg, flange_pose) = match checked {
            Ok(pose) if c.errors.is_empty() => pose.into_row(),
            Ok(_) => return Err(c.errors.into()),
            Err(mut errors) => {
                errors.extend(c.errors);
                return Err(errors.into());
            }
        };
        let measured = body.measured_position_mm.map(|p| TrackerMeasurement {
            measured_position_mm: Some(p),
            measured_pose: body.measured_pose,
        });
        let pose = NewPose {
            joints_deg,
            set: body.set,
            image: None,
            points: body.image_points.unwrap_or_default(),
            measured,
            label: body.label,
            image_detection: None,
            flange_pose,
            stage_reading: None,
            // Checked with the body above.
            group: body.group.as_deref().and_then(|g| PoseGroup::parse(g).ok()),
        };
        self.store_one(pose).await
    }

    /// Checks the joints, then checks, detects and stores the image, then
    /// the pose.
    pub async fn add_image(self, upload: ImagePose) -> ServiceResult<PoseRecord> {
        if self.spec.instrument == Instrument::Stage {
            return self.add_stage_image(upload).await;
        }
        if upload.stage_position_mm.is_some() || upload.sequence.is_some() {
            let field = if upload.stage_position_mm.is_some() {
                "stage_position_mm"
            } else {
                "sequence"
            };
            return Err(ServiceError::invalid(
                field,
                "only a stage session takes it",
            ));
        }
        let mut c = Checker::default();
        let (kind, robot_pose) = check_robot_pose(
            &mut c,
            "",
            upload.joints_deg.as_deref(),
            upload.flange_pose.as_ref(),
            self.joint_count,
        );
        if let Some(kind) = kind {
            kind.check_same(&mut c, "", self.pose_kind);
        }
        c.finish()?;
        let (joints_deg, flange_pose) = robot_pose.expect("checked above").into_row();
        self.store_image_pose(upload, joints_deg, flange_pose, None)
            .await
    }

    /// A stage session's image: the stage's reading instead of joints.
    async fn add_stage_image(self, upload: ImagePose) -> ServiceResult<PoseRecord> {
        if upload.joints_deg.is_some() || upload.flange_pose.is_some() {
            let field = if upload.joints_deg.is_some() {
                "joints_deg"
            } else {
                "flange_pose"
            };
            return Err(ServiceError::invalid(
                field,
                "a stage session takes stage_position_mm and sequence",
            ));
        }
        let reading = StageReading::check(upload.sequence, upload.stage_position_mm)?;
        self.store_image_pose(upload, JointsDeg::stored(Vec::new()), None, Some(reading))
            .await
    }

    /// Checks, detects and stores the image, then the pose carrying it with
    /// where it was taken (joints, a flange pose or a stage reading).
    async fn store_image_pose(
        self,
        upload: ImagePose,
        joints_deg: JointsDeg,
        flange_pose: Option<FlangePoseDoc>,
        stage_reading: Option<StageReading>,
    ) -> ServiceResult<PoseRecord> {
        let ingested = ingest_image(
            self.store.clone(),
            upload.image,
            self.image_check(),
            "image".into(),
        )
        .await?;
        let pose = NewPose {
            joints_deg,
            set: upload.set,
            image: Some(ingested.meta),
            points: Vec::new(),
            measured: None,
            label: upload.label,
            image_detection: ingested.detection,
            flange_pose,
            stage_reading,
            group: upload.group,
        };
        self.store_one(pose).await
    }

    async fn store_one(self, pose: NewPose) -> ServiceResult<PoseRecord> {
        let mut stored = self.store.add_poses(&self.session.id, &[pose]).await?;
        stored
            .pop()
            .ok_or_else(|| ServiceError::internal("pose not stored"))
    }
}

/// The kind a pose names (`None` when it names both or neither: its check
/// says so).
pub fn kind_of(
    joints_deg: Option<&[f64]>,
    flange_pose: Option<&FlangePoseDoc>,
) -> Option<PoseKind> {
    match (joints_deg, flange_pose) {
        (Some(_), None) => Some(PoseKind::Joints),
        (None, Some(_)) => Some(PoseKind::Flange),
        _ => None,
    }
}
