//! Target tests of issue 4 on simulated campaigns (no rendering: measured
//! centres are the area centroids of the projected dots plus noise).

use super::*;
use crate::camera::refine::StationDistance;
use crate::sim::point_views::{simulate_views, SimulatedView, ViewCampaignSpec};

/// Issue 4 targets: fx, fy within 0.01%, cx, cy within 0.1 px, per-axis
/// reprojection RMS within 10% of the detector noise, camera positions
/// within 1:15000 of the distance (RMS over the views), bias-corrected
/// centres within 0.01 px of the true centre images. On the default
/// campaigns (board spanning half the field of view, stratified views) the
/// centre's standard deviation is ~0.008 px (1280x1024) and ~0.02 px
/// (752x582), so every target holds with margin on every seed
/// (BENCHMARKS.md "Camera": 30 campaigns per camera).
const FOCAL_REL_TOL: f64 = 1e-4;
const CENTRE_TOL_PX: f64 = 0.1;
const RMS_REL_TOL: f64 = 0.10;
const CORRECTED_CENTRE_TOL_PX: f64 = 0.01;
const POSITION_RATIO: f64 = 15000.0;
/// The reported centre standard deviation must be consistent with the
/// actual error (the covariance is honest): within this many sigma.
const CENTRE_SIGMAS: f64 = 4.0;

fn views_of(sims: &[SimulatedView]) -> Vec<ViewObservations> {
    sims.iter().map(|s| s.observations.clone()).collect()
}

fn options(spec: &ViewCampaignSpec, mode: CalibrationMode) -> CalibrationOptions {
    CalibrationOptions {
        mode,
        dot_diameter_mm: Some(spec.board.dot_diameter_mm),
        ..Default::default()
    }
}

struct Errors {
    fx_rel: f64,
    fy_rel: f64,
    cx_px: f64,
    cy_px: f64,
    /// Per-axis reprojection RMS over the injected noise sigma.
    rms_over_noise: f64,
    /// RMS camera-position error over the mean distance.
    position_rel: f64,
    /// RMS of (corrected centre - injected noise - true centre image).
    corrected_centre_px: f64,
}

fn errors(spec: &ViewCampaignSpec, sims: &[SimulatedView], cal: &CameraCalibration) -> Errors {
    let (t, c) = (&spec.intrinsics, &cal.intrinsics);
    let (mut pos_sq, mut dist, mut centre_sq, mut n) = (0.0, 0.0, 0.0, 0.0);
    for (s, v) in sims.iter().zip(&cal.views) {
        let truth = s.camera_to_target.inverse().translation.vector;
        pos_sq += (v.pose.target_to_camera.translation.vector - truth).norm_squared();
        dist += truth.norm();
        for (((p, q), o), centroid) in v
            .corrected_pixels
            .iter()
            .zip(&s.true_centre_images)
            .zip(&s.observations.dots)
            .zip(&s.true_centroids)
        {
            centre_sq += (p - (o.pixel - centroid) - q).norm_squared();
            n += 1.0;
        }
    }
    let k = sims.len() as f64;
    let e = Errors {
        fx_rel: (c.fx - t.fx) / t.fx,
        fy_rel: (c.fy - t.fy) / t.fy,
        cx_px: c.cx - t.cx,
        cy_px: c.cy - t.cy,
        rms_over_noise: cal.rms_px / std::f64::consts::SQRT_2 / spec.noise_px,
        position_rel: (pos_sq / k).sqrt() / (dist / k),
        corrected_centre_px: (centre_sq / n).sqrt(),
    };
    println!(
        "{:?}: fx {:+.5}% fy {:+.5}% cx {:+.4} cy {:+.4} px rms/noise {:.3} position 1:{:.0} corrected centres {:.2e} px",
        cal.mode,
        100.0 * e.fx_rel,
        100.0 * e.fy_rel,
        e.cx_px,
        e.cy_px,
        e.rms_over_noise,
        1.0 / e.position_rel,
        e.corrected_centre_px
    );
    e
}

