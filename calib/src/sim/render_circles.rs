//! Circle-board renderer (issues 3 and 14): robocal's symmetric dot grid
//! (with or without origin marker) and OpenCV's asymmetric circle grid,
//! through the simulator's camera and pipeline of `render.rs` (exact inverse
//! mapping through the Brown–Conrady model, supersampled edges, blur,
//! vignetting, noise). The truth of a dot is the projection of its 3-D
//! centre, not a blob centroid.

use nalgebra::{Isometry3, Point3, Vector2};
use rand::Rng;

use super::render::{
    board_point, check, finish, gaussian_blur, RenderError, RenderOptions, RenderedView, TruthDot,
};
use crate::camera::model::Intrinsics;
use crate::vision::circle_board::CircleBoard;
use crate::vision::image::GrayImage;
use crate::vision::target::TargetSpec;

/// What the board looks like at a board-plane point (mm).
struct Scene<'a> {
    board: &'a CircleBoard,
    opts: &'a RenderOptions,
    /// Extent of the dot centres, mm: `(x_max, y_max)` (minima are 0).
    extent: (f64, f64),
}

impl Scene<'_> {
    fn new<'a>(board: &'a CircleBoard, opts: &'a RenderOptions) -> Scene<'a> {
        let mut extent = (0.0f64, 0.0f64);
        for row in 0..board.rows() {
            for col in 0..board.cols() {
                let m = board.dot_centre_mm(row, col);
                extent = (extent.0.max(m[0]), extent.1.max(m[1]));
            }
        }
        Scene {
            board,
            opts,
            extent,
        }
    }

    fn on_board(&self, p: Vector2<f64>) -> bool {
        let m = self.opts.board_margin_mm;
        p.x >= -m && p.y >= -m && p.x <= self.extent.0 + m && p.y <= self.extent.1 + m
    }

    /// The dot nearest `p`: centre and radius, mm. Dots sit on a square
    /// lattice (`CircleBoard::site`), so the nearest lattice site holds it.
    fn nearest_dot(&self, p: Vector2<f64>) -> Option<(Vector2<f64>, f64)> {
        let b = self.board;
        let step = b.site_step_mm();
        // Site coordinates of p: invert the board's site map.
        let (a, s) = match b {
            CircleBoard::Dots(_) => (p.x / step, p.y / step),
            CircleBoard::Asymmetric(t) => {
                let (x, y) = (p.x / t.pitch_mm, p.y / t.pitch_mm);
                (0.5 * (x + y), 0.5 * (y - x))
            }
        };
        let (a, s) = (a.round() as i64, s.round() as i64);
        let (row, col) = match b {
            CircleBoard::Dots(_) => (s, a),
            CircleBoard::Asymmetric(_) => {
                // x = a - s, y = a + s; col = (x - row mod 2) / 2.
                let (x, y) = (a - s, a + s);
                (y, (x - y.rem_euclid(2)).div_euclid(2))
            }
        };
        if row < 0 || col < 0 || row >= b.rows() as i64 || col >= b.cols() as i64 {
            return None;
        }
        let (row, col) = (row as usize, col as usize);
        let m = b.dot_centre_mm(row, col);
        Some((
            Vector2::new(m[0], m[1]),
            0.5 * b.dot_diameter_at_mm(row, col),
        ))
    }

    fn grey(&self, p: Vector2<f64>) -> f64 {
        if !self.on_board(p) {
            return self.opts.background_grey;
        }
        match self.nearest_dot(p) {
            Some((c, r)) if (p - c).norm_squared() <= r * r => self.opts.dot_grey,
            _ => self.opts.board_grey,
        }
    }

    /// Whether an edge (dot outline or board border) passes within `reach`
    /// mm of `p`, so the pixel needs supersampling. The origin marker may
    /// reach beyond its lattice cell: it is checked too.
    fn near_edge(&self, p: Vector2<f64>, reach: f64) -> bool {
        let m = self.opts.board_margin_mm;
        let border = [
            p.x + m,
            p.y + m,
            self.extent.0 + m - p.x,
            self.extent.1 + m - p.y,
        ];
        if border.iter().any(|d| d.abs() <= reach) {
            return true;
        }
        let near = |c: Vector2<f64>, r: f64| ((p - c).norm() - r).abs() <= reach;
        if self.nearest_dot(p).is_some_and(|(c, r)| near(c, r)) {
            return true;
        }
        self.board.marker_diameter_mm().is_some_and(|d| {
            let o = self.board.dot_centre_mm(0, 0);
            near(Vector2::new(o[0], o[1]), 0.5 * d)
        })
    }

    fn shade(&self, c: &[Option<Vector2<f64>>; 4], s: usize) -> f64 {
        let all: Option<Vec<Vector2<f64>>> = c.iter().copied().collect();
        let Some(c) = all else {
            return self.opts.background_grey; // horizon or behind the camera
        };
        let centre = (c[0] + c[1] + c[2] + c[3]) * 0.25;
        let reach = c.iter().map(|p| (p - centre).norm()).fold(0.0, f64::max);
        if !self.near_edge(centre, reach) {
            return self.grey_with_marker(centre);
        }
        let mut sum = 0.0;
        for a in 0..s {
            let ty = (a as f64 + 0.5) / s as f64;
            let left = c[0] + (c[2] - c[0]) * ty;
            let right = c[1] + (c[3] - c[1]) * ty;
            for b in 0..s {
                let tx = (b as f64 + 0.5) / s as f64;
                sum += self.grey_with_marker(left + (right - left) * tx);
            }
        }
        sum / (s * s) as f64
    }

    /// Grey level, with the origin marker drawn over its whole disc.
    fn grey_with_marker(&self, p: Vector2<f64>) -> f64 {
        if let Some(d) = self.board.marker_diameter_mm() {
            let o = self.board.dot_centre_mm(0, 0);
            if (p - Vector2::new(o[0], o[1])).norm() <= 0.5 * d {
                return self.opts.dot_grey;
            }
        }
        self.grey(p)
    }
}

