//! A realistic, deterministic sample report (a 61-pose IRB-2400 camera
//! campaign: 31 calibration poses, one rejected by detection, 30 validation
//! poses) for tests and for looking at the renderings
//! (`cargo run --example render_report`). Not calibration output: the
//! numbers are drawn from a fixed-seed generator to look like one.

use super::model::*;
use std::f64::consts::PI;

/// splitmix64: tiny, deterministic, good enough for sample data.
struct SampleRng(u64);

impl SampleRng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + unit * (hi - lo)
    }
    /// Standard normal (Box–Muller).
    fn normal(&mut self) -> f64 {
        let u1 = self.uniform(f64::MIN_POSITIVE, 1.0);
        let u2 = self.uniform(0.0, 1.0);
        (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
    }
    /// A vector of length `magnitude` in a uniformly random direction.
    fn vector(&mut self, magnitude: f64) -> [f64; 3] {
        let z = self.uniform(-1.0, 1.0);
        let phi = self.uniform(0.0, 2.0 * PI);
        let r = (1.0 - z * z).sqrt();
        [
            magnitude * r * phi.cos(),
            magnitude * r * phi.sin(),
            magnitude * z,
        ]
    }
}

const SEED: u64 = 0x5EED_2400;
const CALIBRATION_POSES: usize = 31;
const VALIDATION_POSES: usize = 30;
/// The calibration pose whose image detection rejects.
const FAILED_POSE: usize = 17;
const IMAGE_WIDTH: u32 = 1280;
const IMAGE_HEIGHT: u32 = 1024;
const DOTS_PER_IMAGE: usize = 99;
/// Residual samples kept per view (of the 99 dots).
const RESIDUALS_PER_VIEW: usize = 55;
/// Board-to-image angle under which a view is flagged (method.md §3).
const LOW_ANGLE_DEG: f64 = 20.0;
/// Per-pixel residual noise of a good dot centre, px.
const RESIDUAL_NOISE_PX: f64 = 0.05;
/// Unmodelled higher-order radial term: residual at the image corner, px.
const UNMODELLED_RADIAL_PX: f64 = 0.12;
const JOINT_LIMITS_DEG: [(f64, f64); 6] = [
    (-150.0, 150.0),
    (-40.0, 90.0),
    (-60.0, 60.0),
    (-180.0, 180.0),
    (-110.0, 110.0),
    (-200.0, 200.0),
];

/// The sample camera campaign report (deterministic).
pub fn sample_report() -> Report {
    sample_report_sized(CALIBRATION_POSES, VALIDATION_POSES)
}

/// The sample with `calibration` + `validation` poses (one calibration
/// pose rejected by detection when there are more than
/// [`FAILED_POSE`]), for looking at the renderings from a handful of
/// poses to hundreds.
pub fn sample_report_sized(calibration: usize, validation: usize) -> Report {
    let mut rng = SampleRng(SEED);
    let per_pose = sample_poses(&mut rng, calibration, validation);
    let camera = sample_camera(&mut rng, &per_pose);
    let residual_field = sample_residuals(&mut rng, per_pose.len());
    let val: Vec<&PoseReport> = per_pose.iter().filter(|p| p.set == "val").collect();
    let before = summary(val.iter().map(|p| p.before_error_mm));
    let after = summary(val.iter().map(|p| p.after_error_mm));
    let (parameters, identifiability) = sample_parameters(&mut rng);
    let low_angle_views = camera.views.iter().filter(|v| v.warning.is_some()).count();
    Report {
        serial: "IRB2400-SN-48213".into(),
        version: 3,
        job_id: "0193a5f2-8b20-7c31-9d4e-5f6a7b8c9d0e".into(),
        session_id: "0193a5f1-2a3b-7c4d-8e5f-60718293a4b5".into(),
        created_at: "2026-11-21T16:42:05Z".into(),
        instrument: "camera".into(),
        measurement: "pose".into(),
        camera: Some(camera),
        detection: Some(DetectionReport {
            images: calibration + validation,
            images_detected: per_pose_count_detected(calibration, validation),
            dots_per_image: DOTS_PER_IMAGE,
            failures: (FAILED_POSE < calibration)
                .then(|| DetectionFailure {
                    pose_id: pose_id(FAILED_POSE),
                    label: pose_label(FAILED_POSE),
                    reason: "61 of 99 dots found: board partly outside the image; retake with the board fully in view".into(),
                })
                .into_iter()
                .collect(),
        }),
        before,
        after,
        per_pose,
        parameters,
        identifiability,
        residual_field,
        hand_eye: None,
        notes: vec![
            "joint6.d_mm and joint6.theta_offset_deg were held at nominal: they trade exactly against the hand-eye transform.".into(),
            "joint1.d_mm and joint1.theta_offset_deg were held at nominal: they trade exactly against the base frame.".into(),
            format!("{low_angle_views} views have a board-to-image angle under 20 degrees; the focal length rests on the other views."),
            "Joint compliance and gear backlash are not modelled; expect larger errors under heavy payloads.".into(),
        ],
        uncertainty_map: Some(super::uncertainty_chart::sample_map()),
        terms: None,
        gate: None,
        model_selection: None,
        release: Default::default(),
        measurement_accuracy: None,
        regions: Vec::new(),
    }
}

