//! Compensation throughput for BENCHMARKS.md: `nearest_within_limits` from
//! ONE seed on a simulated (perturbed) robot of each preset, for targets
//! near the seed (the seed's own run answers) and for targets spread over
//! every joint's range (the branch seeds run whenever the seed's branch
//! leaves the limits). Prints targets per second and how often each start
//! answered, and the mean Levenberg–Marquardt iterations per answered
//! target (Jacobian evaluations over all its runs).
//! Then the same targets through `filter_target` (two IK per target).
//! `cargo run --release -p robocal-calib --example ik_bench -- [targets]`

use std::time::Instant;

use rand::{rngs::StdRng, Rng, SeedableRng};
use robocal_calib::geometry::pose_from_xyz_rpy_deg;
use robocal_calib::kinematics::filter::filter_target;
use robocal_calib::kinematics::ik::{nearest_within_limits, IkStart};
use robocal_calib::kinematics::CalibratedModel;
use robocal_calib::sim::campaign::{perturb_robot, CampaignSpec};

/// CPU time of this thread (s), from Linux's `/proc/thread-self/schedstat`
/// (nanoseconds on a core): the rate per core on a loaded machine, where
/// the wall clock also counts other processes' turns. `None` elsewhere.
fn thread_cpu_s() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// Targets per CPU second between two [`thread_cpu_s`] readings.
fn cpu_rate(targets: usize, from: Option<f64>) -> String {
    match (from, thread_cpu_s()) {
        (Some(a), Some(b)) if b > a => format!("{:.0} targets per CPU s", targets as f64 / (b - a)),
        _ => "CPU time unavailable".into(),
    }
}

/// Joint spread (rad) of the "near the seed" targets.
const NEAR_SPREAD_RAD: f64 = 0.3;

fn main() {
    let targets: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20_000);
    for preset in ["irb2400", "puma560"] {
        let spec = CampaignSpec::standard(preset, 1).expect("preset");
        let mut rng = StdRng::seed_from_u64(1);
        let model = CalibratedModel {
            robot: perturb_robot(&spec.nominal, &spec, &mut rng),
            world_to_base: pose_from_xyz_rpy_deg([800.0, -300.0, 40.0], [2.0, -3.0, 170.0])
                .expect("pose"),
            flange_to_tool: spec.flange_to_camera_guess,
        };
        let seed = spec.home_joints_rad.clone();
        for (label, spread) in [("near the seed", Some(NEAR_SPREAD_RAD)), ("spread", None)] {
            let poses: Vec<_> = (0..targets)
                .map(|_| {
                    let q: Vec<f64> = model
                        .robot
                        .joints
                        .iter()
                        .zip(&seed)
                        .map(|(j, s)| match spread {
                            Some(d) => (s + rng.random_range(-d..=d)).clamp(j.min_rad, j.max_rad),
                            None => rng.random_range(j.min_rad..=j.max_rad),
                        })
                        .collect();
                    model.world_to_tool(&q).expect("in-limit joints")
                })
                .collect();
            let (mut seeded, mut branch, mut failed, mut iterations) = (0, 0, 0, 0);
            let cpu = thread_cpu_s();
            let start = Instant::now();
            for target in &poses {
                match nearest_within_limits(&model, target, &seed) {
                    Ok(s) => {
                        iterations += s.iterations;
                        if s.start == IkStart::Seed {
                            seeded += 1;
                        } else {
                            branch += 1;
                        }
                    }
                    Err(_) => failed += 1,
                }
            }
            let seconds = start.elapsed().as_secs_f64();
            println!(
                "{preset} {label}: {targets} targets in {seconds:.3} s = {rate:.0} targets/s ({}); \
                 answered by the seed {seeded}, by a branch seed {branch}, failed {failed}; \
                 {mean:.1} iterations per answered target",
                cpu_rate(targets, cpu),
                rate = targets as f64 / seconds,
                mean = iterations as f64 / (seeded + branch).max(1) as f64
            );
            // Filter: the calibrated IK, the nominal FK and the replayed
            // controller IK per target.
            let (mut filtered, mut unfiltered) = (0, 0);
            let cpu = thread_cpu_s();
            let start = Instant::now();
            for target in &poses {
                match filter_target(&model, &spec.nominal, target, &seed) {
                    Ok(_) => filtered += 1,
                    Err(_) => unfiltered += 1,
                }
            }
            let seconds = start.elapsed().as_secs_f64();
            println!(
                "{preset} {label} filter: {targets} targets in {seconds:.3} s = {rate:.0} targets/s ({}); \
                 filtered {filtered}, failed {unfiltered}",
                cpu_rate(targets, cpu),
                rate = targets as f64 / seconds
            );
        }
    }
}
