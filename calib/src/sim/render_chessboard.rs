//! Chessboard renderer (issue 14): the simulator's camera and pipeline of
//! `render.rs` (exact inverse mapping through the Brown–Conrady model,
//! supersampled edges, blur, vignetting, noise) with a chessboard of
//! `inner_corners + 1` squares per side, outer top-left square black, in a
//! white margin. The truth of an inner corner is the projection of its 3-D
//! position, OpenCV order (row-major, `cols` corners per row).

use nalgebra::{Isometry3, Point3, Vector2};
use rand::Rng;

use super::render::{board_point, check, finish, gaussian_blur, RenderError, RenderOptions};
use crate::camera::model::Intrinsics;
use crate::vision::chessboard::ChessboardSpec;
use crate::vision::image::GrayImage;

/// Ground truth of one inner corner: the same record as a dot's.
pub type TruthCorner = super::render::TruthDot;

/// A rendered chessboard view and its truth (corners in OpenCV order).
#[derive(Debug, Clone, PartialEq)]
pub struct RenderedChessboard {
    pub image: GrayImage,
    pub truth: Vec<TruthCorner>,
}

struct Scene<'a> {
    spec: &'a ChessboardSpec,
    opts: &'a RenderOptions,
}

impl Scene<'_> {
    /// Board extent in x and y (outer square edges), mm.
    fn extent_mm(&self) -> ([f64; 2], [f64; 2]) {
        let s = self.spec.square_mm;
        (
            [-s, self.spec.cols() as f64 * s],
            [-s, self.spec.rows() as f64 * s],
        )
    }

    fn grey(&self, p: Vector2<f64>) -> f64 {
        let ([x0, x1], [y0, y1]) = self.extent_mm();
        let m = self.opts.board_margin_mm;
        if p.x < x0 - m || p.y < y0 - m || p.x > x1 + m || p.y > y1 + m {
            return self.opts.background_grey;
        }
        if p.x < x0 || p.y < y0 || p.x >= x1 || p.y >= y1 {
            return self.opts.board_grey;
        }
        let s = self.spec.square_mm;
        let (col, row) = ((p.x / s).floor() as isize, (p.y / s).floor() as isize);
        if ChessboardSpec::square_is_black(row, col) {
            self.opts.dot_grey
        } else {
            self.opts.board_grey
        }
    }

    /// Whether a square or board edge lies within `reach` mm.
    fn near_edge(&self, p: Vector2<f64>, reach: f64) -> bool {
        let ([x0, x1], [y0, y1]) = self.extent_mm();
        let m = self.opts.board_margin_mm;
        let border = [p.x - x0 + m, p.y - y0 + m, x1 + m - p.x, y1 + m - p.y];
        if border.iter().any(|d| d.abs() <= reach) {
            return true;
        }
        let s = self.spec.square_mm;
        let near_grid = |x: f64| {
            let f = x / s;
            (f - f.round()).abs() * s <= reach
        };
        near_grid(p.x) || near_grid(p.y)
    }
}

fn shade(scene: &Scene, c: &[Vector2<f64>; 4], s: usize) -> f64 {
    let centre = (c[0] + c[1] + c[2] + c[3]) * 0.25;
    let reach = c.iter().map(|p| (p - centre).norm()).fold(0.0, f64::max);
    if !scene.near_edge(centre, reach) {
        return scene.grey(centre);
    }
    let mut sum = 0.0;
    for a in 0..s {
        let ty = (a as f64 + 0.5) / s as f64;
        let left = c[0] + (c[2] - c[0]) * ty;
        let right = c[1] + (c[3] - c[1]) * ty;
        for b in 0..s {
            sum += scene.grey(left + (right - left) * ((b as f64 + 0.5) / s as f64));
        }
    }
    sum / (s * s) as f64
}

/// Renders the chessboard seen by `camera` with
/// `p_camera = camera_to_target * p_target`; `board_margin_mm` is the white
/// border around the outer squares.
pub fn render_chessboard<R: Rng + ?Sized>(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    spec: &ChessboardSpec,
    width: usize,
    height: usize,
    opts: &RenderOptions,
    rng: &mut R,
) -> Result<RenderedChessboard, RenderError> {
    spec.validate()?;
    check(opts, width, height)?;
    let scene = Scene { spec, opts };
    let target_to_camera = camera_to_target.inverse();
    let corner_row = |i: usize| -> Vec<Option<Vector2<f64>>> {
        (0..=width)
            .map(|j| board_point(camera, &target_to_camera, j as f64 - 0.5, i as f64 - 0.5))
            .collect()
    };
    let mut data = vec![0.0f32; width * height];
    let mut top = corner_row(0);
    for i in 0..height {
        let bottom = corner_row(i + 1);
        for j in 0..width {
            let corners = [top[j], top[j + 1], bottom[j], bottom[j + 1]];
            data[i * width + j] = match corners {
                [Some(a), Some(b), Some(c), Some(d)] => {
                    shade(&scene, &[a, b, c, d], opts.supersampling)
                }
                _ => opts.background_grey,
            } as f32;
        }
        top = bottom;
    }
    if opts.blur_sigma_px > 0.0 {
        gaussian_blur(&mut data, width, height, opts.blur_sigma_px);
    }
    finish(&mut data, width, height, opts, rng);
    Ok(RenderedChessboard {
        image: GrayImage {
            width,
            height,
            data,
        },
        truth: chessboard_truth(camera, camera_to_target, spec, width, height),
    })
}

/// Projections of every inner corner, OpenCV order (row-major).
pub fn chessboard_truth(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    spec: &ChessboardSpec,
    width: usize,
    height: usize,
) -> Vec<TruthCorner> {
    let mut out = Vec::with_capacity(spec.corner_count());
    for row in 0..spec.rows() {
        for col in 0..spec.cols() {
            let m = spec.corner_mm(row, col);
            let q = camera.project(&(camera_to_target * Point3::new(m[0], m[1], m[2])));
            let (x, y) = q.map_or((f64::NAN, f64::NAN), |q| (q.x, q.y));
            let visible =
                x >= -0.5 && y >= -0.5 && x < width as f64 - 0.5 && y < height as f64 - 0.5;
            out.push(TruthCorner {
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
