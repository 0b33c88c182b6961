use nalgebra::Point2;

use super::*;
use crate::camera::calibrate::CalibrationMode;
use crate::sim::point_views::{simulate_views, ViewCampaignSpec};

fn campaign(seed: u64, views: usize) -> (ViewCampaignSpec, Vec<ViewObservations>) {
    let spec = ViewCampaignSpec {
        views,
        ..ViewCampaignSpec::modern_1280x1024(seed)
    };
    let sims = simulate_views(&spec).unwrap();
    (spec, sims.iter().map(|s| s.observations.clone()).collect())
}

fn options(spec: &ViewCampaignSpec) -> CalibrationOptions {
    CalibrationOptions {
        mode: CalibrationMode::Refined,
        dot_diameter_mm: Some(spec.board.dot_diameter_mm),
        ..Default::default()
    }
}

/// A view whose dots all land on one pixel: no pose can start from it.
fn collapse(view: &mut ViewObservations) {
    for d in &mut view.dots {
        d.pixel = Point2::new(640.0, 512.0);
    }
}

#[test]
fn a_degenerate_view_is_left_out_and_named() {
    let (spec, mut views) = campaign(5, 12);
    collapse(&mut views[4]);
    let out = calibrate_leaving_out(&views, &options(&spec)).unwrap();
    assert_eq!(out.left_out.len(), 1, "{:?}", out.left_out);
    assert_eq!(out.left_out[0].view, 4);
    assert!(!out.left_out[0].reason.is_empty());
    assert_eq!(out.kept, vec![0, 1, 2, 3, 5, 6, 7, 8, 9, 10, 11]);
    assert_eq!(out.calibration.views.len(), 11);
    // The rest calibrates as well as without the bad view.
    let fx_rel = out.calibration.intrinsics.fx / spec.intrinsics.fx - 1.0;
    assert!(fx_rel.abs() < 5e-4, "fx off by {fx_rel:e}");
}
