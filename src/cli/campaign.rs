//! Campaign directories: what `robocal simulate` writes, what `robocal
//! upload` zips and what `robocal calibrate-local` calibrates without a
//! server. Layout: `campaign.json` (robot and session documents),
//! `poses.json` (the dataset upload's index: `[{"joints_deg","image","set"}]`,
//! or for a hand–eye campaign `[{"flange_pose","image","set"}]` with the
//! controller's flange poses instead of joints), `images/`, and for
//! simulated campaigns `truth.json`.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use rand::{rngs::StdRng, SeedableRng};
use robocal_calib::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::image_name;
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::rendered_camera::rendered_camera;
use serde::{Deserialize, Serialize};
use serde_json::json;

use crate::domain::{check_robot_pose, FlangePose, JointsDeg, RobotPose};
use crate::pipeline::{self, Input, PoseImage, PoseInput};
use crate::report::Report;
use crate::schema::job::CalibrationOptions;
use crate::schema::pose_body::DatasetPoseDoc;
use crate::schema::robot::RobotBody;
use crate::schema::session::SessionBody;
use crate::schema::Checker;

pub use super::sim_board::{simulated_target, SimBoard};

/// Spreads per-pose noise seeds apart (the golden-ratio constant).
const NOISE_SEED_STRIDE: u64 = 0x9e37_79b9_7f4a_7c15;

/// The name of a campaign's robot and session documents.
pub const CAMPAIGN_FILE: &str = "campaign.json";

/// `campaign.json`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CampaignFile {
    /// The `PUT /v1/robots/{serial}` body.
    pub robot: RobotBody,
    /// The `POST /v1/robots/{serial}/sessions` body.
    pub session: SessionBody,
}

/// The campaign [`simulate`] renders: the standard campaign of
/// `preset` with its simulated camera.
pub fn rendered_spec(
    preset: &str,
    cal: usize,
    val: usize,
    seed: u64,
) -> Result<CampaignSpec, String> {
    let mut spec = CampaignSpec::standard(preset, seed).map_err(|e| e.to_string())?;
    let (intrinsics, image_size, _) = rendered_camera(preset);
    spec.intrinsics = intrinsics;
    spec.image_size = image_size;
    spec.cal_poses = cal;
    spec.val_poses = val;
    Ok(spec)
}

/// Simulates a campaign of `preset` on the dot grid and writes it to
/// `out`; returns the campaign (its truth) so callers that judge it need
/// not simulate again.
pub fn simulate(
    preset: &str,
    out: &Path,
    cal: usize,
    val: usize,
    seed: u64,
) -> Result<(CampaignSpec, Campaign), String> {
    simulate_board(preset, out, cal, val, seed, SimBoard::Dots)
}

/// [`simulate`] with the images showing `board` (the same views, the
/// board in the same target frame).
pub fn simulate_board(
    preset: &str,
    out: &Path,
    cal: usize,
    val: usize,
    seed: u64,
    board: SimBoard,
) -> Result<(CampaignSpec, Campaign), String> {
    let spec = rendered_spec(preset, cal, val, seed)?;
    let (intrinsics, (width, height), pixel_um) = rendered_camera(preset);
    let campaign = simulate_campaign(&spec).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(out.join("images")).map_err(|e| e.to_string())?;
    let options = RenderOptions::default();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let errors: Vec<String> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let (campaign, options) = (&campaign, &options);
                scope.spawn(move || {
                    let mut errors = Vec::new();
                    for (i, pose) in campaign.poses.iter().enumerate().skip(t).step_by(threads) {
                        // Per-pose noise streams: the images do not depend on the thread count.
                        let mut rng = StdRng::seed_from_u64(
                            seed ^ (i as u64 + 1).wrapping_mul(NOISE_SEED_STRIDE),
                        );
                        let camera_to_target = pose.target_to_camera.inverse();
                        let rendered = board.render(
                            &campaign.truth.intrinsics,
                            &camera_to_target,
                            (width as usize, height as usize),
                            options,
                            &mut rng,
                        );
                        let saved = rendered.and_then(|image| {
                            image
                                .to_luma8()
                                .save(out.join(image_name(i)))
                                .map_err(|e| e.to_string())
                        });
                        if let Err(e) = saved {
                            errors.push(format!("pose {}: {e}", i + 1));
                        }
                    }
                    errors
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_default())
            .collect()
    });
    if let Some(e) = errors.first() {
        return Err(e.clone());
    }
    let file = CampaignFile {
        robot: serde_json::from_value(json!({"model": preset.to_uppercase(), "preset": preset}))
            .map_err(|e| e.to_string())?,
        session: serde_json::from_value(json!({
            "instrument": "camera",
            "target": board.session_target(),
            "camera": {
                "width": width, "height": height, "pixel_size_um": pixel_um,
                "nominal_focal_mm": intrinsics.fx * pixel_um / 1000.0,
            },
            "flange_to_camera_guess": {
                "translation_mm": robocal_calib::geometry::PoseXyzRpy::from_pose(&spec.flange_to_camera_guess).translation_mm,
                "rotation_deg": robocal_calib::geometry::PoseXyzRpy::from_pose(&spec.flange_to_camera_guess).rotation_deg,
            },
        }))
        .map_err(|e| e.to_string())?,
    };
    write_json(&out.join("campaign.json"), &file)?;
    write_json(&out.join("poses.json"), &campaign.pose_entries())?;
    write_json(&out.join("truth.json"), &campaign.full_truth())?;
    Ok((spec, campaign))
}

