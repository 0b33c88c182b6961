//! Held-out configurations on the real Aubo i10 campaign (docs/method.md
//! §6–7): 24 photos of a chessboard in 6 groups of 4, joints 1–3 fixed
//! within a group. Each group in turn is held out; the models are fitted on
//! the other five groups' corners and predict the held-out group's corners
//! through the calibrated robot, hand–eye, board pose and intrinsics. The
//! pooled RMS over all 24 photos is printed per model:
//!
//! - `job`: what a calibration job now does on the five groups (the model
//!   ladder chosen by leave-one-group-out *inside* them, then refitted);
//! - `hand_eye`: nominal kinematics, board, hand–eye and camera refined;
//! - every other rung of the ladder fitted as such (`full` is the model
//!   the service approved before the ladder existed).
//!
//! OpenCV's `calibrateHandEye` (Park) with the nominal kinematics is the
//! peer: `bench/aubo_heldout_opencv.py` on the same corners.
//!
//! Run: `cargo run --release -p robocal-calib --example aubo_heldout`

use std::collections::BTreeMap;

use nalgebra::{Point2, Point3};
use robocal_calib::camera::pose::estimate_pose;
use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::config_groups::configuration_groups;
use robocal_calib::kinematics::identifiability::structural_redundancies;
use robocal_calib::kinematics::identify::{
    identify, IdentifyMode, IdentifyOptions, JointNoise, Measurement, Observed,
};
use robocal_calib::kinematics::initial::initial_frames_from_poses;
use robocal_calib::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose};
use robocal_calib::kinematics::model_ladder::{climb, fit_rung, LadderInput, Rung};
use robocal_calib::kinematics::prior::KinematicPrior;
use robocal_calib::kinematics::{
    choose_conventions, CalibratedModel, Instrument, Joint, ParamLayout, RobotModel,
};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/aubo_i10_hkclr");
/// Inner corners per row and the square (mm), as the authors' board.
const CORNERS_PER_ROW: usize = 11;
const SQUARE_MM: f64 = 10.0;
/// The authors' standard DH table: (d mm, a mm, alpha deg, theta offset deg).
const DH: [(f64, f64, f64, f64); 6] = [
    (163.2, 0.0, 90.0, 0.0),
    (0.0, 647.0, 180.0, 90.0),
    (0.0, 600.5, 180.0, 0.0),
    (201.3, 0.0, -90.0, -90.0),
    (102.5, 0.0, 90.0, 0.0),
    (94.0, 0.0, 0.0, 0.0),
];
/// A starting camera (the authors' published intrinsics, PROVENANCE.md):
/// every fit refines it on its own photos.
const START: Intrinsics = Intrinsics {
    fx: 2281.69027,
    fy: 2280.99962,
    cx: 1407.20528,
    cy: 893.295531,
    k1: -7.14967118e-3,
    k2: -1.69424563e-3,
    p1: -4.70604299e-5,
    p2: -2.47795750e-4,
    k3: 4.36516991e-2,
};

fn robot() -> RobotModel {
    let joints: Vec<_> = DH
        .iter()
        .map(|&(d, a, alpha, off)| (None, Joint::dh(a, alpha, d, off, (-360.0, 360.0))))
        .collect();
    RobotModel {
        joints: choose_conventions(&joints),
    }
}

/// A photo's corners: board point (mm) and image point (px).
type Corners = Vec<(Point3<f64>, Point2<f64>)>;

/// Every photo: (group, joints rad, corners as observations), in file order.
fn photos() -> Vec<(usize, ImagePose)> {
    let csv = std::fs::read_to_string(format!(
        "{DIR}/derived_opencv5/corners_findChessboardCorners.csv"
    ))
    .expect("corners");
    let mut corners: BTreeMap<String, Corners> = BTreeMap::new();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let id: usize = f[1].parse().expect("id");
        let p = Point3::new(
            (id % CORNERS_PER_ROW) as f64 * SQUARE_MM,
            (id / CORNERS_PER_ROW) as f64 * SQUARE_MM,
            0.0,
        );
        let uv = Point2::new(f[2].parse().expect("x"), f[3].parse().expect("y"));
        corners.entry(f[0].to_string()).or_default().push((p, uv));
    }
    let mut out = Vec::new();
    for g in 1..=6 {
        let text = std::fs::read_to_string(format!("{DIR}/joints/group{g}.txt")).expect("joints");
        let names: Vec<&String> = corners
            .keys()
            .filter(|k| k.starts_with(&format!("group{g}/")))
            .collect();
        for (name, line) in names
            .into_iter()
            .zip(text.lines().filter(|l| !l.trim().is_empty()))
        {
            let joints_rad = line
                .split(',')
                .map(|v| v.trim().parse::<f64>().expect("joint"))
                .collect();
            out.push((
                g - 1,
                ImagePose {
                    joints_rad,
                    observations: corners[name].clone(),
                },
            ));
        }
    }
    out
}

