//! Connected components of the dark mask by run-length union-find, with area,
//! bounding box and first/second moments per component (method.md §1).
//!
//! Runs keep the cost proportional to the number of dark runs rather than
//! pixels, and nothing per-pixel is allocated beyond the threshold buffer.

use super::image::GrayImage;
use super::threshold::LocalThreshold;

/// One dark connected component (8-connected).
#[derive(Debug, Clone, PartialEq)]
pub struct Blob {
    /// Pixel count.
    pub area: f64,
    /// Centroid, pixels (pixel centre convention).
    pub cx: f64,
    pub cy: f64,
    /// Central second moments (covariance of pixel centres).
    pub mxx: f64,
    pub myy: f64,
    pub mxy: f64,
    /// Inclusive bounding box.
    pub x_min: usize,
    pub x_max: usize,
    pub y_min: usize,
    pub y_max: usize,
}

impl Blob {
    /// Whether the component touches the image border (a clipped dot).
    pub fn touches_border(&self, width: usize, height: usize) -> bool {
        self.x_min == 0 || self.y_min == 0 || self.x_max + 1 >= width || self.y_max + 1 >= height
    }

    /// Area of the ellipse with the same second moments (`4 pi sqrt(det)`);
    /// equals `area` for a filled ellipse, larger for rings, crosses, text.
    pub fn moment_ellipse_area(&self) -> f64 {
        let det = self.mxx * self.myy - self.mxy * self.mxy;
        4.0 * std::f64::consts::PI * det.max(0.0).sqrt()
    }

    /// Semi-axes (major, minor) of the moment ellipse, pixels.
    pub fn moment_semi_axes(&self) -> (f64, f64) {
        let tr = self.mxx + self.myy;
        let disc = ((self.mxx - self.myy).powi(2) + 4.0 * self.mxy * self.mxy).sqrt();
        let l1 = 0.5 * (tr + disc);
        let l2 = (0.5 * (tr - disc)).max(0.0);
        (2.0 * l1.sqrt(), 2.0 * l2.sqrt())
    }
}

#[derive(Default, Clone, Copy)]
struct Acc {
    n: f64,
    sx: f64,
    sy: f64,
    sxx: f64,
    syy: f64,
    sxy: f64,
    x_min: usize,
    x_max: usize,
    y_min: usize,
    y_max: usize,
}

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        let p = parent[i as usize];
        parent[i as usize] = parent[p as usize];
        i = p;
    }
    i
}

/// Sum of k^2 for k in 0..=m (0 for m < 0).
fn sum_sq(m: i64) -> f64 {
    if m < 0 {
        0.0
    } else {
        let m = m as f64;
        m * (m + 1.0) * (2.0 * m + 1.0) / 6.0
    }
}

