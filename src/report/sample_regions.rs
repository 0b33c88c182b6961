//! The sample report as a multi-session set's (issue 18): three regions
//! in two volumes, local sets in two of them, with round figures the
//! rendering tests check cell by cell (`cargo run --example
//! render_report -- --regions` draws it). Not calibration output.

use super::model::{AccuracySummary, ErrorStats, Report};
use super::regions::{LocalModel, RegionReport};
use super::sample::sample_report;

/// Validation poses of each sample region.
pub const REGION_POSES: usize = 10;

/// 3-D statistics with the given mean and max (mm) over [`REGION_POSES`].
pub fn region_stats(mean_mm: f64, max_mm: f64) -> AccuracySummary {
    AccuracySummary {
        norm: ErrorStats {
            n: REGION_POSES,
            mean_mm,
            median_mm: mean_mm,
            std_mm: (max_mm - mean_mm) / 2.0,
            max_mm,
            rms_mm: mean_mm,
        },
        ..Default::default()
    }
}

/// (session, region, volume, before mean/max, after mean/max, local (version, mean, max)).
type SampleRegion = (
    &'static str,
    &'static str,
    &'static str,
    [f64; 2],
    [f64; 2],
    Option<(i64, [f64; 2])>,
);

/// The three sample regions: "front" and "left" in volume "upper", with
/// local sets; "right" in "lower", without.
pub const SAMPLE_REGIONS: [SampleRegion; 3] = [
    (
        "s-front",
        "front",
        "upper",
        [2.1, 4.2],
        [0.061, 0.14],
        Some((3, [0.052, 0.12])),
    ),
    (
        "s-left",
        "left",
        "upper",
        [1.6, 3.3],
        [0.048, 0.11],
        Some((4, [0.047, 0.1])),
    ),
    ("s-right", "right", "lower", [3.4, 6.8], [0.075, 0.19], None),
];

/// The sample camera report with [`SAMPLE_REGIONS`] as its `regions`.
pub fn sample_regions_report() -> Report {
    let mut report = sample_report();
    report.regions = SAMPLE_REGIONS
        .iter()
        .map(
            |(session, region, volume, before, after, local)| RegionReport {
                session_id: session.to_string(),
                region: Some(region.to_string()),
                volume: Some(volume.to_string()),
                before: region_stats(before[0], before[1]),
                after: region_stats(after[0], after[1]),
                local: local.map(|(version, [mean, max])| LocalModel {
                    version,
                    after: region_stats(mean, max),
                }),
            },
        )
        .collect();
    report
}
