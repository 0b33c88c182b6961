//! Accuracy statistics for reports (method.md §7): mean, median, standard
//! deviation, maximum and RMS of the 3-D position error at validation poses,
//! and the same per axis. The field names are the REST contract's
//! (api.md "Results": `{"n","mean_mm","median_mm","std_mm","max_mm","rms_mm"}`).

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Summary of a set of non-negative error magnitudes (mm).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ErrorStats {
    pub n: usize,
    pub mean_mm: f64,
    pub median_mm: f64,
    /// Sample standard deviation (n - 1) of the magnitudes.
    pub std_mm: f64,
    pub max_mm: f64,
    pub rms_mm: f64,
}

impl ErrorStats {
    /// Statistics of `values`; an empty slice gives all zeros with `n = 0`.
    /// Non-finite values are skipped (they cannot be summarised honestly).
    pub fn from_values(values: &[f64]) -> Self {
        let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
        let n = v.len();
        if n == 0 {
            return Self::default();
        }
        v.sort_by(f64::total_cmp);
        let nf = n as f64;
        let mean = v.iter().sum::<f64>() / nf;
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        };
        let var = if n > 1 {
            v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (nf - 1.0)
        } else {
            0.0
        };
        Self {
            n,
            mean_mm: mean,
            median_mm: median,
            std_mm: var.sqrt(),
            max_mm: v[n - 1],
            rms_mm: (v.iter().map(|x| x * x).sum::<f64>() / nf).sqrt(),
        }
    }
}

/// 3-D and per-axis statistics of position errors (measured minus
/// predicted, in the world frame). Per-axis figures summarise `|e_axis|`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct AccuracyStats {
    #[serde(flatten)]
    pub norm: ErrorStats,
    pub x: ErrorStats,
    pub y: ErrorStats,
    pub z: ErrorStats,
}

impl AccuracyStats {
    pub fn from_errors(errors_mm: &[Vector3<f64>]) -> Self {
        let axis = |k: usize| -> ErrorStats {
            ErrorStats::from_values(&errors_mm.iter().map(|e| e[k].abs()).collect::<Vec<_>>())
        };
        Self {
            norm: ErrorStats::from_values(&errors_mm.iter().map(|e| e.norm()).collect::<Vec<_>>()),
            x: axis(0),
            y: axis(1),
            z: axis(2),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_known_values() {
        let s = ErrorStats::from_values(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(s.n, 4);
        assert!((s.mean_mm - 2.5).abs() < 1e-12);
        assert!((s.median_mm - 2.5).abs() < 1e-12);
        assert!((s.std_mm - (5.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert!((s.max_mm - 4.0).abs() < 1e-12);
        assert!((s.rms_mm - 7.5f64.sqrt()).abs() < 1e-12);
        assert_eq!(ErrorStats::from_values(&[]).n, 0);
        assert_eq!(ErrorStats::from_values(&[f64::NAN, 1.0]).n, 1);
    }

    #[test]
    fn accuracy_stats_split_axes() {
        let e = [Vector3::new(3.0, -4.0, 0.0), Vector3::new(0.0, 0.0, -1.0)];
        let a = AccuracyStats::from_errors(&e);
        assert!((a.norm.mean_mm - 3.0).abs() < 1e-12);
        assert!((a.y.max_mm - 4.0).abs() < 1e-12);
        assert!((a.z.mean_mm - 0.5).abs() < 1e-12);
        let json = serde_json::to_value(a).unwrap();
        assert!(json.get("mean_mm").is_some() && json["x"].get("rms_mm").is_some());
    }
}
