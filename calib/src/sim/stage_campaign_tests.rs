//! The stage test on the simulator (issue 18): the paper's campaign
//! (5x5 positions 20 mm apart, three sequences at 700-1000 mm, view angles
//! above 30 deg), rendered and detected, calibrated with the stage's
//! translations in the bundle, each image's camera position compared with
//! the truth.

use nalgebra::Vector3;

use super::*;
use crate::camera::calibrate::CalibrationOptions;
use crate::stage::assessment::AxisTable;
use crate::stage::{calibrate_stage, StageCalibration, StageError};

/// The issue's bounds: true 3-D position error per sequence (mean) and
/// travelled-distance error (mean), mm; the paper's method must find the
/// true per-axis statistics within this factor.
const MAX_MEAN_POSITION_ERROR_MM: f64 = 0.06;
const MAX_MEAN_TRAVEL_ERROR_MM: f64 = 0.03;
const TABLE_FACTOR: f64 = 2.0;
/// The common offset must lie within this many of its predicted σ per axis.
const MAX_OFFSET_Z: f64 = 3.0;
/// Dot noise of the point campaign (px per axis).
const DETECTOR_SIGMA_PX: f64 = 0.01;

fn options(spec: &StageSpec) -> CalibrationOptions {
    CalibrationOptions {
        dot_diameter_mm: Some(spec.target.dot_diameter_mm),
        ..CalibrationOptions::default()
    }
}

/// Per sequence: the true errors of every image's measured camera position
/// in the target frame (`X_i`, the frame of the paper's Table 1;
/// `target_to_camera` is the camera's pose in the target frame).
fn true_errors(
    campaign: &StageCampaign,
    fit: &StageCalibration,
    sequence: u32,
) -> Vec<Vector3<f64>> {
    campaign
        .poses
        .iter()
        .zip(&fit.views)
        .filter(|(p, _)| p.sequence == sequence)
        .map(|(p, v)| {
            v.pose.target_to_camera.translation.vector - p.target_to_camera.translation.vector
        })
        .collect()
}

fn mean_norm(errors: &[Vector3<f64>]) -> f64 {
    errors.iter().map(|e| e.norm()).sum::<f64>() / errors.len().max(1) as f64
}

