//! The service's fit against the Cramér–Rao bound (method.md §6.9) on every
//! simulated campaign kind (`sim::campaign_kinds`): per campaign, the
//! default job's identification (`sim::default_job`: the calib functions
//! the pipeline calls, with its default options, on simulated dot centres)
//! and the bound of the same calibration images; the validation error of
//! both at the validation poses against the true camera, and their ratio.
//! Ratios are pooled over the campaigns of a kind: RMS as
//! `sqrt(Σ job² / Σ bound²)`, mean as `Σ job / Σ bound`.
//!
//! `cargo run -p robocal-calib --release --example crb_ratio -- [campaigns per kind] [--kinds k1,k2] [--sigma-px s] [--first-seed n]`
//!
//! Kinds: irb_1.3mp, puma_paper, irb_hard, kr16_5mp, puma_compliance
//! (also run with the job's `non_geometric` option), grouped_6x4,
//! grouped_6x4_small.

use std::time::Instant;

use robocal_calib::bound::campaign_bound;
use robocal_calib::sim::campaign_kinds::{simulate_kind, CampaignKind};
use robocal_calib::sim::default_job::default_job_fit;

const DEFAULT_CAMPAIGNS: u64 = 3;
/// First seed of the grouped campaigns: the ladder's tests use 21 and 22.
const GROUPED_FIRST_SEED: u64 = 21;

#[derive(Default)]
struct Pooled {
    campaigns: usize,
    job_ms: f64,
    job_mean: f64,
    job_par_ms: f64,
    bound_ms: f64,
    bound_mean: f64,
    bound_par_ms: f64,
    bound_enc_ms: f64,
    rungs: Vec<String>,
}

impl Pooled {
    fn row(&self, name: &str, option: &str) -> String {
        let n = self.campaigns.max(1) as f64;
        format!(
            "| {name}{option} | {} | {:.4} | {:.4} ({:.4}, {:.4}) | **{:.2}x** | {:.4} / {:.4} = {:.2}x | {:.2}x | {} |",
            self.campaigns,
            (self.job_ms / n).sqrt(),
            (self.bound_ms / n).sqrt(),
            (self.bound_par_ms / n).sqrt(),
            (self.bound_enc_ms / n).sqrt(),
            (self.job_ms / self.bound_ms).sqrt(),
            self.job_mean / n,
            self.bound_mean / n,
            self.job_mean / self.bound_mean,
            (self.job_par_ms / self.bound_par_ms).sqrt(),
            self.rungs.join(" "),
        )
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let campaigns: u64 = args
        .first()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_CAMPAIGNS);
    let kinds: Vec<CampaignKind> = match value("--kinds") {
        Some(list) => list
            .split(',')
            .map(|k| CampaignKind::parse(k).unwrap_or_else(|| panic!("unknown kind {k}")))
            .collect(),
        None => CampaignKind::ALL.to_vec(),
    };
    let sigma_px: Option<f64> = value("--sigma-px").and_then(|s| s.parse().ok());
    let first_seed: Option<u64> = value("--first-seed").and_then(|s| s.parse().ok());
    let mut rows = Vec::new();
    for kind in kinds {
        let options: &[bool] = if kind == CampaignKind::PumaCompliance {
            &[false, true]
        } else {
            &[false]
        };
        let first = first_seed.unwrap_or(if kind.grouping().is_some() {
            GROUPED_FIRST_SEED
        } else {
            1
        });
        let mut pooled = [Pooled::default(), Pooled::default()];
        for seed in first..first + campaigns {
            let t0 = Instant::now();
            let Ok(k) = simulate_kind(kind, seed, |s| {
                if let Some(px) = sigma_px {
                    s.pixel_sigma_px = px;
                }
            }) else {
                eprintln!(
                    "{} seed {seed}: campaign could not be simulated",
                    kind.as_str()
                );
                continue;
            };
            let bound = match campaign_bound(&k.spec, &k.campaign, &k.cal, false) {
                Ok(b) => b,
                Err(e) => {
                    eprintln!("{} seed {seed}: bound failed: {e}", kind.as_str());
                    continue;
                }
            };
            let bound_s = t0.elapsed().as_secs_f64();
            for (o, &non_geometric) in options.iter().enumerate() {
                let t1 = Instant::now();
                let fit = match default_job_fit(&k.spec, &k.cal, non_geometric) {
                    Ok(f) => f,
                    Err(e) => {
                        eprintln!("{} seed {seed}: job failed: {e}", kind.as_str());
                        continue;
                    }
                };
                let Ok(v) = fit.validation(&k.spec, &k.campaign) else {
                    eprintln!("{} seed {seed}: validation failed", kind.as_str());
                    continue;
                };
                let b = &bound.validation;
                let rung = fit.rung.map_or("-".to_string(), |r| r.as_str().to_string());
                let terms: Vec<String> = fit.terms.terms.iter().map(|t| t.name()).collect();
                eprintln!(
                    "{} seed {seed}{}: job {:.5} mm RMS ({:.5} mean, parameters {:.5}); bound {:.5} RMS ({:.5} mean; parameters {:.5}, encoder {:.5}; {} unknowns, {} undetermined); ratio {:.3}; rung {rung}, terms {terms:?}; bound {bound_s:.1} s, job {:.1} s",
                    kind.as_str(),
                    if non_geometric { " +terms" } else { "" },
                    v.rms_mm,
                    v.mean_mm,
                    v.parameters_rms_mm,
                    b.rms_mm,
                    b.mean_mm,
                    b.parameters_rms_mm,
                    b.encoder_rms_mm,
                    bound.covariance.nrows(),
                    bound.undetermined,
                    v.rms_mm / b.rms_mm,
                    t1.elapsed().as_secs_f64(),
                );
                let p = &mut pooled[o];
                p.campaigns += 1;
                p.job_ms += v.rms_mm.powi(2);
                p.job_mean += v.mean_mm;
                p.job_par_ms += v.parameters_rms_mm.powi(2);
                p.bound_ms += b.rms_mm.powi(2);
                p.bound_mean += b.mean_mm;
                p.bound_par_ms += b.parameters_rms_mm.powi(2);
                p.bound_enc_ms += b.encoder_rms_mm.powi(2);
                p.rungs.push(rung);
            }
        }
        for (o, &non_geometric) in options.iter().enumerate() {
            let option = if non_geometric {
                " (`non_geometric`)"
            } else {
                ""
            };
            rows.push(pooled[o].row(kind.as_str(), option));
        }
    }
    println!("| kind | campaigns | job RMS mm | bound RMS mm (parameters, encoder) | ratio | mean: job / bound | parameters' ratio | rungs |");
    println!("|---|---|---|---|---|---|---|---|");
    for r in rows {
        println!("{r}");
    }
}
