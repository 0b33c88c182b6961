//! The robust limit that judges a pose by its peers (issue 14, "poses
//! that lie"): a pose is out when its figure exceeds
//! `max(RATIO x median, median + MADS x 1.4826 MAD)` of the poses in the
//! fit. The ratio term guards clean data (where the MAD is tiny and every
//! pose has about the noise level), the MAD term data with a shared,
//! pose-dependent misfit (robot inaccuracy). The same limit serves the
//! consensus of board estimates (mm) and the reprojection of each pose
//! under a fit of the others (px).

/// Median of a slice (NaN-free); 0 for an empty one.
pub fn median(values: &[f64]) -> f64 {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// A pose is out beyond this multiple of the median of its peers ...
pub const OUTLIER_RATIO: f64 = 3.0;
/// ... and beyond this many robust standard deviations above it.
pub const OUTLIER_MADS: f64 = 5.0;
/// MAD to standard deviation for Gaussian data.
const MAD_TO_SIGMA: f64 = 1.4826;

/// The robust limit of the module doc over the figures of the poses in the fit.
pub fn robust_limit(figures: &[f64]) -> f64 {
    let med = median(figures);
    let deviations: Vec<f64> = figures.iter().map(|v| (v - med).abs()).collect();
    let mad = median(&deviations);
    (OUTLIER_RATIO * med).max(med + OUTLIER_MADS * MAD_TO_SIGMA * mad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limit_follows_the_median_and_the_spread() {
        let tight = [1.0, 1.01, 0.99, 1.0, 1.02];
        assert!((robust_limit(&tight) - 3.0).abs() < 1e-9);
        let spread = [1.0, 2.0, 3.0, 4.0, 5.0];
        // median 3, MAD 1: 3 + 5 * 1.4826 = 10.4 > 9.
        assert!((robust_limit(&spread) - (3.0 + 5.0 * MAD_TO_SIGMA)).abs() < 1e-9);
    }
}
