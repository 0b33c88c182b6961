//! Perspective bias of ellipse centres (method.md §4 "beyond"): the centre of
//! a dot's image is not the image of the dot's centre. A homography fitted to
//! the dots around each dot (target mm -> pixels) predicts the offset
//! exactly for a pinhole camera, and to first order under lens distortion,
//! without knowing the camera.

use std::collections::HashMap;

use nalgebra::Vector2;

use super::circle_board::CircleBoard;
use super::homography::Homography;

/// Board neighbourhood (rows and columns either side) of the local homography.
const BIAS_RADIUS: i64 = 2;
/// Dots needed for a local homography.
const MIN_BIAS_DOTS: usize = 6;

/// Offsets `ellipse centre - image of dot centre`, pixels, for the found
/// dots `(row, col, ellipse centre)` (any subset of the board, any order);
/// `None` where no local homography could be fitted.
pub fn perspective_bias(
    dots: &[(usize, usize, Vector2<f64>)],
    board: &CircleBoard,
) -> Vec<Option<Vector2<f64>>> {
    let found: HashMap<(i64, i64), Vector2<f64>> = dots
        .iter()
        .map(|&(r, c, p)| ((r as i64, c as i64), p))
        .collect();
    dots.iter()
        .map(|&(row, col, _)| {
            let (mut plane, mut image) = (Vec::new(), Vec::new());
            for dr in -BIAS_RADIUS..=BIAS_RADIUS {
                for dc in -BIAS_RADIUS..=BIAS_RADIUS {
                    let (r, c) = (row as i64 + dr, col as i64 + dc);
                    if let Some(&p) = found.get(&(r, c)) {
                        let m = board.dot_centre_mm(r as usize, c as usize);
                        plane.push(Vector2::new(m[0], m[1]));
                        image.push(p);
                    }
                }
            }
            if plane.len() < MIN_BIAS_DOTS {
                return None;
            }
            let h = Homography::fit(&plane, &image)?;
            let m = board.dot_centre_mm(row, col);
            let radius = 0.5 * board.dot_diameter_at_mm(row, col);
            h.circle_centre_bias(&Vector2::new(m[0], m[1]), radius)
        })
        .collect()
}
