//! The identification's parameter vector (method.md §5–6): its layout, the
//! parameter names reported to users, and how a correction vector `x` is
//! applied to a reference model.
//!
//! Layout, for a robot of `n` joints:
//! - per joint `i` (1-based in names): `dtheta_i`, `a_i`, `d_i` (DH) or
//!   `beta_i` (Hayati), `alpha_i` — 4 values, added to the reference;
//! - the world-to-base transform (`target_to_base` for a camera session,
//!   `instrument_to_base` for a tracker session): 6 values
//!   `[tx, ty, tz, rx, ry, rz]` applied by [`perturb_left`];
//! - the flange-to-tool transform: `flange_to_camera` (6 values, applied by
//!   [`perturb_left`]) for a camera, or `flange_to_tool` (3 values, the
//!   tool point in the flange frame) for a tracker.
//!
//! `x = 0` is the reference model itself, so a nominal model is the zero of
//! the parameter vector and the identified correction reads directly.

use nalgebra::{DVector, Vector3, Vector6};
use serde::{Deserialize, Serialize};

use super::model::{Convention, KinematicsError, RobotModel};
use crate::geometry::{perturb_left, Pose};

/// Values per joint in the parameter vector.
pub const PARAMS_PER_JOINT: usize = 4;
/// Values of the world-to-base transform.
pub const BASE_PARAMS: usize = 6;

/// What measured the end of the chain (api.md "Sessions").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Instrument {
    /// Flange camera seeing the board: full pose per image, 6 rows;
    /// unknowns `target_to_base` and `flange_to_camera`.
    Camera,
    /// Laser tracker measuring a reflector on the flange: position only,
    /// 3 rows; unknowns `instrument_to_base` and the tool point.
    Tracker,
}

impl Instrument {
    /// Residual rows per measured pose.
    pub fn rows(self) -> usize {
        match self {
            Instrument::Camera => 6,
            Instrument::Tracker => 3,
        }
    }

    /// Values of the flange-to-tool part.
    pub fn tool_params(self) -> usize {
        match self {
            Instrument::Camera => 6,
            Instrument::Tracker => 3,
        }
    }

    fn base_name(self) -> &'static str {
        match self {
            Instrument::Camera => "target_to_base",
            Instrument::Tracker => "instrument_to_base",
        }
    }

    fn tool_name(self) -> &'static str {
        match self {
            Instrument::Camera => "flange_to_camera",
            Instrument::Tracker => "flange_to_tool",
        }
    }
}

/// What one entry of the parameter vector moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ParamKind {
    /// Joint offset `dtheta` (rad).
    JointOffset,
    /// Common normal length `a` (mm).
    Length,
    /// DH offset along the joint axis `d` (mm).
    Offset,
    /// Hayati tilt `beta` (rad).
    Tilt,
    /// Twist `alpha` (rad).
    Twist,
    /// World-to-base component 0..6 (`tx,ty,tz` mm, `rx,ry,rz` rad).
    Base(usize),
    /// Flange-to-tool component 0..6 (0..3 for a tool point).
    Tool(usize),
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Param {
    pub kind: ParamKind,
    /// 0-based joint index for joint parameters.
    pub joint: Option<usize>,
    pub name: String,
}

/// One identified parameter for reports (api.md "parameter set": values
/// plus standard deviations, and what was held fixed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParamEstimate {
    pub name: String,
    /// Identified correction to the reference (mm or rad, see `unit`).
    pub correction: f64,
    pub std_dev: f64,
    pub fixed: bool,
    pub unit: String,
}

/// A robot chain with its world and tool transforms: everything the
/// identification estimates (method.md §5).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibratedModel {
    pub robot: RobotModel,
    /// `target_to_base` (camera) or `instrument_to_base` (tracker).
    pub world_to_base: Pose,
    /// `flange_to_camera` (camera) or the tool point as a translation-only
    /// pose (tracker).
    pub flange_to_tool: Pose,
}

impl CalibratedModel {
    /// `world_to_tool(q) = world_to_base * base_to_flange(q) * flange_to_tool`.
    pub fn world_to_tool(&self, q_rad: &[f64]) -> Result<Pose, KinematicsError> {
        Ok(self.world_to_base * self.robot.base_to_flange(q_rad)? * self.flange_to_tool)
    }

