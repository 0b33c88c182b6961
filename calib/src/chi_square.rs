//! The chi-square distribution's upper tail, for the re-check's test
//! (method.md §7: residuals against their predicted covariance): the
//! regularized upper incomplete gamma function `Q(k/2, x/2)`, by its series
//! below `a + 1` and Lentz's continued fraction above (Numerical Recipes
//! §6.2), with Lanczos' log-gamma.

/// Relative accuracy the series and the continued fraction stop at.
const EPSILON: f64 = 1e-14;
/// Iteration cap of either expansion (they converge in tens).
const MAX_TERMS: usize = 10_000;
/// Smallest number the continued fraction divides by (Lentz).
const TINY: f64 = 1e-300;
/// Lanczos coefficients (g = 7, n = 9).
const LANCZOS: [f64; 9] = [
    0.999_999_999_999_809_9,
    676.520_368_121_885_1,
    -1_259.139_216_722_402_8,
    771.323_428_777_653_1,
    -176.615_029_162_140_6,
    12.507_343_278_686_905,
    -0.138_571_095_265_720_12,
    9.984_369_578_019_572e-6,
    1.505_632_735_149_311_6e-7,
];
const LANCZOS_G: f64 = 7.0;

/// `ln Γ(x)` for `x > 0`.
pub fn ln_gamma(x: f64) -> f64 {
    if x < 0.5 {
        // Reflection: Γ(x) Γ(1 - x) = π / sin(πx).
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let t = x + LANCZOS_G + 0.5;
    let sum = LANCZOS[1..]
        .iter()
        .enumerate()
        .fold(LANCZOS[0], |acc, (i, c)| acc + c / (x + i as f64 + 1.0));
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// Regularized upper incomplete gamma `Q(a, x) = Γ(a, x) / Γ(a)`; `None`
/// for `a <= 0`, `x < 0` or non-finite input.
pub fn upper_gamma_q(a: f64, x: f64) -> Option<f64> {
    if !(a > 0.0 && x >= 0.0 && a.is_finite() && x.is_finite()) {
        return None;
    }
    if x == 0.0 {
        return Some(1.0);
    }
    let log_prefactor = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        // Series for P(a, x).
        let (mut term, mut sum, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..MAX_TERMS {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * EPSILON {
                break;
            }
        }
        Some((1.0 - sum * log_prefactor.exp()).clamp(0.0, 1.0))
    } else {
        // Continued fraction for Q(a, x).
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / TINY;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..MAX_TERMS {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < TINY {
                d = TINY;
            }
            c = b + an / c;
            if c.abs() < TINY {
                c = TINY;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < EPSILON {
                break;
            }
        }
        Some((log_prefactor.exp() * h).clamp(0.0, 1.0))
    }
}

/// Probability that a chi-square variable with `dof` degrees of freedom
/// exceeds `statistic` (the test's p-value); `None` for `dof == 0` or a
/// negative or non-finite statistic.
pub fn chi_square_p_value(statistic: f64, dof: usize) -> Option<f64> {
    if dof == 0 {
        return None;
    }
    upper_gamma_q(dof as f64 / 2.0, statistic / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tabulated upper quantiles: P(χ²_k > x) = p.
    #[test]
    fn matches_tabulated_quantiles() {
        for (x, k, p) in [
            (3.841_458_820_694_124, 1, 0.05),
            (6.634_896_601_021_214, 1, 0.01),
            (18.307_038_053_275_146, 10, 0.05),
            (88.379_418_780_664_05, 60, 0.01),
            (43.187_958_987_742_98, 60, 0.95),
        ] {
            let got = chi_square_p_value(x, k).unwrap();
            assert!((got - p).abs() < 1e-6, "k={k} x={x}: {got} vs {p}");
        }
    }

    #[test]
    fn exponential_case_and_bad_input() {
        // k = 2: P(χ² > x) = exp(-x/2).
        for x in [0.1, 1.0, 5.0, 40.0] {
            let got = chi_square_p_value(x, 2).unwrap();
            assert!((got - (-x / 2.0_f64).exp()).abs() < 1e-12);
        }
        assert_eq!(chi_square_p_value(0.0, 3), Some(1.0));
        assert!(chi_square_p_value(1.0, 0).is_none());
        assert!(chi_square_p_value(f64::NAN, 3).is_none());
        assert!(chi_square_p_value(-1.0, 3).is_none());
    }

    #[test]
    fn ln_gamma_of_integers_is_log_factorial() {
        let mut factorial = 1.0_f64;
        for n in 1..20 {
            assert!((ln_gamma(n as f64) - factorial.ln()).abs() < 1e-10, "{n}");
            factorial *= n as f64;
        }
        assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
    }
}
