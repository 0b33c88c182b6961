//! ChArUco board renderer (issue 14): the simulator's camera and pipeline
//! of `render.rs` (exact inverse mapping through the Brown–Conrady model,
//! supersampled edges, blur, vignetting, noise) with the board drawn as
//! OpenCV draws it (layout and marker bits of `vision::charuco`). The
//! truth of an inner corner is the projection of its 3-D position.

use nalgebra::{Isometry3, Point3, Vector2};
use rand::Rng;

use super::render::{board_point, check, finish, gaussian_blur, RenderError, RenderOptions};
use crate::camera::model::Intrinsics;
use crate::vision::aruco::Dictionary;
use crate::vision::charuco::{corner_mm, inner_corner_grid, CharucoSpec};
use crate::vision::image::GrayImage;

/// Ground truth of one inner chessboard corner: the same record as a dot's
/// (board indices, projection, visibility).
pub type TruthCorner = super::render::TruthDot;

/// A rendered ChArUco view and its truth (corners in OpenCV id order).
#[derive(Debug, Clone, PartialEq)]
pub struct RenderedCharuco {
    pub image: GrayImage,
    pub truth: Vec<TruthCorner>,
}

struct Scene<'a> {
    spec: &'a CharucoSpec,
    dict: &'a Dictionary,
    /// Marker id of each square (row-major), if any.
    ids: Vec<Option<usize>>,
    opts: &'a RenderOptions,
}

impl Scene<'_> {
    fn size_mm(&self) -> (f64, f64) {
        let s = self.spec.square_mm;
        (self.spec.cols() as f64 * s, self.spec.rows() as f64 * s)
    }

    fn grey(&self, p: Vector2<f64>) -> f64 {
        let (w, h) = self.size_mm();
        let m = self.opts.board_margin_mm;
        if p.x < -m || p.y < -m || p.x > w + m || p.y > h + m {
            return self.opts.background_grey;
        }
        if p.x < 0.0 || p.y < 0.0 || p.x >= w || p.y >= h {
            return self.opts.board_grey;
        }
        let s = self.spec.square_mm;
        let (col, row) = ((p.x / s) as usize, (p.y / s) as usize);
        let Some(id) = self.ids[row * self.spec.cols() + col] else {
            return self.opts.dot_grey; // black square
        };
        let inset = 0.5 * (s - self.spec.marker_mm);
        let (u, v) = (p.x - col as f64 * s - inset, p.y - row as f64 * s - inset);
        let mk = self.spec.marker_mm;
        if u < 0.0 || v < 0.0 || u >= mk || v >= mk {
            return self.opts.board_grey;
        }
        let n = self.dict.marker_size;
        let bit = mk / (n + 2) as f64;
        let (c, r) = ((u / bit) as usize, (v / bit) as usize);
        let white = (1..=n).contains(&r) && (1..=n).contains(&c) && self.dict.bit(id, r - 1, c - 1);
        if white {
            self.opts.board_grey
        } else {
            self.opts.dot_grey
        }
    }

    /// Whether a square, bit-cell or board edge lies within `reach` mm.
    fn near_edge(&self, p: Vector2<f64>, reach: f64) -> bool {
        let (w, h) = self.size_mm();
        let m = self.opts.board_margin_mm;
        let near_grid = |x: f64, pitch: f64| {
            let f = x / pitch;
            (f - f.round()).abs() * pitch <= reach
        };
        let border = [p.x + m, p.y + m, w + m - p.x, h + m - p.y];
        if border.iter().any(|d| d.abs() <= reach) {
            return true;
        }
        let s = self.spec.square_mm;
        if near_grid(p.x, s) || near_grid(p.y, s) {
            return true;
        }
        let inset = 0.5 * (s - self.spec.marker_mm);
        let bit = self.spec.marker_mm / (self.dict.marker_size + 2) as f64;
        let (u, v) = (p.x.rem_euclid(s) - inset, p.y.rem_euclid(s) - inset);
        let inside = |t: f64| t >= -reach && t <= self.spec.marker_mm + reach;
        inside(u) && inside(v) && (near_grid(u, bit) || near_grid(v, bit))
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

/// Renders the ChArUco board seen by `camera` with
/// `p_camera = camera_to_target * p_target`; `board_margin_mm` is the white
/// border around the squares.
pub fn render_charuco<R: Rng + ?Sized>(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    spec: &CharucoSpec,
    width: usize,
    height: usize,
    opts: &RenderOptions,
    rng: &mut R,
) -> Result<RenderedCharuco, RenderError> {
    spec.validate()?;
    check(opts, width, height)?;
    let dict = spec.dictionary()?;
    let mut ids = vec![None; spec.cols() * spec.rows()];
    for cell in crate::vision::charuco::marker_cells(spec) {
        ids[cell.row * spec.cols() + cell.col] = Some(cell.id);
    }
    let scene = Scene {
        spec,
        dict,
        ids,
        opts,
    };
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
    Ok(RenderedCharuco {
        image: GrayImage {
            width,
            height,
            data,
        },
        truth: charuco_truth(camera, camera_to_target, spec, width, height),
    })
}

/// Projections of every inner corner, OpenCV id order (row-major).
pub fn charuco_truth(
    camera: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    spec: &CharucoSpec,
    width: usize,
    height: usize,
) -> Vec<TruthCorner> {
    let (nx, ny) = inner_corner_grid(spec);
    let mut out = Vec::with_capacity(nx * ny);
    for row in 0..ny {
        for col in 0..nx {
            let m = corner_mm(spec, row, col);
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
