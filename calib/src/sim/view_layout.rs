//! Where a simulated campaign puts the board in the image and how it tilts
//! it (issue 4 campaign design, BENCHMARKS.md "Camera"): the random layout
//! of the first campaigns, and a planned (stratified) one whose board
//! images reach every region of the frame, corners included, each region
//! seeing the board tilted in every direction.

use std::f64::consts::TAU;

use nalgebra::{Isometry3, Point2, Translation3, UnitQuaternion, Vector2, Vector3};
use rand::{rngs::StdRng, Rng};

use super::view_spec::{ViewCampaignSpec, ViewLayout};

/// Stratified layout: slide iterations to fit the board into the frame,
/// their overshoot, and the extra margin (px) between the dot centres and
/// the frame that leaves room for the centroid offsets.
const FIT_ITERATIONS: usize = 8;
const FIT_OVERSHOOT: f64 = 1.05;
const FIT_EXTRA_MARGIN_PX: f64 = 1.0;
/// How far (fraction of the image size) the stratified layout's aim cells
/// reach beyond each edge of the frame.
const STRATIFIED_AIM_OVERREACH: f64 = 0.25;
/// Range of the random layout's aim point, as fractions of the image size.
const RANDOM_AIM_FRACTION: (f64, f64) = (0.1, 0.9);
/// `pi (3 - sqrt 5)`: successive multiples spread evenly round the circle.
const GOLDEN_ANGLE_RAD: f64 = 2.399_963_229_728_653;

/// The board pose that puts the board centre's image at `aim`, the board
/// centre `distance_mm` from the camera.
pub(crate) fn board_pose(
    spec: &ViewCampaignSpec,
    aim: &Point2<f64>,
    distance_mm: f64,
    rotation: UnitQuaternion<f64>,
) -> Option<Isometry3<f64>> {
    let ray = spec.intrinsics.pixel_to_ray(aim)?;
    let centre_camera = Vector3::new(ray.x, ray.y, 1.0).normalize() * distance_mm;
    let t = centre_camera - rotation * spec.board.centre().coords;
    Some(Isometry3::from_parts(Translation3::from(t), rotation))
}

/// Like [`board_pose`], then slides the board's image (same distance and
/// attitude) just far enough to bring every dot inside the frame, so that
/// aims near an edge or corner put the board against that edge or corner;
/// `None` if the board's image is larger than the frame.
pub(crate) fn fit_into_frame(
    spec: &ViewCampaignSpec,
    mut aim: Point2<f64>,
    distance_mm: f64,
    rotation: UnitQuaternion<f64>,
) -> Option<Isometry3<f64>> {
    let (w, h) = (spec.image_size.width as f64, spec.image_size.height as f64);
    let m = spec.margin_px + FIT_EXTRA_MARGIN_PX;
    let board = &spec.board;
    for _ in 0..FIT_ITERATIONS {
        let pose = board_pose(spec, &aim, distance_mm, rotation)?;
        let (mut lo, mut hi) = (Point2::new(f64::INFINITY, f64::INFINITY), Point2::origin());
        for row in 0..board.rows {
            for col in 0..board.cols {
                let p = spec.intrinsics.project(&(pose * board.point(row, col)))?;
                lo = lo.inf(&p);
                hi = hi.sup(&p);
            }
        }
        if hi.x - lo.x > w - 1.0 - 2.0 * m || hi.y - lo.y > h - 1.0 - 2.0 * m {
            return None;
        }
        let shift = |lo: f64, hi: f64, size: f64| {
            if lo < m {
                m - lo
            } else if hi > size - 1.0 - m {
                size - 1.0 - m - hi
            } else {
                0.0
            }
        };
        let d = Vector2::new(shift(lo.x, hi.x, w), shift(lo.y, hi.y, h));
        if d == Vector2::zeros() {
            return Some(pose);
        }
        // Perspective and distortion make the image move a little less or
        // more than the aim: overshoot slightly and re-check.
        aim += d * FIT_OVERSHOOT;
    }
    None
}

/// Where one view puts the board: the board centre's image (fractions of
/// the image size) and the board's attitude (tilt axis direction in the
/// image plane, roll about the board normal).
pub(crate) struct Placement {
    pub aim_fraction: Point2<f64>,
    pub tilt_axis_rad: f64,
    pub roll_rad: f64,
}

/// Draw view `index` of `views` for `layout`.
pub(crate) fn placement(
    layout: ViewLayout,
    index: usize,
    views: usize,
    rng: &mut StdRng,
) -> Placement {
    match layout {
        ViewLayout::Random => Placement {
            aim_fraction: Point2::new(
                rng.random_range(RANDOM_AIM_FRACTION.0..RANDOM_AIM_FRACTION.1),
                rng.random_range(RANDOM_AIM_FRACTION.0..RANDOM_AIM_FRACTION.1),
            ),
            tilt_axis_rad: rng.random_range(0.0..TAU),
            roll_rad: rng.random_range(0.0..TAU),
        },
        ViewLayout::Stratified {
            cells_x,
            cells_y,
            roll_spread_deg,
        } => stratified(
            index,
            cells_x.max(1),
            cells_y.max(1),
            roll_spread_deg,
            views,
            rng,
        ),
    }
}

