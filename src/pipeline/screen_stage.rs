//! Poses that lie (issue 14): a pose whose joints contradict its image — a
//! wrong joint file, a pose recorded before the robot settled — is found
//! before identification and left out of it, so it cannot bend the fit.
//!
//! The screening is `calib`'s [`screen_joint_poses`]: the nominal forward
//! kinematics stand in for controller flange poses, the camera stage's
//! intrinsics are held, and a hand–eye/board bundle is refitted until the
//! robust residual limit stops changing the inlier set.
//!
//! The nominal model's own errors add a pose-dependent misfit that can push
//! an honest pose over that limit (a badly built robot). So a flagged pose
//! is only a candidate: [`confirm`] judges it again under the *identified*
//! model, where that misfit is gone, and gives back every candidate that
//! fits as well as the validation poses do; the caller then identifies
//! again with them.

use robocal_calib::handeye::robust::robust_limit;
use robocal_calib::handeye::screen_joint_poses;
use robocal_calib::kinematics::image_pose::ImagePose;
use robocal_calib::kinematics::{CalibratedModel, RobotModel};

use super::camera_stage::CameraStep;
use super::identify_stage::Identified;
use super::{PipelineError, PoseInput};

/// Fewest usable poses for a screening to mean anything: with fewer, a
/// liar cannot be told from the truth by majority.
pub const MIN_POSES_TO_SCREEN: usize = 6;

/// A candidate whose position error under the identified model is below
/// this is given back whatever its peers do, mm: a robot-accuracy residual,
/// not a contradiction between joints and image.
pub const CONFIRM_FLOOR_MM: f64 = 0.5;

/// A pose left out, with why.
#[derive(Debug, Clone, PartialEq)]
pub struct Outlier {
    /// Index into the session's poses.
    pub pose: usize,
    pub reason: String,
}

/// The usable poses split into those kept and the candidates whose joints
/// seem to contradict their image. A screening that cannot run (too few
/// poses, a degenerate campaign) keeps every pose and says so in the
/// returned note.
pub fn screen_poses(
    robot: &RobotModel,
    poses: &[PoseInput],
    camera: &CameraStep,
    usable: &[usize],
) -> (Vec<usize>, Vec<Outlier>, Option<String>) {
    if usable.len() < MIN_POSES_TO_SCREEN {
        return (usable.to_vec(), Vec::new(), None);
    }
    let images: Vec<ImagePose> = usable
        .iter()
        .map(|&i| ImagePose {
            joints_rad: poses[i].joints_deg.to_radians(),
            observations: camera.observations_of(i).unwrap_or_default().to_vec(),
        })
        .collect();
    let model = CalibratedModel {
        robot: robot.clone(),
        world_to_base: nalgebra::Isometry3::identity(),
        flange_to_tool: nalgebra::Isometry3::identity(),
    };
    let verdicts = match screen_joint_poses(&model, &camera.intrinsics(), &images) {
        Ok(v) => v,
        Err(e) => {
            let note = format!("Pose screening could not run ({e}); every pose was used.");
            return (usable.to_vec(), Vec::new(), Some(note));
        }
    };
    let mut kept = Vec::new();
    let mut outliers = Vec::new();
    for (&pose, verdict) in usable.iter().zip(&verdicts) {
        if verdict.outlier {
            let reason = verdict
                .reason
                .clone()
                .unwrap_or_else(|| "its joints contradict its image".into());
            outliers.push(Outlier { pose, reason });
        } else {
            kept.push(pose);
        }
    }
    (kept, outliers, None)
}

/// The report's note on the confirmed outliers, if any.
pub fn note(poses: &[PoseInput], outliers: &[Outlier]) -> Option<String> {
    (!outliers.is_empty()).then(|| {
        let names: Vec<&str> = outliers.iter().map(|o| poses[o.pose].label.as_str()).collect();
        format!(
            "{} pose(s) left out because their joints contradict their image: {} (per_pose[].outlier).",
            outliers.len(),
            names.join(", ")
        )
    })
}

/// Identifies on `usable` with `candidates` left out, then gives back the
/// candidates the identified model explains ([`confirm`]) and identifies
/// again with them; the identification and the confirmed outliers.
pub fn identify_confirmed(
    usable: Vec<usize>,
    candidates: Vec<Outlier>,
    identify: impl Fn(&[usize], &[Outlier]) -> Result<Identified, PipelineError>,
) -> Result<(Identified, Vec<Outlier>), PipelineError> {
    let mut identified = identify(&usable, &candidates)?;
    let (back, outliers) = confirm(&identified, &candidates);
    if !back.is_empty() {
        let mut usable = usable;
        usable.extend(back);
        usable.sort_unstable();
        identified = identify(&usable, &outliers)?;
    }
    Ok((identified, outliers))
}

/// The candidates split, under the identified model, into poses to give
/// back (their error is like the validation poses') and confirmed outliers.
pub fn confirm(identified: &Identified, candidates: &[Outlier]) -> (Vec<usize>, Vec<Outlier>) {
    let peers: Vec<f64> = identified
        .val_errors
        .iter()
        .map(|(_, _, a)| a.norm())
        .collect();
    let limit_mm = robust_limit(&peers).max(CONFIRM_FLOOR_MM);
    let mut back = Vec::new();
    let mut confirmed = Vec::new();
    for o in candidates {
        let after = identified
            .outlier_errors
            .iter()
            .find(|(i, _, _)| *i == o.pose)
            .map(|(_, _, a)| a.norm());
        match after {
            Some(e) if e <= limit_mm => back.push(o.pose),
            Some(e) => confirmed.push(Outlier {
                pose: o.pose,
                reason: format!(
                    "{}; after calibration it still misses by {e:.2} mm (limit {limit_mm:.2} mm)",
                    o.reason
                ),
            }),
            None => confirmed.push(o.clone()),
        }
    }
    (back, confirmed)
}