fn assert_refined_targets(e: &Errors, sd: &IntrinsicsStdDev) {
    assert!(
        e.fx_rel.abs() < FOCAL_REL_TOL && e.fy_rel.abs() < FOCAL_REL_TOL,
        "focal: fx {:+e} fy {:+e}",
        e.fx_rel,
        e.fy_rel
    );
    assert!(
        e.cx_px.abs() < CENTRE_TOL_PX && e.cy_px.abs() < CENTRE_TOL_PX,
        "centre: cx {:+} cy {:+} px",
        e.cx_px,
        e.cy_px
    );
    assert!(
        e.cx_px.abs() < CENTRE_SIGMAS * sd.cx && e.cy_px.abs() < CENTRE_SIGMAS * sd.cy,
        "centre error inconsistent with its reported sd {} {}",
        sd.cx,
        sd.cy
    );
    assert!((e.rms_over_noise - 1.0).abs() < RMS_REL_TOL, "rms");
    assert!(
        e.position_rel < 1.0 / POSITION_RATIO,
        "positions 1:{:.0}",
        1.0 / e.position_rel
    );
    assert!(
        e.corrected_centre_px < CORRECTED_CENTRE_TOL_PX,
        "bias correction"
    );
}

fn campaign(spec: &ViewCampaignSpec) {
    let sims = simulate_views(spec).unwrap();
    let views = views_of(&sims);
    let refined = calibrate(&views, &options(spec, CalibrationMode::Refined)).unwrap();
    assert!(!refined.paper_mode);
    let sd = refined.std_dev.unwrap();
    assert!(
        sd.fx > 0.0 && sd.fx < 1e-4 * spec.intrinsics.fx && sd.cx > 0.0 && sd.cx < CENTRE_TOL_PX
    );
    assert_eq!(refined.views.len(), spec.views);
    assert!(refined
        .views
        .iter()
        .all(|v| v.board_angle_deg > 15.0 && v.rms_px < 0.05));
    let e = errors(spec, &sims, &refined);
    assert_refined_targets(&e, &sd);
    // The paper's method on the same data: flagged, and far less accurate.
    let paper = calibrate(&views, &options(spec, CalibrationMode::Paper)).unwrap();
    assert!(paper.paper_mode && paper.std_dev.is_none());
    let p = errors(spec, &sims, &paper);
    assert!(p.fx_rel.abs() > 10.0 * e.fx_rel.abs() && p.rms_over_noise > 5.0);
}

#[test]
fn refined_mode_meets_targets_on_a_modern_camera() {
    for seed in [11, 13] {
        campaign(&ViewCampaignSpec::modern_1280x1024(seed));
    }
}

#[test]
fn refined_mode_meets_targets_on_a_camera_like_the_papers() {
    for seed in [12, 14] {
        campaign(&ViewCampaignSpec::paper_752x582(seed));
    }
}

/// Just above [`crate::camera::sequence::STAGE2_MIN_ANGLE_DEG`].
const WEAK_TILT_DEG: f64 = 10.5;

fn small_spec(seed: u64, views: usize) -> ViewCampaignSpec {
    ViewCampaignSpec {
        views,
        ..ViewCampaignSpec::modern_1280x1024(seed)
    }
}

#[test]
fn gross_outliers_are_dropped_and_reported() {
    let spec = small_spec(3, 15);
    let sims = simulate_views(&spec).unwrap();
    let mut views = views_of(&sims);
    let bad = [(2usize, 10usize), (7, 40), (11, 80)];
    for &(v, i) in &bad {
        views[v].dots[i].pixel.x += 1.5;
    }
    let cal = calibrate(&views, &options(&spec, CalibrationMode::Refined)).unwrap();
    let mut found: Vec<(usize, u32, u32)> = cal
        .outliers
        .iter()
        .map(|o| (o.view, o.row, o.col))
        .collect();
    found.sort();
    let expected: Vec<(usize, u32, u32)> = bad
        .iter()
        .map(|&(v, i)| (v, views[v].dots[i].row, views[v].dots[i].col))
        .collect();
    assert_eq!(found, expected);
    assert!(
        cal.warnings
            .iter()
            .filter(|w| w.contains("outlier"))
            .count()
            == 3
    );
    assert!((cal.intrinsics.fx / spec.intrinsics.fx - 1.0).abs() < 5.0 * FOCAL_REL_TOL);
}

#[test]
fn fixed_intrinsics_are_kept_and_poses_fitted() {
    let spec = small_spec(4, 5);
    let sims = simulate_views(&spec).unwrap();
    let opts = CalibrationOptions {
        fixed_intrinsics: Some(spec.intrinsics),
        ..options(&spec, CalibrationMode::Refined)
    };
    let cal = calibrate(&views_of(&sims), &opts).unwrap();
    assert_eq!(cal.intrinsics, spec.intrinsics);
    assert!(cal.std_dev.is_none());
    for (s, v) in sims.iter().zip(&cal.views) {
        let truth = s.camera_to_target.inverse().translation.vector;
        assert!((v.pose.target_to_camera.translation.vector - truth).norm() < 0.2);
    }
}

