//! What a calibration consumes: per image, the detected dots (grid row and
//! column, target point in mm, observed centre in px) and the image size.

use nalgebra::{Matrix2, Point2, Point3};
use serde::{Deserialize, Serialize};

use super::error::CameraError;

/// Fewest dots per image for Tsai's coplanar stage 1 (method.md §3: >= 5);
/// one more keeps stage 2 over-determined.
pub const MIN_DOTS_PER_VIEW: usize = 6;
/// Target points whose second principal spread is below this fraction of
/// the first are collinear.
const COLLINEAR_RATIO: f64 = 1e-6;
/// |z| of a board point above this (mm) means the target is not planar.
const PLANAR_TOLERANCE_MM: f64 = 1e-9;

/// `(target point mm, pixel)` pairs of one image.
pub type Correspondences = Vec<(Point3<f64>, Point2<f64>)>;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ImageSize {
    pub width: u32,
    pub height: u32,
}

/// One detected dot: grid position, its centre on the board (target frame,
/// mm, z = 0) and its measured centre in the image (px).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DotObservation {
    pub row: u32,
    pub col: u32,
    pub target_mm: Point3<f64>,
    pub pixel: Point2<f64>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ViewObservations {
    pub image_size: ImageSize,
    pub dots: Vec<DotObservation>,
}

impl ViewObservations {
    /// `(target point, pixel)` pairs.
    pub fn pairs(&self) -> Vec<(Point3<f64>, Point2<f64>)> {
        self.dots.iter().map(|d| (d.target_mm, d.pixel)).collect()
    }
}

/// Refuse views that cannot be calibrated: non-finite values, too few dots,
/// points off the board plane, collinear points, mixed image sizes.
pub fn validate_views(views: &[ViewObservations]) -> Result<ImageSize, CameraError> {
    let Some(first) = views.first() else {
        return Err(CameraError::TooFewImages {
            usable: 0,
            required: 1,
        });
    };
    let size = first.image_size;
    for (view, obs) in views.iter().enumerate() {
        let s = obs.image_size;
        if s.width == 0 || s.height == 0 {
            return Err(CameraError::EmptyImage {
                view,
                width: s.width,
                height: s.height,
            });
        }
        if s != size {
            return Err(CameraError::InconsistentImageSize {
                view,
                width: s.width,
                height: s.height,
                expected_width: size.width,
                expected_height: size.height,
            });
        }
        validate_points(view, &obs.pairs())?;
    }
    Ok(size)
}

/// Checks of one view's points (also used by the pose estimator).
pub fn validate_points(
    view: usize,
    pairs: &[(Point3<f64>, Point2<f64>)],
) -> Result<(), CameraError> {
    if pairs.iter().any(|(p, q)| {
        !p.coords
            .iter()
            .chain(q.coords.iter())
            .all(|v| v.is_finite())
    }) {
        return Err(CameraError::NonFinite { view });
    }
    if pairs.len() < MIN_DOTS_PER_VIEW {
        return Err(CameraError::TooFewPoints {
            view,
            count: pairs.len(),
            required: MIN_DOTS_PER_VIEW,
        });
    }
    if pairs.iter().any(|(p, _)| p.z.abs() > PLANAR_TOLERANCE_MM) {
        return Err(CameraError::NotPlanar { view });
    }
    if is_collinear(pairs.iter().map(|(p, _)| Point2::new(p.x, p.y))) {
        return Err(CameraError::CollinearPoints { view });
    }
    Ok(())
}

/// True when the 2-D points (nearly) lie on one line.
pub fn is_collinear(points: impl Iterator<Item = Point2<f64>> + Clone) -> bool {
    let n = points.clone().count() as f64;
    if n < 3.0 {
        return true;
    }
    let mean = points
        .clone()
        .fold(Point2::origin().coords, |a, p| a + p.coords)
        / n;
    let mut scatter = Matrix2::zeros();
    for p in points {
        let d = p.coords - mean;
        scatter += d * d.transpose();
    }
    let eig = scatter.symmetric_eigenvalues();
    let (lo, hi) = (eig.min(), eig.max());
    hi <= 0.0 || lo <= COLLINEAR_RATIO * hi
}