/// Labels pixels darker than their threshold and returns the components with
/// at least `min_area` pixels.
pub fn find_blobs(img: &GrayImage, threshold: &LocalThreshold, min_area: f64) -> Vec<Blob> {
    let w = img.width;
    let (mut thr, mut scratch) = (vec![0.0f32; w], Vec::new());
    // (x0, x1 exclusive, row) per run, and union-find parents.
    let mut runs: Vec<(u32, u32, u32)> = Vec::new();
    let mut parent: Vec<u32> = Vec::new();
    let mut prev_start = 0usize;
    for y in 0..img.height {
        let row = &img.data[y * w..(y + 1) * w];
        threshold.row(y, &mut thr, &mut scratch);
        let cur_start = runs.len();
        let mut x = 0usize;
        while x < w {
            if row[x] < thr[x] {
                let x0 = x;
                while x < w && row[x] < thr[x] {
                    x += 1;
                }
                let id = runs.len() as u32;
                runs.push((x0 as u32, x as u32, y as u32));
                parent.push(id);
            } else {
                x += 1;
            }
        }
        // Merge with 8-connected runs of the previous row (both lists sorted).
        let mut p = prev_start;
        for c in cur_start..runs.len() {
            let (cx0, cx1, _) = runs[c];
            while p < cur_start && runs[p].1 < cx0 {
                p += 1;
            }
            let mut q = p;
            while q < cur_start && runs[q].0 <= cx1 {
                let (a, b) = (find(&mut parent, c as u32), find(&mut parent, q as u32));
                if a != b {
                    parent[a.max(b) as usize] = a.min(b);
                }
                q += 1;
            }
        }
        prev_start = cur_start;
    }
    let mut acc: Vec<Acc> = vec![Acc::default(); runs.len()];
    let mut roots: Vec<u32> = Vec::new();
    for (i, &(x0, x1, y)) in runs.iter().enumerate() {
        let r = find(&mut parent, i as u32) as usize;
        let (x0, x1, y) = (x0 as usize, x1 as usize, y as usize);
        let n = (x1 - x0) as f64;
        let sx = n * (x0 + x1 - 1) as f64 * 0.5;
        let yf = y as f64;
        let a = &mut acc[r];
        if a.n == 0.0 {
            roots.push(r as u32);
            a.x_min = x0;
            a.x_max = x1 - 1;
            a.y_min = y;
            a.y_max = y;
        }
        a.n += n;
        a.sx += sx;
        a.sy += n * yf;
        a.sxx += sum_sq(x1 as i64 - 1) - sum_sq(x0 as i64 - 1);
        a.syy += n * yf * yf;
        a.sxy += sx * yf;
        a.x_min = a.x_min.min(x0);
        a.x_max = a.x_max.max(x1 - 1);
        a.y_max = a.y_max.max(y);
    }
    roots
        .into_iter()
        .map(|r| acc[r as usize])
        .filter(|a| a.n >= min_area)
        .map(|a| {
            let (cx, cy) = (a.sx / a.n, a.sy / a.n);
            Blob {
                area: a.n,
                cx,
                cy,
                mxx: a.sxx / a.n - cx * cx,
                myy: a.syy / a.n - cy * cy,
                mxy: a.sxy / a.n - cx * cy,
                x_min: a.x_min,
                x_max: a.x_max,
                y_min: a.y_min,
                y_max: a.y_max,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disc_and_u_shape_are_single_components_with_correct_moments() {
        let (w, h) = (60, 40);
        let mut data = vec![200.0f32; w * h];
        // Disc of radius 6 at (15.3, 20.0).
        for y in 0..h {
            for x in 0..w {
                let (dx, dy) = (x as f64 - 15.3, y as f64 - 20.0);
                if dx * dx + dy * dy <= 36.0 {
                    data[y * w + x] = 20.0;
                }
            }
        }
        // A "U": two verticals joined at the bottom (tests run merging).
        for y in 5..30 {
            data[y * w + 35] = 20.0;
            data[y * w + 45] = 20.0;
        }
        for x in 35..=45 {
            data[30 * w + x] = 20.0;
        }
        let img = GrayImage::new(w, h, data).unwrap();
        let flat = GrayImage::new(w, h, vec![111.0; w * h]).unwrap();
        // Mean 111 minus the minimum 10 % offset: a flat threshold of ~100.
        let thr = crate::vision::threshold::local_threshold(&flat, 8);
        let mut blobs = find_blobs(&img, &thr, 1.0);
        blobs.sort_by(|a, b| a.cx.partial_cmp(&b.cx).unwrap());
        assert_eq!(blobs.len(), 2);
        let d = &blobs[0];
        assert!((d.cx - 15.3).abs() < 0.35 && (d.cy - 20.0).abs() < 1e-9);
        assert!((d.area / d.moment_ellipse_area() - 1.0).abs() < 0.1);
        assert_eq!(blobs[1].area, 25.0 * 2.0 + 11.0);
        assert!(blobs[1].moment_ellipse_area() > 1.5 * blobs[1].area);
    }
}
