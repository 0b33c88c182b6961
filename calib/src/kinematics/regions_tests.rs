//! The multi-region fit on the simulator's truth (issue 18): one robot,
//! the board placed in several regions of its workspace.

use super::*;
use crate::geometry::pose_error;
use crate::kinematics::identify::{frame_indices, identify, validate, IdentifyOptions};
use crate::kinematics::identify_options::JointNoise;
use crate::kinematics::joint_refine::joint_refine;
use crate::kinematics::{Instrument, ParamLayout};
use crate::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use crate::sim::campaign_io::PoseSet;
use crate::sim::oracle::truth_measurements;
use crate::sim::start_model::start_model;

/// Home joints (deg) of the PUMA 560 that put the board in three regions:
/// in front, swung 70 degrees to the left, and swung right and lower.
const REGION_HOMES_DEG: [[f64; 6]; 3] = [
    [0.0, 70.0, -140.0, 0.0, -20.0, 0.0],
    [70.0, 60.0, -130.0, 0.0, -20.0, 0.0],
    [-60.0, 85.0, -150.0, 0.0, -25.0, 0.0],
];
/// Gravity deflection of joints 2 and 3 (rad per m of lever arm): an
/// unmodelled error of about 0.05 mm at the validation poses, the size the
/// image-level fit leaves (larger ones: BENCHMARKS.md "Regions").
const COMPLIANCE_RAD_PER_M: f64 = 2e-4;
const CAL_POSES: usize = 30;
const VAL_POSES: usize = 20;

struct Region {
    spec: CampaignSpec,
    campaign: Campaign,
    start: CalibratedModel,
    images: Vec<ImagePose>,
}

/// The same robot (one seed: the robot and hand–eye are drawn first)
/// with its board placed by each home pose.
fn regions(seed: u64, compliance_rad_per_m: f64) -> Vec<Region> {
    REGION_HOMES_DEG
        .iter()
        .map(|home| {
            let mut spec = CampaignSpec::standard("puma560", seed).unwrap();
            spec.home_joints_rad = home.iter().map(|d| d.to_radians()).collect();
            spec.cal_poses = CAL_POSES;
            spec.val_poses = VAL_POSES;
            spec.compliance_rad_per_m = compliance_rad_per_m;
            let campaign = simulate_campaign(&spec).unwrap();
            let start = start_model(&spec, &truth_measurements(&campaign, PoseSet::Cal)).unwrap();
            let images = campaign
                .poses
                .iter()
                .filter(|p| p.set == PoseSet::Cal)
                .map(|p| ImagePose {
                    joints_rad: p.joints_rad.clone(),
                    observations: p.observations(&campaign.truth.board),
                })
                .collect();
            Region {
                spec,
                campaign,
                start,
                images,
            }
        })
        .collect()
}

fn noise(spec: &CampaignSpec) -> ImageNoise {
    ImageNoise {
        sigma_px: spec.pixel_sigma_px,
        joint: JointNoise::Known {
            sigma_rad: spec.encoder_sigma_deg.to_radians(),
        },
    }
}

/// Layout indices every region identifies (the pose-level analysis).
fn shared_free(regions: &[Region]) -> Vec<usize> {
    let sets: Vec<Vec<usize>> = regions
        .iter()
        .map(|r| {
            let cal = truth_measurements(&r.campaign, PoseSet::Cal);
            identify(
                &r.start,
                Instrument::Camera,
                &cal,
                IdentifyOptions::default(),
            )
            .unwrap()
            .identifiability
            .free
        })
        .collect();
    sets[0]
        .iter()
        .copied()
        .filter(|i| sets.iter().all(|s| s.contains(i)))
        .collect()
}

/// Mean 3-D camera position error (mm) of `model` at `region`'s
/// validation poses against the simulator's true camera poses.
fn mean_error_mm(model: &CalibratedModel, region: &Region) -> f64 {
    let val = truth_measurements(&region.campaign, PoseSet::Val);
    validate(model, &val).unwrap().0.norm.mean_mm
}

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

/// The one fit over all regions; region `i`'s model is the shared one
/// with `session_target_to_base[i]`.
fn global_fit(regions: &[Region], free: &[usize]) -> JointRefinement {
    let spec = &regions[0].spec;
    let input: Vec<RegionPoses> = regions
        .iter()
        .map(|r| RegionPoses {
            target_to_base_start: r.start.world_to_base,
            poses: r.images.clone(),
        })
        .collect();
    joint_refine_regions(
        &regions[0].start,
        &spec.intrinsics,
        &input,
        free,
        noise(spec),
        false,
    )
    .unwrap()
}

