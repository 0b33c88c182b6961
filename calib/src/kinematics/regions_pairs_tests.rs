//! Issue 18's claims on the simulator, over independent campaigns: "the
//! multi-region model is within 1.15x of each region's local model in that
//! region, and better than the local model of another region carried over
//! with only a base re-fit".
//!
//! One campaign decides little: every model's validation error is mostly
//! its depth-scale error (the focal length against the board distance,
//! method.md §4), so which of two models wins one campaign is close to a
//! coin weighted by their σ_fx (docs/decisions/0029-regions-judged-over-campaigns.md). The
//! claims are therefore asserted on the mean over seeds (each seed is a
//! new true robot, hand–eye and draw of poses), and the carried-over one
//! per pair (region r, model carried from region s) as a paired
//! comparison: the mean of `carried − global` must exceed [`T_MIN`] of its
//! standard errors.

use super::fixture::{region_figures, Setup, COMPLIANCE_RAD_PER_M, REGION_HOMES_DEG};
use crate::kinematics::nongeometric::TermKind;

const REGIONS: usize = REGION_HOMES_DEG.len();
/// Campaigns the asserted figures average over (about 0.45 s each here).
const SEEDS: std::ops::RangeInclusive<u64> = 1..=24;
/// Campaigns of the printed figures (`pairs_sweep`).
const SWEEP_SEEDS: std::ops::RangeInclusive<u64> = 1..=80;
/// Paired t a pair must reach: one-sided p < 1% at 23 degrees of freedom
/// (t_0.99 = 2.50), so the six pairs together err less than 6% of the time.
const T_MIN: f64 = 2.5;
/// The bound: the one model of the whole workspace loses at most
/// 15% against a region's own model in that region.
const LOCAL_RATIO_LIMIT: f64 = 1.15;
/// Calibration must at least shrink the nominal model's error this much
/// (it does 20–55x on these campaigns).
const CALIBRATION_GAIN_FLOOR: f64 = 5.0;
/// The simulator's compliance (joints 2 and 3, lever arm to the flange) as
/// the terms of issue 19 model it: the gravity torque at the tool point.
const COMPLIANCE_TERMS: [TermKind; 2] = [
    TermKind::ComplianceTool { joint: 1 },
    TermKind::ComplianceTool { joint: 2 },
];

/// Region `r` judged over the seeds: mean errors (mm) of its nominal,
/// local and global models, and one [`Pair`] per other region.
struct RegionMeans {
    nominal_mm: f64,
    local_mm: f64,
    global_mm: f64,
    pairs: Vec<Pair>,
}

/// The model carried from region `from` into the region, against the
/// global one, seed by seed.
struct Pair {
    from: usize,
    carried_mm: f64,
    /// Mean of `carried − global` (mm) and its standard error.
    advantage_mm: f64,
    standard_error_mm: f64,
    global_wins: usize,
}

impl Pair {
    fn t(&self) -> f64 {
        self.advantage_mm / self.standard_error_mm
    }
}

fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// Standard error of the mean of `x` (sample standard deviation / √n).
fn standard_error(x: &[f64]) -> f64 {
    let m = mean(x);
    let n = x.len() as f64;
    (x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt()
}

fn over_seeds(seeds: std::ops::RangeInclusive<u64>, setup: &Setup) -> Vec<RegionMeans> {
    let runs: Vec<_> = seeds.map(|seed| region_figures(seed, setup)).collect();
    (0..REGIONS)
        .map(|r| {
            let of = |pick: &dyn Fn(&super::fixture::RegionFigures) -> f64| {
                runs.iter().map(|run| pick(&run[r])).collect::<Vec<f64>>()
            };
            let global = of(&|f| f.global_mm);
            let pairs = (0..REGIONS)
                .filter(|&s| s != r)
                .map(|s| {
                    let carried = of(&|f| {
                        f.carried_mm
                            .iter()
                            .find(|(from, _)| *from == s)
                            .map(|(_, mm)| *mm)
                            .unwrap()
                    });
                    let advantage: Vec<f64> =
                        carried.iter().zip(&global).map(|(c, g)| c - g).collect();
                    Pair {
                        from: s,
                        carried_mm: mean(&carried),
                        advantage_mm: mean(&advantage),
                        standard_error_mm: standard_error(&advantage),
                        global_wins: advantage.iter().filter(|d| **d > 0.0).count(),
                    }
                })
                .collect();
            RegionMeans {
                nominal_mm: mean(&of(&|f| f.nominal_mm)),
                local_mm: mean(&of(&|f| f.local_mm)),
                global_mm: mean(&global),
                pairs,
            }
        })
        .collect()
}

fn print(label: &str, seeds: usize, means: &[RegionMeans]) {
    for (r, m) in means.iter().enumerate() {
        eprintln!(
            "{label}, {seeds} seeds, region {r}: nominal {:.4} local {:.4} global {:.4} mm \
             (global/local {:.2})",
            m.nominal_mm,
            m.local_mm,
            m.global_mm,
            m.global_mm / m.local_mm
        );
        for p in &m.pairs {
            eprintln!(
                "  carried from region {}: {:.4} mm, carried - global {:.4} ± {:.4} mm \
                 (t {:.1}), global better in {}/{seeds}",
                p.from,
                p.carried_mm,
                p.advantage_mm,
                p.standard_error_mm,
                p.t(),
                p.global_wins
            );
        }
    }
}

fn assert_within_ratio_of_local(means: &[RegionMeans]) {
    for (r, m) in means.iter().enumerate() {
        assert!(
            m.global_mm <= LOCAL_RATIO_LIMIT * m.local_mm,
            "region {r}: global {} vs local {} mm",
            m.global_mm,
            m.local_mm
        );
        assert!(m.global_mm < m.nominal_mm / CALIBRATION_GAIN_FLOOR);
    }
}

fn assert_better_per_pair(means: &[RegionMeans]) {
    for (r, m) in means.iter().enumerate() {
        for p in &m.pairs {
            assert!(
                p.t() >= T_MIN,
                "region {r}, carried from {}: global better by {} ± {} mm",
                p.from,
                p.advantage_mm,
                p.standard_error_mm
            );
        }
    }
}

/// Issue 18 on the simulator (a complete model: no unmodelled error): in
/// every region the multi-region model is within 1.15x of the local model,
/// and better than each other region's local model carried over, pair by
/// pair, on the mean over 24 campaigns.
#[test]
fn the_multi_region_model_beats_every_carried_over_model_per_pair() {
    let means = over_seeds(SEEDS, &Setup::with_compliance(0.0));
    print("compliance 0", SEEDS.count(), &means);
    assert_within_ratio_of_local(&means);
    assert_better_per_pair(&means);
}

/// With an unmodelled compliance (about 0.05 mm) and geometry only, the
/// multi-region model stays within 1.15x of each local model on the mean
/// over 24 campaigns, but no longer beats it (1.0–1.07x in two regions)
/// and beats the carried-over models only in some pairs: region 2's local
/// model carried into region 0 or 1, and region 0's into region 1, are as
/// good as the global one (BENCHMARKS.md "Regions").
/// The geometry absorbs the compliance region by region; modelled, the
/// pairs are restored (next test).
#[test]
fn with_unmodelled_compliance_the_model_stays_within_the_local_bound() {
    let means = over_seeds(SEEDS, &Setup::with_compliance(COMPLIANCE_RAD_PER_M));
    print("compliance 2e-4", SEEDS.count(), &means);
    assert_within_ratio_of_local(&means);
}

/// The same compliance modelled by issue 19's terms in every fit (the
/// global one, each local one; a carried-over model keeps its own terms):
/// the multi-region model beats every carried-over model per pair again.
#[test]
fn modelled_compliance_restores_the_per_pair_claim() {
    let setup = Setup {
        terms: Some(&COMPLIANCE_TERMS),
        ..Setup::with_compliance(COMPLIANCE_RAD_PER_M)
    };
    let means = over_seeds(SEEDS, &setup);
    print("compliance 2e-4 with terms", SEEDS.count(), &means);
    assert_within_ratio_of_local(&means);
    assert_better_per_pair(&means);
}

/// The figures of BENCHMARKS.md "Regions", over 80
/// campaigns (`cargo test -p robocal-calib --lib pairs_sweep -- --ignored
/// --nocapture`, about 3 min).
#[test]
#[ignore = "prints the figures of BENCHMARKS.md"]
fn pairs_sweep() {
    let complete = Setup::with_compliance(0.0);
    let service_sized = Setup {
        cal_poses: SERVICE_CAL_POSES,
        val_poses: SERVICE_VAL_POSES,
        ..complete
    };
    let compliant = Setup::with_compliance(COMPLIANCE_RAD_PER_M);
    let modelled = Setup {
        terms: Some(&COMPLIANCE_TERMS),
        ..compliant
    };
    for (label, setup) in [
        ("compliance 0", complete),
        ("compliance 0, 24 + 12 poses", service_sized),
        ("compliance 2e-4", compliant),
        ("compliance 2e-4 with terms", modelled),
    ] {
        print(label, SWEEP_SEEDS.count(), &over_seeds(SWEEP_SEEDS, &setup));
    }
}

/// Poses per region of the service's it test `multi_session`.
const SERVICE_CAL_POSES: usize = 24;
const SERVICE_VAL_POSES: usize = 12;
