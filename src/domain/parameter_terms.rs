//! The non-geometric terms a parameter set keeps (issue 19, method.md §6
//! "beyond"): each term typed with its value, σ and unit, and the payload
//! and tool point its gravity torques were evaluated with. Stored and
//! served under the set's `terms`; [`TermsDoc::term_model`] is the one
//! conversion to calib's `TermModel`. The torque bases are evaluated on the
//! set's own identified chain (the fit evaluated them on the geometric fit
//! before the terms; the lever arms differ by the geometric corrections,
//! below a millimetre in a metre, so the deflections by under 0.1 %).

use nalgebra::DMatrix;
use robocal_calib::kinematics::identify::Measurement;
use robocal_calib::kinematics::nongeometric::{NonGeometric, TermKind};
use robocal_calib::kinematics::term_model::{TermCovariance, TermModel};
use robocal_calib::kinematics::term_range::{identified_ranges, IdentifiedRange};
use robocal_calib::kinematics::term_selection::TermIdentification;
use robocal_calib::kinematics::{CalibratedModel, Instrument, ParamLayout};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// One kept term.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct KeptTerm {
    /// `periodic_{joint}.{sin|cos}{harmonic}`, `compliance_{joint}.mass_at_{k}`,
    /// `compliance_{joint}.mass_at_tool` or `compliance_{joint}.payload` (joints 1-based).
    pub name: String,
    /// The basis the value multiplies (joints 0-based).
    #[schema(value_type = Object)]
    pub term: TermKind,
    /// The identified value, in `unit`.
    pub value: f64,
    /// Its 1σ, in `unit`.
    pub std_dev: f64,
    /// `rad` (periodic), `rad*kg/(N*m)` (a lumped mass's compliance) or
    /// `rad/(N*m)` (compliance under the given payload).
    pub unit: String,
}

/// A set's kept terms.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct TermsDoc {
    /// The session's payload at the tool (kg; 0 when none was given).
    pub payload_kg: f64,
    /// The tool point the tool and payload torques act at, flange frame (mm).
    pub tool_point_mm: [f64; 3],
    pub terms: Vec<KeptTerm>,
    /// The terms' covariance with the set's parameters, when they were
    /// refined with them on the image points (camera sessions); absent:
    /// `forward`'s σ takes terms and parameters as independent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub covariance: Option<TermsCovarianceDoc>,
    /// The span of each joint with a kept periodic term over the
    /// calibration poses: outside it the term extrapolates, and `forward`
    /// says so in the pose's `warnings` (calib's `term_range`). Absent in
    /// sets stored before it was kept.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joint_ranges_deg: Vec<TermJointRange>,
}

/// One joint's span over the calibration poses (deg).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct TermJointRange {
    /// 1-based, as in the parameters' names.
    pub joint: usize,
    pub min_deg: f64,
    pub max_deg: f64,
}

/// Covariances of the kept terms (camera sets: the terms were refined on
/// the image points), in the units of the set's `parameters` rows (mm or
/// deg) and each term's `unit`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct TermsCovarianceDoc {
    /// Parameter names, as the set's `covariance.names`.
    pub names: Vec<String>,
    /// One row per name, one column per term (`terms` order).
    pub with_parameters: Vec<Vec<f64>>,
    /// Term by term.
    pub among_terms: Vec<Vec<f64>>,
}

impl TermsCovarianceDoc {
    /// The free parameters `free` (layout indices) of `c` (internal units).
    fn of(c: &TermCovariance, layout: &ParamLayout, free: &[usize]) -> Self {
        Self {
            names: free
                .iter()
                .map(|&i| layout.params[i].name.clone())
                .collect(),
            with_parameters: free
                .iter()
                .map(|&i| {
                    let scale = if layout.is_angle(i) {
                        1f64.to_degrees()
                    } else {
                        1.0
                    };
                    c.cross.row(i).iter().map(|v| v * scale).collect()
                })
                .collect(),
            among_terms: c
                .terms
                .row_iter()
                .map(|r| r.iter().copied().collect())
                .collect(),
        }
    }

