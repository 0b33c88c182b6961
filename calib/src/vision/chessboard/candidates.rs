//! Corner candidates of a chessboard: saddle points of the smoothed image.
//!
//! Detection runs on a box-decimated copy (a few hundred thousand pixels
//! whatever the camera): the Hessian determinant of the smoothed grey levels
//! is strongly negative at an X-junction and near zero on straight edges, so
//! its local minima are the candidates. Each is then checked on a ring
//! around it: an X-junction shows four alternating light/dark sectors,
//! point-symmetric, while the T-junctions along the board's outer edge,
//! blob corners and texture do not.

use nalgebra::Vector2;

use crate::vision::image::{GrayImage, GreyLevels};

/// Smoothing of the decimated image before the Hessian, level pixels.
const RESPONSE_SIGMA_PX: f64 = 1.0;
/// Candidates must reach this fraction of the strongest saddle response
/// (contrast² scale: 0.01 keeps corners at a tenth of the best contrast).
const RESPONSE_FRACTION: f32 = 0.01;
/// Non-maximum suppression radius, level pixels.
const NMS_RADIUS_PX: isize = 2;
/// Ring radius of the sector check, level pixels, and samples on it.
const RING_RADIUS_PX: f64 = 3.5;
const RING_SAMPLES: usize = 32;
/// Least grey-level range on the ring (8-bit scale).
const MIN_RING_CONTRAST: f32 = 8.0;
/// Least fraction of ring samples whose opposite sample is on the same side
/// of the mid grey (point symmetry of an X-junction).
const MIN_RING_SYMMETRY: f64 = 0.8;
/// Most candidates kept (strongest first) per expected corner.
pub const MAX_CANDIDATES_PER_CORNER: usize = 12;
/// Gaussian kernel half-width in sigmas.
const KERNEL_SIGMAS: f64 = 3.0;

/// One saddle candidate, level-image coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    pub pos: Vector2<f64>,
    pub response: f32,
}

/// Decimation factors divisible by this read half of each block's rows.
const ROW_SUBSAMPLE_FACTOR: usize = 4;

/// Box-decimates `img` by `factor` (mean of each `factor`² block); level
/// pixel `(u, v)` has its centre at `((u + 0.5) f - 0.5, (v + 0.5) f - 0.5)`.
/// Factor 1 is an f32 copy.
pub fn decimate<I: GreyLevels>(img: &I, factor: usize) -> GrayImage {
    let factor = factor.max(1);
    let (w, h) = (img.width() / factor, img.height() / factor);
    let mut data = vec![0.0f32; w * h];
    // Factors divisible by 4 average the middle half of each block's rows
    // (same centre, half the memory read: the level only seeds the search,
    // and the smoothing after it removes what the skipped rows would).
    let (first_row, rows) = if factor.is_multiple_of(ROW_SUBSAMPLE_FACTOR) {
        (factor / 4, factor / 2)
    } else {
        (0, factor)
    };
    let norm = 1.0 / (rows * factor) as f32;
    // Rows are summed first (whole-row adds, which vectorise), then each
    // block of `factor` columns of the sum.
    let mut acc = vec![0.0f32; w * factor];
    for (v, out) in data.chunks_exact_mut(w.max(1)).enumerate() {
        acc.fill(0.0);
        for dy in first_row..first_row + rows {
            img.add_row(v * factor + dy, &mut acc);
        }
        for (o, block) in out.iter_mut().zip(acc.chunks_exact(factor)) {
            *o = block.iter().sum::<f32>() * norm;
        }
    }
    GrayImage {
        width: w,
        height: h,
        data,
    }
}

/// Separable Gaussian blur with clamped borders.
pub fn smooth(img: &GrayImage, sigma: f64) -> GrayImage {
    let r = (KERNEL_SIGMAS * sigma).ceil() as isize;
    let mut k: Vec<f32> = (-r..=r)
        .map(|x| (-((x * x) as f64) / (2.0 * sigma * sigma)).exp() as f32)
        .collect();
    let total: f32 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= total);
    let (w, h) = (img.width, img.height);
    let clamp = |x: isize, n: usize| x.clamp(0, n as isize - 1) as usize;
    let mut tmp = vec![0.0f32; w * h];
    let ru = r as usize;
    for y in 0..h {
        let row = &img.data[y * w..(y + 1) * w];
        let out = &mut tmp[y * w..(y + 1) * w];
        // Interior: one whole-slice multiply-add per tap (vectorises).
        if w > 2 * ru {
            let inner = &mut out[ru..w - ru];
            for (t, kv) in k.iter().enumerate() {
                for (o, v) in inner.iter_mut().zip(&row[t..t + w - 2 * ru]) {
                    *o += kv * v;
                }
            }
        }
        // Clamped reads only within `r` of the row's ends.
        for x in (0..ru.min(w)).chain(w.saturating_sub(ru).max(ru.min(w))..w) {
            out[x] = k
                .iter()
                .enumerate()
                .map(|(t, kv)| kv * row[clamp(x as isize + t as isize - r, w)])
                .sum();
        }
    }
    let mut out = vec![0.0f32; w * h];
    for y in 0..h {
        for (t, kv) in k.iter().enumerate() {
            let src = &tmp[clamp(y as isize + t as isize - r, h) * w..][..w];
            let dst = &mut out[y * w..(y + 1) * w];
            for (d, s) in dst.iter_mut().zip(src) {
                *d += kv * s;
            }
        }
    }
    GrayImage {
        width: w,
        height: h,
        data: out,
    }
}

