//! Is the sequence offset's σ honest? Over campaigns of varied layout
//! ([`StageSpec::varied`]), the true common offset of each sequence (the
//! mean of its images' true position errors) against the stated σ
//! (`SequenceAccuracy::offset_sd_mm`, calib `stage::offset`), per axis:
//! the RMS of `offset / σ` must be near 1 (issue 18; session 11).

use nalgebra::Vector3;

use super::*;
use crate::camera::calibrate::CalibrationOptions;
use crate::stage::calibrate_stage;

/// `RMS(offset / σ)` must lie within these bounds (the brief's 0.7-1.4).
const MIN_RATIO: f64 = 0.7;
const MAX_RATIO: f64 = 1.4;
/// Layouts of the point-campaign check (9 offsets each per grid).
const POINT_LAYOUTS: u64 = 16;
/// Layouts of the rendered check (each 27 or 75 rendered images).
const RENDERED_LAYOUTS: u64 = 8;
/// The detector's precision on the rendered images (px per axis), split
/// as the rendered campaign splits it: about a sixth of the variance is
/// shared by a sequence's images (`crate::stage::noise`).
const INDEPENDENT_SIGMA_PX: f64 = 0.006;
const SHARED_SIGMA_PX: f64 = 0.003;

/// The images of a campaign, rendered and detected or as noisy points.
enum Images {
    Points { independent_px: f64, shared_px: f64 },
    Rendered,
}

/// `offset / σ` per sequence and axis of one campaign.
fn offset_z(spec: StageSpec, images: &Images) -> Vec<f64> {
    let mut spec = spec;
    let (views, options) = match images {
        Images::Points {
            independent_px,
            shared_px,
        } => {
            spec.pixel_sigma_px = *independent_px;
            spec.shared_pixel_sigma_px = *shared_px;
            let campaign = simulate_stage(&spec).unwrap();
            (
                campaign.point_views().unwrap(),
                CalibrationOptions::default(),
            )
        }
        Images::Rendered => {
            let campaign = simulate_stage(&spec).unwrap();
            let render = crate::sim::render::RenderOptions::default();
            let views = (0..campaign.poses.len())
                .map(|i| campaign.rendered_view(i, &render).unwrap())
                .collect();
            let options = CalibrationOptions {
                dot_diameter_mm: Some(spec.target.dot_diameter_mm),
                ..CalibrationOptions::default()
            };
            (views, options)
        }
    };
    let campaign = simulate_stage(&spec).unwrap();
    let fit = calibrate_stage(&views, &options).unwrap();
    let mut z = Vec::new();
    for acc in &fit.accuracy {
        let errors: Vec<Vector3<f64>> = campaign
            .poses
            .iter()
            .zip(&fit.views)
            .filter(|(p, _)| p.sequence == acc.sequence)
            .map(|(p, v)| {
                v.pose.target_to_camera.translation.vector - p.target_to_camera.translation.vector
            })
            .collect();
        let offset = errors.iter().sum::<Vector3<f64>>() / errors.len() as f64;
        z.extend((0..3).map(|k| offset[k] / acc.offset_sd_mm[k]));
    }
    z
}

/// `RMS(offset / σ)` over `layouts` campaigns of `side` x `side` positions.
fn offset_ratio(side: usize, layouts: u64, images: &Images) -> f64 {
    let z: Vec<f64> = (1..=layouts)
        .flat_map(|seed| {
            let spec = StageSpec {
                grid_side: side,
                ..StageSpec::varied(seed)
            };
            offset_z(spec, images)
        })
        .collect();
    (z.iter().map(|z| z * z).sum::<f64>() / z.len() as f64).sqrt()
}

fn check(ratios: &[(&str, f64)]) {
    for (case, ratio) in ratios {
        println!("{case}: RMS(true offset / stated σ) = {ratio:.2}");
    }
    let off: Vec<_> = ratios
        .iter()
        .filter(|(_, r)| !(MIN_RATIO..=MAX_RATIO).contains(r))
        .collect();
    assert!(off.is_empty(), "{off:?}");
}

/// Point campaigns: independent dot noise, and the rendered images' mix
/// of independent and shared noise, on 9- and 25-image sequences.
#[test]
fn the_offset_sigma_is_honest_on_point_campaigns() {
    let white = Images::Points {
        independent_px: INDEPENDENT_SIGMA_PX,
        shared_px: 0.0,
    };
    let shared = Images::Points {
        independent_px: INDEPENDENT_SIGMA_PX,
        shared_px: SHARED_SIGMA_PX,
    };
    check(&[
        ("3x3, independent", offset_ratio(3, POINT_LAYOUTS, &white)),
        ("5x5, independent", offset_ratio(5, POINT_LAYOUTS, &white)),
        ("3x3, shared", offset_ratio(3, POINT_LAYOUTS, &shared)),
        ("5x5, shared", offset_ratio(5, POINT_LAYOUTS, &shared)),
    ]);
}

/// Rendered and detected images (about 4 min): the detector's own errors.
#[test]
#[ignore = "renders 816 images (~4 min): cargo test -p robocal-calib --lib offset_sigma_is_honest_on_rendered -- --ignored --nocapture"]
fn the_offset_sigma_is_honest_on_rendered_campaigns() {
    check(&[
        (
            "3x3, rendered",
            offset_ratio(3, RENDERED_LAYOUTS, &Images::Rendered),
        ),
        (
            "5x5, rendered",
            offset_ratio(5, RENDERED_LAYOUTS, &Images::Rendered),
        ),
    ]);
}
