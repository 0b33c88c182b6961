//! Issue 19 on the simulator: how often non-geometric terms are kept on a
//! robot without them (false positives), and what is kept and how close to
//! the noise floor validation gets on one with them.
//!
//! `cargo run --release -p robocal-calib --example nongeometric_bench [seeds]`

use robocal_calib::kinematics::identify::{validate, IdentifyMode};
use robocal_calib::kinematics::nongeometric::CandidateOptions;
use robocal_calib::kinematics::term_selection::{identify_with_terms, Verdict, CRITERION};
use robocal_calib::kinematics::term_validate::validate_with_terms;
use robocal_calib::kinematics::{presets, Instrument};
use robocal_calib::sim::tracker_campaign::{simulate_tracker, TrackerSpec};

const POSES: usize = 150;
const VAL_POSES: usize = 200;
const NOISE_MM: f64 = 0.01;
const DEFAULT_SEEDS: u64 = 100;

fn main() {
    let seeds: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_SEEDS);
    let robot = presets::ur10();
    let candidates = CandidateOptions::for_robot(&robot);
    println!("criterion: {CRITERION}");
    for switch in [false, true] {
        let (mut campaigns_with_terms, mut geo_rms, mut with_rms, mut recovered) = (0, 0.0, 0.0, 0);
        for seed in 0..seeds {
            let c = simulate_tracker(
                &robot,
                &TrackerSpec {
                    poses: POSES + VAL_POSES,
                    noise_mm: NOISE_MM,
                    seed: 50_000 + seed,
                    non_geometric: switch,
                    orientation_noise_rad: None,
                },
            );
            let (cal, val) = c.measurements.split_at(POSES);
            let Ok(id) = identify_with_terms(
                &c.start,
                Instrument::Tracker,
                cal,
                IdentifyMode::Weighted.into(),
                &candidates,
            ) else {
                println!("seed {seed}: identification failed");
                continue;
            };
            if !id.terms.terms.is_empty() {
                campaigns_with_terms += 1;
            }
            let all_true_kept =
                c.true_terms
                    .terms
                    .iter()
                    .zip(&c.true_terms.values)
                    .all(|(t, v)| {
                        id.report.iter().any(|l| {
                            l.term == *t
                                && l.verdict == Verdict::Kept
                                && (l.value - v).abs() <= 3.0 * l.std_dev
                        })
                    });
            if all_true_kept {
                recovered += 1;
            }
            geo_rms += validate(&id.geometric.model, val).unwrap().0.norm.rms_mm;
            with_rms += validate_with_terms(&id.model, &id.terms, val)
                .unwrap()
                .0
                .norm
                .rms_mm;
        }
        let n = seeds as f64;
        println!(
            "switch {switch}: {seeds} campaigns of {POSES} poses, noise {NOISE_MM} mm: terms kept in {campaigns_with_terms} ({:.1}%); every true term kept within 3σ in {recovered}; validation rms geometric {:.4} mm, with terms {:.4} mm (floor {:.4})",
            100.0 * campaigns_with_terms as f64 / n,
            geo_rms / n,
            with_rms / n,
            3f64.sqrt() * NOISE_MM
        );
    }
}