/// Bilinear grey level, `None` outside.
pub fn bilinear(img: &GrayImage, x: f64, y: f64) -> Option<f32> {
    if x.is_nan() || y.is_nan() || x < 0.0 || y < 0.0 {
        return None;
    }
    // Non-negative: truncation is the floor (and no libm call).
    let (x0, y0) = (x as usize, y as usize);
    if x0 + 1 >= img.width || y0 + 1 >= img.height {
        return None;
    }
    let (fx, fy) = ((x - x0 as f64) as f32, (y - y0 as f64) as f32);
    let i = y0 * img.width + x0;
    let top = img.data[i] + (img.data[i + 1] - img.data[i]) * fx;
    let bottom =
        img.data[i + img.width] + (img.data[i + img.width + 1] - img.data[i + img.width]) * fx;
    Some(top + (bottom - top) * fy)
}

/// Saddle response `Ixy² - Ixx Iyy` (positive at X-junctions) of a smoothed image.
fn response(s: &GrayImage) -> Vec<f32> {
    let (w, h) = (s.width, s.height);
    let mut out = vec![0.0f32; w * h];
    for y in 1..h.saturating_sub(1) {
        for x in 1..w - 1 {
            let at = |dx: isize, dy: isize| {
                s.data[(y as isize + dy) as usize * w + (x as isize + dx) as usize]
            };
            let c = at(0, 0);
            let ixx = at(1, 0) - 2.0 * c + at(-1, 0);
            let iyy = at(0, 1) - 2.0 * c + at(0, -1);
            let ixy = 0.25 * (at(1, 1) - at(1, -1) - at(-1, 1) + at(-1, -1));
            out[y * w + x] = ixy * ixy - ixx * iyy;
        }
    }
    out
}

/// Whether the ring around `p` shows the four alternating, point-symmetric
/// sectors of an X-junction.
fn ring_is_x_junction(s: &GrayImage, p: Vector2<f64>, ring_dirs: &[(f64, f64)]) -> bool {
    let mut ring = [0.0f32; RING_SAMPLES];
    for (v, &(cos, sin)) in ring.iter_mut().zip(ring_dirs) {
        match bilinear(s, p.x + RING_RADIUS_PX * cos, p.y + RING_RADIUS_PX * sin) {
            Some(g) => *v = g,
            None => return false,
        }
    }
    let (lo, hi) = ring
        .iter()
        .fold((f32::MAX, f32::MIN), |(l, h), &v| (l.min(v), h.max(v)));
    if hi - lo < MIN_RING_CONTRAST {
        return false;
    }
    let mid = 0.5 * (lo + hi);
    let dark: Vec<bool> = ring.iter().map(|&v| v < mid).collect();
    let transitions = (0..RING_SAMPLES)
        .filter(|&k| dark[k] != dark[(k + 1) % RING_SAMPLES])
        .count();
    let symmetric = (0..RING_SAMPLES)
        .filter(|&k| dark[k] == dark[(k + RING_SAMPLES / 2) % RING_SAMPLES])
        .count();
    transitions == 4 && symmetric as f64 >= MIN_RING_SYMMETRY * RING_SAMPLES as f64
}

/// Saddle candidates of `level` (already decimated), strongest first, at
/// most `max_count`; also returns the smoothed level image.
pub fn find_candidates(level: &GrayImage, max_count: usize) -> (Vec<Candidate>, GrayImage) {
    let s = smooth(level, RESPONSE_SIGMA_PX);
    let r = response(&s);
    let (w, h) = (s.width, s.height);
    let best = r.iter().copied().fold(0.0f32, f32::max);
    let floor = RESPONSE_FRACTION * best;
    let mut out = Vec::new();
    if best <= 0.0 {
        return (out, s);
    }
    let m = NMS_RADIUS_PX;
    for y in m..h as isize - m {
        for x in m..w as isize - m {
            let v = r[y as usize * w + x as usize];
            if v <= floor {
                continue;
            }
            let mut is_max = true;
            'nms: for dy in -m..=m {
                for dx in -m..=m {
                    let o = r[(y + dy) as usize * w + (x + dx) as usize];
                    // Ties broken by raster order so a plateau keeps one.
                    if o > v || (o == v && (dy < 0 || (dy == 0 && dx < 0))) {
                        is_max = false;
                        break 'nms;
                    }
                }
            }
            if is_max {
                out.push(Candidate {
                    pos: sub_pixel_peak(&r, w, x as usize, y as usize),
                    response: v,
                });
            }
        }
    }
    out.sort_by(|a, b| b.response.total_cmp(&a.response));
    // The ring's directions once per image, not a sin and cos per sample.
    let ring_dirs: Vec<(f64, f64)> = (0..RING_SAMPLES)
        .map(|k| (std::f64::consts::TAU * k as f64 / RING_SAMPLES as f64).sin_cos())
        .map(|(sin, cos)| (cos, sin))
        .collect();
    out.retain(|c| ring_is_x_junction(&s, c.pos, &ring_dirs));
    out.truncate(max_count);
    (out, s)
}

/// Parabolic sub-pixel peak of the response around `(x, y)`.
fn sub_pixel_peak(r: &[f32], w: usize, x: usize, y: usize) -> Vector2<f64> {
    let at = |dx: isize, dy: isize| {
        r[(y as isize + dy) as usize * w + (x as isize + dx) as usize] as f64
    };
    let off = |m: f64, c: f64, p: f64| {
        let d = m - 2.0 * c + p;
        if d < 0.0 {
            (0.5 * (m - p) / d).clamp(-0.5, 0.5)
        } else {
            0.0
        }
    };
    let c = at(0, 0);
    Vector2::new(
        x as f64 + off(at(-1, 0), c, at(1, 0)),
        y as f64 + off(at(0, -1), c, at(0, 1)),
    )
}