    /// The same model with another tool on the flange (api.md "compensate":
    /// a torch seen by the camera is `flange_to_camera * camera_to_torch`).
    pub fn with_tool(&self, flange_to_tool: Pose) -> Self {
        Self {
            flange_to_tool,
            ..self.clone()
        }
    }
}

/// The parameter vector's layout for one robot and instrument.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParamLayout {
    pub instrument: Instrument,
    pub params: Vec<Param>,
    joints: usize,
}

const BASE_COMPONENTS: [&str; 6] = ["tx", "ty", "tz", "rx", "ry", "rz"];
const POINT_COMPONENTS: [&str; 3] = ["x", "y", "z"];

impl ParamLayout {
    pub fn new(robot: &RobotModel, instrument: Instrument) -> Self {
        let mut params = Vec::new();
        for (i, joint) in robot.joints.iter().enumerate() {
            let n = i + 1;
            let third = match joint.convention {
                Convention::Dh => (ParamKind::Offset, format!("d_{n}")),
                Convention::Hayati => (ParamKind::Tilt, format!("beta_{n}")),
            };
            for (kind, name) in [
                (ParamKind::JointOffset, format!("dtheta_{n}")),
                (ParamKind::Length, format!("a_{n}")),
                third,
                (ParamKind::Twist, format!("alpha_{n}")),
            ] {
                params.push(Param {
                    kind,
                    joint: Some(i),
                    name,
                });
            }
        }
        for (k, c) in BASE_COMPONENTS.iter().enumerate() {
            params.push(Param {
                kind: ParamKind::Base(k),
                joint: None,
                name: format!("{}.{c}", instrument.base_name()),
            });
        }
        let tool_components: &[&str] = match instrument {
            Instrument::Camera => &BASE_COMPONENTS,
            Instrument::Tracker => &POINT_COMPONENTS,
        };
        for (k, c) in tool_components.iter().enumerate() {
            params.push(Param {
                kind: ParamKind::Tool(k),
                joint: None,
                name: format!("{}.{c}", instrument.tool_name()),
            });
        }
        Self {
            instrument,
            params,
            joints: robot.joints.len(),
        }
    }

    pub fn len(&self) -> usize {
        self.params.len()
    }

    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    pub fn joints(&self) -> usize {
        self.joints
    }

    /// Index of the first world-to-base value.
    pub fn base_start(&self) -> usize {
        self.joints * PARAMS_PER_JOINT
    }

    /// Index of the first flange-to-tool value.
    pub fn tool_start(&self) -> usize {
        self.base_start() + BASE_PARAMS
    }

    pub fn names(&self) -> Vec<String> {
        self.params.iter().map(|p| p.name.clone()).collect()
    }

