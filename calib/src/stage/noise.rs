//! The dot error of a stage campaign as the offset's σ needs it: a part
//! each image draws anew and a part the images of a sequence share.
//!
//! Within a sequence the stage only translates the camera by a few tens of
//! millimetres at 700-1000 mm, so every dot looks nearly the same in every
//! image (size, tilt, blur, place in the vignetting): what the detector and
//! the dot-centre bias correction get wrong for it, they get wrong alike in
//! all of them. Measured on rendered campaigns of 8 varied layouts
//! (session 11): √n × the per-dot mean of the true pixel errors over a
//! sequence is 1.5x (9 images) to 2.1x (25 images) their RMS, where
//! independent errors give 1 (the errors of two images of a sequence
//! correlate by ~0.16 whatever their distance on the stage). A covariance
//! that assumes independent dots (`σ² (JᵀJ)⁺`, method.md §"Uncertainty")
//! then understates whatever averages over a sequence's images: the
//! intrinsics (1.4-1.5x) and the sequence's common offset (1.9x).
//!
//! Model: the error of dot `d` in image `v` of sequence `s` is
//! `b_{s,d} + w_{v,d}` per pixel axis, `w` independent with one variance
//! `σ_w²`, `b` shared by the sequence's images. `σ_w²` is the scatter
//! within the groups (sequence, dot, axis) of the bundle's residuals. The
//! shared part is not one variance: the origin marker (12 mm), corrected
//! for its centre bias with the small dots' diameter (8 mm,
//! `camera::refine_loop`), carries 5-20x the others' shared error
//! (0.013-0.05 px against a median 0.003 px on one rendered campaign), and one pooled `σ_b²` spreads it over every dot (RMS of
//! offset / σ 1.44 on 9-image sequences, against 1.18 per group). So each
//! group keeps its own: `b_g² ≈ c m_g² - σ_w²/n_g` from its mean residual `m_g` over its
//! `n_g` images, unbiased (it may be negative; the covariance it enters,
//! `σ_w² Σ_i l_i l_iᵀ + b_g² (Σ_i l_i)(Σ_i l_i)ᵀ` over the group's rows
//! `i`, stays positive semi-definite by Cauchy–Schwarz). The bundle's
//! parameters absorb part of the group means (each sequence's pose is
//! common to its images): `c = G / (G - N)` (G groups, N parameters), the
//! correction `σ²` gets from `m - N` degrees of freedom.

/// The two parts of the dot error (px², per pixel axis).
#[derive(Debug, Clone, PartialEq)]
pub struct DotErrorModel {
    /// Variance of the part drawn anew in every image.
    pub independent_var: f64,
    /// Per group (sequence, dot, axis): the square of its shared error,
    /// estimated without bias (so possibly negative).
    pub shared_sq: Vec<f64>,
}

impl DotErrorModel {
    /// From the residuals `r` of a fit with `parameters` unknowns and, per
    /// residual, the group (sequence, dot, axis) it belongs to (`group[i] <
    /// groups`).
    pub fn estimate(residuals: &[f64], group: &[usize], groups: usize, parameters: usize) -> Self {
        let mut count = vec![0usize; groups];
        let mut sum = vec![0.0; groups];
        for (&r, &g) in residuals.iter().zip(group) {
            count[g] += 1;
            sum[g] += r;
        }
        let mean: Vec<f64> = sum
            .iter()
            .zip(&count)
            .map(|(s, &n)| if n > 0 { s / n as f64 } else { 0.0 })
            .collect();
        let within: f64 = residuals
            .iter()
            .zip(group)
            .map(|(&r, &g)| (r - mean[g]).powi(2))
            .sum();
        let used = count.iter().filter(|&&n| n > 0).count();
        let independent_var = within / residuals.len().saturating_sub(used).max(1) as f64;
        let absorbed = used as f64 / used.saturating_sub(parameters).max(1) as f64;
        let shared_sq = mean
            .iter()
            .zip(&count)
            .map(|(m, &n)| {
                if n > 0 {
                    absorbed * m * m - independent_var / n as f64
                } else {
                    0.0
                }
            })
            .collect();
        Self {
            independent_var,
            shared_sq,
        }
    }

    /// The shared part's variance pooled over the groups (px²).
    pub fn pooled_shared_var(&self) -> f64 {
        self.shared_sq.iter().sum::<f64>() / self.shared_sq.len().max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{rngs::StdRng, SeedableRng};
    use rand_distr::{Distribution, Normal};

    /// Groups of 9 with a known shared and independent part: both found
    /// within 10 % (2000 groups); none where there is none.
    #[test]
    fn both_parts_are_found_from_grouped_residuals() {
        const GROUPS: usize = 2000;
        const PER_GROUP: usize = 9;
        let (shared_sd, independent_sd) = (0.006, 0.004);
        let mut rng = StdRng::seed_from_u64(11);
        let shared = Normal::new(0.0, shared_sd).unwrap();
        let independent = Normal::new(0.0, independent_sd).unwrap();
        let (mut r, mut group) = (Vec::new(), Vec::new());
        for g in 0..GROUPS {
            let b = shared.sample(&mut rng);
            for _ in 0..PER_GROUP {
                r.push(b + independent.sample(&mut rng));
                group.push(g);
            }
        }
        let model = DotErrorModel::estimate(&r, &group, GROUPS, 0);
        let rel = |a: f64, b: f64| (a / b - 1.0).abs();
        assert!(
            rel(model.pooled_shared_var(), shared_sd * shared_sd) < 0.1,
            "{model:?}"
        );
        assert!(
            rel(model.independent_var, independent_sd * independent_sd) < 0.1,
            "{model:?}"
        );
        // Independent residuals only: no shared part to speak of.
        let white: Vec<f64> = (0..GROUPS * PER_GROUP)
            .map(|_| independent.sample(&mut rng))
            .collect();
        let model = DotErrorModel::estimate(&white, &group, GROUPS, 0);
        assert!(
            model.pooled_shared_var().abs() < 0.01 * independent_sd * independent_sd,
            "{}",
            model.pooled_shared_var()
        );
    }
}
