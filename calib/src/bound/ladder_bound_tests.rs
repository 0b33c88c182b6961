//! The default job (its model ladder) on campaigns shot in configuration
//! groups, 6 of 4 poses, with the simulator's usual link errors and with
//! errors ten times smaller: its validation error at the unseen
//! configurations stays within [`MAX_RATIO`] of the campaign's Cramér–Rao
//! bound. One campaign's error scatters widely around its bound (0.3–2.4x
//! on eight well-spread campaigns), so the ratio is pooled over
//! [`SEEDS`] campaigns per case, `sqrt(Σ job² / Σ bound²)`.

use super::campaign_bound;
use crate::sim::campaign_kinds::{simulate_kind, CampaignKind};
use crate::sim::default_job::default_job_fit;

/// The largest ratio allowed (the ladder's target on such campaigns).
const MAX_RATIO: f64 = 1.5;
/// Campaigns pooled per case (the ladder's tests use seeds 21 and 22).
const SEEDS: std::ops::RangeInclusive<u64> = 21..=24;

#[test]
fn the_ladder_job_is_within_its_ratio_of_the_bound_on_grouped_campaigns() {
    for kind in [CampaignKind::Grouped, CampaignKind::GroupedSmallErrors] {
        let (mut job, mut bound) = (0.0, 0.0);
        for seed in SEEDS {
            let k = simulate_kind(kind, seed, |_| {}).unwrap();
            let b = campaign_bound(&k.spec, &k.campaign, &k.cal, false).unwrap();
            let fit = default_job_fit(&k.spec, &k.cal, false).unwrap();
            let v = fit.validation(&k.spec, &k.campaign).unwrap();
            eprintln!(
                "{} seed {seed}: job {:.5} mm RMS ({:?}), bound {:.5}",
                kind.as_str(),
                v.rms_mm,
                fit.rung,
                b.validation.rms_mm
            );
            job += v.rms_mm.powi(2);
            bound += b.validation.rms_mm.powi(2);
        }
        let ratio = (job / bound).sqrt();
        eprintln!("{}: pooled ratio {ratio:.3}", kind.as_str());
        assert!(
            ratio <= MAX_RATIO,
            "{}: {ratio:.3}x the bound",
            kind.as_str()
        );
    }
}
