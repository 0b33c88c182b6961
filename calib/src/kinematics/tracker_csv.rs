//! The CSV layouts of the public laser-tracker campaigns the tests and
//! benchmarks read (`calib/tests/data/kinematic`, issue 5 and 19), parsed
//! from text into measured tool positions (and, for a 6-DoF probe, the
//! orientation: [`super::tracker_pose`]) at recorded joints. Reading the
//! files is the caller's; a row that does not parse is an error naming
//! its line.

use nalgebra::{Isometry3, Translation3, Vector3};

use super::measurement::{Measurement, Observed};
use super::tracker_pose::{probe_pose_covariance, rotation_from_intrinsic_xyz_deg};

/// Columns of the Jacobi 2025 UR5 files: `step_order,x_t,y_t,z_t,x_dif,
/// y_dif,z_dif,joint_1..6` (mm, deg).
const JACOBI_TARGET: usize = 1;
const JACOBI_DIFFERENCE: usize = 4;
const JACOBI_JOINTS_DEG: usize = 7;
/// Columns of the Landgraf 2021 UR10 files (`;`, decimal comma): joints
/// (rad) from 7, measured x, y, z (mm) at 14, 16, 18 each followed by its
/// standard deviation, the T-Mac's rx, ry, rz (deg) at 20, 22, 24 each
/// followed by its standard deviation (deg).
const LANDGRAF_JOINTS_RAD: usize = 7;
const LANDGRAF_POSITION: [usize; 3] = [14, 16, 18];
const LANDGRAF_ANGLES: [usize; 3] = [20, 22, 24];
/// A value's standard deviation is the next column.
const STD_NEXT: usize = 1;
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
    /// Per-axis standard deviation of `position_mm` (mm), where the file
    /// has it (Landgraf 2021).
    pub position_std_mm: Option<Vector3<f64>>,
    /// The 6-DoF probe's orientation, where the file has it (Landgraf
    /// 2021's T-Mac; the Jacobi 2025 reflector has none).
    pub orientation: Option<ProbeOrientation>,
}

/// A 6-DoF probe's measured orientation as the file gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeOrientation {
    /// Intrinsic X-Y-Z angles (deg): `R = Rx · Ry · Rz` is the probe's
    /// rotation in the tracker frame ([`super::tracker_pose`]).
    pub angles_deg: [f64; 3],
    /// Standard deviation of each angle (deg).
    pub std_deg: [f64; 3],
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

    /// The row as a full-pose measurement (`Observed::Pose`, the probe's
    /// pose in the tracker frame) with the covariance of
    /// [`probe_pose_covariance`]: the file's standard deviations plus the
    /// instrument's accuracy floors in quadrature. `None` for a row without
    /// orientation.
    pub fn pose_measurement(&self) -> Option<Measurement> {
        let o = self.orientation?;
        let position_std_mm = self.position_std_mm.unwrap_or_else(Vector3::zeros);
        Some(Measurement {
            joints_rad: self.joints_rad.clone(),
            observed: Observed::Pose {
                world_to_tool: Isometry3::from_parts(
                    Translation3::from(self.position_mm),
                    rotation_from_intrinsic_xyz_deg(o.angles_deg),
                ),
                covariance: Some(probe_pose_covariance(
                    &position_std_mm,
                    o.angles_deg,
                    o.std_deg,
                )),
            },
        })
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
                position_std_mm: None,
                orientation: None,
            }
        })
        .collect())
}

