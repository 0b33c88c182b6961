//! Test fixture of the multi-region fit (issue 18, method.md §7): one
//! simulated robot with its board placed in three regions of the
//! workspace, and the models compared in each region against the
//! simulator's truth — the region's own local model, the one model of all
//! regions, and the other regions' local models carried over with only a
//! base re-fit.

use super::*;
use crate::kinematics::identify::{frame_indices, identify, validate, IdentifyOptions};
use crate::kinematics::identify_options::JointNoise;
use crate::kinematics::joint_refine::{joint_refine, joint_refine_with_terms};
use crate::kinematics::nongeometric::{NonGeometric, TermKind};
use crate::kinematics::{Instrument, ParamLayout};
use crate::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use crate::sim::campaign_io::PoseSet;
use crate::sim::oracle::truth_measurements;
use crate::sim::start_model::start_model;

/// Home joints (deg) of the PUMA 560 that put the board in three regions:
/// in front, swung 70 degrees to the left, and swung right and lower.
pub(super) const REGION_HOMES_DEG: [[f64; 6]; 3] = [
    [0.0, 70.0, -140.0, 0.0, -20.0, 0.0],
    [70.0, 60.0, -130.0, 0.0, -20.0, 0.0],
    [-60.0, 85.0, -150.0, 0.0, -25.0, 0.0],
];
/// Gravity deflection of joints 2 and 3 (rad per m of lever arm): an
/// unmodelled error that raises the multi-region model's mean validation
/// error from about 0.035 to 0.085 mm (larger ones: BENCHMARKS.md
/// "Regions").
pub(super) const COMPLIANCE_RAD_PER_M: f64 = 2e-4;
/// Poses per region (the service's it test `multi_session` uses 24 + 12).
const CAL_POSES: usize = 30;
const VAL_POSES: usize = 20;

/// What a campaign of the fixture is: the unmodelled compliance, the
/// poses per region, and the non-geometric terms every fit refines (none:
/// geometry only).
#[derive(Debug, Clone, Copy)]
pub(super) struct Setup {
    pub(super) compliance_rad_per_m: f64,
    pub(super) cal_poses: usize,
    pub(super) val_poses: usize,
    pub(super) terms: Option<&'static [TermKind]>,
}

impl Setup {
    /// Geometry only, [`CAL_POSES`] + [`VAL_POSES`] per region.
    pub(super) fn with_compliance(compliance_rad_per_m: f64) -> Self {
        Self {
            compliance_rad_per_m,
            cal_poses: CAL_POSES,
            val_poses: VAL_POSES,
            terms: None,
        }
    }
}

pub(super) struct Region {
    pub(super) spec: CampaignSpec,
    pub(super) campaign: Campaign,
    pub(super) start: CalibratedModel,
    pub(super) images: Vec<ImagePose>,
}

/// The same robot (one seed: the robot and hand–eye are drawn first)
/// with its board placed by each home pose. Each placement draws its
/// stations and noise from its own stream, as separate sessions would.
pub(super) fn regions(seed: u64, compliance_rad_per_m: f64) -> Vec<Region> {
    regions_of(seed, &Setup::with_compliance(compliance_rad_per_m))
}

