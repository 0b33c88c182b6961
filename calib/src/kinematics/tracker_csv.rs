//! The CSV layouts of the public laser-tracker campaigns the tests and
//! benchmarks read (`calib/tests/data/kinematic`, issue 5 and 19), parsed
//! from text into measured tool positions at recorded joints. Reading the
//! files is the caller's; a row that does not parse is an error naming
//! its line.

use nalgebra::Vector3;

use super::measurement::{Measurement, Observed};

/// Columns of the Jacobi 2025 UR5 files: `step_order,x_t,y_t,z_t,x_dif,
/// y_dif,z_dif,joint_1..6` (mm, deg).
const JACOBI_TARGET: usize = 1;
const JACOBI_DIFFERENCE: usize = 4;
const JACOBI_JOINTS_DEG: usize = 7;
/// Columns of the Landgraf 2021 UR10 files (`;`, decimal comma): joints
/// (rad) from 7, measured x, y, z (mm) at 14, 16, 18.
const LANDGRAF_JOINTS_RAD: usize = 7;
const LANDGRAF_POSITION: [usize; 3] = [14, 16, 18];
const JOINTS: usize = 6;

#[derive(Debug, thiserror::Error, PartialEq)]
#[error("line {line}: column {column} is not a number")]
pub struct TrackerCsvError {
    /// 1-based, header included.
    pub line: usize,
    /// 0-based.
    pub column: usize,
}

/// One measured pose of a campaign.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerRow {
    pub joints_rad: Vec<f64>,
    /// The tracker's measured position (mm, tracker frame).
    pub position_mm: Vector3<f64>,
    /// The controller's own error at the pose (nominal model), where the
    /// file has it (Jacobi 2025's `*_dif`).
    pub controller_error_mm: Option<Vector3<f64>>,
}

impl TrackerRow {
    /// The row as a position measurement (no covariance given).
    pub fn measurement(&self) -> Measurement {
        Measurement {
            joints_rad: self.joints_rad.clone(),
            observed: Observed::Position {
                position_mm: self.position_mm,
                covariance: None,
            },
        }
    }
}

/// The numbers of each data line (header skipped, blank lines left out),
/// with `decimal_comma` read as a point; `needed` columns must parse.
fn numbers(
    text: &str,
    separator: char,
    decimal_comma: bool,
    needed: &[usize],
) -> Result<Vec<Vec<f64>>, TrackerCsvError> {
    text.lines()
        .enumerate()
        .skip(1)
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, line)| {
            let v: Vec<f64> = line
                .split(separator)
                .map(|s| {
                    let s = s.trim();
                    let s = if decimal_comma {
                        s.replace(',', ".")
                    } else {
                        s.to_string()
                    };
                    s.parse().unwrap_or(f64::NAN)
                })
                .collect();
            match needed
                .iter()
                .find(|&&c| !v.get(c).is_some_and(|x| x.is_finite()))
            {
                Some(&column) => Err(TrackerCsvError {
                    line: i + 1,
                    column,
                }),
                None => Ok(v),
            }
        })
        .collect()
}

/// A Jacobi 2025 UR5 file: the measured position is target minus
/// difference; the difference is the controller's error.
pub fn jacobi2025_rows(text: &str) -> Result<Vec<TrackerRow>, TrackerCsvError> {
    let needed: Vec<usize> = (JACOBI_TARGET..JACOBI_JOINTS_DEG + JOINTS).collect();
    let rows = numbers(text, ',', false, &needed)?;
    Ok(rows
        .iter()
        .map(|v| {
            let target = Vector3::from_fn(|k, _| v[JACOBI_TARGET + k]);
            let difference = Vector3::from_fn(|k, _| v[JACOBI_DIFFERENCE + k]);
            TrackerRow {
                joints_rad: (0..JOINTS)
                    .map(|k| v[JACOBI_JOINTS_DEG + k].to_radians())
                    .collect(),
                position_mm: target - difference,
                controller_error_mm: Some(difference),
            }
        })
        .collect())
}

/// A Landgraf 2021 UR10 file.
pub fn landgraf2021_rows(text: &str) -> Result<Vec<TrackerRow>, TrackerCsvError> {
    let mut needed: Vec<usize> = (LANDGRAF_JOINTS_RAD..LANDGRAF_JOINTS_RAD + JOINTS).collect();
    needed.extend(LANDGRAF_POSITION);
    let rows = numbers(text, ';', true, &needed)?;
    Ok(rows
        .iter()
        .map(|v| TrackerRow {
            joints_rad: v[LANDGRAF_JOINTS_RAD..LANDGRAF_JOINTS_RAD + JOINTS].to_vec(),
            position_mm: Vector3::from(LANDGRAF_POSITION.map(|c| v[c])),
            controller_error_mm: None,
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_parse_and_a_bad_number_names_its_line() {
        let ur5 = "step_order,x_t,y_t,z_t,x_dif,y_dif,z_dif,j1,j2,j3,j4,j5,j6\n\
                   1,10,20,30,1,2,3,0,90,0,0,0,180\n\n";
        let rows = jacobi2025_rows(ur5).unwrap();
        assert_eq!(rows.len(), 1);
        assert_eq!(rows[0].position_mm, Vector3::new(9.0, 18.0, 27.0));
        assert!((rows[0].joints_rad[1] - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let bad = ur5.replace(",20,", ",x,");
        assert_eq!(
            jacobi2025_rows(&bad),
            Err(TrackerCsvError { line: 2, column: 2 })
        );
        let ur10 = format!(
            "h\n{}\n",
            (0..19)
                .map(|c| format!("{c},5"))
                .collect::<Vec<_>>()
                .join(";")
        );
        let rows = landgraf2021_rows(&ur10).unwrap();
        assert_eq!(rows[0].joints_rad[0], 7.5);
        assert_eq!(rows[0].position_mm, Vector3::new(14.5, 16.5, 18.5));
        assert!(landgraf2021_rows("h\n1;2\n").is_err());
    }
}
