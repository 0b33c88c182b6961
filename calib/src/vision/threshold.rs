//! Local (adaptive) threshold via an integral image (method.md §1: the board
//! is lit unevenly and vignetted, so one global threshold cannot separate
//! dark dots from the light board everywhere).

#[cfg(test)]
use super::image::GrayImage;
use super::image::GreyLevels;

/// Fraction of the shorter image side used as the local-mean window radius.
pub const WINDOW_RADIUS_FRACTION: f64 = 1.0 / 16.0;
/// Bounds of the automatic window radius, pixels.
pub const MIN_WINDOW_RADIUS_PX: usize = 8;
pub const MAX_WINDOW_RADIUS_PX: usize = 128;
/// A pixel is dark when it is below the local mean by at least this
/// fraction of the mean ...
pub const RELATIVE_OFFSET: f32 = 0.10;
/// ... and at least this many grey levels (noise guard).
pub const MIN_OFFSET_GREY: f32 = 8.0;

/// Automatic window radius for an image: larger than a dot, smaller than
/// the scale of the lighting variation.
pub fn auto_window_radius(width: usize, height: usize) -> usize {
    let r = (width.min(height) as f64 * WINDOW_RADIUS_FRACTION).round() as usize;
    r.clamp(MIN_WINDOW_RADIUS_PX, MAX_WINDOW_RADIUS_PX)
}

/// Side of the blocks the local mean is computed on, pixels. The mean over
/// a window of ~100 px is smooth, so block means, a box filter over blocks
/// and bilinear interpolation back to pixels cost a fraction of a per-pixel
/// integral image with no visible difference in the threshold.
pub const BLOCK_PX: usize = 8;

/// Per-pixel dark threshold, kept as block values and produced one image
/// row at a time (no full-size buffer).
#[derive(Debug, Clone)]
pub struct LocalThreshold {
    blocks_wide: usize,
    blocks_high: usize,
    block_thr: Vec<f32>,
    /// Per image column: left block, right block, weight of the right one.
    xs: Vec<(usize, usize, f32)>,
}

fn interp(p: usize, n: usize) -> (usize, usize, f32) {
    let f = ((p as f32 + 0.5) / BLOCK_PX as f32 - 0.5).max(0.0);
    let i0 = (f as usize).min(n - 1);
    let i1 = (i0 + 1).min(n - 1);
    (i0, i1, (f - i0 as f32).min(1.0))
}

impl LocalThreshold {
    /// Writes the thresholds of image row `y` into `out` (image width long).
    pub fn row(&self, y: usize, out: &mut [f32], scratch: &mut Vec<f32>) {
        let bw = self.blocks_wide;
        let (y0, y1, fy) = interp(y, self.blocks_high);
        scratch.clear();
        scratch.extend((0..bw).map(|bx| {
            self.block_thr[y0 * bw + bx] * (1.0 - fy) + self.block_thr[y1 * bw + bx] * fy
        }));
        for (o, &(x0, x1, fx)) in out.iter_mut().zip(&self.xs) {
            *o = scratch[x0] * (1.0 - fx) + scratch[x1] * fx;
        }
    }

    /// The whole threshold image (for tests and inspection).
    pub fn to_image(&self, height: usize) -> Vec<f32> {
        let w = self.xs.len();
        let mut out = vec![0.0f32; w * height];
        let mut scratch = Vec::new();
        for y in 0..height {
            self.row(y, &mut out[y * w..(y + 1) * w], &mut scratch);
        }
        out
    }
}

/// Grey level below which each pixel counts as dark, from the mean of the
/// window of about `(2 radius + 1)^2` pixels around it (clipped at the
/// image border), computed through an integral image of block sums.
pub fn local_threshold<I: GreyLevels>(img: &I, radius: usize) -> LocalThreshold {
    let (w, h) = (img.width(), img.height());
    let (bw, bh) = (w.div_ceil(BLOCK_PX), h.div_ceil(BLOCK_PX));
    let mut sums = vec![0.0f64; bw * bh];
    // Each block row's pixel rows are added column-wise first (8-bit levels
    // sum exactly in f32 over a block row), then split into blocks.
    let mut column_sums = vec![0.0f32; w];
    for by in 0..bh {
        column_sums.fill(0.0);
        for y in by * BLOCK_PX..((by + 1) * BLOCK_PX).min(h) {
            img.add_row(y, &mut column_sums);
        }
        let out = &mut sums[by * bw..(by + 1) * bw];
        for (o, chunk) in out.iter_mut().zip(column_sums.chunks(BLOCK_PX)) {
            *o = chunk.iter().sum::<f32>() as f64;
        }
    }
    let count = |bx: usize, by: usize| -> f64 {
        let cw = (w - bx * BLOCK_PX).min(BLOCK_PX);
        let ch = (h - by * BLOCK_PX).min(BLOCK_PX);
        (cw * ch) as f64
    };
    // Integral images of block sums and pixel counts.
    let stride = bw + 1;
    let mut int_sum = vec![0.0f64; stride * (bh + 1)];
    let mut int_cnt = vec![0.0f64; stride * (bh + 1)];
    for by in 0..bh {
        let (mut rs, mut rc) = (0.0, 0.0);
        for bx in 0..bw {
            rs += sums[by * bw + bx];
            rc += count(bx, by);
            int_sum[(by + 1) * stride + bx + 1] = int_sum[by * stride + bx + 1] + rs;
            int_cnt[(by + 1) * stride + bx + 1] = int_cnt[by * stride + bx + 1] + rc;
        }
    }
    let rb = (radius as f64 / BLOCK_PX as f64).round().max(1.0) as usize;
    let mut block_thr = vec![0.0f32; bw * bh];
    for by in 0..bh {
        let (y0, y1) = (by.saturating_sub(rb), (by + rb + 1).min(bh));
        for bx in 0..bw {
            let (x0, x1) = (bx.saturating_sub(rb), (bx + rb + 1).min(bw));
            let box_of = |a: &[f64]| {
                a[y1 * stride + x1] - a[y1 * stride + x0] - a[y0 * stride + x1]
                    + a[y0 * stride + x0]
            };
            let mean = (box_of(&int_sum) / box_of(&int_cnt)) as f32;
            block_thr[by * bw + bx] = mean - (RELATIVE_OFFSET * mean).max(MIN_OFFSET_GREY);
        }
    }
    LocalThreshold {
        blocks_wide: bw,
        blocks_high: bh,
        block_thr,
        xs: (0..w).map(|x| interp(x, bw)).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dark_spot_on_gradient_is_below_threshold_and_background_is_not() {
        let (w, h) = (120, 80);
        let mut data = vec![0.0f32; w * h];
        for y in 0..h {
            for x in 0..w {
                // Strong left-to-right illumination gradient (60 grey levels).
                data[y * w + x] = 80.0 + 0.5 * x as f32;
            }
        }
        data[40 * w + 100] = 30.0;
        let img = GrayImage::new(w, h, data).unwrap();
        let thr = local_threshold(&img, 10).to_image(h);
        assert!(img.at(100, 40) < thr[40 * w + 100]);
        for (v, t) in img.data.iter().zip(&thr).take(30 * w) {
            assert!(v >= t, "background {v} flagged dark (threshold {t})");
        }
    }
}
