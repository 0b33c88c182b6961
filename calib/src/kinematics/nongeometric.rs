//! Errors a DH table cannot hold (issue 19, method.md §6 "beyond"): joint
//! deflections that depend on the configuration, added to the recorded
//! joint angles before the geometric chain, `q' = q + Δθ(q)`.
//!
//! Every candidate term is linear in one unknown value `p`:
//! `Δθ_i(q) = p · f(q)` with a known basis `f`:
//! - **angle-periodic** (gear eccentricity): `f = sin(h θ_i)` or `cos(h θ_i)`
//!   for harmonics `h = 1, 2`;
//! - **compliance under gravity**: `Δθ_i = c_i · τ_i(q)` where the gravity
//!   torque about joint `i` is a lumped sum over unknown masses `m_k` at the
//!   link frame origins downstream of the joint and at the tool point:
//!   `τ_i(q) = Σ_k m_k · g · ((p_k − o_i) × (−ẑ)) · z_i` (base frame, z up).
//!   Each product `c_i · m_k` is one value, so no mass table is needed; the
//!   basis is the torque of 1 kg at `p_k` (N·m), the value is in
//!   rad·kg/(N·m). With a given payload the tool point also gets a term of
//!   basis `payload · g · lever` whose value is `c_i` itself (rad/(N·m)).
//!
//! The bases are evaluated on a fixed robot (the nominal or geometric
//! model given at construction), so the deflection is exactly linear in the
//! values and the fit's Jacobian is the `dtheta_i` column times `f(q)`.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::model::{KinematicsError, RobotModel};
use super::params::CalibratedModel;
use crate::geometry::Pose;

/// Standard gravity (m/s²): torques in N·m from masses in kg and mm levers.
pub const GRAVITY_M_PER_S2: f64 = 9.806_65;
const MM_PER_M: f64 = 1000.0;
/// Highest harmonic of the angle-periodic candidates.
pub const MAX_HARMONIC: u32 = 2;
/// Link frame origins closer than this to the previous candidate point are
/// not separate mass points (their torques would be the same function).
const MIN_POINT_SPACING_MM: f64 = 20.0;

/// Which basis function a term multiplies.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum TermKind {
    /// `sin(h θ_i)` (`cosine == false`) or `cos(h θ_i)`.
    Periodic {
        joint: usize,
        harmonic: u32,
        cosine: bool,
    },
    /// Gravity torque of 1 kg at the origin of the frame after joint
    /// `point` (0-based) about joint `joint`.
    Compliance { joint: usize, point: usize },
    /// Gravity torque of 1 kg at the tool point about joint `joint`.
    ComplianceTool { joint: usize },
    /// Gravity torque of the given payload at the tool point (value `c_i`).
    CompliancePayload { joint: usize },
}

impl TermKind {
    /// The joint whose angle the term deflects (0-based).
    pub fn joint(&self) -> usize {
        match *self {
            TermKind::Periodic { joint, .. }
            | TermKind::Compliance { joint, .. }
            | TermKind::ComplianceTool { joint }
            | TermKind::CompliancePayload { joint } => joint,
        }
    }

    /// Name for reports, joints 1-based (`periodic_2.cos1`, `compliance_2.p3`).
    pub fn name(&self) -> String {
        match *self {
            TermKind::Periodic {
                joint,
                harmonic,
                cosine,
            } => format!(
                "periodic_{}.{}{harmonic}",
                joint + 1,
                if cosine { "cos" } else { "sin" }
            ),
            TermKind::Compliance { joint, point } => {
                format!("compliance_{}.mass_at_{}", joint + 1, point + 1)
            }
            TermKind::ComplianceTool { joint } => format!("compliance_{}.mass_at_tool", joint + 1),
            TermKind::CompliancePayload { joint } => format!("compliance_{}.payload", joint + 1),
        }
    }

    /// Unit of the term's value.
    pub fn unit(&self) -> &'static str {
        match self {
            TermKind::Periodic { .. } => "rad",
            TermKind::Compliance { .. } | TermKind::ComplianceTool { .. } => "rad*kg/(N*m)",
            TermKind::CompliancePayload { .. } => "rad/(N*m)",
        }
    }
}

