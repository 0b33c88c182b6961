//! Joint angles in degrees, as a client sends them and the store keeps them.
//! Checked once, in one place, against the robot's joint count and one
//! bound ([`MAX_JOINT_DEG`]); turned into the radians the numerics take
//! (`calib/`, method.md §2) by one function, [`JointsDeg::to_radians`].

use serde::Serialize;

use super::Checker;

/// Largest joint angle accepted anywhere (uploads, forward, compensate
/// seeds), degrees: two turns either way, beyond any real joint's travel,
/// so a number past it is a unit mistake (radians sent twice, milli-degrees).
pub const MAX_JOINT_DEG: f64 = super::MAX_ANGLE_DEG;

/// One robot configuration: a joint angle per joint, degrees. Serialised
/// as the plain array the contract and the store use; read back only
/// through [`JointsDeg::check`] or [`JointsDeg::stored`].
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(transparent)]
pub struct JointsDeg(Vec<f64>);

impl JointsDeg {
    /// Checks `values` (the field `field` of a request) against the robot's
    /// `joint_count` and [`MAX_JOINT_DEG`], recording every failure in `c`;
    /// the typed joints when they pass.
    pub fn check(
        c: &mut Checker,
        field: &str,
        values: &[f64],
        joint_count: usize,
    ) -> Option<JointsDeg> {
        let before = c.errors.len();
        if values.len() != joint_count {
            c.fail(
                field,
                format!(
                    "the robot has {joint_count} joints, got {} values",
                    values.len()
                ),
            );
        }
        for (i, v) in values.iter().enumerate() {
            c.bounded(format!("{field}[{i}]"), *v, MAX_JOINT_DEG, "deg");
        }
        (c.errors.len() == before).then(|| JointsDeg(values.to_vec()))
    }

    /// Joints read back from the store: they were checked when uploaded.
    pub fn stored(values: Vec<f64>) -> JointsDeg {
        JointsDeg(values)
    }

    pub fn as_deg(&self) -> &[f64] {
        &self.0
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The joints in radians, as `calib/` takes them.
    pub fn to_radians(&self) -> Vec<f64> {
        self.0.iter().map(|d| d.to_radians()).collect()
    }

    /// Joints the numerics found (radians), in the contract's degrees.
    pub fn from_radians(rad: &[f64]) -> JointsDeg {
        JointsDeg(rad.iter().map(|r| r.to_degrees()).collect())
    }

    pub fn into_vec(self) -> Vec<f64> {
        self.0
    }
}

impl PartialEq<Vec<f64>> for JointsDeg {
    fn eq(&self, other: &Vec<f64>) -> bool {
        &self.0 == other
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_a_wrong_count_and_angles_past_the_bound() {
        let mut c = Checker::default();
        assert!(JointsDeg::check(&mut c, "q", &[0.0, MAX_JOINT_DEG + 1.0], 3).is_none());
        let fields: Vec<&str> = c.errors.iter().map(|e| e.field.as_str()).collect();
        assert_eq!(fields, ["q", "q[1]"]);
    }

    #[test]
    fn converts_to_radians_once_checked() {
        let mut c = Checker::default();
        let q = JointsDeg::check(&mut c, "q", &[180.0, -90.0], 2).unwrap();
        assert!(c.errors.is_empty());
        let rad = q.to_radians();
        assert!((rad[0] - std::f64::consts::PI).abs() < 1e-15);
        assert!((rad[1] + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }
}
