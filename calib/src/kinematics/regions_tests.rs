//! The multi-region fit on the simulator's truth (issue 18): one robot,
//! the board placed in several regions of its workspace. The claims about
//! the models' accuracy per region are in `regions_pairs_tests.rs`.

use super::fixture::{
    global_fit, region_figures, region_poses, regions, shared_free, Region, Setup,
};
use super::*;
use crate::geometry::pose_error;
use crate::kinematics::identify_options::JointNoise;
use crate::sim::campaign::CampaignSpec;

#[test]
fn empty_input_is_an_error() {
    let robot = crate::kinematics::presets::puma560();
    let start = CalibratedModel {
        robot,
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    };
    let cam = CampaignSpec::standard("puma560", 1).unwrap().intrinsics;
    let n = ImageNoise {
        sigma_px: 0.1,
        joint: JointNoise::default(),
    };
    assert_eq!(
        joint_refine_regions(&start, &cam, &[], &[0], n, false).unwrap_err(),
        IdentifyError::NoPoses
    );
    let empty = RegionPoses {
        target_to_base_start: Pose::identity(),
        poses: Vec::new(),
    };
    assert_eq!(
        joint_refine_regions(&start, &cam, &[empty], &[0], n, false).unwrap_err(),
        IdentifyError::EmptyRegion { region: 0 }
    );
}

/// Without unmodelled errors the fit recovers the boards' placement
/// relative to each other. It does not depend on where the fit puts the
/// base frame (held parameters move every base alike), so it is compared
/// with the truth directly.
#[test]
fn multi_region_fit_recovers_the_board_placements() {
    let regions = regions(18, 0.0);
    let free = shared_free(&regions);
    let global = global_fit(&regions, &free, None);
    assert_eq!(global.session_target_to_base.len(), regions.len());
    let true_bases: Vec<Pose> = regions
        .iter()
        .map(|r| r.campaign.truth.model().unwrap().world_to_base)
        .collect();
    for r in 1..regions.len() {
        let found = global.session_target_to_base[0] * global.session_target_to_base[r].inverse();
        let truth = true_bases[0] * true_bases[r].inverse();
        let e = pose_error(&found, &truth);
        eprintln!("board 0 to board {r}: {e:?}");
        assert!(
            e.fixed_rows::<3>(0).norm() < BOARD_TO_BOARD_TOLERANCE_MM
                && e.fixed_rows::<3>(3).norm() < BOARD_TO_BOARD_TOLERANCE_RAD,
            "region {r}: {e:?}"
        );
    }
    let fx_error = (global.intrinsics.fx - regions[0].spec.intrinsics.fx).abs();
    assert!(fx_error < FX_TOLERANCE_PX, "fx off by {fx_error} px");
}

/// One campaign (seed 18) against the size of the unmodelled error
/// (`cargo test -p robocal-calib --lib compliance_sweep -- --ignored --nocapture`;
/// BENCHMARKS.md "Regions", whose regions still shared their draws). One
/// seed says little: see `regions_pairs_tests.rs` for figures over seeds.
#[test]
#[ignore = "prints the figures of BENCHMARKS.md"]
fn compliance_sweep() {
    for compliance in COMPLIANCE_SWEEP_RAD_PER_M {
        for (i, f) in region_figures(18, &Setup::with_compliance(compliance))
            .iter()
            .enumerate()
        {
            eprintln!(
                "compliance {compliance:e} rad/m region {i}: nominal {:.3} local {:.3} global {:.3} carried {:.3?} mm",
                f.nominal_mm, f.local_mm, f.global_mm, f.carried_mm
            );
        }
    }
}

const COMPLIANCE_SWEEP_RAD_PER_M: [f64; 5] = [0.0, 2e-4, 5e-4, 1e-3, 2e-3];

/// Recovered board-to-board transform (30 images per board at 0.1 px).
const BOARD_TO_BOARD_TOLERANCE_MM: f64 = 0.2;
const BOARD_TO_BOARD_TOLERANCE_RAD: f64 = 2e-4;
/// Recovered focal length (px of 3480).
const FX_TOLERANCE_PX: f64 = 1.0;

/// The three-region campaign fitted globally, with what the covariance
/// takes: (regions, free set, fit, every image, each image's session).
fn fitted_regions() -> (
    Vec<Region>,
    Vec<usize>,
    JointRefinement,
    Vec<ImagePose>,
    Vec<usize>,
) {
    let regions = regions(18, 0.0);
    let free = shared_free(&regions);
    let global = global_fit(&regions, &free, None);
    let images: Vec<ImagePose> = regions.iter().flat_map(|r| r.images.clone()).collect();
    let session_of = session_of(&region_poses(&regions));
    (regions, free, global, images, session_of)
}

/// The covariance of the multi-region fit, recomputed with every pose on
/// its own session's board, reproduces the fit's own standard deviations
/// (the further sessions' bases marginalised, as in the fit).
#[test]
fn multi_region_covariance_reproduces_the_fit_std_devs() {
    use crate::kinematics::joint_covariance::joint_refine_covariance_sessions;
    let (_, free, global, images, session_of) = fitted_regions();
    let cov =
        joint_refine_covariance_sessions(&global, &images, &free, false, &session_of).unwrap();
    for &i in &free {
        let (sd, want) = (cov[(i, i)].max(0.0).sqrt(), global.std_devs[i]);
        assert!(
            (sd - want).abs() <= COVARIANCE_RELATIVE * want,
            "{}: {sd} vs {want}",
            global.layout.params[i].name
        );
    }
}

/// Relative agreement of the recomputed σ with the fit's.
const COVARIANCE_RELATIVE: f64 = 0.02;

/// Session 1's covariance equals session 0's of the same fit with the two
/// sessions' places swapped: each board's σ is its own, not the first's.
#[test]
fn each_session_sees_its_own_board_covariance() {
    use crate::kinematics::joint_covariance::session_covariances;
    let (regions, free, global, images, session_of) = fitted_regions();
    let all = session_covariances(&global, &images, &free, false, &session_of).unwrap();
    assert_eq!(all.len(), regions.len());
    let mut swapped = global.clone();
    swapped.session_target_to_base.swap(0, 1);
    swapped.model.world_to_base = swapped.session_target_to_base[0];
    let swapped_of: Vec<usize> = session_of
        .iter()
        .map(|&s| match s {
            0 => 1,
            1 => 0,
            other => other,
        })
        .collect();
    let seen = session_covariances(&swapped, &images, &free, false, &swapped_of).unwrap();
    let scale = all[1].amax();
    let gap = (&all[1] - &seen[0]).amax();
    assert!(gap <= 1e-6 * scale, "{gap} of {scale}");
    // And the boards differ: session 0's base σ is not session 1's.
    let apart = (&all[0] - &all[1]).amax();
    assert!(apart > 1e-2 * scale, "{apart} of {scale}");
}