/// Prints every figure, then checks the issue's bounds.
fn check_campaign(campaign: &StageCampaign, fit: &StageCalibration) {
    let (truth, start) = (campaign.spec.intrinsics, fit.start.intrinsics);
    println!(
        "fx {:.3} fy {:.3} (true {:.3} {:.3}; free start {:.3} {:.3}), sd fx {:.4?}, rms {:.4} px",
        fit.intrinsics.fx,
        fit.intrinsics.fy,
        truth.fx,
        truth.fy,
        start.fx,
        start.fy,
        fit.std_dev.map(|s| s.fx),
        fit.rms_px
    );
    assert_eq!(fit.accuracy.len(), campaign.spec.sequences.len());
    let mut failures = Vec::new();
    for acc in &fit.accuracy {
        let errors = true_errors(campaign, fit, acc.sequence);
        let true_table = AxisTable::from_errors(&errors);
        let true_3d = mean_norm(&errors);
        let n = errors.len() as f64;
        let offset = errors.iter().sum::<Vector3<f64>>() / n;
        println!(
            "sequence {} at {:.0} mm: true 3-D mean {:.4} (common offset {:.4?}) per axis mean {:.4?} median {:.4?} std {:.4?}",
            acc.sequence, acc.distance_mm, true_3d, offset, true_table.mean_mm, true_table.median_mm, true_table.std_mm
        );
        println!(
            "  paper's method: mean {:.4?} median {:.4?} std {:.4?} max 3-D {:.4}; travel mean {:.4} max {:.4}",
            acc.mean_mm, acc.median_mm, acc.std_mm, acc.max_3d_mm,
            acc.travelled_distance_error_mm.mean_mm, acc.travelled_distance_error_mm.max_mm
        );
        if true_3d > MAX_MEAN_POSITION_ERROR_MM {
            failures.push(format!(
                "sequence {}: true 3-D mean {true_3d}",
                acc.sequence
            ));
        }
        if acc.travelled_distance_error_mm.mean_mm > MAX_MEAN_TRAVEL_ERROR_MM {
            failures.push(format!(
                "sequence {}: travel {:?}",
                acc.sequence, acc.travelled_distance_error_mm
            ));
        }
        // Table 1's figures as 3-D vectors (root sum of squares over the
        // axes): the depth-heavy axis alone is underestimated (see below).
        let rss = |v: [f64; 3]| Vector3::from(v).norm();
        let stats = [
            ("mean", acc.mean_mm, true_table.mean_mm),
            ("median", acc.median_mm, true_table.median_mm),
            ("std", acc.std_mm, true_table.std_mm),
        ];
        for (what, paper, truth) in stats {
            let ratio = rss(paper) / rss(truth);
            println!("  {what}: paper's method / true = {ratio:.2}");
            if !(1.0 / TABLE_FACTOR..=TABLE_FACTOR).contains(&ratio) {
                failures.push(format!(
                    "sequence {} {what}: paper's method {:.4?} vs true {:.4?}",
                    acc.sequence, paper, truth
                ));
            }
        }
        // The offset against its stated σ (`crate::stage::offset`).
        let z: Vec<f64> = (0..3).map(|k| offset[k] / acc.offset_sd_mm[k]).collect();
        println!(
            "  common offset {:.4?} / predicted σ {:.4?} = {z:.2?}",
            offset, acc.offset_sd_mm
        );
        if z.iter().any(|z| z.abs() > MAX_OFFSET_Z) {
            failures.push(format!(
                "sequence {}: offset {offset:.4?} vs σ {:.4?}",
                acc.sequence, acc.offset_sd_mm
            ));
        }
        // The whole per-axis error the service states (the stage-referenced
        // scatter and the offset's σ) against the true per-axis RMS.
        let rms = |t: &AxisTable, k: usize| t.mean_mm[k].hypot(t.std_mm[k]);
        let stated: Vec<f64> = (0..3)
            .map(|k| rms(&acc.stage_referenced, k).hypot(acc.offset_sd_mm[k]) / rms(&true_table, k))
            .collect();
        println!("  stated per-axis RMS / true RMS {stated:.2?}");
        if stated
            .iter()
            .any(|r| !(1.0 / TABLE_FACTOR..=TABLE_FACTOR).contains(r))
        {
            failures.push(format!(
                "sequence {}: stated / true RMS {stated:.2?}",
                acc.sequence
            ));
        }
        // The stage-referenced table per axis against the true scatter (the
        // true errors less their common offset, which no method without
        // the board's pose on the stage can see).
        let scatter: Vec<Vector3<f64>> = errors.iter().map(|e| e - offset).collect();
        let true_scatter = AxisTable::from_errors(&scatter);
        let staged = acc.stage_referenced;
        println!(
            "  stage-referenced: mean {:.4?} median {:.4?} std {:.4?}; true scatter mean {:.4?} median {:.4?} std {:.4?}",
            staged.mean_mm, staged.median_mm, staged.std_mm,
            true_scatter.mean_mm, true_scatter.median_mm, true_scatter.std_mm
        );
        let per_axis = [
            ("mean", staged.mean_mm, true_scatter.mean_mm, acc.mean_mm),
            (
                "median",
                staged.median_mm,
                true_scatter.median_mm,
                acc.median_mm,
            ),
            ("std", staged.std_mm, true_scatter.std_mm, acc.std_mm),
        ];
        for (what, staged, truth, paper) in per_axis {
            let ratios: Vec<f64> = (0..3).map(|k| staged[k] / truth[k]).collect();
            let paper_ratios: Vec<f64> = (0..3).map(|k| paper[k] / truth[k]).collect();
            println!(
                "  {what} per axis / true scatter: stage-referenced {ratios:.2?}, paper's {paper_ratios:.2?}"
            );
            if ratios
                .iter()
                .any(|r| !(1.0 / TABLE_FACTOR..=TABLE_FACTOR).contains(r))
            {
                failures.push(format!(
                    "sequence {} {what}: stage-referenced {staged:.4?} vs true scatter {truth:.4?}",
                    acc.sequence
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Rendered and detected images: the issue's claim.
#[test]
fn rendered_stage_campaign_measures_within_the_issue_bounds() {
    let campaign = simulate_stage(&StageSpec::paper(18)).unwrap();
    let render = crate::sim::render::RenderOptions::default();
    let views: Vec<_> = (0..campaign.poses.len())
        .map(|i| campaign.rendered_view(i, &render).unwrap())
        .collect();
    let fit = calibrate_stage(&views, &options(&campaign.spec)).unwrap();
    check_campaign(&campaign, &fit);
}

/// Dot centres with Gaussian noise only (no detector bias): the same bounds
/// at the detector's precision on these rendered images (rms 0.009 px per
/// dot in the rendered test, so 0.01 px per axis).
#[test]
fn point_stage_campaign_measures_within_the_issue_bounds() {
    let campaign = simulate_stage(&StageSpec::paper(7)).unwrap();
    let mut campaign = campaign;
    campaign.spec.pixel_sigma_px = DETECTOR_SIGMA_PX;
    let views = campaign.point_views().unwrap();
    let fit = calibrate_stage(&views, &CalibrationOptions::default()).unwrap();
    check_campaign(&campaign, &fit);
}

#[test]
fn bad_stage_layouts_are_refused_naming_the_field() {
    let campaign = simulate_stage(&StageSpec::paper(3)).unwrap();
    let mut views = campaign.point_views().unwrap();
    views.truncate(28); // sequence 2 keeps 3 positions
    let err = calibrate_stage(&views, &CalibrationOptions::default()).unwrap_err();
    assert!(
        matches!(
            err,
            StageError::TooFewPositions {
                sequence: 2,
                count: 3,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(err.field(), "sequence");
    let mut views = campaign.point_views().unwrap();
    for v in views.iter_mut().filter(|v| v.sequence == 1) {
        v.stage_position_mm.y = 0.5 * v.stage_position_mm.x;
    }
    let err = calibrate_stage(&views, &CalibrationOptions::default()).unwrap_err();
    assert_eq!(err, StageError::CollinearPositions { sequence: 1 });
    assert_eq!(err.field(), "stage_position_mm");
    views[0].stage_position_mm.x = f64::NAN;
    let err = calibrate_stage(&views, &CalibrationOptions::default()).unwrap_err();
    assert_eq!(err, StageError::NonFinitePosition { view: 0 });
}