/// Bad input to the non-geometric model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NonGeometricError {
    #[error("payload_kg must be a finite mass >= 0, got {0}")]
    BadPayload(f64),
    #[error("joint {joint} does not exist (robot has {dof})")]
    NoSuchJoint { joint: usize, dof: usize },
}

/// Which candidates to offer (issue 19).
#[derive(Debug, Clone, PartialEq)]
pub struct CandidateOptions {
    /// Joints (0-based) with periodic candidates; all by default.
    pub periodic_joints: Vec<usize>,
    /// Elastic joints (0-based) with compliance candidates: 2 and 3 of a 6R.
    pub compliant_joints: Vec<usize>,
    /// Payload at the tool (kg), if known; 0 = none.
    pub payload_kg: f64,
}

impl CandidateOptions {
    /// Periodic errors on every joint, compliance on the shoulder and elbow.
    pub fn for_robot(robot: &RobotModel) -> Self {
        Self {
            periodic_joints: (0..robot.dof()).collect(),
            compliant_joints: (1..robot.dof().min(3)).collect(),
            payload_kg: 0.0,
        }
    }
}

/// Candidate terms and their values: the non-geometric part of a model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NonGeometric {
    /// The robot the bases are evaluated on (fixed during a fit).
    pub basis_robot: RobotModel,
    /// Tool point in the flange frame (mm) for the tool and payload torques.
    pub tool_point_mm: Vector3<f64>,
    pub payload_kg: f64,
    pub terms: Vec<TermKind>,
    pub values: Vec<f64>,
}

impl NonGeometric {
    /// No terms: the geometric model itself.
    pub fn none(model: &CalibratedModel) -> Self {
        Self {
            basis_robot: model.robot.clone(),
            tool_point_mm: model.flange_to_tool.translation.vector,
            payload_kg: 0.0,
            terms: Vec::new(),
            values: Vec::new(),
        }
    }

    /// Every candidate term of `options` for `model`, all values zero.
    pub fn candidates(
        model: &CalibratedModel,
        options: &CandidateOptions,
    ) -> Result<Self, NonGeometricError> {
        if !(options.payload_kg.is_finite() && options.payload_kg >= 0.0) {
            return Err(NonGeometricError::BadPayload(options.payload_kg));
        }
        let dof = model.robot.dof();
        let check = |joint: usize| {
            if joint < dof {
                Ok(())
            } else {
                Err(NonGeometricError::NoSuchJoint { joint, dof })
            }
        };
        let mut terms = Vec::new();
        for &joint in &options.periodic_joints {
            check(joint)?;
            for harmonic in 1..=MAX_HARMONIC {
                for cosine in [false, true] {
                    terms.push(TermKind::Periodic {
                        joint,
                        harmonic,
                        cosine,
                    });
                }
            }
        }
        let zero = vec![0.0; dof];
        let origins = frame_origins(&model.robot, &zero)
            .map_err(|_| NonGeometricError::NoSuchJoint { joint: dof, dof })?;
        for &joint in &options.compliant_joints {
            check(joint)?;
            // The tool first: a payload's torque is the one every arm has.
            terms.push(TermKind::ComplianceTool { joint });
            if options.payload_kg > 0.0 {
                terms.push(TermKind::CompliancePayload { joint });
            }
            let mut last = origins[joint];
            // Frame origins beyond the joint, the flange excluded: its mass
            // is the tool's (the tool point stands for the whole end body).
            for (point, origin) in origins.iter().enumerate().take(dof).skip(joint + 1) {
                if (origin - last).norm() >= MIN_POINT_SPACING_MM {
                    terms.push(TermKind::Compliance {
                        joint,
                        point: point - 1,
                    });
                    last = *origin;
                }
            }
        }
        let values = vec![0.0; terms.len()];
        Ok(Self {
            basis_robot: model.robot.clone(),
            tool_point_mm: model.flange_to_tool.translation.vector,
            payload_kg: options.payload_kg,
            terms,
            values,
        })
    }