/// The sample as a laser-tracker session: positions only, no camera.
pub fn sample_tracker_report() -> Report {
    let mut report = sample_report();
    report.serial = "UR10-2019-0731".into();
    report.instrument = "tracker".into();
    report.measurement = "position".into();
    report.camera = None;
    report.detection = None;
    report.residual_field.clear();
    for pose in &mut report.per_pose {
        pose.reprojection_rms_px = None;
    }
    report
        .parameters
        .retain(|p| !p.name.starts_with("flange_to_camera"));
    report.notes = vec!["Positions measured by a laser tracker: no camera calibration.".into()];
    report
}

/// Pose ids as the service makes them (UUIDv7: 36 characters, the
/// leading ones shared by poses uploaded together).
fn pose_id(index: usize) -> String {
    format!("0193a5f2-7c1e-7d40-8a6b-{:012x}", 0x3c5e_0000 + index)
}

/// Labels as a camera's file names look.
fn pose_label(index: usize) -> String {
    format!("IRB2400_2026-11-21_pose_{:03}.png", index + 1)
}

fn per_pose_count_detected(calibration: usize, validation: usize) -> usize {
    calibration + validation - usize::from(FAILED_POSE < calibration)
}

fn sample_poses(rng: &mut SampleRng, calibration: usize, validation: usize) -> Vec<PoseReport> {
    let mut poses = Vec::new();
    for index in 0..calibration + validation {
        if index == FAILED_POSE && FAILED_POSE < calibration {
            continue;
        }
        let joints_deg = JOINT_LIMITS_DEG
            .iter()
            .map(|(lo, hi)| rng.uniform(*lo, *hi))
            .collect();
        let calibration = index < calibration;
        // Calibration poses fit a little better than validation poses.
        let (before, after) = if calibration {
            (rng.uniform(0.8, 2.6), rng.uniform(0.04, 0.11))
        } else {
            (rng.uniform(1.0, 3.0), rng.uniform(0.05, 0.15))
        };
        let before_error_mm = rng.vector(before);
        let after_error_mm = rng.vector(after);
        poses.push(PoseReport {
            pose_id: pose_id(index),
            label: pose_label(index),
            set: if calibration { "cal" } else { "val" }.into(),
            joints_deg,
            before_error_mm,
            after_error_mm,
            before_mm: norm(before_error_mm),
            after_mm: norm(after_error_mm),
            reprojection_rms_px: Some(rng.uniform(0.05, 0.10)),
            outlier: false,
            reason: None,
            camera_in_target: None,
        });
    }
    poses
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sample_camera(rng: &mut SampleRng, poses: &[PoseReport]) -> CameraReport {
    let views = poses
        .iter()
        .map(|p| {
            let board_angle_deg = rng.uniform(14.0, 48.0);
            let warning = (board_angle_deg < LOW_ANGLE_DEG).then(|| {
                "board-to-image angle under 20 degrees: focal length poorly conditioned".to_string()
            });
            ViewReport {
                pose_id: p.pose_id.clone(),
                label: p.label.clone(),
                rms_px: p.reprojection_rms_px.unwrap_or_default(),
                board_angle_deg,
                warning,
            }
        })
        .collect();
    CameraReport {
        mode: "refined".into(),
        camera_calibration_id: None,
        image_width: IMAGE_WIDTH,
        image_height: IMAGE_HEIGHT,
        intrinsics: Intrinsics {
            fx: 1402.73,
            fy: 1401.96,
            cx: 641.28,
            cy: 509.84,
            k1: -0.213_47,
            k2: 0.118_62,
            p1: 0.000_31,
            p2: -0.000_22,
            k3: 0.0,
        },
        std: Some(CameraStd {
            fx: 0.41,
            fy: 0.40,
            cx: 0.23,
            cy: 0.21,
            k1: 0.000_62,
            k2: 0.0021,
            p1: 0.000_018,
            p2: 0.000_017,
            ..CameraStd::default()
        }),
        reprojection_rms_px: 0.072,
        outliers_dropped: 3,
        views,
    }
}

fn sample_residuals(rng: &mut SampleRng, views: usize) -> Vec<ResidualSample> {
    let (w, h) = (f64::from(IMAGE_WIDTH), f64::from(IMAGE_HEIGHT));
    let (cx, cy) = (w / 2.0, h / 2.0);
    let corner_r2 = cx * cx + cy * cy;
    let mut samples = Vec::with_capacity(views * RESIDUALS_PER_VIEW);
    for _ in 0..views {
        // Each view's board covers a different part of the image.
        let (bw, bh) = (rng.uniform(0.4, 0.8) * w, rng.uniform(0.4, 0.8) * h);
        let (x0, y0) = (rng.uniform(0.0, w - bw), rng.uniform(0.0, h - bh));
        for _ in 0..RESIDUALS_PER_VIEW {
            let (x, y) = (x0 + rng.uniform(0.0, bw), y0 + rng.uniform(0.0, bh));
            let (rx, ry) = (x - cx, y - cy);
            let radial = UNMODELLED_RADIAL_PX * ((rx * rx + ry * ry) / corner_r2).powi(2);
            let r = (rx * rx + ry * ry).sqrt().max(1.0);
            samples.push(ResidualSample {
                x_px: x,
                y_px: y,
                dx_px: radial * rx / r + RESIDUAL_NOISE_PX * rng.normal(),
                dy_px: radial * ry / r + RESIDUAL_NOISE_PX * rng.normal(),
            });
        }
    }
    samples
}

/// (name, unit, nominal, std, fixed) of the IRB-2400 sample parameters.
type ParameterSpec = (&'static str, &'static str, f64, f64, bool);

const PARAMETERS: [ParameterSpec; 22] = [
    ("joint1.d_mm", "mm", 615.0, 0.0, true),
    ("joint1.theta_offset_deg", "deg", 0.0, 0.0, true),
    ("joint1.a_mm", "mm", 100.0, 0.031, false),
    ("joint1.alpha_deg", "deg", -90.0, 0.0021, false),
    ("joint2.a_mm", "mm", 705.0, 0.044, false),
    ("joint2.theta_offset_deg", "deg", -90.0, 0.0034, false),
    ("joint2.beta_deg", "deg", 0.0, 0.0019, false),
    ("joint3.a_mm", "mm", 135.0, 0.038, false),
    ("joint3.alpha_deg", "deg", -90.0, 0.0027, false),
    ("joint3.theta_offset_deg", "deg", 0.0, 0.0041, false),
    ("joint4.d_mm", "mm", 755.0, 0.052, false),
    ("joint4.alpha_deg", "deg", 90.0, 0.0032, false),
    ("joint5.alpha_deg", "deg", -90.0, 0.0045, false),
    ("joint5.theta_offset_deg", "deg", 0.0, 0.0058, false),
    ("joint6.d_mm", "mm", 85.0, 0.0, true),
    ("joint6.theta_offset_deg", "deg", 0.0, 0.0, true),
    ("target_to_base.tx_mm", "mm", -1250.0, 0.12, false),
    ("target_to_base.ty_mm", "mm", 310.0, 0.11, false),
    ("target_to_base.tz_mm", "mm", -402.0, 0.09, false),
    ("flange_to_camera.tx_mm", "mm", 0.0, 0.07, false),
    ("flange_to_camera.ty_mm", "mm", 62.0, 0.07, false),
    ("flange_to_camera.tz_mm", "mm", 118.0, 0.10, false),
];

fn sample_parameters(rng: &mut SampleRng) -> (Vec<ParameterReport>, IdentifiabilityReport) {
    let parameters: Vec<ParameterReport> = PARAMETERS
        .iter()
        .map(|&(name, unit, nominal, std, fixed)| {
            let deviation = if unit == "mm" {
                rng.uniform(-1.5, 1.5)
            } else {
                rng.uniform(-0.08, 0.08)
            };
            let identified = if fixed { nominal } else { nominal + deviation };
            ParameterReport {
                name: name.into(),
                unit: unit.into(),
                nominal,
                identified,
                std,
                fixed,
            }
        })
        .collect();
    let fixed: Vec<String> = parameters
        .iter()
        .filter(|p| p.fixed)
        .map(|p| p.name.clone())
        .collect();
    let identifiability = IdentifiabilityReport {
        parameters: parameters.len(),
        rank: parameters.len() - fixed.len(),
        condition_number: 412.7,
        observability_index: 0.0213,
        fixed,
        weak: Vec::new(),
    };
    (parameters, identifiability)
}

/// Statistics of the 3-D magnitudes and absolute axis components.
fn summary(errors: impl Iterator<Item = [f64; 3]>) -> AccuracySummary {
    let errors: Vec<[f64; 3]> = errors.collect();
    let axis = |i: usize| stats(errors.iter().map(|e| e[i].abs()).collect());
    AccuracySummary {
        norm: stats(errors.iter().map(|e| norm(*e)).collect()),
        x: axis(0),
        y: axis(1),
        z: axis(2),
    }
}

fn stats(mut values: Vec<f64>) -> ErrorStats {
    let n = values.len();
    if n == 0 {
        return ErrorStats::default();
    }
    values.sort_by(f64::total_cmp);
    let mean = values.iter().sum::<f64>() / n as f64;
    let median = if n % 2 == 1 {
        values[n / 2]
    } else {
        (values[n / 2 - 1] + values[n / 2]) / 2.0
    };
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n.max(2) - 1) as f64;
    let rms = (values.iter().map(|v| v * v).sum::<f64>() / n as f64).sqrt();
    ErrorStats {
        n,
        mean_mm: mean,
        median_mm: median,
        std_mm: var.sqrt(),
        max_mm: values[n - 1],
        rms_mm: rms,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_is_deterministic_and_in_the_stated_ranges() {
        let a = sample_report();
        assert_eq!(a, sample_report());
        let val: Vec<_> = a.per_pose.iter().filter(|p| p.set == "val").collect();
        assert_eq!(val.len(), VALIDATION_POSES);
        assert!(val
            .iter()
            .all(|p| (1.0..3.0).contains(&p.before_mm) && (0.05..0.15).contains(&p.after_mm)));
        assert_eq!(a.camera.as_ref().unwrap().views.len(), 60);
        assert!(a.residual_field.len() > 3000);
        assert_eq!(a.after.norm.n, VALIDATION_POSES);
        assert!(a.before.norm.max_mm >= a.before.norm.median_mm);
    }
}