/// Without unmodelled errors the fit recovers the boards' placement
/// relative to each other. It does not depend on where the fit puts the
/// base frame (held parameters move every base alike), so it is compared
/// with the truth directly.
#[test]
fn multi_region_fit_recovers_the_board_placements() {
    let regions = regions(18, 0.0);
    let free = shared_free(&regions);
    let global = global_fit(&regions, &free);
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

/// One region's validation figures (mean 3-D error, mm): the nominal
/// start, its local model, the multi-region model, and every other
/// region's local model carried over with a base re-fit.
struct RegionFigures {
    nominal_mm: f64,
    local_mm: f64,
    global_mm: f64,
    carried_mm: Vec<f64>,
}

fn region_figures(compliance_rad_per_m: f64) -> Vec<RegionFigures> {
    let regions = regions(18, compliance_rad_per_m);
    let free = shared_free(&regions);
    let cam = regions[0].spec.intrinsics;
    let global = global_fit(&regions, &free);
    let layout = ParamLayout::new(&regions[0].spec.nominal, Instrument::Camera);
    let base_only = frame_indices(&layout, false);
    let locals: Vec<JointRefinement> = regions
        .iter()
        .map(|r| joint_refine(&r.start, &cam, &r.images, &free, noise(&r.spec), false).unwrap())
        .collect();
    regions
        .iter()
        .enumerate()
        .map(|(i, region)| {
            let global_here = CalibratedModel {
                world_to_base: global.session_target_to_base[i],
                ..global.model.clone()
            };
            let carried_mm = locals
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, other)| {
                    let start = CalibratedModel {
                        world_to_base: region.start.world_to_base,
                        ..other.model.clone()
                    };
                    let noise = noise(&region.spec);
                    let carried = joint_refine(
                        &start,
                        &other.intrinsics,
                        &region.images,
                        &base_only,
                        noise,
                        true,
                    )
                    .unwrap();
                    mean_error_mm(&carried.model, region)
                })
                .collect();
            RegionFigures {
                nominal_mm: mean_error_mm(&region.start, region),
                local_mm: mean_error_mm(&locals[i].model, region),
                global_mm: mean_error_mm(&global_here, region),
                carried_mm,
            }
        })
        .collect()
}

/// Issue 18, on the simulator without and with a small unmodelled joint
/// compliance: in every region the multi-region model is within 1.15x of
/// that region's local model, and better than the other regions' local
/// models carried over with a base re-fit, on average over them. (Pair by
/// pair it is not always: one carried-over model matches it within the
/// noise in two of six pairs, see BENCHMARKS.md "Regions".)
#[test]
fn multi_region_model_matches_local_models_and_beats_carried_over_ones() {
    for compliance in [0.0, COMPLIANCE_RAD_PER_M] {
        for (i, f) in region_figures(compliance).iter().enumerate() {
            eprintln!(
                "compliance {compliance:e} region {i}: nominal {:.3} mm, local {:.3} mm, \
                 global {:.3} mm, carried over {:.3?} mm",
                f.nominal_mm, f.local_mm, f.global_mm, f.carried_mm
            );
            assert!(
                f.global_mm <= LOCAL_RATIO_LIMIT * f.local_mm,
                "region {i}: global {} vs local {}",
                f.global_mm,
                f.local_mm
            );
            let carried_mean_mm = f.carried_mm.iter().sum::<f64>() / f.carried_mm.len() as f64;
            assert!(
                f.global_mm < carried_mean_mm,
                "region {i}: global {} vs carried over {:?}",
                f.global_mm,
                f.carried_mm
            );
            assert!(f.global_mm < f.nominal_mm / CALIBRATION_GAIN_FLOOR);
        }
    }
}

/// The figures of BENCHMARKS.md against the size of the unmodelled error
/// (`cargo test -p robocal-calib --lib compliance_sweep -- --ignored --nocapture`).
#[test]
#[ignore = "prints the figures of BENCHMARKS.md"]
fn compliance_sweep() {
    for compliance in COMPLIANCE_SWEEP_RAD_PER_M {
        for (i, f) in region_figures(compliance).iter().enumerate() {
            eprintln!(
                "compliance {compliance:e} rad/m region {i}: nominal {:.3} local {:.3} global {:.3} carried {:.3?} mm",
                f.nominal_mm, f.local_mm, f.global_mm, f.carried_mm
            );
        }
    }
}

const COMPLIANCE_SWEEP_RAD_PER_M: [f64; 5] = [0.0, 2e-4, 5e-4, 1e-3, 2e-3];

/// The bound: the one model of the whole workspace loses at most
/// 15% against a region's own model in that region.
const LOCAL_RATIO_LIMIT: f64 = 1.15;
/// Calibration must at least shrink the nominal model's error this much
/// (it does about 15x on this campaign).
const CALIBRATION_GAIN_FLOOR: f64 = 5.0;
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
    let global = global_fit(&regions, &free);
    let images: Vec<ImagePose> = regions.iter().flat_map(|r| r.images.clone()).collect();
    let session_of: Vec<usize> = session_of(
        &regions
            .iter()
            .map(|r| RegionPoses {
                target_to_base_start: r.start.world_to_base,
                poses: r.images.clone(),
            })
            .collect::<Vec<_>>(),
    );
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
