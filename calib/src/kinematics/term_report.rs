//! The selection report of non-geometric terms (issue 19): what happened
//! to each candidate and why ([`super::term_selection`]).

use serde::{Deserialize, Serialize};

use super::nongeometric::{NonGeometric, TermKind};

/// What happened to one candidate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    Kept,
    NotIdentifiable,
    NotSignificant,
    /// Lowers the error inside the covered region but not on held-out
    /// regions of its joint's range.
    DoesNotGeneralise,
    NoInformationGain,
}

impl Verdict {
    /// Its serde name (`kept`, `not_identifiable`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Kept => "kept",
            Verdict::NotIdentifiable => "not_identifiable",
            Verdict::NotSignificant => "not_significant",
            Verdict::DoesNotGeneralise => "does_not_generalise",
            Verdict::NoInformationGain => "no_information_gain",
        }
    }
}

/// One line of the selection report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TermReport {
    pub name: String,
    pub term: TermKind,
    pub verdict: Verdict,
    /// Value when kept, or when last fitted before being rejected.
    pub value: f64,
    pub std_dev: f64,
    pub unit: String,
    pub why: String,
}

pub(super) fn line(
    all: &NonGeometric,
    t: usize,
    verdict: Verdict,
    value: f64,
    std_dev: f64,
    why: String,
) -> TermReport {
    let term = all.terms[t];
    TermReport {
        name: term.name(),
        term,
        verdict,
        value,
        std_dev,
        unit: term.unit().into(),
        why,
    }
}

#[cfg(test)]
mod tests {
    use super::Verdict;

    /// `as_str` is the name the report's JSON carries.
    #[test]
    fn verdict_names_are_their_serde_names() {
        for v in [
            Verdict::Kept,
            Verdict::NotIdentifiable,
            Verdict::NotSignificant,
            Verdict::DoesNotGeneralise,
            Verdict::NoInformationGain,
        ] {
            assert_eq!(serde_json::to_value(v).unwrap(), v.as_str());
        }
    }
}
