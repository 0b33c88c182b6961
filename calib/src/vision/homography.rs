//! Plane-to-image homographies by the normalised DLT: the local model of the
//! board under perspective used to grow the lattice and to predict the
//! perspective bias of ellipse centres (method.md §1, §4 "beyond").

use nalgebra::{Matrix3, SMatrix, Vector2, Vector3};

/// A 3x3 homography mapping plane points to image points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Homography(pub Matrix3<f64>);

/// Similarity that moves points to zero mean and unit RMS norm / sqrt(2).
fn normaliser(points: &[Vector2<f64>]) -> Matrix3<f64> {
    let n = points.len() as f64;
    let mean = points.iter().fold(Vector2::zeros(), |a, p| a + p) / n;
    let rms = (points
        .iter()
        .map(|p| (p - mean).norm_squared())
        .sum::<f64>()
        / n)
        .sqrt();
    let s = if rms > 0.0 {
        std::f64::consts::SQRT_2 / rms
    } else {
        1.0
    };
    Matrix3::new(s, 0.0, -s * mean.x, 0.0, s, -s * mean.y, 0.0, 0.0, 1.0)
}

impl Homography {
    /// Fits `image ~ H plane` to >= 4 correspondences; `None` if degenerate.
    pub fn fit(plane: &[Vector2<f64>], image: &[Vector2<f64>]) -> Option<Self> {
        if plane.len() < 4 || plane.len() != image.len() {
            return None;
        }
        let (tp, ti) = (normaliser(plane), normaliser(image));
        let mut ata = SMatrix::<f64, 9, 9>::zeros();
        for (p, q) in plane.iter().zip(image) {
            let p = tp * Vector3::new(p.x, p.y, 1.0);
            let q = ti * Vector3::new(q.x, q.y, 1.0);
            let r1 = SMatrix::<f64, 9, 1>::from_column_slice(&[
                p.x,
                p.y,
                1.0,
                0.0,
                0.0,
                0.0,
                -q.x * p.x,
                -q.x * p.y,
                -q.x,
            ]);
            let r2 = SMatrix::<f64, 9, 1>::from_column_slice(&[
                0.0,
                0.0,
                0.0,
                p.x,
                p.y,
                1.0,
                -q.y * p.x,
                -q.y * p.y,
                -q.y,
            ]);
            ata += r1 * r1.transpose() + r2 * r2.transpose();
        }
        let eig = ata.symmetric_eigen();
        let (imin, _) = eig
            .eigenvalues
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))?;
        // Degenerate configurations have a second (near-)zero eigenvalue.
        let mut sorted: Vec<f64> = eig.eigenvalues.iter().copied().collect();
        sorted.sort_by(f64::total_cmp);
        if sorted[1] <= 1e-10 * sorted[8] {
            return None;
        }
        let h = eig.eigenvectors.column(imin);
        let hn = Matrix3::new(h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8]);
        let m = ti.try_inverse()? * hn * tp;
        let m = m / m[(2, 2)];
        m.iter().all(|v| v.is_finite()).then_some(Self(m))
    }

    /// Image of a plane point; `None` at the line at infinity.
    pub fn apply(&self, p: &Vector2<f64>) -> Option<Vector2<f64>> {
        let q = self.0 * Vector3::new(p.x, p.y, 1.0);
        (q.z.abs() > f64::EPSILON).then(|| Vector2::new(q.x / q.z, q.y / q.z))
    }

    /// Offset from the image of a circle's centre to the centre of the
    /// circle's image (an ellipse): `ellipse centre - H(centre)`.
    ///
    /// The image conic's centre is the pole of the line at infinity,
    /// `C'^-1 e3 = H C^-1 H^T e3`, with `C^-1 = diag(1, 1, -1/r^2)` for a
    /// circle of radius `r` about the (translated) origin.
    pub fn circle_centre_bias(&self, centre: &Vector2<f64>, radius: f64) -> Option<Vector2<f64>> {
        let shift = Matrix3::new(1.0, 0.0, centre.x, 0.0, 1.0, centre.y, 0.0, 0.0, 1.0);
        let h = self.0 * shift;
        let h3 = h.row(2);
        let v = h * Vector3::new(h3[0], h3[1], -h3[2] / (radius * radius));
        let truth = self.apply(centre)?;
        if v.z.abs() <= f64::EPSILON {
            return None;
        }
        Some(Vector2::new(v.x / v.z, v.y / v.z) - truth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_h() -> Homography {
        Homography(Matrix3::new(
            12.0, 2.0, 300.0, -1.5, 9.0, 200.0, 0.002, 0.004, 1.0,
        ))
    }

    #[test]
    fn fit_recovers_a_known_homography() {
        let h = sample_h();
        let plane: Vec<_> = (0..9)
            .map(|k| Vector2::new((k % 3) as f64 * 25.0, (k / 3) as f64 * 25.0))
            .collect();
        let image: Vec<_> = plane.iter().map(|p| h.apply(p).unwrap()).collect();
        let fit = Homography::fit(&plane, &image).unwrap();
        for (p, q) in plane.iter().zip(&image) {
            assert!((fit.apply(p).unwrap() - q).norm() < 1e-8);
        }
        let collinear: Vec<_> = (0..5).map(|k| Vector2::new(k as f64, 0.0)).collect();
        assert!(Homography::fit(&collinear, &collinear).is_none());
    }

    #[test]
    fn circle_bias_matches_sampled_ellipse_centre() {
        let h = sample_h();
        let (c, r) = (Vector2::new(50.0, 25.0), 4.0);
        // Ellipse centre = midpoint of extreme image points along u and v,
        // found by dense sampling of the circle.
        let pts: Vec<_> = (0..200_000)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / 200_000.0;
                h.apply(&(c + r * Vector2::new(t.cos(), t.sin()))).unwrap()
            })
            .collect();
        let umin = pts.iter().map(|p| p.x).fold(f64::MAX, f64::min);
        let umax = pts.iter().map(|p| p.x).fold(f64::MIN, f64::max);
        let vmin = pts.iter().map(|p| p.y).fold(f64::MAX, f64::min);
        let vmax = pts.iter().map(|p| p.y).fold(f64::MIN, f64::max);
        let centre = Vector2::new(0.5 * (umin + umax), 0.5 * (vmin + vmax));
        let bias = h.circle_centre_bias(&c, r).unwrap();
        let expect = centre - h.apply(&c).unwrap();
        assert!(bias.norm() > 1e-3, "bias {bias} should be visible");
        assert!((bias - expect).norm() < 1e-5, "{bias} vs {expect}");
    }
}