fn write_json(path: &Path, value: &impl Serialize) -> Result<(), String> {
    let text = serde_json::to_string_pretty(value).map_err(|e| e.to_string())?;
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads `campaign.json` and `poses.json` of a campaign directory (each
/// pose with its joints or the controller's flange pose, as the dataset
/// upload takes them).
pub fn read(dir: &Path) -> Result<(CampaignFile, Vec<DatasetPoseDoc>), String> {
    Ok((
        read_json(&dir.join(CAMPAIGN_FILE))?,
        read_json(&dir.join("poses.json"))?,
    ))
}

/// Runs the whole pipeline on a campaign directory, without a server.
pub fn calibrate_local(dir: &Path, serial: &str) -> Result<Report, String> {
    let set = run_local(dir, serial)?
        .parameter_set
        .ok_or("the pipeline produced no parameter set")?;
    let mut report: Report = serde_json::from_value(set.report).map_err(|e| e.to_string())?;
    // No server: no job, no stored version; say so instead of printing blanks.
    report.job_id = LOCAL_JOB.into();
    Ok(report)
}

/// What a report calibrated without a server names as its job.
pub const LOCAL_JOB: &str = "none (calibrate-local, no server)";

/// The pipeline's output on a campaign directory, without a server.
pub fn run_local(dir: &Path, serial: &str) -> Result<pipeline::Output, String> {
    run_local_with(dir, serial, CalibrationOptions::default())
}

/// [`run_local`] with the calibration job's `options`.
pub fn run_local_with(
    dir: &Path,
    serial: &str,
    options: CalibrationOptions,
) -> Result<pipeline::Output, String> {
    let (file, entries) = read(dir)?;
    let kinematics = file.robot.resolve().map_err(|e| format!("{e:?}"))?;
    let mut poses = Vec::with_capacity(entries.len());
    for (i, entry) in entries.iter().enumerate() {
        // The header only: the detect stage reads each image when it
        // detects it and drops it then, so no image is held for the job.
        let path = dir.join(&entry.image);
        let (width, height) = image::ImageReader::open(&path)
            .and_then(|r| r.with_guessed_format())
            .map_err(|e| e.to_string())
            .and_then(|r| r.into_dimensions().map_err(|e| e.to_string()))
            .map_err(|e| format!("{}: {e}", entry.image))?;
        let image = PoseImage {
            key: path.to_string_lossy().into_owned(),
            width,
            height,
            detection: None,
        };
        let (joints_deg, flange_pose) = robot_pose(entry, i, kinematics.joints.len())?;
        poses.push(PoseInput {
            id: format!("p{:03}", i + 1),
            label: entry.image.clone(),
            joints_deg,
            flange_pose,
            set: entry.set,
            image: Some(image),
            image_points: Vec::new(),
            measured_position_mm: None,
            measured_pose: None,
            stage_reading: None,
            group: entry.group.clone(),
        });
    }
    let input = Input {
        serial: serial.to_string(),
        session_id: "local".into(),
        robot: crate::schema::robot::doc_to_model(&kinematics),
        prior: Default::default(),
        kinematics,
        session: file.session,
        poses,
        options,
        fixed_camera: None,
        images: local_images(),
        test_stage_delay: std::time::Duration::ZERO,
        validate_only: false,
        regions: Vec::new(),
        local_models: Vec::new(),
        approved: None,
        kind: crate::domain::JobKind::Calibration,
    };
    pipeline::run(&input, &|_, _, _| {}, &AtomicBool::new(false)).map_err(|e| e.to_string())
}

/// Where pose `i` of `poses.json` says the robot was: its joints, or (a
/// hand–eye campaign) no joints and the controller's flange pose; every
/// problem named by its field.
fn robot_pose(
    entry: &DatasetPoseDoc,
    i: usize,
    joint_count: usize,
) -> Result<(JointsDeg, Option<FlangePose>), String> {
    let mut c = Checker::default();
    let prefix = format!("poses.json[{i}].");
    let (_, checked) = check_robot_pose(
        &mut c,
        &prefix,
        entry.joints_deg.as_deref(),
        entry.flange_pose.as_ref(),
        joint_count,
    );
    let typed = match checked {
        Some(RobotPose::Joints(joints)) => Some((joints, None)),
        Some(RobotPose::Flange(doc)) => {
            FlangePose::check(&mut c, &format!("{prefix}flange_pose"), &doc)
                .map(|f| (JointsDeg::stored(Vec::new()), Some(f)))
        }
        None => None,
    };
    typed.ok_or_else(|| {
        let errors: Vec<String> = c
            .errors
            .iter()
            .map(|e| format!("{}: {}", e.field, e.message))
            .collect();
        errors.join("; ")
    })
}

/// Reads a campaign's images from disk (keys are paths), one decode per
/// core at a time.
fn local_images() -> pipeline::ImageSource {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    pipeline::ImageSource {
        read: std::sync::Arc::new(|path: &str| {
            std::fs::read(path).map_err(|e| format!("{path}: {e}"))
        }),
        gate: std::sync::Arc::new(crate::imaging::DecodeGate::new(cores)),
    }
}