    /// The same bases with only the terms at `keep` (indices into `terms`).
    pub fn subset(&self, keep: &[usize]) -> Self {
        Self {
            terms: keep.iter().map(|&k| self.terms[k]).collect(),
            values: keep.iter().map(|&k| self.values[k]).collect(),
            ..self.clone()
        }
    }

    /// `f_k(q)` of every term at the recorded joints `q_rad`.
    pub fn basis(&self, q_rad: &[f64]) -> Result<Vec<f64>, KinematicsError> {
        let needs_frames = self
            .terms
            .iter()
            .any(|t| !matches!(t, TermKind::Periodic { .. }));
        let (origins, axes, tool) = if needs_frames {
            let origins = frame_origins(&self.basis_robot, q_rad)?;
            let axes = frame_axes(&self.basis_robot, q_rad)?;
            let flange = self.basis_robot.base_to_flange(q_rad)?;
            (
                origins,
                axes,
                flange * nalgebra::Point3::from(self.tool_point_mm),
            )
        } else {
            (Vec::new(), Vec::new(), nalgebra::Point3::origin())
        };
        // Torque (N·m) of `kg` at `p` about the axis through origin `j`.
        let torque = |joint: usize, p: &Vector3<f64>, kg: f64| {
            let lever_m = (p - origins[joint]) / MM_PER_M;
            let force = Vector3::new(0.0, 0.0, -kg * GRAVITY_M_PER_S2);
            axes[joint].dot(&lever_m.cross(&force))
        };
        Ok(self
            .terms
            .iter()
            .map(|t| match *t {
                TermKind::Periodic {
                    joint,
                    harmonic,
                    cosine,
                } => {
                    let angle = harmonic as f64 * q_rad[joint];
                    if cosine {
                        angle.cos()
                    } else {
                        angle.sin()
                    }
                }
                TermKind::Compliance { joint, point } => torque(joint, &origins[point + 1], 1.0),
                TermKind::ComplianceTool { joint } => torque(joint, &tool.coords, 1.0),
                TermKind::CompliancePayload { joint } => {
                    torque(joint, &tool.coords, self.payload_kg)
                }
            })
            .collect())
    }

    /// The deflected joints `q + Δθ(q)` that enter the geometric chain.
    pub fn deflected(&self, q_rad: &[f64]) -> Result<Vec<f64>, KinematicsError> {
        let mut out = q_rad.to_vec();
        if self.terms.is_empty() {
            return Ok(out);
        }
        for ((t, f), v) in self.terms.iter().zip(self.basis(q_rad)?).zip(&self.values) {
            if let Some(q) = out.get_mut(t.joint()) {
                *q += v * f;
            }
        }
        Ok(out)
    }

    /// `world_to_tool` of `model` with these deflections.
    pub fn world_to_tool(
        &self,
        model: &CalibratedModel,
        q_rad: &[f64],
    ) -> Result<Pose, KinematicsError> {
        model.world_to_tool(&self.deflected(q_rad)?)
    }
}

/// Origins (mm, base frame) of frame 0 (the base) and of the frame after
/// each joint: `origins[i]` is on joint `i`'s axis.
fn frame_origins(robot: &RobotModel, q_rad: &[f64]) -> Result<Vec<Vector3<f64>>, KinematicsError> {
    Ok(frames(robot, q_rad)?
        .iter()
        .map(|f| f.translation.vector)
        .collect())
}

/// Axis of joint `i` (z of frame `i`, base frame) for every joint.
fn frame_axes(robot: &RobotModel, q_rad: &[f64]) -> Result<Vec<Vector3<f64>>, KinematicsError> {
    Ok(frames(robot, q_rad)?
        .iter()
        .map(|f| f.rotation * Vector3::z())
        .collect())
}

fn frames(robot: &RobotModel, q_rad: &[f64]) -> Result<Vec<Pose>, KinematicsError> {
    robot.base_to_flange(q_rad)?; // checks the joint count
    let mut frame = Pose::identity();
    let mut out = vec![frame];
    for (joint, &q) in robot.joints.iter().zip(q_rad) {
        frame *= joint.link_transform(q);
        out.push(frame);
    }
    Ok(out)
}

#[cfg(test)]
#[path = "nongeometric_tests.rs"]
mod tests;