/// A Landgraf 2021 UR10 file: joints, position, and, where the row has
/// all of them, the position's standard deviations and the T-Mac's
/// orientation with its standard deviations.
pub fn landgraf2021_rows(text: &str) -> Result<Vec<TrackerRow>, TrackerCsvError> {
    let mut needed: Vec<usize> = (LANDGRAF_JOINTS_RAD..LANDGRAF_JOINTS_RAD + JOINTS).collect();
    needed.extend(LANDGRAF_POSITION);
    let rows = numbers(text, ';', true, &needed)?;
    let all = |v: &[f64], cols: [usize; 3]| {
        let x = cols.map(|c| v.get(c).copied().unwrap_or(f64::NAN));
        x.iter().all(|x| x.is_finite()).then_some(x)
    };
    Ok(rows
        .iter()
        .map(|v| TrackerRow {
            joints_rad: v[LANDGRAF_JOINTS_RAD..LANDGRAF_JOINTS_RAD + JOINTS].to_vec(),
            position_mm: Vector3::from(LANDGRAF_POSITION.map(|c| v[c])),
            controller_error_mm: None,
            position_std_mm: all(v, LANDGRAF_POSITION.map(|c| c + STD_NEXT)).map(Vector3::from),
            orientation: all(v, LANDGRAF_ANGLES)
                .zip(all(v, LANDGRAF_ANGLES.map(|c| c + STD_NEXT)))
                .map(|(angles_deg, std_deg)| ProbeOrientation {
                    angles_deg,
                    std_deg,
                }),
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
        // 19 columns: no std of z (column 19), no orientation.
        assert_eq!(rows[0].position_std_mm, None);
        assert!(rows[0].orientation.is_none() && rows[0].pose_measurement().is_none());
    }

    /// The first row of Series_B/measurements_joint_configurations.csv.
    const UR10_B_FIRST: &str =
        "2,02011E+13;0,000121973;-0,365141;1,4273;1,56998;1,57013;-2,78E-05;\
        -3,14159;-1,5708;0;-1,5708;0;0;21,86750031;383,76294;0,031674;-3240,8734;0,013252;\
        201,93157;0,0037622;-90,179302;0,0011832;-20,118749;0,0013871;-90,169308;0,0041345";

    #[test]
    fn a_landgraf_line_gives_the_probe_pose_with_its_covariance() {
        use crate::kinematics::tracker_pose::{
            intrinsic_xyz_deg, PROBE_ROTATION_FLOOR_DEG, TRACKER_POSITION_FLOOR_MM,
        };
        let rows = landgraf2021_rows(&format!("header\n{UR10_B_FIRST}\n")).unwrap();
        let r = &rows[0];
        assert_eq!((r.joints_rad.len(), r.joints_rad[2]), (6, 0.0));
        assert!((r.joints_rad[0] + std::f64::consts::PI).abs() < 1e-5);
        assert_eq!(
            r.position_mm,
            Vector3::new(383.76294, -3240.8734, 201.93157)
        );
        assert_eq!(
            r.position_std_mm,
            Some(Vector3::new(0.031674, 0.013252, 0.0037622))
        );
        let o = r.orientation.unwrap();
        assert_eq!(o.angles_deg, [-90.179302, -20.118749, -90.169308]);
        assert_eq!(o.std_deg, [0.0011832, 0.0013871, 0.0041345]);
        let m = r.pose_measurement().unwrap();
        let Observed::Pose {
            world_to_tool,
            covariance: Some(c),
        } = m.observed
        else {
            panic!("a full pose with covariance")
        };
        assert_eq!(world_to_tool.translation.vector, r.position_mm);
        let back = intrinsic_xyz_deg(&world_to_tool.rotation);
        for k in 0..3 {
            assert!((back[k] - o.angles_deg[k]).abs() < 1e-9, "{back:?}");
        }
        // Position: the file's std and the floor in quadrature.
        let sx = (0.031674f64.powi(2) + TRACKER_POSITION_FLOOR_MM.powi(2)).sqrt();
        assert!((c[(0, 0)].sqrt() - sx).abs() < 1e-12);
        assert_eq!(c.fixed_view::<3, 3>(0, 3).amax(), 0.0);
        // Orientation: the floor dominates (0.001-0.004 deg against 0.01).
        let floor = PROBE_ROTATION_FLOOR_DEG.to_radians();
        let trace = c.fixed_view::<3, 3>(3, 3).trace();
        assert!(trace > 3.0 * floor * floor && trace < 3.3 * floor * floor);
    }
}
