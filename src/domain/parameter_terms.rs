//! The non-geometric terms a parameter set keeps (issue 19, method.md §6
//! "beyond"): each term typed with its value, σ and unit, and the payload
//! and tool point its gravity torques were evaluated with. Stored and
//! served under the set's `terms`; [`TermsDoc::term_model`] is the one
//! conversion to calib's `TermModel`. The torque bases are evaluated on the
//! set's own identified chain (the fit evaluated them on the geometric fit
//! before the terms; the lever arms differ by the geometric corrections,
//! below a millimetre in a metre, so the deflections by under 0.1 %).

use robocal_calib::kinematics::nongeometric::{NonGeometric, TermKind};
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::term_selection::TermIdentification;
use robocal_calib::kinematics::CalibratedModel;
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
}

impl TermsDoc {
    /// The kept terms of a selection, `None` when it kept none.
    pub fn of(selection: &TermIdentification) -> Option<Self> {
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
        })
    }

    /// `model` with these terms (bases on `model`'s chain).
    pub fn term_model(&self, model: CalibratedModel) -> Result<TermModel, String> {
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
        Ok(TermModel {
            model,
            terms,
            term_std_devs: self.terms.iter().map(|k| k.std_dev).collect(),
        })
    }
}
