//! A controller flange pose (issue 14), checked once at the edge and typed
//! from then on: the flange in the robot base frame, `base_to_flange`
//! (`p_base = base_to_flange * p_flange`, mm), as
//! `calib::handeye::FlangeView` takes it.

use robocal_calib::geometry::{pose_from_matrix_rows, pose_from_xyz_rpy_deg, Pose};

use super::FlangePoseDoc;
use super::JointsDeg;
use super::{Checker, MAX_ANGLE_DEG, MAX_LENGTH_MM};

/// The flange in the base frame, as the controller reported it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlangePose(Pose);

impl FlangePose {
    /// Checks `doc` (the request field `field`), recording every failure in
    /// `c`: finite, bounded translation; exactly one of `rotation_deg` and
    /// `matrix`; a matrix orthonormal with determinant +1 (to
    /// `calib::geometry`'s tolerance). The typed pose when it passes.
    pub fn check(c: &mut Checker, field: &str, doc: &FlangePoseDoc) -> Option<FlangePose> {
        let before = c.errors.len();
        for (i, v) in doc.translation_mm.iter().enumerate() {
            c.bounded(
                format!("{field}.translation_mm[{i}]"),
                *v,
                MAX_LENGTH_MM,
                "mm",
            );
        }
        let pose = match (&doc.rotation_deg, &doc.matrix) {
            (Some(_), Some(_)) => {
                c.fail(field, "give rotation_deg or matrix, not both");
                None
            }
            (None, None) => {
                c.fail(field, "needs rotation_deg or matrix");
                None
            }
            (Some(angles), None) => {
                for (i, v) in angles.iter().enumerate() {
                    c.bounded(
                        format!("{field}.rotation_deg[{i}]"),
                        *v,
                        MAX_ANGLE_DEG,
                        "deg",
                    );
                }
                pose_from_xyz_rpy_deg(doc.translation_mm, *angles).ok()
            }
            (None, Some(m)) => {
                let [x, y, z] = doc.translation_mm;
                let rows = [
                    [m[0][0], m[0][1], m[0][2], x],
                    [m[1][0], m[1][1], m[1][2], y],
                    [m[2][0], m[2][1], m[2][2], z],
                    [0.0, 0.0, 0.0, 1.0],
                ];
                match pose_from_matrix_rows(&rows) {
                    Ok(p) => Some(p),
                    Err(e) => {
                        c.fail(format!("{field}.matrix"), e.to_string());
                        None
                    }
                }
            }
        };
        (c.errors.len() == before)
            .then_some(pose)
            .flatten()
            .map(FlangePose)
    }

    /// A flange pose read back from the store: it was checked at upload.
    /// `None` when the stored document no longer makes a pose.
    pub fn stored(doc: &FlangePoseDoc) -> Option<FlangePose> {
        FlangePose::check(&mut Checker::default(), "flange_pose", doc)
    }

    /// `base_to_flange`.
    pub fn base_to_flange(&self) -> Pose {
        self.0
    }
}

/// What a pose says of where the robot was: its joint angles, or the
/// controller's flange pose. A session takes one kind only (its first pose
/// decides), so a job is either a kinematic calibration or a hand–eye one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoseKind {
    Joints,
    Flange,
}

impl PoseKind {
    /// The kind of a stored pose.
    pub fn of_stored(flange_pose: Option<&FlangePoseDoc>) -> PoseKind {
        match flange_pose {
            Some(_) => PoseKind::Flange,
            None => PoseKind::Joints,
        }
    }

    /// The request field that carries this kind.
    pub fn field(self) -> &'static str {
        match self {
            PoseKind::Joints => "joints_deg",
            PoseKind::Flange => "flange_pose",
        }
    }

    /// Records a failure on `{prefix}{field}` when this pose's kind is not
    /// the session's (`session`: the kind of its poses so far, if any).
    pub fn check_same(self, c: &mut Checker, prefix: &str, session: Option<PoseKind>) {
        if let Some(other) = session.filter(|&k| k != self) {
            c.fail(
                format!("{prefix}{}", self.field()),
                format!(
                    "this session's poses carry {}; a session does not mix joint angles and flange poses",
                    other.field()
                ),
            );
        }
    }
}

/// Where a checked pose says the robot was.
#[derive(Debug, Clone, PartialEq)]
pub enum RobotPose {
    /// Its joint angles, checked against the robot.
    Joints(JointsDeg),
    /// The controller's flange pose, checked (the document as uploaded).
    Flange(FlangePoseDoc),
}

