//! Random board views for detector tests and benchmarks (issue 3): a camera
//! 600–1000 mm from the board, 20–60 degrees between board and image plane,
//! random roll, the whole board inside the image.

use std::f64::consts::TAU;

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};
use rand::Rng;

use crate::camera::model::Intrinsics;
use crate::vision::target::TargetSpec;

/// Ranges of random views.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewRanges {
    pub distance_mm: (f64, f64),
    pub tilt_deg: (f64, f64),
    /// Largest offset of the aim point from the board centre, mm.
    pub aim_offset_mm: f64,
    /// Largest extra pan/tilt of the optical axis off the aim point, degrees.
    pub pointing_jitter_deg: f64,
    /// Every dot centre must lie this far inside the image, pixels.
    pub border_px: f64,
}

impl Default for ViewRanges {
    fn default() -> Self {
        Self {
            distance_mm: (600.0, 1000.0),
            tilt_deg: (20.0, 60.0),
            aim_offset_mm: 40.0,
            pointing_jitter_deg: 4.0,
            border_px: 40.0,
        }
    }
}

/// Tries per view before giving up on fitting the board in the image.
const MAX_VIEW_ATTEMPTS: usize = 1000;

/// The issue-3 reference camera for 1280x1024: fx = fy = 2000 px with mild
/// Brown–Conrady distortion (about 6 px at the image corners).
pub fn reference_camera() -> Intrinsics {
    Intrinsics {
        fx: 2000.0,
        fy: 2000.0,
        cx: 639.5,
        cy: 511.5,
        k1: -0.07,
        k2: 0.02,
        p1: 2e-4,
        p2: -1e-4,
        k3: 0.0,
    }
}

/// Draws `camera_to_target` for a random view with the whole board inside a
/// `width x height` image; `None` if the ranges make that impossible.
pub fn random_view<R: Rng + ?Sized>(
    camera: &Intrinsics,
    target: &TargetSpec,
    width: usize,
    height: usize,
    ranges: &ViewRanges,
    rng: &mut R,
) -> Option<Isometry3<f64>> {
    let centre = Vector3::new(
        0.5 * (target.cols - 1) as f64 * target.pitch_mm,
        0.5 * (target.rows - 1) as f64 * target.pitch_mm,
        0.0,
    );
    for _ in 0..MAX_VIEW_ATTEMPTS {
        let d = rng.random_range(ranges.distance_mm.0..=ranges.distance_mm.1);
        let tilt = rng
            .random_range(ranges.tilt_deg.0..=ranges.tilt_deg.1)
            .to_radians();
        let azimuth = rng.random_range(0.0..TAU);
        let roll = rng.random_range(0.0..TAU);
        let aim = centre
            + Vector3::new(
                rng.random_range(-1.0..=1.0) * ranges.aim_offset_mm,
                rng.random_range(-1.0..=1.0) * ranges.aim_offset_mm,
                0.0,
            );
        // The camera sits in front of the board (negative target z).
        let dir = Vector3::new(
            tilt.sin() * azimuth.cos(),
            tilt.sin() * azimuth.sin(),
            -tilt.cos(),
        );
        let position = aim + d * dir;
        let z = -dir;
        let helper = if z.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let x0 = helper.cross(&z).normalize();
        let y0 = z.cross(&x0);
        let r = Matrix3::from_columns(&[x0, y0, z]);
        let jitter = ranges.pointing_jitter_deg.to_radians();
        let spin = Rotation3::from_euler_angles(
            rng.random_range(-1.0..=1.0) * jitter,
            rng.random_range(-1.0..=1.0) * jitter,
            roll,
        );
        let rot = Rotation3::from_matrix_unchecked(r) * spin;
        let target_to_camera = Isometry3::from_parts(
            Translation3::from(position),
            UnitQuaternion::from_rotation_matrix(&rot),
        );
        let camera_to_target = target_to_camera.inverse();
        let inside = (0..target.rows).all(|row| {
            (0..target.cols).all(|col| {
                let m = target.dot_centre_mm(row, col);
                camera
                    .project(&(camera_to_target * Point3::new(m[0], m[1], m[2])))
                    .is_some_and(|p| {
                        p.x > ranges.border_px
                            && p.y > ranges.border_px
                            && p.x < width as f64 - ranges.border_px
                            && p.y < height as f64 - ranges.border_px
                    })
            })
        });
        if inside {
            return Some(camera_to_target);
        }
    }
    None
}