    /// Indices of the joint offsets `dtheta_i`, in joint order: their
    /// Jacobian columns are the tool's motion per radian of each joint.
    pub fn joint_offset_indices(&self) -> Vec<usize> {
        (0..self.params.len())
            .filter(|&i| self.params[i].kind == ParamKind::JointOffset)
            .collect()
    }

    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.params.iter().position(|p| p.name == name)
    }

    /// Whether a parameter is an angle (rad) rather than a length (mm).
    pub fn is_angle(&self, index: usize) -> bool {
        match self.params[index].kind {
            ParamKind::JointOffset | ParamKind::Tilt | ParamKind::Twist => true,
            ParamKind::Length | ParamKind::Offset => false,
            ParamKind::Base(k) => k >= 3,
            ParamKind::Tool(k) => self.instrument == Instrument::Camera && k >= 3,
        }
    }

    /// Per-parameter report rows from a correction, its standard deviations
    /// and the names held fixed.
    pub fn estimates(
        &self,
        correction: &DVector<f64>,
        std_devs: &DVector<f64>,
        fixed: &[String],
    ) -> Vec<ParamEstimate> {
        self.params
            .iter()
            .enumerate()
            .map(|(i, p)| ParamEstimate {
                name: p.name.clone(),
                correction: correction[i],
                std_dev: std_devs[i],
                fixed: fixed.contains(&p.name),
                unit: if self.is_angle(i) { "rad" } else { "mm" }.into(),
            })
            .collect()
    }

    /// The model `reference + x` (see the module doc). `x` must have
    /// [`Self::len`] entries.
    pub fn apply(&self, reference: &CalibratedModel, x: &DVector<f64>) -> CalibratedModel {
        debug_assert_eq!(x.len(), self.len());
        let mut model = reference.clone();
        for (i, joint) in model.robot.joints.iter_mut().enumerate() {
            let p = &x.as_slice()[i * PARAMS_PER_JOINT..(i + 1) * PARAMS_PER_JOINT];
            joint.theta_offset_rad += p[0];
            joint.a_mm += p[1];
            match joint.convention {
                Convention::Dh => joint.d_mm += p[2],
                Convention::Hayati => joint.beta_rad += p[2],
            }
            joint.alpha_rad += p[3];
        }
        let b = self.base_start();
        model.world_to_base = perturb_left(
            &reference.world_to_base,
            &Vector6::from_column_slice(&x.as_slice()[b..b + BASE_PARAMS]),
        );
        let t = self.tool_start();
        model.flange_to_tool = match self.instrument {
            Instrument::Camera => perturb_left(
                &reference.flange_to_tool,
                &Vector6::from_column_slice(&x.as_slice()[t..t + 6]),
            ),
            Instrument::Tracker => {
                let mut tool = reference.flange_to_tool;
                tool.translation.vector += Vector3::from_column_slice(&x.as_slice()[t..t + 3]);
                tool
            }
        };
        model
    }

    /// The correction `x` with `apply(reference, x) ~ model` (exact for the
    /// joint and translation terms, the rotation-vector difference for the
    /// rotations): used to compare an identified model with the truth.
    pub fn difference(&self, model: &CalibratedModel, reference: &CalibratedModel) -> DVector<f64> {
        let mut x = DVector::zeros(self.len());
        for (i, (m, r)) in model
            .robot
            .joints
            .iter()
            .zip(&reference.robot.joints)
            .enumerate()
        {
            let o = i * PARAMS_PER_JOINT;
            x[o] = m.theta_offset_rad - r.theta_offset_rad;
            x[o + 1] = m.a_mm - r.a_mm;
            x[o + 2] = match m.convention {
                Convention::Dh => m.d_mm - r.d_mm,
                Convention::Hayati => m.beta_rad - r.beta_rad,
            };
            x[o + 3] = m.alpha_rad - r.alpha_rad;
        }
        let b = self.base_start();
        let base = crate::geometry::pose_error(&model.world_to_base, &reference.world_to_base);
        x.rows_mut(b, BASE_PARAMS).copy_from(&base);
        let t = self.tool_start();
        let tool = crate::geometry::pose_error(&model.flange_to_tool, &reference.flange_to_tool);
        let k = self.instrument.tool_params();
        x.rows_mut(t, k).copy_from(&tool.rows(0, k));
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::presets;

    #[test]
    fn layout_names_and_round_trip() {
        let robot = presets::irb2400();
        let layout = ParamLayout::new(&robot, Instrument::Camera);
        assert_eq!(layout.len(), 36);
        assert_eq!(layout.names()[6], "beta_2");
        assert_eq!(layout.names()[24], "target_to_base.tx");
        assert_eq!(layout.names()[35], "flange_to_camera.rz");
        let tracker = ParamLayout::new(&robot, Instrument::Tracker);
        assert_eq!(tracker.len(), 33);
        assert_eq!(tracker.names()[32], "flange_to_tool.z");
        assert!(layout.is_angle(0) && !layout.is_angle(1) && layout.is_angle(6));
        let reference = CalibratedModel {
            robot,
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::identity(),
        };
        let x = DVector::from_fn(36, |i, _| 1e-3 * (i as f64 - 17.0));
        let moved = layout.apply(&reference, &x);
        let back = layout.difference(&moved, &reference);
        assert!((&back - &x).amax() < 1e-9);
        let rows = layout.estimates(&x, &x.map(f64::abs), &["d_1".to_string()]);
        assert!(rows[2].fixed && !rows[1].fixed && rows[0].unit == "rad" && rows[1].unit == "mm");
    }
}