    /// Back to internal units over `layout` (zero rows at parameters not
    /// named), for `terms` terms.
    fn covariance(&self, layout: &ParamLayout, terms: usize) -> Result<TermCovariance, String> {
        let square =
            self.among_terms.len() == terms && self.among_terms.iter().all(|r| r.len() == terms);
        if !square
            || self.with_parameters.len() != self.names.len()
            || self.with_parameters.iter().any(|r| r.len() != terms)
        {
            return Err(format!(
                "terms covariance is not {} x {terms} and {terms} x {terms}",
                self.names.len()
            ));
        }
        let mut cross = DMatrix::zeros(layout.len(), terms);
        for (name, row) in self.names.iter().zip(&self.with_parameters) {
            let i = layout
                .index_of(name)
                .ok_or_else(|| format!("terms covariance names unknown parameter {name}"))?;
            let scale = if layout.is_angle(i) {
                1f64.to_radians()
            } else {
                1.0
            };
            for (t, v) in row.iter().enumerate() {
                cross[(i, t)] = v * scale;
            }
        }
        Ok(TermCovariance {
            cross,
            terms: DMatrix::from_fn(terms, terms, |a, b| self.among_terms[a][b]),
        })
    }
}

impl TermsDoc {
    /// The kept terms of a selection, `None` when it kept none; their
    /// covariance with the parameters `free` of `layout` when it has one.
    pub fn of(
        selection: &TermIdentification,
        layout: &ParamLayout,
        free: &[usize],
        calibration: &[Measurement],
    ) -> Option<Self> {
        if selection.terms.terms.is_empty() {
            return None;
        }
        let t = &selection.terms;
        Some(Self {
            payload_kg: t.payload_kg,
            tool_point_mm: t.tool_point_mm.into(),
            terms: t
                .terms
                .iter()
                .zip(&t.values)
                .zip(&selection.term_std_devs)
                .map(|((term, &value), &std_dev)| KeptTerm {
                    name: term.name(),
                    term: *term,
                    value,
                    std_dev,
                    unit: term.unit().into(),
                })
                .collect(),
            covariance: selection
                .term_covariance
                .as_ref()
                .map(|c| TermsCovarianceDoc::of(c, layout, free)),
            joint_ranges_deg: identified_ranges(t, calibration)
                .iter()
                .map(|r| TermJointRange {
                    joint: r.joint + 1,
                    min_deg: r.min_rad.to_degrees(),
                    max_deg: r.max_rad.to_degrees(),
                })
                .collect(),
        })
    }

    /// The report's note on where the kept periodic terms hold: each
    /// joint's span over the calibration poses (`None` without one).
    pub fn range_note(&self) -> Option<String> {
        if self.joint_ranges_deg.is_empty() {
            return None;
        }
        let spans: Vec<String> = self
            .joint_ranges_deg
            .iter()
            .map(|r| format!("joint {} {:.1}° to {:.1}°", r.joint, r.min_deg, r.max_deg))
            .collect();
        Some(format!(
            "Kept periodic terms were identified over {}: outside these spans they extrapolate, and forward warns per pose. Cover the joints' working range to use them there.",
            spans.join(", ")
        ))
    }

    /// `model` with these terms (bases on `model`'s chain); their
    /// covariance read in the parameter layout of `instrument`.
    pub fn term_model(
        &self,
        model: CalibratedModel,
        instrument: Instrument,
    ) -> Result<TermModel, String> {
        let dof = model.robot.dof();
        if let Some(bad) = self.terms.iter().find(|k| k.term.joint() >= dof) {
            return Err(format!("term {} names a joint the robot has not", bad.name));
        }
        let terms = NonGeometric {
            basis_robot: model.robot.clone(),
            tool_point_mm: self.tool_point_mm.into(),
            payload_kg: self.payload_kg,
            terms: self.terms.iter().map(|k| k.term).collect(),
            values: self.terms.iter().map(|k| k.value).collect(),
        };
        let covariance = self
            .covariance
            .as_ref()
            .map(|c| {
                c.covariance(
                    &ParamLayout::new(&model.robot, instrument),
                    self.terms.len(),
                )
            })
            .transpose()?;
        Ok(TermModel {
            model,
            terms,
            term_std_devs: self.terms.iter().map(|k| k.std_dev).collect(),
            covariance,
            ranges: self
                .joint_ranges_deg
                .iter()
                .filter(|r| (1..=dof).contains(&r.joint))
                .map(|r| IdentifiedRange {
                    joint: r.joint - 1,
                    min_rad: r.min_deg.to_radians(),
                    max_rad: r.max_deg.to_radians(),
                })
                .collect(),
        })
    }
}
