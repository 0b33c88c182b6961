//! Simulated calibration views without rendering images (issue 4): a known
//! camera looks at a dot board from random poses; each dot's observed
//! centre is the area centroid of its projected circular boundary (what a
//! good detector measures, method.md §4 **beyond**) plus Gaussian noise.

use nalgebra::{Isometry3, Point2, Point3, Translation3, Unit, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};
use rand_distr::{Distribution, Normal};

use crate::camera::bias::projected_disc_centroid;
use crate::camera::model::Intrinsics;
use crate::camera::observations::{DotObservation, ImageSize, ViewObservations};

/// Boundary samples for the simulated "true" measured centres: far more
/// than the calibrator's own prediction uses, so the two are independent
/// to well below 1e-4 px.
pub const TRUTH_BOUNDARY_SAMPLES: usize = 512;
/// Pose draws per view before giving up on fitting the board in the image.
const MAX_POSE_ATTEMPTS: usize = 2000;

/// A flat board of dark dots; dot (r, c) at `(c p, r p, 0)` (method.md §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DotBoard {
    pub rows: u32,
    pub cols: u32,
    pub pitch_mm: f64,
    pub dot_diameter_mm: f64,
}

impl DotBoard {
    /// The board: 9x9 dots of 8 mm on a 25 mm pitch.
    pub fn standard() -> Self {
        Self {
            rows: 9,
            cols: 9,
            pitch_mm: 25.0,
            dot_diameter_mm: 8.0,
        }
    }

    pub fn point(&self, row: u32, col: u32) -> Point3<f64> {
        Point3::new(col as f64 * self.pitch_mm, row as f64 * self.pitch_mm, 0.0)
    }