/// Sum of squared reprojection errors and point count of `pose` under a
/// fitted model and camera.
fn squared(model: &CalibratedModel, cam: &Intrinsics, pose: &ImagePose) -> (f64, usize) {
    let inv = model.world_to_tool(&pose.joints_rad).expect("fk").inverse();
    let sum = pose
        .observations
        .iter()
        .map(|(p, uv)| {
            let pred = cam.project(&(inv * p)).expect("in front");
            (pred.coords - uv.coords).norm_squared()
        })
        .sum();
    (sum, pose.observations.len())
}

/// The job's steps on `train`: pose-level start, full joint refinement
/// (noise estimated), the ladder over the training groups.
struct Trained {
    start: CalibratedModel,
    campaign_free: Vec<usize>,
    identifiable: Vec<usize>,
    noise: ImageNoise,
    intrinsics: Intrinsics,
}

fn train(robot: &RobotModel, poses: &[ImagePose]) -> Trained {
    let data: Vec<Measurement> = poses
        .iter()
        .map(|p| {
            let e = estimate_pose(&START, &p.observations, None).expect("pnp");
            Measurement {
                joints_rad: p.joints_rad.clone(),
                observed: Observed::Pose {
                    world_to_tool: e.target_to_camera,
                    covariance: Some(e.covariance_6x6),
                },
            }
        })
        .collect();
    let mut start = CalibratedModel {
        robot: robot.clone(),
        world_to_base: nalgebra::Isometry3::identity(),
        flange_to_tool: nalgebra::Isometry3::identity(),
    };
    (start.world_to_base, start.flange_to_tool) =
        initial_frames_from_poses(&start, &data).expect("frames");
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::default(),
    };
    let id = identify(&start, Instrument::Camera, &data, options).expect("identify");
    let full = joint_refine(
        &id.model,
        &START,
        poses,
        &id.identifiability.free,
        ImageNoise {
            sigma_px: 0.1,
            joint: JointNoise::Estimate,
        },
        false,
    )
    .expect("refine");
    let nominal = CalibratedModel {
        robot: robot.clone(),
        ..full.model.clone()
    };
    let layout = ParamLayout::new(robot, Instrument::Camera);
    let structural = structural_redundancies(&layout, &nominal).expect("structure");
    Trained {
        start: nominal,
        campaign_free: id.identifiability.free.clone(),
        identifiable: (0..layout.len())
            .filter(|i| !structural.contains(i))
            .collect(),
        noise: ImageNoise {
            sigma_px: full.sigma_px,
            joint: JointNoise::Known {
                sigma_rad: full.joint_sigma_rad,
            },
        },
        intrinsics: full.intrinsics,
    }
}

fn main() {
    let robot = robot();
    let photos = photos();
    assert_eq!(photos.len(), 24, "24 photos with corners");
    let prior = KinematicPrior::default();
    let names: Vec<&str> = std::iter::once("job")
        .chain(Rung::ALL.iter().map(|r| r.as_str()))
        .collect();
    let mut sums = vec![(0.0, 0usize); names.len()];
    let mut chosen = Vec::new();
    for held in 0..6 {
        let train_poses: Vec<ImagePose> = photos
            .iter()
            .filter(|(g, _)| *g != held)
            .map(|(_, p)| p.clone())
            .collect();
        let test: Vec<&ImagePose> = photos
            .iter()
            .filter(|(g, _)| *g == held)
            .map(|(_, p)| p)
            .collect();
        let t = train(&robot, &train_poses);
        let joints: Vec<Vec<f64>> = train_poses.iter().map(|p| p.joints_rad.clone()).collect();
        let groups = configuration_groups(&joints, &[]);
        let input = LadderInput {
            nominal: &t.start,
            intrinsics: &t.intrinsics,
            poses: &train_poses,
            groups: &groups,
            measured: &[],
            campaign_free: &t.campaign_free,
            identifiable: &t.identifiable,
            prior: &prior,
            noise: t.noise,
            hold_intrinsics: false,
            candidates: None,
        };
        let ladder = climb(&input, &Rung::ALL).expect("five groups");
        chosen.push(ladder.chosen.as_str());
        let rungs = std::iter::once(ladder.chosen).chain(Rung::ALL);
        for (k, rung) in rungs.enumerate() {
            let (fit, _) = fit_rung(rung, &input, &train_poses, t.noise).expect("fit");
            for pose in &test {
                let (s, n) = squared(&fit.model, &fit.intrinsics, pose);
                sums[k].0 += s;
                sums[k].1 += n;
            }
        }
    }
    println!("Aubo i10, leave-one-group-out (6 folds, 24 photos pooled), held-out corner RMS:");
    for (name, (s, n)) in names.iter().zip(&sums) {
        println!("  {name:<20} {:.3} px", (s / *n as f64).sqrt());
    }
    println!("  job's choice per fold: {chosen:?}");
}
