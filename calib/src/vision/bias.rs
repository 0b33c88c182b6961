//! Perspective bias of ellipse centres (method.md §4 "beyond"): the centre of
//! a dot's image is not the image of the dot's centre. A homography fitted to
//! the dots around each dot (target mm -> pixels) predicts the offset
//! exactly for a pinhole camera, and to first order under lens distortion,
//! without knowing the camera.

use nalgebra::Vector2;

use super::homography::Homography;
use super::target::TargetSpec;

/// Lattice neighbourhood (Chebyshev radius, dots) of the local homography.
const BIAS_RADIUS: i64 = 2;
/// Dots needed for a local homography.
const MIN_BIAS_DOTS: usize = 6;

/// Offsets `ellipse centre - image of dot centre`, pixels, for dots given in
/// row-major order `(row, col, ellipse centre)`; `None` where no local
/// homography could be fitted.
pub fn perspective_bias(
    dots: &[(usize, usize, Vector2<f64>)],
    target: &TargetSpec,
) -> Vec<Option<Vector2<f64>>> {
    let at = |r: i64, c: i64| -> Option<Vector2<f64>> {
        if r < 0 || c < 0 || r >= target.rows as i64 || c >= target.cols as i64 {
            return None;
        }
        dots.get(r as usize * target.cols + c as usize).map(|d| d.2)
    };
    dots.iter()
        .map(|&(row, col, _)| {
            let (mut plane, mut image) = (Vec::new(), Vec::new());
            for dr in -BIAS_RADIUS..=BIAS_RADIUS {
                for dc in -BIAS_RADIUS..=BIAS_RADIUS {
                    let (r, c) = (row as i64 + dr, col as i64 + dc);
                    if let Some(p) = at(r, c) {
                        let m = target.dot_centre_mm(r as usize, c as usize);
                        plane.push(Vector2::new(m[0], m[1]));
                        image.push(p);
                    }
                }
            }
            if plane.len() < MIN_BIAS_DOTS {
                return None;
            }
            let h = Homography::fit(&plane, &image)?;
            let m = target.dot_centre_mm(row, col);
            let radius = 0.5 * target.dot_diameter_at_mm(row, col);
            h.circle_centre_bias(&Vector2::new(m[0], m[1]), radius)
        })
        .collect()
}