#[test]
fn reference_distances_pull_the_focal_length() {
    // Few, weakly tilted views: fx is loosely determined by the images; a
    // set of station distances 1% longer than the truth must lengthen the
    // fitted stations (and raise fx with them), consistent ones must not.
    // (Tilts just above the paper stage's 10 deg cut-off: below it no view
    // would enter the Tsai averages that start the refinement.)
    let spec = ViewCampaignSpec {
        tilt_deg: (WEAK_TILT_DEG, WEAK_TILT_DEG + 4.0),
        ..small_spec(5, 6)
    };
    let sims = simulate_views(&spec).unwrap();
    let views = views_of(&sims);
    let centre = |s: &SimulatedView| s.camera_to_target.inverse().translation.vector;
    let refs = |scale: f64| -> Vec<StationDistance> {
        (1..sims.len())
            .map(|b| StationDistance {
                view_a: 0,
                view_b: b,
                distance_mm: scale * (centre(&sims[0]) - centre(&sims[b])).norm(),
                sigma_mm: 0.001,
            })
            .collect()
    };
    let run = |r: Vec<StationDistance>| {
        let opts = CalibrationOptions {
            reference_distances: r,
            ..options(&spec, CalibrationMode::Refined)
        };
        calibrate(&views, &opts).unwrap()
    };
    let plain = run(Vec::new());
    let consistent = run(refs(1.0));
    let longer = run(refs(1.01));
    println!(
        "fx plain {} consistent {} longer {}",
        plain.intrinsics.fx, consistent.intrinsics.fx, longer.intrinsics.fx
    );
    assert!(
        (consistent.intrinsics.fx / spec.intrinsics.fx - 1.0).abs()
            <= (plain.intrinsics.fx / spec.intrinsics.fx - 1.0).abs() + 1e-4
    );
    assert!(longer.intrinsics.fx > consistent.intrinsics.fx * 1.002);
}

#[test]
fn degenerate_input_is_refused() {
    let spec = small_spec(6, 4);
    let sims = simulate_views(&spec).unwrap();
    let views = views_of(&sims);
    let opts = options(&spec, CalibrationMode::Refined);
    assert!(matches!(
        calibrate(&views[..2], &opts),
        Err(CameraError::TooFewImages {
            usable: 2,
            required: 3
        })
    ));
    let mut sizes = views.clone();
    sizes[2].image_size.width = 640;
    assert!(matches!(
        calibrate(&sizes, &opts),
        Err(CameraError::InconsistentImageSize { view: 2, .. })
    ));
    let mut line = views.clone();
    line[1].dots.retain(|d| d.row == 4);
    assert!(matches!(
        calibrate(&line, &opts),
        Err(CameraError::CollinearPoints { view: 1 })
    ));
    let mut nan = views.clone();
    nan[3].dots[0].pixel.x = f64::NAN;
    assert!(matches!(
        calibrate(&nan, &opts),
        Err(CameraError::NonFinite { view: 3 })
    ));
    let mut few = views.clone();
    few[0].dots.truncate(4);
    assert!(matches!(
        calibrate(&few, &opts),
        Err(CameraError::TooFewPoints { view: 0, .. })
    ));
    let flat = ViewCampaignSpec {
        tilt_deg: (0.0, 2.0),
        ..small_spec(7, 5)
    };
    let flat_views = views_of(&simulate_views(&flat).unwrap());
    assert!(matches!(
        calibrate(&flat_views, &opts),
        Err(CameraError::AllFrontoParallel { .. })
    ));
    let bad_ref = CalibrationOptions {
        reference_distances: vec![StationDistance {
            view_a: 0,
            view_b: 9,
            distance_mm: 10.0,
            sigma_mm: 0.1,
        }],
        ..opts.clone()
    };
    assert!(matches!(
        calibrate(&views, &bad_ref),
        Err(CameraError::InvalidOption {
            field: "reference_distances",
            ..
        })
    ));
    let bad_diameter = CalibrationOptions {
        dot_diameter_mm: Some(-1.0),
        ..opts
    };
    assert!(matches!(
        calibrate(&views, &bad_diameter),
        Err(CameraError::InvalidOption {
            field: "dot_diameter_mm",
            ..
        })
    ));
}

#[test]
fn low_board_angles_are_warned_about() {
    let spec = ViewCampaignSpec {
        tilt_deg: (12.0, 18.0),
        ..small_spec(8, 4)
    };
    let sims = simulate_views(&spec).unwrap();
    let cal = calibrate(&views_of(&sims), &options(&spec, CalibrationMode::Refined)).unwrap();
    assert_eq!(
        cal.warnings
            .iter()
            .filter(|w| w.contains("board-to-image angle"))
            .count(),
        4
    );
}
