//! Monte-Carlo figures for BENCHMARKS.md "Kinematics": simulated IRB-2400
//! and PUMA-560 campaigns (60 cal + 30 val), every identification method.
//! `cargo run --release -p robocal-calib --example kinematics_bench -- [runs]`

use robocal_calib::sim::campaign::CampaignSpec;
use robocal_calib::sim::experiment::run_experiment;

fn main() {
    let runs: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1);
    let first: u64 = std::env::var("SEED_START")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0);
    let presets: Vec<String> = std::env::var("PRESETS")
        .map(|v| v.split(',').map(str::to_string).collect())
        .unwrap_or_else(|_| vec!["irb2400".into(), "puma560".into()]);
    for preset in presets.iter().map(String::as_str) {
        let mut all = Vec::new();
        for seed in first..first + runs {
            let mut spec = CampaignSpec::standard(preset, seed + 1).expect("preset");
            if let Some(v) = std::env::var("ENCODER_DEG")
                .ok()
                .and_then(|v| v.parse().ok())
            {
                spec.encoder_sigma_deg = v;
            }
            if let Some(v) = std::env::var("COMPLIANCE")
                .ok()
                .and_then(|v| v.parse().ok())
            {
                spec.compliance_rad_per_m = v;
            }
            match run_experiment(&spec) {
                Ok(r) => {
                    all.push(r.clone());
                    println!(
                    "{preset} seed {s}: before {b:.4} oracle {o:.4} two-step plain {tp:.4} weighted {tw:.4} paper {pa:.4} joint {j:.4} | joint/oracle {ratio:.3} improvement {imp:.1}x worst {w:.2} sigma ({wn}) z rms {zr:.2} joint noise est {jn:.2e} deg comp {c:.4} ik {ik:.1e} rms {rms:.3}px cond {cond:.1} O1 {o1:.3e} t_id {ti:.3}s t_joint {tj:.3}s it {it:?} fixed {fixed:?}",
                    it = r.joint_iterations,
                    s = seed + 1,
                    b = r.before.norm.mean_mm,
                    o = r.oracle.norm.mean_mm,
                    tp = r.two_step_plain.norm.mean_mm,
                    tw = r.two_step_weighted.norm.mean_mm,
                    pa = r.paper.norm.mean_mm,
                    j = r.joint.norm.mean_mm,
                    ratio = r.joint.norm.mean_mm / r.oracle.norm.mean_mm,
                    imp = r.before.norm.mean_mm / r.joint.norm.mean_mm,
                    w = r.worst_sigma_ratio.0,
                    wn = r.worst_sigma_ratio.1,
                    jn = r.estimated_joint_sigma_rad.to_degrees(),
                    zr = r.sigma_ratio_rms,
                    c = r.compensated.norm.mean_mm,
                    ik = r.max_ik_residual_mm,
                    rms = r.reprojection_rms_px,
                    cond = r.condition_number,
                    o1 = r.observability_index,
                    ti = r.identify_seconds,
                    tj = r.joint_refine_seconds,
                    fixed = r.fixed,
                )
                }
                Err(e) => println!("{preset} seed {}: error {e}", seed + 1),
            }
        }
        summary(preset, &all);
    }
}

fn summary(preset: &str, all: &[robocal_calib::sim::experiment::ExperimentResult]) {
    if all.is_empty() {
        return;
    }
    let n = all.len() as f64;
    let mean = |f: &dyn Fn(&robocal_calib::sim::experiment::ExperimentResult) -> f64| {
        all.iter().map(f).sum::<f64>() / n
    };
    let oracle = mean(&|r| r.oracle.norm.mean_mm);
    // Standard error of the mean z^2 over campaigns: the 30 z of one
    // campaign are strongly correlated, so 20 campaigns give z rms only to
    // about +-0.05 (400-campaign blocks of 20 spread 0.91-1.14).
    let z2 = mean(&|r| r.sigma_ratio_rms.powi(2));
    let z2_se = (mean(&|r| (r.sigma_ratio_rms.powi(2) - z2).powi(2)) / (n - 1.0).max(1.0)).sqrt();
    let joint = mean(&|r| r.joint.norm.mean_mm);
    println!(
        "SUMMARY {preset} ({} campaigns, mean of per-campaign mean 3-D val error, mm): before {:.4} | oracle {:.4} (known-intrinsics oracle {:.4}) | two-step plain {:.4} ({:.2}x oracle) | two-step weighted {:.4} ({:.2}x) | paper mode {:.4} ({:.2}x) | joint {:.4} ({:.2}x oracle) | improvement {:.1}x | compensated {:.4} | joint val max {:.4} | campaigns with all params within 3 sigma {}/{} (z rms {:.3}, mean z^2 {:.3} +- {:.3}, joint noise est {:.3e} deg) | identify {:.3} s, joint refine {:.3} s",
        all.len(),
        mean(&|r| r.before.norm.mean_mm),
        oracle,
        mean(&|r| r.oracle_known_intrinsics.norm.mean_mm),
        mean(&|r| r.two_step_plain.norm.mean_mm),
        mean(&|r| r.two_step_plain.norm.mean_mm) / oracle,
        mean(&|r| r.two_step_weighted.norm.mean_mm),
        mean(&|r| r.two_step_weighted.norm.mean_mm) / oracle,
        mean(&|r| r.paper.norm.mean_mm),
        mean(&|r| r.paper.norm.mean_mm) / oracle,
        joint,
        joint / oracle,
        mean(&|r| r.before.norm.mean_mm) / joint,
        mean(&|r| r.compensated.norm.mean_mm),
        mean(&|r| r.joint.norm.max_mm),
        all.iter().filter(|r| r.worst_sigma_ratio.0 <= 3.0).count(),
        all.len(),
        (mean(&|r| r.sigma_ratio_rms.powi(2))).sqrt(),
        z2,
        z2_se,
        mean(&|r| r.estimated_joint_sigma_rad.to_degrees()),
        mean(&|r| r.identify_seconds),
        mean(&|r| r.joint_refine_seconds),
    );
}
