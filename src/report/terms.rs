//! The report's account of the non-geometric terms (issue 19): every
//! candidate kept or rejected, with its size and why (method.md §6
//! "beyond": identifiability, the Wald test, held-out regions, BIC and
//! cross-validation against the geometric fit).

use robocal_calib::kinematics::term_selection::TermIdentification;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// One candidate term's verdict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct TermLine {
    pub name: String,
    /// `kept`, `not_identifiable`, `not_significant`, `does_not_generalise`
    /// or `no_information_gain`.
    pub verdict: String,
    /// Value when kept, or when last fitted before it was rejected (0 when
    /// never fitted), in `unit`.
    pub value: f64,
    /// Its 1σ, in `unit` (0 when never fitted).
    pub std_dev: f64,
    pub unit: String,
    pub why: String,
}

/// The selection of non-geometric terms.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct TermsReport {
    /// How the selection decides.
    pub criterion: String,
    /// The session's payload at the tool (kg).
    pub payload_kg: f64,
    /// The Wald threshold `|value|/σ` a term had to pass.
    pub z_threshold: f64,
    pub bic_geometric: f64,
    pub bic_with_terms: f64,
    pub kept: usize,
    pub lines: Vec<TermLine>,
}

impl TermsReport {
    pub fn of(selection: &TermIdentification, payload_kg: f64) -> Self {
        let lines: Vec<TermLine> = selection
            .report
            .iter()
            .map(|l| TermLine {
                name: l.name.clone(),
                verdict: l.verdict.as_str().into(),
                value: finite_or_zero(l.value),
                std_dev: finite_or_zero(l.std_dev),
                unit: l.unit.clone(),
                why: l.why.clone(),
            })
            .collect();
        Self {
            criterion: selection.criterion.into(),
            payload_kg,
            z_threshold: selection.z_threshold,
            bic_geometric: selection.bic_geometric,
            bic_with_terms: selection.bic_with_terms,
            kept: selection.terms.terms.len(),
            lines,
        }
    }
}

/// JSON has no NaN: a figure never computed is reported as 0.
fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}