/// Renders `board` seen by `camera` with the target at `camera_to_target`
/// (`p_camera = camera_to_target * p_target`).
pub fn render_circle_board<R: Rng + ?Sized>(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    board: &CircleBoard,
    width: usize,
    height: usize,
    opts: &RenderOptions,
    rng: &mut R,
) -> Result<RenderedView, RenderError> {
    board.validate()?;
    check(opts, width, height)?;
    let scene = Scene::new(board, opts);
    let target_to_camera = camera_to_target.inverse();
    let s = opts.supersampling;
    let mut data = vec![0.0f32; width * height];
    // Board points of the pixel corners, two corner rows at a time.
    let corner_row = |i: usize| -> Vec<Option<Vector2<f64>>> {
        (0..=width)
            .map(|j| board_point(camera, &target_to_camera, j as f64 - 0.5, i as f64 - 0.5))
            .collect()
    };
    let mut top = corner_row(0);
    for i in 0..height {
        let bottom = corner_row(i + 1);
        for j in 0..width {
            let corners = [top[j], top[j + 1], bottom[j], bottom[j + 1]];
            data[i * width + j] = scene.shade(&corners, s) as f32;
        }
        top = bottom;
    }
    if opts.blur_sigma_px > 0.0 {
        gaussian_blur(&mut data, width, height, opts.blur_sigma_px);
    }
    finish(&mut data, width, height, opts, rng);
    let truth = circle_truth(camera, camera_to_target, board, width, height);
    Ok(RenderedView {
        image: GrayImage {
            width,
            height,
            data,
        },
        truth,
    })
}

/// Projections of every dot centre, row-major.
pub fn circle_truth(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    board: &CircleBoard,
    width: usize,
    height: usize,
) -> Vec<TruthDot> {
    let mut out = Vec::with_capacity(board.dot_count());
    for row in 0..board.rows() {
        for col in 0..board.cols() {
            let m = board.dot_centre_mm(row, col);
            let p = camera_to_target * Point3::new(m[0], m[1], m[2]);
            let (x, y, visible) = match camera.project(&p) {
                Some(q) => (
                    q.x,
                    q.y,
                    q.x >= -0.5
                        && q.y >= -0.5
                        && q.x < width as f64 - 0.5
                        && q.y < height as f64 - 0.5,
                ),
                None => (f64::NAN, f64::NAN, false),
            };
            out.push(TruthDot {
                row,
                col,
                x,
                y,
                visible,
            });
        }
    }
    out
}

/// Renders the board seen by `camera` with the target at `camera_to_target`
/// (`p_camera = camera_to_target * p_target`).
pub fn render_target<R: Rng + ?Sized>(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    target: &TargetSpec,
    width: usize,
    height: usize,
    opts: &RenderOptions,
    rng: &mut R,
) -> Result<RenderedView, RenderError> {
    render_circle_board(
        camera,
        camera_to_target,
        &CircleBoard::Dots(*target),
        width,
        height,
        opts,
        rng,
    )
}

/// Projections of every dot centre, row-major.
pub fn target_truth(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    target: &TargetSpec,
    width: usize,
    height: usize,
) -> Vec<TruthDot> {
    circle_truth(
        camera,
        camera_to_target,
        &CircleBoard::Dots(*target),
        width,
        height,
    )
}