/// A planned view: views cycle through the `cells_x x cells_y` image cells
/// (corners included); the k-th visit of a cell tilts the board about an
/// axis `k` equal steps round the circle from the cell's first, so every
/// region of the image sees the board tilted in every direction. The
/// board's rows stay within `roll_spread_deg` of the image rows (either
/// way round, alternating): a board pushed into a corner then fills it.
/// Jitter within the cell and the step keeps views distinct.
fn stratified(
    index: usize,
    cells_x: u32,
    cells_y: u32,
    roll_spread_deg: f64,
    views: usize,
    rng: &mut StdRng,
) -> Placement {
    let cells = (cells_x * cells_y) as usize;
    let cell = index % cells;
    let visit = index / cells;
    let visits = views.div_ceil(cells).max(1);
    let (col, row) = (
        (cell as u32 % cells_x) as f64,
        (cell as u32 / cells_x) as f64,
    );
    // Cells tile the frame widened by STRATIFIED_AIM_OVERREACH each side:
    // edge and corner cells aim mostly outside the frame and the board is
    // pushed flat against the edge, or into the corner.
    let span = 1.0 + 2.0 * STRATIFIED_AIM_OVERREACH;
    let aim_fraction = Point2::new(
        (col + rng.random_range(0.0..1.0)) / cells_x as f64 * span - STRATIFIED_AIM_OVERREACH,
        (row + rng.random_range(0.0..1.0)) / cells_y as f64 * span - STRATIFIED_AIM_OVERREACH,
    );
    let step = TAU / visits as f64;
    // Offset the cells' starting directions by the golden angle so that
    // neighbouring cells do not share tilt directions.
    let start = cell as f64 * GOLDEN_ANGLE_RAD;
    let tilt_axis_rad = start + visit as f64 * step + rng.random_range(0.0..step);
    let spread = roll_spread_deg.clamp(0.0, 180.0).to_radians();
    let jitter = if spread > 0.0 {
        rng.random_range(-spread..=spread)
    } else {
        0.0
    };
    let half_turns = (index % 2) as f64 * std::f64::consts::PI;
    Placement {
        aim_fraction,
        tilt_axis_rad,
        roll_rad: half_turns + jitter,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::point_views::{simulate_views, Board};

    /// Distance (fraction of the image width, Chebyshev) from a frame
    /// corner within which some dot must come: a tilted board's image is a
    /// trapezoid, so even pushed against both edges its nearest dot stays
    /// 4–12% of the width from the frame corner.
    const CORNER_REACH: f64 = 0.15;

    #[test]
    fn default_boards_span_half_the_field_of_view() {
        let modern = ViewCampaignSpec::modern_1280x1024(0).board;
        let paper = ViewCampaignSpec::paper_752x582(0).board;
        assert_eq!((modern.rows, modern.cols), (15, 19));
        assert_eq!((paper.rows, paper.cols), (11, 14));
        assert_eq!(Board::standard().rows, 9);
    }

    #[test]
    fn stratified_views_reach_every_corner_and_tilt_both_ways() {
        for spec in [
            ViewCampaignSpec::modern_1280x1024(3),
            ViewCampaignSpec::paper_752x582(4),
        ] {
            let sims = simulate_views(&spec).unwrap();
            let (w, h) = (spec.image_size.width as f64, spec.image_size.height as f64);
            let corners = [(0.0, 0.0), (w, 0.0), (0.0, h), (w, h)];
            for (x, y) in corners {
                let nearest = sims
                    .iter()
                    .flat_map(|s| &s.observations.dots)
                    .map(|d| (d.pixel.x - x).abs().max((d.pixel.y - y).abs()))
                    .fold(f64::INFINITY, f64::min);
                println!("corner ({x}, {y}) of {w}x{h}: nearest dot {nearest:.0} px");
                assert!(
                    nearest < CORNER_REACH * w,
                    "corner ({x}, {y}) of {w}x{h}: nearest dot {nearest} px"
                );
            }
            // Board normals (camera frame) lean every way: both signs of
            // the normal's x and y components occur in every third of views.
            for chunk in sims.chunks(sims.len() / 3) {
                let normals: Vec<_> = chunk
                    .iter()
                    .map(|s| s.camera_to_target.rotation * Vector3::z())
                    .collect();
                for axis in 0..2 {
                    assert!(normals.iter().any(|n| n[axis] > 0.1));
                    assert!(normals.iter().any(|n| n[axis] < -0.1));
                }
            }
            assert!(sims
                .iter()
                .all(|s| (spec.tilt_deg.0..=spec.tilt_deg.1).contains(&s.tilt_deg)));
        }
    }
}