    fn centre(&self) -> Point3<f64> {
        Point3::new(
            (self.cols - 1) as f64 * self.pitch_mm / 2.0,
            (self.rows - 1) as f64 * self.pitch_mm / 2.0,
            0.0,
        )
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct ViewCampaignSpec {
    pub intrinsics: Intrinsics,
    pub image_size: ImageSize,
    pub board: DotBoard,
    pub views: usize,
    pub distance_mm: (f64, f64),
    pub tilt_deg: (f64, f64),
    /// Standard deviation of the detector noise per axis (px).
    pub noise_px: f64,
    /// Dots must stay this far inside the image (px).
    pub margin_px: f64,
    pub seed: u64,
}

impl ViewCampaignSpec {
    /// A modern 1280x1024 camera with square pixels (issue 4).
    pub fn modern_1280x1024(seed: u64) -> Self {
        Self {
            intrinsics: Intrinsics {
                fx: 1200.0,
                fy: 1200.0,
                cx: 645.3,
                cy: 508.7,
                k1: -0.12,
                k2: 0.09,
                p1: 3e-4,
                p2: -2e-4,
                k3: 0.0,
            },
            image_size: ImageSize {
                width: 1280,
                height: 1024,
            },
            board: DotBoard::standard(),
            views: 60,
            distance_mm: (600.0, 1000.0),
            tilt_deg: (20.0, 45.0),
            noise_px: 0.01,
            margin_px: 15.0,
            seed,
        }
    }

    /// A camera like the paper's analog one: 752x582, `fy/fx = 0.9825`.
    pub fn paper_752x582(seed: u64) -> Self {
        Self {
            intrinsics: Intrinsics {
                fx: 1000.0,
                fy: 982.5,
                cx: 380.2,
                cy: 287.6,
                k1: -0.08,
                k2: 0.03,
                p1: 2e-4,
                p2: 1e-4,
                k3: 0.0,
            },
            image_size: ImageSize {
                width: 752,
                height: 582,
            },
            ..Self::modern_1280x1024(seed)
        }
    }
}

/// One simulated view with its truth.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulatedView {
    /// True target pose in the camera frame.
    pub camera_to_target: Isometry3<f64>,
    /// Noisy measured centres (area centroids of the projected dots).
    pub observations: ViewObservations,
    /// True images of the dots' 3-D centres, in the order of `observations.dots`.
    pub true_centre_images: Vec<Point2<f64>>,
    /// Noise-free measured centres (area centroids).
    pub true_centroids: Vec<Point2<f64>>,
    pub tilt_deg: f64,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ViewSimError {
    #[error("no pose within {attempts} draws keeps the whole board inside the image")]
    BoardDoesNotFit { attempts: usize },
    #[error("invalid specification: {0}")]
    InvalidSpec(String),
}

/// Draw `spec.views` views (deterministic for a seed).
pub fn simulate_views(spec: &ViewCampaignSpec) -> Result<Vec<SimulatedView>, ViewSimError> {
    if !(spec.noise_px >= 0.0
        && spec.distance_mm.0 > 0.0
        && spec.distance_mm.1 >= spec.distance_mm.0)
        || spec.tilt_deg.1 < spec.tilt_deg.0
    {
        return Err(ViewSimError::InvalidSpec(
            "ranges must be ordered, noise >= 0".into(),
        ));
    }
    let mut rng = StdRng::seed_from_u64(spec.seed);
    let noise =
        Normal::new(0.0, spec.noise_px).map_err(|e| ViewSimError::InvalidSpec(e.to_string()))?;
    (0..spec.views)
        .map(|_| simulate_one(spec, &mut rng, &noise))
        .collect()
}

fn simulate_one(
    spec: &ViewCampaignSpec,
    rng: &mut StdRng,
    noise: &Normal<f64>,
) -> Result<SimulatedView, ViewSimError> {
    let (w, h) = (spec.image_size.width as f64, spec.image_size.height as f64);
    let radius = spec.board.dot_diameter_mm / 2.0;
    for _ in 0..MAX_POSE_ATTEMPTS {
        let distance = rng.random_range(spec.distance_mm.0..=spec.distance_mm.1);
        let tilt = rng.random_range(spec.tilt_deg.0..=spec.tilt_deg.1);
        let axis_angle = rng.random_range(0.0..std::f64::consts::TAU);
        let roll = rng.random_range(0.0..std::f64::consts::TAU);
        let aim = Point2::new(
            rng.random_range(0.1 * w..0.9 * w),
            rng.random_range(0.1 * h..0.9 * h),
        );
        let Some(ray) = spec.intrinsics.pixel_to_ray(&aim) else {
            continue;
        };
        let centre_camera = Vector3::new(ray.x, ray.y, 1.0).normalize() * distance;
        let axis = Unit::new_normalize(Vector3::new(axis_angle.cos(), axis_angle.sin(), 0.0));
        let rotation = UnitQuaternion::from_axis_angle(&axis, tilt.to_radians())
            * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), roll);
        let t = centre_camera - rotation * spec.board.centre().coords;
        let pose = Isometry3::from_parts(Translation3::from(t), rotation);
        if let Some(view) = observe(spec, &pose, radius, w, h, rng, noise) {
            return Ok(SimulatedView {
                tilt_deg: tilt,
                ..view
            });
        }
    }
    Err(ViewSimError::BoardDoesNotFit {
        attempts: MAX_POSE_ATTEMPTS,
    })
}

fn observe(
    spec: &ViewCampaignSpec,
    pose: &Isometry3<f64>,
    radius: f64,
    w: f64,
    h: f64,
    rng: &mut StdRng,
    noise: &Normal<f64>,
) -> Option<SimulatedView> {
    let board = &spec.board;
    let inside = |p: &Point2<f64>| {
        let m = spec.margin_px;
        p.x >= m && p.y >= m && p.x <= w - 1.0 - m && p.y <= h - 1.0 - m
    };
    let (mut dots, mut centres, mut centroids) = (Vec::new(), Vec::new(), Vec::new());
    for row in 0..board.rows {
        for col in 0..board.cols {
            let target = board.point(row, col);
            let centre = spec.intrinsics.project(&(pose * target))?;
            let centroid = projected_disc_centroid(
                &spec.intrinsics,
                pose,
                &target,
                radius,
                TRUTH_BOUNDARY_SAMPLES,
            )?;
            if !inside(&centroid) {
                return None;
            }
            let pixel = centroid + nalgebra::Vector2::new(noise.sample(rng), noise.sample(rng));
            dots.push(DotObservation {
                row,
                col,
                target_mm: target,
                pixel,
            });
            centres.push(centre);
            centroids.push(centroid);
        }
    }
    Some(SimulatedView {
        camera_to_target: *pose,
        observations: ViewObservations {
            image_size: spec.image_size,
            dots,
        },
        true_centre_images: centres,
        true_centroids: centroids,
        tilt_deg: 0.0,
    })
}
