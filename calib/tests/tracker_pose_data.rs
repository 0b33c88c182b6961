//! Issue 19: a 6-DoF tracker's orientation used with its own weight. The
//! UR10 of Landgraf 2021 (Leica T-Mac) on every 10th pose of Series B,
//! position only (`Instrument::Tracker`) against full pose
//! (`Instrument::Camera` layout), checked on the held-out poses between
//! them (same tracker station: no base re-fit). Debug, a few seconds.
//! The full campaign with Series C and D: `examples/ur10_pose_bench.rs`.

use nalgebra::{UnitQuaternion, Vector3};
use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::identify::{identify, Identification, IdentifyMode, Measurement};
use robocal_calib::kinematics::initial::initial_world_to_base;
use robocal_calib::kinematics::tracker_csv::{landgraf2021_rows, TrackerRow};
use robocal_calib::kinematics::tracker_pose::PROBE_ROTATION_FLOOR_DEG;
use robocal_calib::kinematics::{presets, CalibratedModel, Instrument};

const SERIES_B: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/kinematic/ur10_landgraf2021/Series_B/measurements_joint_configurations.csv"
);
/// Fit on every 10th pose, hold out the poses half-way between them.
const EVERY: usize = 10;
const HELD_OUT_OFFSET: usize = 5;
/// Probe origin and rotation in the flange frame to start from
/// (`Trafo_TM_F_init.txt`: 109 mm along z, rotated -90° about z).
const TOOL_GUESS_MM: [f64; 3] = [0.0, 0.0, 109.0];
const TOOL_GUESS_RZ_DEG: f64 = -90.0;
/// The wrist parameters whose σ the orientation must lower (joint 6's are
/// all fixed with a 6-DoF tool: they are a constant transform after it).
const WRIST: [&str; 6] = ["dtheta_4", "d_4", "alpha_4", "dtheta_5", "d_5", "alpha_5"];
/// Held-out orientation error (deg, rms of the 3-D angle) the full-pose fit
/// must stay under. The probe's stated 0.01° per angle is 0.017° as a 3-D
/// rms, but the robot's unmodelled error is larger: the fit's own residual
/// here is 0.050° in-sample and 0.061° held out (0.075–0.11° on Series C
/// and D, BENCHMARKS.md "Non-geometric terms"), so "the level of the probe" is not
/// reached on this robot. 0.08° (5× the probe) passes the calibrated
/// model and fails the nominal kinematics with fitted frames (0.114°) or
/// a wrong Euler convention (≥ 2.6°).
const HELD_OUT_ORIENTATION_RMS_DEG: f64 = 0.08;

fn split() -> (Vec<TrackerRow>, Vec<TrackerRow>) {
    let rows = landgraf2021_rows(&std::fs::read_to_string(SERIES_B).unwrap()).unwrap();
    let fit = rows.iter().step_by(EVERY).cloned().collect();
    let held = rows
        .iter()
        .skip(HELD_OUT_OFFSET)
        .step_by(EVERY)
        .cloned()
        .collect();
    (fit, held)
}

fn start(data: &[Measurement], rotation_about_z_deg: f64) -> CalibratedModel {
    let mut m = CalibratedModel {
        robot: presets::ur10(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::translation(TOOL_GUESS_MM[0], TOOL_GUESS_MM[1], TOOL_GUESS_MM[2]),
    };
    m.flange_to_tool.rotation =
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rotation_about_z_deg.to_radians());
    m.world_to_base = initial_world_to_base(&m, data).unwrap();
    m
}

fn sigma(id: &Identification, name: &str) -> f64 {
    let i = id.layout.index_of(name).unwrap();
    if id.identifiability.fixed.iter().any(|f| f == name) {
        f64::INFINITY
    } else {
        id.std_devs[i]
    }
}

/// RMS (deg) of the 3-D angle between measured and predicted orientation.
fn orientation_rms_deg(model: &CalibratedModel, rows: &[TrackerRow]) -> f64 {
    let sum: f64 = rows
        .iter()
        .map(|r| {
            let m = r.pose_measurement().unwrap();
            let robocal_calib::kinematics::identify::Observed::Pose { world_to_tool, .. } =
                m.observed
            else {
                unreachable!("a pose")
            };
            let pred = model.world_to_tool(&r.joints_rad).unwrap();
            pred.rotation
                .angle_to(&world_to_tool.rotation)
                .to_degrees()
                .powi(2)
        })
        .sum();
    (sum / rows.len() as f64).sqrt()
}

#[test]
fn ur10_probe_orientation_lowers_wrist_sigma_and_predicts_held_out_orientation() {
    let (fit_rows, held_rows) = split();
    let positions: Vec<Measurement> = fit_rows.iter().map(TrackerRow::measurement).collect();
    let poses: Vec<Measurement> = fit_rows
        .iter()
        .map(|r| r.pose_measurement().unwrap())
        .collect();
    let options = IdentifyMode::Weighted.into();
    let a = identify(
        &start(&positions, 0.0),
        Instrument::Tracker,
        &positions,
        options,
    )
    .unwrap();
    let b = identify(
        &start(&positions, TOOL_GUESS_RZ_DEG),
        Instrument::Camera,
        &poses,
        options,
    )
    .unwrap();
    for name in WRIST {
        let (sa, sb) = (sigma(&a, name), sigma(&b, name));
        println!("σ {name}: position only {sa:.2e}, full pose {sb:.2e}");
        assert!(
            sb < sa,
            "{name}: the orientation must lower σ ({sb:.2e} vs {sa:.2e})"
        );
    }
    let in_sample = orientation_rms_deg(&b.model, &fit_rows);
    let before = orientation_rms_deg(&b.before, &held_rows);
    let after = orientation_rms_deg(&b.model, &held_rows);
    println!(
        "orientation, 3-D rms: in-sample {in_sample:.4}°; held out ({} poses) nominal kinematics {before:.4}°, calibrated {after:.4}° (probe {PROBE_ROTATION_FLOOR_DEG}° per angle)",
        held_rows.len()
    );
    assert!(
        after < before,
        "calibration improves the held-out orientation"
    );
    assert!(after < HELD_OUT_ORIENTATION_RMS_DEG, "{after}°");
}