impl RobotPose {
    pub fn kind(&self) -> PoseKind {
        match self {
            RobotPose::Joints(_) => PoseKind::Joints,
            RobotPose::Flange(_) => PoseKind::Flange,
        }
    }

    /// The pose as a pose row keeps it: its joints, or for a flange pose no
    /// joints (the row's `joints_deg` is empty) and the flange document.
    pub fn into_row(self) -> (JointsDeg, Option<FlangePoseDoc>) {
        match self {
            RobotPose::Joints(joints) => (joints, None),
            RobotPose::Flange(doc) => (JointsDeg::stored(Vec::new()), Some(doc)),
        }
    }
}

/// Checks where one pose says the robot was: exactly one of `joints_deg`
/// (against the robot's `joint_count`) and `flange_pose`; fields are named
/// `{prefix}joints_deg` / `{prefix}flange_pose`. The pose's kind when it
/// names one (even if its values fail, so the caller can still report a
/// mixed session), and the checked pose when it passes.
pub fn check_robot_pose(
    c: &mut Checker,
    prefix: &str,
    joints_deg: Option<&[f64]>,
    flange_pose: Option<&FlangePoseDoc>,
    joint_count: usize,
) -> (Option<PoseKind>, Option<RobotPose>) {
    match (joints_deg, flange_pose) {
        (Some(_), Some(_)) => {
            c.fail(
                format!("{prefix}flange_pose"),
                "a pose carries joints_deg or flange_pose, not both",
            );
            (None, None)
        }
        (None, None) => {
            c.fail(
                format!("{prefix}joints_deg"),
                "required (or the controller's flange_pose)",
            );
            (None, None)
        }
        (Some(joints), None) => {
            let typed = JointsDeg::check(c, &format!("{prefix}joints_deg"), joints, joint_count);
            (Some(PoseKind::Joints), typed.map(RobotPose::Joints))
        }
        (None, Some(doc)) => {
            let pose = FlangePose::check(c, &format!("{prefix}flange_pose"), doc);
            (
                Some(PoseKind::Flange),
                pose.map(|_| RobotPose::Flange(doc.clone())),
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(rotation_deg: Option<[f64; 3]>, matrix: Option<[[f64; 3]; 3]>) -> FlangePoseDoc {
        FlangePoseDoc {
            translation_mm: [700.0, 5.0, 850.0],
            rotation_deg,
            matrix,
        }
    }

    fn fields(d: &FlangePoseDoc) -> Vec<String> {
        let mut c = Checker::default();
        assert!(FlangePose::check(&mut c, "flange_pose", d).is_none());
        c.errors.into_iter().map(|e| e.field).collect()
    }

    #[test]
    fn angles_and_matrix_give_the_same_pose() {
        let mut c = Checker::default();
        let by_angles = FlangePose::check(&mut c, "f", &doc(Some([0.0, 0.0, 90.0]), None)).unwrap();
        let by_matrix = FlangePose::check(
            &mut c,
            "f",
            &doc(
                None,
                Some([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
            ),
        )
        .unwrap();
        assert!(c.errors.is_empty());
        let d = by_angles.base_to_flange().inverse() * by_matrix.base_to_flange();
        assert!(d.translation.vector.norm() < 1e-9 && d.rotation.angle() < 1e-12);
    }

    #[test]
    fn refuses_both_neither_a_sheared_matrix_and_nan() {
        assert_eq!(
            fields(&doc(Some([0.0; 3]), Some([[1.0, 0.0, 0.0]; 3]))),
            ["flange_pose"]
        );
        assert_eq!(fields(&doc(None, None)), ["flange_pose"]);
        let sheared = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(fields(&doc(None, Some(sheared))), ["flange_pose.matrix"]);
        let mirror = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
        assert_eq!(fields(&doc(None, Some(mirror))), ["flange_pose.matrix"]);
        let mut nan = doc(Some([0.0, f64::NAN, 0.0]), None);
        assert_eq!(fields(&nan), ["flange_pose.rotation_deg[1]"]);
        nan.translation_mm[2] = f64::INFINITY;
        assert_eq!(
            fields(&nan),
            [
                "flange_pose.translation_mm[2]",
                "flange_pose.rotation_deg[1]"
            ]
        );
    }
}
