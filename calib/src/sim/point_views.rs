//! Simulated calibration views without rendering images (issue 4): a known
//! camera looks at a dot board from random poses; each dot's observed
//! centre is the area centroid of its projected circular boundary (what a
//! good detector measures, method.md §4 **beyond**) plus Gaussian noise.

use nalgebra::{Isometry3, Point2, Unit, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};
use rand_distr::{Distribution, Normal};

pub use super::campaign_io::Board;
use super::view_layout::{board_pose, fit_into_frame, placement};
pub use super::view_spec::{
    ViewCampaignSpec, ViewLayout, BOARD_FIELD_FRACTION, LAYOUT_CELLS, LAYOUT_ROLL_SPREAD_DEG,
};
use crate::camera::bias::DiscBoundary;
use crate::camera::observations::{DotObservation, ViewObservations};

/// Boundary samples for the simulated "true" measured centres: far more
/// than the calibrator's own prediction uses, so the two are independent
/// to well below 1e-4 px.
pub const TRUTH_BOUNDARY_SAMPLES: usize = 512;
/// The truth's boundary directions, tabulated once.
fn truth_boundary() -> &'static DiscBoundary {
    static BOUNDARY: std::sync::OnceLock<DiscBoundary> = std::sync::OnceLock::new();
    BOUNDARY.get_or_init(|| DiscBoundary::new(TRUTH_BOUNDARY_SAMPLES))
}

/// Pose draws per view before giving up on fitting the board in the image.
const MAX_POSE_ATTEMPTS: usize = 2000;
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
        .map(|i| simulate_one(spec, i, &mut rng, &noise))
        .collect()
}

fn simulate_one(
    spec: &ViewCampaignSpec,
    index: usize,
    rng: &mut StdRng,
    noise: &Normal<f64>,
) -> Result<SimulatedView, ViewSimError> {
    let (w, h) = (spec.image_size.width as f64, spec.image_size.height as f64);
    let radius = spec.board.dot_diameter_mm / 2.0;
    for _ in 0..MAX_POSE_ATTEMPTS {
        let distance = rng.random_range(spec.distance_mm.0..=spec.distance_mm.1);
        let tilt = rng.random_range(spec.tilt_deg.0..=spec.tilt_deg.1);
        let place = placement(spec.layout, index, spec.views, rng);
        let axis = Unit::new_normalize(Vector3::new(
            place.tilt_axis_rad.cos(),
            place.tilt_axis_rad.sin(),
            0.0,
        ));
        let rotation = UnitQuaternion::from_axis_angle(&axis, tilt.to_radians())
            * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), place.roll_rad);
        let aim = Point2::new(place.aim_fraction.x * w, place.aim_fraction.y * h);
        let pose = match spec.layout {
            ViewLayout::Random => board_pose(spec, &aim, distance, rotation),
            ViewLayout::Stratified { .. } => fit_into_frame(spec, aim, distance, rotation),
        };
        let Some(pose) = pose else {
            continue;
        };
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
    // Cheap rejection first: most drawn poses of a large board do not fit.
    let centres_inside = (0..board.rows).all(|row| {
        (0..board.cols).all(|col| {
            spec.intrinsics
                .project(&(pose * board.point(row, col)))
                .is_some_and(|p| inside(&p))
        })
    });
    if !centres_inside {
        return None;
    }
    let (mut dots, mut centres, mut centroids) = (Vec::new(), Vec::new(), Vec::new());
    for row in 0..board.rows {
        for col in 0..board.cols {
            let target = board.point(row, col);
            let centre = spec.intrinsics.project(&(pose * target))?;
            let centroid =
                truth_boundary().projected_centroid(&spec.intrinsics, pose, &target, radius)?;
            if !inside(&centroid) {
                return None;
            }
            let pixel = centroid + nalgebra::Vector2::new(noise.sample(rng), noise.sample(rng));
            dots.push(DotObservation {
                row: row as u32,
                col: col as u32,
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
