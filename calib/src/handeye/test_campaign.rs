//! Test-only: a simulated flange-pose campaign with known truth, and the
//! lies the screening must catch.

use nalgebra::Point2;
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, Normal};

use super::calibrate::FlangeOptions;
use super::view::FlangeView;
use crate::camera::model::Intrinsics;
use crate::geometry::{pose_from_matrix_rows, Pose};
use crate::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use crate::vision::BoardPoint;

/// Poses of the campaign (issue 14's test: 20).
pub const POSES: usize = 20;

pub struct FlangeCampaign {
    pub campaign: Campaign,
    pub target_to_base: Pose,
    pub flange_to_camera: Pose,
    /// The flange poses of the true robot at its true joints.
    pub flanges: Vec<Pose>,
}

impl FlangeCampaign {
    pub fn new(seed: u64) -> Self {
        let spec = CampaignSpec {
            cal_poses: POSES,
            val_poses: 0,
            ..CampaignSpec::standard("irb2400", seed).unwrap()
        };
        let campaign = simulate_campaign(&spec).unwrap();
        let t = &campaign.truth;
        let flanges = campaign
            .poses
            .iter()
            .map(|p| t.robot.base_to_flange(&p.true_joints_rad).unwrap())
            .collect();
        Self {
            target_to_base: pose_from_matrix_rows(&t.target_to_base).unwrap(),
            flange_to_camera: pose_from_matrix_rows(&t.flange_to_camera).unwrap(),
            campaign,
            flanges,
        }
    }

    pub fn intrinsics(&self) -> Intrinsics {
        self.campaign.truth.intrinsics
    }

    /// The user's rough camera guess: 2 % off in focal, 10 px in the
    /// centre, no distortion.
    pub fn options(&self) -> FlangeOptions {
        let t = self.intrinsics();
        FlangeOptions {
            start_intrinsics: Intrinsics::pinhole(
                t.fx * 1.02,
                t.fy * 1.02,
                t.cx + 10.0,
                t.cy - 10.0,
            ),
            distortion: true,
            hold_intrinsics: false,
            fit_board_scale: false,
            estimate_flange_noise: false,
        }
    }

    /// The views with the simulator's own noisy pixels, or (with `noise`)
    /// fresh noise of the campaign's sigma drawn from `noise`'s seed.
    pub fn views(&self, noise: Option<u64>) -> Vec<FlangeView> {
        let board = &self.campaign.truth.board;
        let sigma = self.campaign.truth.pixel_sigma_px;
        let mut rng = StdRng::seed_from_u64(noise.unwrap_or(0));
        let normal = Normal::new(0.0, sigma).unwrap();
        self.campaign
            .poses
            .iter()
            .zip(&self.flanges)
            .map(|(p, f)| {
                let pixels: Vec<Point2<f64>> = match noise {
                    None => p.observed_px.clone(),
                    Some(_) => p
                        .ideal_px
                        .iter()
                        .map(|q| {
                            Point2::new(
                                q.x + normal.sample(&mut rng),
                                q.y + normal.sample(&mut rng),
                            )
                        })
                        .collect(),
                };
                let points = (0..board.rows)
                    .flat_map(|r| (0..board.cols).map(move |c| (r, c)))
                    .zip(pixels)
                    .map(|((row, col), uv)| {
                        let t = board.point(row, col);
                        BoardPoint {
                            row,
                            col,
                            target_mm: [t.x, t.y, t.z],
                            x_px: uv.x,
                            y_px: uv.y,
                        }
                    })
                    .collect();
                FlangeView {
                    base_to_flange: *f,
                    points,
                }
            })
            .collect()
    }
}