fn regions_of(seed: u64, setup: &Setup) -> Vec<Region> {
    REGION_HOMES_DEG
        .iter()
        .zip(1u64..)
        .map(|(home, stream)| {
            let mut spec = CampaignSpec::standard("puma560", seed).unwrap();
            spec.home_joints_rad = home.iter().map(|d| d.to_radians()).collect();
            spec.cal_poses = setup.cal_poses;
            spec.val_poses = setup.val_poses;
            spec.compliance_rad_per_m = setup.compliance_rad_per_m;
            spec.pose_stream = stream;
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

pub(super) fn noise(spec: &CampaignSpec) -> ImageNoise {
    ImageNoise {
        sigma_px: spec.pixel_sigma_px,
        joint: JointNoise::Known {
            sigma_rad: spec.encoder_sigma_deg.to_radians(),
        },
    }
}

/// Layout indices every region identifies (the pose-level analysis).
pub(super) fn shared_free(regions: &[Region]) -> Vec<usize> {
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

/// Every region's start board and calibration images: the fit's input.
pub(super) fn region_poses(regions: &[Region]) -> Vec<RegionPoses> {
    regions
        .iter()
        .map(|r| RegionPoses {
            target_to_base_start: r.start.world_to_base,
            poses: r.images.clone(),
        })
        .collect()
}

/// The one fit over all regions; region `i`'s model is the shared one
/// with `session_target_to_base[i]`. With `terms`, those non-geometric
/// terms are refined with it (issue 19's terms in the multi-region fit).
pub(super) fn global_fit(
    regions: &[Region],
    free: &[usize],
    terms: Option<&[TermKind]>,
) -> JointRefinement {
    let spec = &regions[0].spec;
    let input = region_poses(regions);
    let (start, cam, noise) = (&regions[0].start, &spec.intrinsics, noise(spec));
    let fit = match terms {
        None => joint_refine_regions(start, cam, &input, free, noise, false),
        Some(kinds) => {
            let terms = zero_terms(start, kinds);
            joint_refine_regions_with_terms(start, cam, &input, free, &terms, noise, false)
        }
    };
    fit.unwrap()
}

/// `kinds` on `model`'s chain, every value zero: a fit's start.
fn zero_terms(model: &CalibratedModel, kinds: &[TermKind]) -> NonGeometric {
    NonGeometric {
        terms: kinds.to_vec(),
        values: vec![0.0; kinds.len()],
        ..NonGeometric::none(model)
    }
}

/// A model as it is used: the geometry on a board and, if any, the
/// non-geometric terms deflecting the joints before the chain.
struct Used<'a> {
    model: CalibratedModel,
    terms: Option<&'a NonGeometric>,
}

/// The terms a fit refined, if any.
fn terms_of(fit: &JointRefinement) -> Option<&NonGeometric> {
    fit.terms.as_ref().map(|t| &t.terms)
}

/// `poses` with their joints deflected by `terms` (as the chain sees them).
fn deflect(poses: &[ImagePose], terms: Option<&NonGeometric>) -> Vec<ImagePose> {
    poses
        .iter()
        .map(|p| ImagePose {
            joints_rad: terms.map_or(p.joints_rad.clone(), |t| {
                t.deflected(&p.joints_rad).unwrap()
            }),
            observations: p.observations.clone(),
        })
        .collect()
}

/// Mean 3-D camera position error (mm) of `used` at `region`'s validation
/// poses against the simulator's true camera poses.
fn mean_error_mm(used: &Used, region: &Region) -> f64 {
    let mut val = truth_measurements(&region.campaign, PoseSet::Val);
    if let Some(t) = used.terms {
        for m in val.iter_mut() {
            m.joints_rad = t.deflected(&m.joints_rad).unwrap();
        }
    }
    validate(&used.model, &val).unwrap().0.norm.mean_mm
}

/// One region's validation figures (mean 3-D error, mm): the nominal
/// start, its local model, the multi-region model, and every other
/// region's local model carried over with a base re-fit, with the index of
/// the region it comes from.
pub(super) struct RegionFigures {
    pub(super) nominal_mm: f64,
    pub(super) local_mm: f64,
    pub(super) global_mm: f64,
    pub(super) carried_mm: Vec<(usize, f64)>,
}

/// The figures of every region of the campaign `seed` of `setup`. With
/// terms, every fit (global and local) refines them, and a carried-over
/// model keeps its own.
pub(super) fn region_figures(seed: u64, setup: &Setup) -> Vec<RegionFigures> {
    let terms = setup.terms;
    let regions = regions_of(seed, setup);
    let free = shared_free(&regions);
    let cam = regions[0].spec.intrinsics;
    let global = global_fit(&regions, &free, terms);
    let layout = ParamLayout::new(&regions[0].spec.nominal, Instrument::Camera);
    let base_only = frame_indices(&layout, false);
    let locals: Vec<JointRefinement> = regions
        .iter()
        .map(|r| {
            let fit = match terms {
                None => joint_refine(&r.start, &cam, &r.images, &free, noise(&r.spec), false),
                Some(kinds) => joint_refine_with_terms(
                    &r.start,
                    &cam,
                    &r.images,
                    &free,
                    &zero_terms(&r.start, kinds),
                    noise(&r.spec),
                    false,
                ),
            };
            fit.unwrap()
        })
        .collect();
    regions
        .iter()
        .enumerate()
        .map(|(i, region)| {
            let global_here = Used {
                model: CalibratedModel {
                    world_to_base: global.session_target_to_base[i],
                    ..global.model.clone()
                },
                terms: terms_of(&global),
            };
            let local = Used {
                model: locals[i].model.clone(),
                terms: terms_of(&locals[i]),
            };
            let carried_mm = locals
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(j, other)| {
                    let start = CalibratedModel {
                        world_to_base: region.start.world_to_base,
                        ..other.model.clone()
                    };
                    // Only the base is re-fitted: the source's terms are
                    // applied to this region's joints, not refined.
                    let images = deflect(&region.images, terms_of(other));
                    let noise = noise(&region.spec);
                    let base =
                        joint_refine(&start, &other.intrinsics, &images, &base_only, noise, true)
                            .unwrap();
                    let carried = Used {
                        model: base.model,
                        terms: terms_of(other),
                    };
                    (j, mean_error_mm(&carried, region))
                })
                .collect();
            let nominal = Used {
                model: region.start.clone(),
                terms: None,
            };
            RegionFigures {
                nominal_mm: mean_error_mm(&nominal, region),
                local_mm: mean_error_mm(&local, region),
                global_mm: mean_error_mm(&global_here, region),
                carried_mm,
            }
        })
        .collect()
}
