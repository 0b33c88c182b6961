//! One image of a flange-pose campaign: where the controller says the
//! flange was, and the board points found in the image.

use nalgebra::{Point2, Point3};

use crate::geometry::Pose;
use crate::vision::BoardPoint;

/// One pose of the campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct FlangeView {
    /// The flange pose in the robot base frame, as the controller reports
    /// it (`p_base = base_to_flange * p_flange`), mm.
    pub base_to_flange: Pose,
    /// Identified board points of the image.
    pub points: Vec<BoardPoint>,
}

impl FlangeView {
    /// `(target point mm, pixel)` pairs, the form the camera code uses.
    pub fn pairs(&self) -> Vec<(Point3<f64>, Point2<f64>)> {
        self.points
            .iter()
            .map(|p| {
                (
                    Point3::new(p.target_mm[0], p.target_mm[1], p.target_mm[2]),
                    Point2::new(p.x_px, p.y_px),
                )
            })
            .collect()
    }
}
