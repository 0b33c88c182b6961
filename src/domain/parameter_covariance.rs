//! The full parameter covariance stored with a parameter set (issue
//! "Deploy the result"): what `forward`'s predicted uncertainties and the
//! `dh-json` export read. Stored in the set's document (a JSON column in
//! both backends: no migration), in the units of the set's `parameters`
//! rows, so that `sqrt(matrix[i][i])` is the `std` of parameter `names[i]`.

use nalgebra::DMatrix;
use robocal_calib::kinematics::ParamLayout;
use serde::{Deserialize, Serialize};

/// Unit names of the two kinds of parameter (as in `parameters[].unit`).
const UNIT_MM: &str = "mm";
const UNIT_DEG: &str = "deg";

/// Covariance of the identified parameters (held ones have none and are
/// left out).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, utoipa::ToSchema)]
pub struct CovarianceDoc {
    /// Parameter names (as in `parameters[].name`), the matrix's order.
    pub names: Vec<String>,
    /// Per name, `mm` or `deg`: entry `[i][j]` is in `units[i]·units[j]`.
    pub units: Vec<String>,
    /// Symmetric, row-major, `names.len()` square.
    pub matrix: Vec<Vec<f64>>,
}

impl CovarianceDoc {
    /// The identified parameters `free` (layout indices) of a layout-sized
    /// covariance in internal units (mm, rad).
    pub fn from_layout(layout: &ParamLayout, covariance: &DMatrix<f64>, free: &[usize]) -> Self {
        let scale = |i: usize| {
            if layout.is_angle(i) {
                1f64.to_degrees()
            } else {
                1.0
            }
        };
        Self {
            names: free
                .iter()
                .map(|&i| layout.params[i].name.clone())
                .collect(),
            units: free
                .iter()
                .map(|&i| {
                    if layout.is_angle(i) {
                        UNIT_DEG
                    } else {
                        UNIT_MM
                    }
                    .to_string()
                })
                .collect(),
            matrix: free
                .iter()
                .map(|&i| {
                    free.iter()
                        .map(|&j| covariance[(i, j)] * scale(i) * scale(j))
                        .collect()
                })
                .collect(),
        }
    }

    /// Back to a layout-sized covariance in internal units (zero at
    /// parameters not named), checked against `layout`.
    pub fn to_layout(&self, layout: &ParamLayout) -> Result<DMatrix<f64>, String> {
        let n = self.names.len();
        if self.units.len() != n
            || self.matrix.len() != n
            || self.matrix.iter().any(|r| r.len() != n)
        {
            return Err(format!("covariance is not {n} x {n} with {n} units"));
        }
        let index: Vec<usize> = self
            .names
            .iter()
            .map(|name| {
                layout
                    .index_of(name)
                    .ok_or_else(|| format!("covariance names unknown parameter {name}"))
            })
            .collect::<Result<_, _>>()?;
        let scale = |i: usize| {
            if layout.is_angle(i) {
                1f64.to_radians()
            } else {
                1.0
            }
        };
        let mut full = DMatrix::zeros(layout.len(), layout.len());
        for (a, &i) in index.iter().enumerate() {
            for (b, &j) in index.iter().enumerate() {
                full[(i, j)] = self.matrix[a][b] * scale(i) * scale(j);
            }
        }
        Ok(full)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::kinematics::{presets, Instrument};

    #[test]
    fn stored_units_round_trip_and_match_the_parameter_rows() {
        let layout = ParamLayout::new(&presets::irb2400(), Instrument::Camera);
        let n = layout.len();
        let a = DMatrix::from_fn(n, n, |i, j| 1e-4 * ((i * 3 + j * 5) % 7) as f64);
        let cov = &a * a.transpose();
        let free: Vec<usize> = (1..n).step_by(2).collect();
        let doc = CovarianceDoc::from_layout(&layout, &cov, &free);
        for (k, &i) in free.iter().enumerate() {
            let sd_internal = cov[(i, i)].sqrt();
            let sd_doc = doc.matrix[k][k].sqrt();
            let want = if layout.is_angle(i) {
                sd_internal.to_degrees()
            } else {
                sd_internal
            };
            assert!(
                (sd_doc - want).abs() < 1e-12 * want.max(1.0),
                "{}",
                doc.names[k]
            );
        }
        let back = doc.to_layout(&layout).unwrap();
        for &i in &free {
            for &j in &free {
                assert!((back[(i, j)] - cov[(i, j)]).abs() < 1e-15);
            }
        }
        assert_eq!(back[(0, 0)], 0.0);
        let mut bad = doc.clone();
        bad.names[0] = "nope".into();
        assert!(bad.to_layout(&layout).unwrap_err().contains("nope"));
        bad.matrix.pop();
        assert!(bad.to_layout(&layout).is_err());
    }
}
