//! Camera stations in the target frame: where a candidate pose puts the
//! camera before any robot is asked (the same geometry as the simulator's
//! stations, `sim/campaign.rs`, so that planned and simulated campaigns
//! share their ranges).

use nalgebra::{Point3, Rotation3, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng};

use crate::geometry::Pose;

/// Random aim point offset from the board centre (mm): the board need not
/// sit at the image centre, which helps the distortion terms.
pub const AIM_JITTER_MM: f64 = 30.0;
/// Roll of the camera about its line of sight (deg, both ways): rolls make
/// the wrist joints turn and separate their terms.
pub const ROLL_RANGE_DEG: f64 = 90.0;

/// One sampled station: the camera pose and the values it was drawn with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Station {
    pub target_to_camera: Pose,
    pub view_angle_rad: f64,
    pub distance_mm: f64,
}

/// The camera at `distance_mm` from `centre` along a direction
/// `view_angle_rad` from the board normal at `azimuth_rad`, looking at
/// `aim` (target frame, z into the board: the camera sits at negative z),
/// rolled by `roll_rad` about its line of sight.
pub fn station_at(
    centre: &Point3<f64>,
    aim: &Point3<f64>,
    view_angle_rad: f64,
    azimuth_rad: f64,
    distance_mm: f64,
    roll_rad: f64,
) -> Station {
    let dir = Vector3::new(
        view_angle_rad.sin() * azimuth_rad.cos(),
        view_angle_rad.sin() * azimuth_rad.sin(),
        -view_angle_rad.cos(),
    );
    let position = centre.coords + dir * distance_mm;
    let z = (aim.coords - position).normalize();
    // Any x orthogonal to z; the target's x unless z is nearly along it.
    let reference = if z.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let x0 = (reference - z * z.dot(&reference)).normalize();
    let y0 = z.cross(&x0);
    let look = Rotation3::from_basis_unchecked(&[x0, y0, z]);
    let roll = Rotation3::from_axis_angle(&Vector3::z_axis(), roll_rad);
    Station {
        target_to_camera: Pose::from_parts(
            position.into(),
            UnitQuaternion::from_rotation_matrix(&(look * roll)),
        ),
        view_angle_rad,
        distance_mm,
    }
}

/// A random station within the ranges (radians and mm).
pub fn random_station(
    centre: &Point3<f64>,
    view_angle_rad: (f64, f64),
    distance_mm: (f64, f64),
    rng: &mut StdRng,
) -> Station {
    let angle = rng.random_range(view_angle_rad.0..=view_angle_rad.1);
    let azimuth = rng.random_range(0.0..std::f64::consts::TAU);
    let distance = rng.random_range(distance_mm.0..=distance_mm.1);
    let aim = centre
        + Vector3::new(
            rng.random_range(-AIM_JITTER_MM..=AIM_JITTER_MM),
            rng.random_range(-AIM_JITTER_MM..=AIM_JITTER_MM),
            0.0,
        );
    let roll = rng
        .random_range(-ROLL_RANGE_DEG..=ROLL_RANGE_DEG)
        .to_radians();
    station_at(centre, &aim, angle, azimuth, distance, roll)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn station_respects_angle_distance_and_looks_at_the_aim() {
        let centre = Point3::new(100.0, 100.0, 0.0);
        let aim = Point3::new(110.0, 90.0, 0.0);
        let s = station_at(&centre, &aim, 0.5, 1.0, 800.0, 0.3);
        let pos = s.target_to_camera.translation.vector;
        assert!(((pos - centre.coords).norm() - 800.0).abs() < 1e-9);
        let normal_angle = ((centre.coords - pos).normalize().dot(&Vector3::z())).acos();
        assert!((normal_angle - 0.5).abs() < 1e-9);
        let axis = s.target_to_camera.rotation * Vector3::z();
        assert!((axis - (aim.coords - pos).normalize()).norm() < 1e-9);
    }
}
