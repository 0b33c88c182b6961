use super::*;
use crate::geometry::pose_error;
use crate::kinematics::presets;
use crate::sim::tracker_campaign::{simulate_tracker, TrackerSpec};

/// The probe's frame found from the poses alone, its rotation unknown to
/// the start: within what the nominal kinematics' own errors (about 1 mrad
/// per joint, 0.5 mm per length) allow.
const ROTATION_TOLERANCE_RAD: f64 = 0.01;
const TRANSLATION_TOLERANCE_MM: f64 = 5.0;

#[test]
fn a_probe_frame_is_found_from_the_measured_poses() {
    let c = simulate_tracker(
        &presets::ur10(),
        &TrackerSpec {
            poses: 40,
            noise_mm: 0.01,
            seed: 11,
            non_geometric: false,
            orientation_noise_rad: Some(2e-4),
        },
    );
    // The start knows the tool point only: its rotation is a quarter turn off.
    let tool_turn = pose_error(&c.truth.flange_to_tool, &c.start.flange_to_tool);
    assert!(tool_turn.fixed_rows::<3>(3).norm() > 1.0);
    let (world_to_base, flange_to_tool) =
        initial_frames_from_poses(&c.start, &c.measurements).unwrap();
    for (found, truth) in [
        (world_to_base, c.truth.world_to_base),
        (flange_to_tool, c.truth.flange_to_tool),
    ] {
        let e = pose_error(&found, &truth);
        assert!(
            e.fixed_rows::<3>(0).norm() < TRANSLATION_TOLERANCE_MM,
            "{e}"
        );
        assert!(e.fixed_rows::<3>(3).norm() < ROTATION_TOLERANCE_RAD, "{e}");
    }
}

#[test]
fn a_position_among_the_poses_is_refused() {
    let mut c = simulate_tracker(
        &presets::ur10(),
        &TrackerSpec {
            poses: 10,
            noise_mm: 0.01,
            seed: 2,
            non_geometric: false,
            orientation_noise_rad: Some(2e-4),
        },
    );
    c.measurements[4].observed = Observed::Position {
        position_mm: c.measurements[4].observed.position_mm(),
        covariance: None,
    };
    assert!(matches!(
        initial_frames_from_poses(&c.start, &c.measurements),
        Err(IdentifyError::WrongMeasurement { pose: 4, .. })
    ));
}
