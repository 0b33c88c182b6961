//! A dataset upload: the archive (already spooled to a file by the HTTP
//! edge) is opened, its manifest checked as a whole, then each image read,
//! checked, detected and stored by its own task (bounded by the decode
//! gate) and taken in manifest order; all poses are stored in one
//! transaction, or none (and the images stored on the way are discarded).

use std::path::Path;

use super::dataset::{DatasetError, DatasetLimits, DatasetReader};
use super::error::{ServiceError, ServiceResult};
use super::images::ingest_image;
use super::intake::PoseIntake;
use super::staged_images::StagedImages;
use crate::domain::{check_robot_pose, label_from_archive_path, RobotPose};
use crate::schema::pose_body::check_group;
use crate::schema::session::Instrument;
use crate::schema::Checker;
use crate::store::{NewPose, PoseRecord};

/// Images in flight per decode slot: one being detected, one being stored
/// or waiting for a slot.
const IN_FLIGHT_PER_DECODE: usize = 2;

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

/// An image's refusal names its file as well as its manifest entry (the
/// user knows the photo by its name, not by its index).
fn naming_file(e: ServiceError, file: &str) -> ServiceError {
    match e {
        ServiceError::Invalid(mut errors) => {
            for error in &mut errors {
                error.message = format!("{file}: {}", error.message);
            }
            ServiceError::Invalid(errors)
        }
        other => other,
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
        let pause_per_image = limits.test_pause_per_image;
        let mut reader = tokio::task::spawn_blocking(move || DatasetReader::open(&path, limits))
            .await
            .map_err(ServiceError::internal)??;
        let mut c = Checker::default();
        if reader.manifest.is_empty() {
            c.fail("poses.json", "holds no poses");
        }
        let mut session_kind = self.pose_kind;
        let mut robot_poses: Vec<Option<RobotPose>> = Vec::with_capacity(reader.manifest.len());
        let mut groups = Vec::with_capacity(reader.manifest.len());
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
            groups.push(check_group(
                &mut c,
                &format!("{prefix}group"),
                p.group.as_deref(),
            ));
        }
        c.finish()?;
        let mut robot_poses = robot_poses
            .into_iter()
            .map(|q| q.expect("checked above").into_row());
        let check = self.image_check();
        // Images are read from the archive one after another; each is then
        // checked, detected (on a blocking thread, under the decode gate)
        // and stored by its own task, so storing one image overlaps with
        // detecting the next. At most `IN_FLIGHT_PER_DECODE` images per
        // decode slot are in flight (their compressed bytes bound the
        // memory); results are taken, and poses built, in manifest order.
        let in_flight_max = check.gate.size() * IN_FLIGHT_PER_DECODE;
        let count = reader.manifest.len();
        let mut in_flight = std::collections::VecDeque::with_capacity(in_flight_max);
        let mut staged = StagedImages::new(self.store.clone());
        let mut poses = Vec::with_capacity(count);
        let mut failure = None;
        for i in 0..=count {
            if i < count && failure.is_none() {
                let name = reader.manifest[i].image.clone();
                let field = format!("poses.json[{i}].image");
                let (back, bytes) = tokio::task::spawn_blocking(move || {
                    let bytes = reader.read_image(&name).map_err(ServiceError::from);
                    (reader, bytes)
                })
                .await
                .map_err(ServiceError::internal)?;
                reader = back;
                let file = reader.manifest[i].image.clone();
                match bytes {
                    Ok(bytes) => {
                        let ingest = ingest_image(self.store.clone(), bytes, check.clone(), field);
                        in_flight.push_back(tokio::spawn(async move {
                            ingest.await.map_err(|e| naming_file(e, &file))
                        }))
                    }
                    Err(e) => failure = Some(e),
                }
            }
            // Take the oldest image once the pipeline is full, and every
            // remaining one after the last read (or a failure: the images
            // in flight are still awaited so that those stored are discarded).
            while in_flight.len() >= in_flight_max
                || ((i == count || failure.is_some()) && !in_flight.is_empty())
            {
                let task = in_flight.pop_front().expect("not empty");
                let ingested = match task.await.map_err(ServiceError::internal) {
                    Ok(Ok(ingested)) => ingested,
                    Ok(Err(e)) | Err(e) => {
                        failure.get_or_insert(e);
                        continue;
                    }
                };
                staged.stored(&ingested.meta.sha256);
                if !pause_per_image.is_zero() {
                    tokio::time::sleep(pause_per_image).await;
                }
                if failure.is_some() {
                    continue;
                }
                let k = poses.len();
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
                    stage_reading: None,
                    group: groups[k].clone(),
                });
            }
            if failure.is_some() && in_flight.is_empty() {
                break;
            }
        }
        if let Some(e) = failure {
            staged.discard().await;
            return Err(e);
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
