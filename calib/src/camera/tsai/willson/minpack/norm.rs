//! MINPACK's machine constants and `enorm`, shared by `lmdif` and `lmpar`.

/// Machine precision `dpmpar(1)` for IEEE double (2^-52).
pub(super) const EPSMCH: f64 = f64::EPSILON;
/// Smallest positive normal double, `dpmpar(2)`.
pub(super) const DWARF: f64 = f64::MIN_POSITIVE;
/// `enorm`'s thresholds between small, intermediate and large components.
const RDWARF: f64 = 3.834e-20;
const RGIANT: f64 = 1.304e19;
/// Euclidean norm with MINPACK's overflow/underflow-safe accumulation.
pub(super) fn enorm(x: &[f64]) -> f64 {
    let (mut s1, mut s2, mut s3) = (0.0f64, 0.0f64, 0.0f64);
    let (mut x1max, mut x3max) = (0.0f64, 0.0f64);
    let agiant = RGIANT / x.len() as f64;
    for &xi in x {
        let xabs = xi.abs();
        if xabs > RDWARF && xabs < agiant {
            s2 += xabs * xabs;
        } else if xabs <= RDWARF {
            if xabs > x3max {
                let r = x3max / xabs;
                s3 = 1.0 + s3 * (r * r);
                x3max = xabs;
            } else if xabs != 0.0 {
                let r = xabs / x3max;
                s3 += r * r;
            }
        } else if xabs > x1max {
            let r = x1max / xabs;
            s1 = 1.0 + s1 * (r * r);
            x1max = xabs;
        } else {
            let r = xabs / x1max;
            s1 += r * r;
        }
    }
    if s1 != 0.0 {
        x1max * (s1 + (s2 / x1max) / x1max).sqrt()
    } else if s2 != 0.0 {
        if s2 >= x3max {
            (s2 * (1.0 + (x3max / s2) * (x3max * s3))).sqrt()
        } else {
            (x3max * ((s2 / x3max) + (x3max * s3))).sqrt()
        }
    } else {
        x3max * s3.sqrt()
    }
}
