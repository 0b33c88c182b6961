//! Local (adaptive) threshold via an integral image (method.md §1: the board
//! is lit unevenly and vignetted, so one global threshold cannot separate
//! dark dots from the light board everywhere).

use super::image::GrayImage;

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

/// Grey level below which each pixel counts as dark, from the mean of the
/// `(2 radius + 1)^2` window around it (clipped at the image border).
pub fn local_threshold(img: &GrayImage, radius: usize) -> Vec<f32> {
    let (w, h) = (img.width, img.height);
    let stride = w + 1;
    // Integral image with a zero first row and column; f64 keeps sums exact
    // enough for any accepted image size.
    let mut integral = vec![0.0f64; stride * (h + 1)];
    for y in 0..h {
        let mut row_sum = 0.0f64;
        let src = &img.data[y * w..(y + 1) * w];
        let (above, below) = integral.split_at_mut((y + 1) * stride);
        let above = &above[y * stride..];
        let out = &mut below[..stride];
        for x in 0..w {
            row_sum += src[x] as f64;
            out[x + 1] = above[x + 1] + row_sum;
        }
    }
    let mut thr = vec![0.0f32; w * h];
    for y in 0..h {
        let y0 = y.saturating_sub(radius);
        let y1 = (y + radius + 1).min(h);
        let top = &integral[y0 * stride..(y0 + 1) * stride];
        let bot = &integral[y1 * stride..(y1 + 1) * stride];
        let rows = (y1 - y0) as f64;
        let out = &mut thr[y * w..(y + 1) * w];
        for (x, o) in out.iter_mut().enumerate() {
            let x0 = x.saturating_sub(radius);
            let x1 = (x + radius + 1).min(w);
            let sum = bot[x1] - bot[x0] - top[x1] + top[x0];
            let mean = (sum / (rows * (x1 - x0) as f64)) as f32;
            *o = mean - (RELATIVE_OFFSET * mean).max(MIN_OFFSET_GREY);
        }
    }
    thr
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
                // Strong left-to-right illumination gradient.
                data[y * w + x] = 80.0 + 1.2 * x as f32;
            }
        }
        data[40 * w + 100] = 30.0;
        let img = GrayImage::new(w, h, data).unwrap();
        let thr = local_threshold(&img, 10);
        assert!(img.at(100, 40) < thr[40 * w + 100]);
        for (v, t) in img.data.iter().zip(&thr).take(30 * w) {
            assert!(v >= t, "background {v} flagged dark (threshold {t})");
        }
    }
}
