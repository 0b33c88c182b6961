//! The sample report as a stage set's (issue 18): three sequences at 700,
//! 850 and 1000 mm with round figures the rendering tests check (`cargo run
//! --example render_report -- --stage` draws it). Not calibration output.

use super::measurement_accuracy::{
    AxisStatsReport, MeasurementAccuracyReport, SequenceAccuracyReport, TravelErrorReport,
};
use super::model::Report;
use super::sample::sample_report;

/// Images of each sample sequence (the paper's 5x5 stage grid).
pub const SEQUENCE_IMAGES: usize = 25;

/// A sequence whose per-axis mean error is `mean` (mm) on every axis.
pub fn sample_sequence(sequence: u32, distance_mm: f64, mean: f64) -> SequenceAccuracyReport {
    SequenceAccuracyReport {
        sequence,
        distance_mm,
        images: SEQUENCE_IMAGES,
        mean_mm: [mean; 3],
        median_mm: [mean; 3],
        std_mm: [mean / 2.0; 3],
        max_mm: [2.0 * mean; 3],
        max_3d_mm: 4.0 * mean,
        travelled_distance_error_mm: TravelErrorReport { mean, max: mean },
        stage_referenced_mm: Some(AxisStatsReport {
            mean: [mean; 3],
            median: [mean; 3],
            std: [mean / 2.0; 3],
            max: [2.0 * mean; 3],
        }),
        offset_sd_mm: Some([mean / 2.0; 3]),
    }
}

/// The sample camera report with three stage sequences.
pub fn sample_stage_report() -> Report {
    let mut report = sample_report();
    report.measurement_accuracy = Some(MeasurementAccuracyReport {
        sequences: vec![
            sample_sequence(1, 700.0, 0.01),
            sample_sequence(2, 850.0, 0.02),
            sample_sequence(3, 1000.0, 0.03),
        ],
    });
    report
}
