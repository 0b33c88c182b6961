//! A dataset upload: the archive (already spooled to a file by the HTTP
//! edge) is opened, its manifest checked as a whole, then each image read,
//! checked and detected on up to the decode gate's size of threads at once
//! and stored in manifest order; all poses are stored in one
//! transaction, or none (and the images stored on the way are discarded).

use std::path::Path;

use super::dataset::{DatasetError, DatasetLimits, DatasetReader};
use super::error::{ServiceError, ServiceResult};
use super::images::inspect_and_hash;
use super::intake::PoseIntake;
use super::staged_images::StagedImages;
use crate::domain::{check_robot_pose, label_from_archive_path, RobotPose};
use crate::schema::session::Instrument;
use crate::schema::Checker;
use crate::store::{NewPose, PoseRecord};

impl From<DatasetError> for ServiceError {
    fn from(e: DatasetError) -> ServiceError {
        match e {
            DatasetError::Malformed { field, message } => {
                ServiceError::Malformed { field, message }
            }
            DatasetError::Invalid(errors) => ServiceError::Invalid(errors),
            DatasetError::TooLarge { limit, bytes } => ServiceError::TooLarge { limit, bytes },
        }
    }
}

impl PoseIntake {
    /// Refuses a dataset for a tracker session (checked before the body is read).
    pub fn check_takes_dataset(&self) -> ServiceResult<()> {
        if self.spec.instrument != Instrument::Camera {
            return Err(ServiceError::invalid(
                "instrument",
                "datasets of images need a camera session",
            ));
        }
        Ok(())
    }

    /// Stores every pose of the archive at `archive`, or none.
    pub async fn add_dataset(
        self,
        archive: &Path,
        limits: DatasetLimits,
    ) -> ServiceResult<Vec<PoseRecord>> {
        let path = archive.to_path_buf();
        let mut reader = tokio::task::spawn_blocking(move || DatasetReader::open(&path, limits))
            .await
            .map_err(ServiceError::internal)??;
        let mut c = Checker::default();
        if reader.manifest.is_empty() {
            c.fail("poses.json", "holds no poses");
        }
        let mut session_kind = self.pose_kind;
        let mut robot_poses: Vec<Option<RobotPose>> = Vec::with_capacity(reader.manifest.len());
        for (i, p) in reader.manifest.iter().enumerate() {
            let prefix = format!("poses.json[{i}].");
            let (kind, typed) = check_robot_pose(
                &mut c,
                &prefix,
                p.joints_deg.as_deref(),
                p.flange_pose.as_ref(),
                self.joint_count,
            );
            if let Some(kind) = kind {
                kind.check_same(&mut c, &prefix, session_kind);
                session_kind = session_kind.or(Some(kind));
            }
            robot_poses.push(typed);
        }
        c.finish()?;
        let mut robot_poses = robot_poses
            .into_iter()
            .map(|q| q.expect("checked above").into_row());
        let check = self.image_check();
        // Images are read from the archive one after another, but checked and
        // detected on up to `gate.size()` blocking threads at once (the
        // decode gate bounds the memory either way), and stored in manifest
        // order.
        let in_flight_max = check.gate.size();
        let count = reader.manifest.len();
        let mut in_flight = std::collections::VecDeque::with_capacity(in_flight_max);
        let mut staged = StagedImages::new(self.store.clone());
        let mut poses = Vec::with_capacity(count);
        for i in 0..=count {
            if i < count {
                let name = reader.manifest[i].image.clone();
                let field = format!("poses.json[{i}].image");
                let (back, bytes) = tokio::task::spawn_blocking(move || {
                    let bytes = reader.read_image(&name).map_err(ServiceError::from);
                    (reader, bytes)
                })
                .await
                .map_err(ServiceError::internal)?;
                reader = back;
                let check = check.clone();
                in_flight.push_back(bytes.map(|bytes| {
                    tokio::task::spawn_blocking(move || {
                        inspect_and_hash(&bytes, &check)
                            .map(|ingested| (ingested, bytes))
                            .map_err(|m| ServiceError::invalid(field, m))
                    })
                }));
            }
            // Accept the oldest image once the gate's worth is in flight,
            // and every remaining one after the last read.
            while in_flight.len() >= in_flight_max || (i == count && !in_flight.is_empty()) {
                let k = poses.len();
                let result = match in_flight.pop_front().expect("not empty") {
                    Ok(task) => task.await.map_err(ServiceError::internal).and_then(|r| r),
                    Err(e) => Err(e),
                };
                let (ingested, bytes) = match result {
                    Ok(ok) => ok,
                    Err(e) => {
                        for task in in_flight.drain(..).flatten() {
                            task.abort();
                        }
                        staged.discard().await;
                        return Err(e);
                    }
                };
                self.store.put_blob(&ingested.meta, &bytes).await?;
                staged.stored(&ingested.meta.sha256);
                let (joints_deg, flange_pose) = robot_poses.next().expect("one per manifest entry");
                poses.push(NewPose {
                    joints_deg,
                    set: reader.manifest[k].set,
                    image: Some(ingested.meta),
                    points: Vec::new(),
                    measured: None,
                    label: label_from_archive_path(&reader.manifest[k].image),
                    image_detection: ingested.detection,
                    flange_pose,
                });
            }
        }
        let stored = match self.store.add_poses(&self.session.id, &poses).await {
            Ok(stored) => stored,
            Err(e) => {
                staged.discard().await;
                return Err(e.into());
            }
        };
        staged.keep();
        Ok(stored)
    }
}
